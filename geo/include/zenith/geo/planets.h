// Mercury to Neptune: apparent places from VSOP87 and V magnitudes from Mallama & Hilton (2018).
//
// Positions: VSOP87B heliocentric series (Bretagnon & Francou 1988) for every planet and the
// Earth, truncated per planet (geo/src/vsop87b_<planet>.inc, made by
// scripts/gen_vsop87b_table.py; each header states the measured truncation error, < 0.2" and
// < 120 km over 1950-2100). Light time (the planet where it was when the light left it), the
// Sun's light deflection, annual aberration (Lorentz transformation with the Earth's
// heliocentric velocity), then IAU 2006/2000B precession-nutation to the true equator and
// equinox of date: the chain the Sun and the stars use. Accuracy against ERFA and JPL Horizons
// is measured in tests/geo/planets_test.cpp.
//
// Validity: the truncation was chosen and measured for 1950-2100 (TT). Outside that window the
// functions here return no position (std::nullopt / an empty list): the dropped terms grow as
// tau^i and the error is no longer the one stated.
//
// Magnitudes: Mallama & Hilton 2018, "Computing apparent planetary magnitudes for The
// Astronomical Almanac", Astronomy and Computing 25, 10-24, equations 2-17 for the phase angles
// seen from the Earth (Mercury's and Venus's full phase curves included), Saturn with its rings
// (the ring tilt as the geometric mean of the saturnicentric latitudes of the Sun and the Earth),
// Uranus with its sub-Sun/sub-Earth planetographic latitudes and Neptune with its secular term.
// Mars's rotation and orbital-position corrections (Mallama 2007 tables, each within +-0.09 mag)
// are applied when the caller gives the angles (PlanetMagnitudeAspect); the ephemeris computes
// them from the IAU 2009 rotation model of Mars (Archinal et al. 2011).
#pragma once

#include <array>
#include <glm/glm.hpp>
#include <optional>
#include <string_view>
#include <vector>

#include "zenith/geo/observer.h"
#include "zenith/geo/time.h"

namespace zenith::geo {

enum class Planet { kMercury, kVenus, kEarth, kMars, kJupiter, kSaturn, kUranus, kNeptune };

// The planets seen in the sky, in order from the Sun (the Earth excluded).
inline constexpr std::array<Planet, 7> kSkyPlanets = {
    Planet::kMercury, Planet::kVenus,  Planet::kMars,   Planet::kJupiter,
    Planet::kSaturn,  Planet::kUranus, Planet::kNeptune};

// Lower-case English name: "mercury" ... "neptune" (as in batch column names).
std::string_view PlanetName(Planet planet);

// Equatorial radius, metres (IAU WGCCRE 2015, Archinal et al. 2018).
double PlanetEquatorialRadius(Planet planet);

// Window (TT Julian dates) over which the truncated series are measured: 1950-01-01 0h to
// 2100-01-01 0h.
inline constexpr double kPlanetSeriesFirstJdTt = 2433282.5;
inline constexpr double kPlanetSeriesLastJdTt = 2488069.5;
inline bool PlanetSeriesValid(double jd_tt) {
    return jd_tt >= kPlanetSeriesFirstJdTt && jd_tt <= kPlanetSeriesLastJdTt;
}

// Geometric heliocentric position (truncated VSOP87B) in GCRS axes, metres; the Earth included.
// Evaluated at any date (for tests and tools); only 1950-2100 is within the stated accuracy.
glm::dvec3 PlanetHeliocentricGcrs(Planet planet, double jd_tt);

struct PlanetPosition {
    Planet planet = Planet::kMercury;
    // Geocentric apparent place, TOD (true equator and equinox of date): the apparent direction
    // times the light-time distance, metres.
    glm::dvec3 geocentric_tod{0.0};
    double right_ascension = 0.0;  // radians, [0, 2pi), geocentric apparent, TOD
    double declination = 0.0;      // radians, geocentric apparent, TOD
    // Topocentric apparent RA/Dec (TOD) and azimuth/elevation (geometric); filled only by the
    // functions that take an observer.
    Topocentric topocentric;
    double elevation = 0.0;    // radians: topocentric, geometric or refracted as requested
    double distance_au = 0.0;  // geocentric, Earth now to planet at emission
    double heliocentric_distance_au = 0.0;  // Sun to planet at emission
    double phase_angle = 0.0;               // radians, Sun-planet-Earth
    double illuminated_fraction = 0.0;      // (1 + cos phase_angle) / 2
    double elongation = 0.0;                // radians, geocentric angle Sun-planet
    double magnitude_v = 0.0;               // apparent V magnitude, top of atmosphere
    double angular_diameter_arcsec = 0.0;   // equatorial diameter seen from the geocentre
};

// Geocentric apparent place and magnitude; std::nullopt outside 1950-2100 or for the Earth.
std::optional<PlanetPosition> PlanetGeocentric(Planet planet, double jd_tt);

// All seven planets (kSkyPlanets order) for one observer: geocentric values as above plus the
// topocentric place (parallax, and diurnal aberration unless disabled). Empty outside
// 1950-2100. The Earth's position and velocity are computed once for all seven.
std::vector<PlanetPosition> PlanetsTopocentric(const Time& t, const Observer& observer,
                                               bool diurnal_aberration = true);

// What a magnitude formula needs besides distances and phase angle. Angles in degrees.
struct PlanetMagnitudeAspect {
    // Saturn: saturnicentric latitudes of the Sun and the Earth (ring plane). Uranus:
    // planetographic latitudes of the sub-Sun and sub-Earth points.
    double sub_sun_latitude_deg = 0.0;
    double sub_earth_latitude_deg = 0.0;
    bool saturn_rings = true;  // false: Saturn's globe alone (Mallama & Hilton eqs. 11-12)
    // Mars (Mallama & Hilton eqs. 6-7 and Mallama 2007 tables): sub-Earth and sub-Sun west
    // longitudes and the heliocentric ecliptic longitude; no correction when absent.
    std::optional<double> mars_sub_earth_longitude_deg;
    std::optional<double> mars_sub_sun_longitude_deg;
    std::optional<double> mars_heliocentric_longitude_deg;
    double year = 2020.0;  // decimal year, for Neptune's secular brightening (eq. 16)
};

// Apparent V magnitude from the heliocentric distance r and geocentric distance delta (au) and
// the phase angle (degrees), Mallama & Hilton 2018. For the Earth, the magnitude seen from
// elsewhere (eq. 5). Outside the phase angles the formulas were fitted to (e.g. Saturn beyond
// 6.5 deg, which only a spacecraft sees) the nearest formula is extrapolated; never NaN for
// finite input.
double PlanetMagnitudeV(Planet planet, double r_au, double delta_au, double phase_angle_deg,
                        const PlanetMagnitudeAspect& aspect = {});

}  // namespace zenith::geo
