// The Sun's geocentric apparent position: VSOP87D heliocentric Earth series (truncated, see
// data/README.md), FK5 frame correction, IAU 2000B nutation, annual aberration.
#pragma once

#include <glm/glm.hpp>

#include "zenith/geo/time.h"

namespace zenith::geo {

inline constexpr double kAstronomicalUnit = 149597870700.0;  // m (IAU 2012)

struct EclipticPosition {
    double longitude = 0.0;  // radians, [0, 2pi)
    double latitude = 0.0;   // radians
    double distance = 0.0;   // metres
};

// Heliocentric Earth, mean ecliptic and equinox of date (VSOP87D, dynamical frame), metres.
EclipticPosition EarthHeliocentricVsop87(double jd_tt);

// Geocentric apparent ecliptic coordinates of the Sun, true equinox of date (Meeus ch. 25 chain).
EclipticPosition SunApparentEcliptic(double jd_tt);

// Geocentric apparent position of the Sun in TOD (true equator and equinox of date), metres.
glm::dvec3 SunApparentTod(double jd_tt);

// Earth's velocity about the Sun in GCRS axes, m/s (for annual aberration of stars).
glm::dvec3 EarthVelocityGcrs(double jd_tt);

}  // namespace zenith::geo
