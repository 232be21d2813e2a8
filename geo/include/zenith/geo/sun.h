// The Sun's geocentric apparent position: VSOP87 heliocentric Earth series, FK5 frame correction,
// IAU 2000B nutation, annual aberration (Meeus, Astronomical Algorithms, ch. 25).
//
// The series is VSOP87B (ecliptic and equinox J2000; Bretagnon & Francou 1988), truncated to 770
// of 2564 terms (geo/src/vsop87b_earth.inc, made by scripts/gen_vsop87b_table.py: < 0.016" and
// < 11 km of truncation error over 1950-2100), precessed to date with IAU 2006.
// Measured against ERFA (eraEpv00/DE405 + eraAb + eraPnm06a), 1950-2100: apparent direction
// 0.075" max, 0.046" RMS (tests/geo/sun_test.cpp).
// Inputs are TT Julian dates and must be finite (validated where instants are made, time.h);
// NaN in gives NaN out.
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

// Heliocentric Earth, mean ecliptic and equinox of date (VSOP87B precessed with IAU 2006; the
// geometric position, no FK5 correction), distance in metres.
EclipticPosition EarthHeliocentricVsop87(double jd_tt);

// Heliocentric Earth (geometric, VSOP87B as above) in GCRS axes, metres: the J2000 ecliptic frame
// rotated by the IAU 2006 obliquity and frame bias, no precession.
glm::dvec3 EarthHeliocentricGcrs(double jd_tt);

// Geocentric apparent ecliptic coordinates of the Sun, true equinox of date (Meeus ch. 25 chain).
EclipticPosition SunApparentEcliptic(double jd_tt);

// Geocentric apparent position of the Sun in TOD (true equator and equinox of date), metres.
glm::dvec3 SunApparentTod(double jd_tt);

// Earth's velocity about the Sun in GCRS axes, m/s (for annual aberration of stars). Heliocentric:
// within 1.2e-6 of eraEpv00's heliocentric velocity and 5.4e-4 of its barycentric one (the Sun's
// ~13 m/s about the barycentre), i.e. < 0.011" of stellar aberration.
glm::dvec3 EarthVelocityGcrs(double jd_tt);

}  // namespace zenith::geo
