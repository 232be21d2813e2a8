// Apparent places and magnitudes of the planets (see planets.h for the models and their sources).
//
// Chain, for an observer at the geocentre at TT instant t (all vectors heliocentric, GCRS axes):
//   E      Earth at t (VSOP87B)
//   P(t')  planet at t' = t - tau, tau the light time |P(t') - E| / c, with one evaluation of
//          the full series: the light time is first found from a coarse series (the leading
//          terms), then refined from the full position with a linear step (see Compute).
//   p      unit vector E -> P(t'), deflected by the Sun's gravity (the formula of eraLd, IERS
//          Conventions 2010 eq. 7.3 in its Solar System form), then aberrated by the Earth's
//          heliocentric velocity (Lorentz transformation, as stars in stars.cpp), then rotated to
//          TOD with TodFromGcrs (IAU 2006/2000B).
// The barycentre is not used: heliocentric light time and velocity differ from barycentric ones
// by the Sun's ~13 m/s about the barycentre, < 0.01" of aberration.
#include "zenith/geo/planets.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <span>

#include "vsop87.h"
#include "zenith/geo/angles.h"
#include "zenith/geo/earth_orientation.h"
#include "zenith/geo/sun.h"

namespace zenith::geo {
namespace {

using detail::EvaluateVsop;
using detail::FromSpherical;
using detail::GcrsFromEclipticJ2000;
using detail::VsopSeries;
using detail::VsopTerm;

#include "vsop87b_jupiter.inc"
#include "vsop87b_mars.inc"
#include "vsop87b_mercury.inc"
#include "vsop87b_neptune.inc"
#include "vsop87b_saturn.inc"
#include "vsop87b_uranus.inc"
#include "vsop87b_venus.inc"

constexpr double kDegToRad = std::numbers::pi / 180.0;
constexpr double kRadToDeg = 180.0 / std::numbers::pi;
constexpr double kSpeedOfLight = 299792458.0;  // m/s
// Schwarzschild radius of the Sun, 2 GM_sun / c^2, metres (IAU 2015 nominal GM_sun).
constexpr double kSunSchwarzschildRadius = 2953.25;

struct PlanetSeries {
    VsopSeries l, b, r;
};

PlanetSeries SeriesOf(Planet planet) {
    switch (planet) {
        case Planet::kMercury:
            return {kMercuryL, kMercuryB, kMercuryR};
        case Planet::kVenus:
            return {kVenusL, kVenusB, kVenusR};
        case Planet::kMars:
            return {kMarsL, kMarsB, kMarsR};
        case Planet::kJupiter:
            return {kJupiterL, kJupiterB, kJupiterR};
        case Planet::kSaturn:
            return {kSaturnL, kSaturnB, kSaturnR};
        case Planet::kUranus:
            return {kUranusL, kUranusB, kUranusR};
        case Planet::kNeptune:
            return {kNeptuneL, kNeptuneB, kNeptuneR};
        case Planet::kEarth:
            break;
    }
    return {};
}

// Unit vector of a pole given by right ascension and declination in degrees (ICRF).
glm::dvec3 PoleVector(double ra_deg, double dec_deg) {
    return FromSpherical(ra_deg * kDegToRad, dec_deg * kDegToRad, 1.0);
}

// IAU WGCCRE pole directions, T in Julian centuries of TDB (~TT) since J2000 (Archinal et al.
// 2011 for Mars, 2018 for Saturn and Uranus; Saturn's ring plane is its equator).
glm::dvec3 SaturnPole(double t) { return PoleVector(40.589 - 0.036 * t, 83.537 - 0.004 * t); }
glm::dvec3 UranusPole() { return PoleVector(257.311, -15.175); }
glm::dvec3 MarsPole(double t) { return PoleVector(317.68143 - 0.1061 * t, 52.88650 - 0.0609 * t); }

// Latitude (degrees) of direction `to` (unit) in the frame whose north pole is `pole`.
double LatitudeDeg(const glm::dvec3& pole, const glm::dvec3& to) {
    return std::asin(std::clamp(glm::dot(pole, to), -1.0, 1.0)) * kRadToDeg;
}

// West longitude (degrees, [0, 360)) on Mars of the sub-point of direction `to` (unit, from
// Mars), IAU 2009 rotation: W = 176.630 + 350.89198226 d, measured from the ascending node of
// Mars's equator on the ICRF equator, Q = z x pole.
double MarsWestLongitudeDeg(const glm::dvec3& pole, const glm::dvec3& to, double days) {
    const glm::dvec3 node = glm::normalize(glm::cross(glm::dvec3(0.0, 0.0, 1.0), pole));
    const glm::dvec3 ninety = glm::cross(pole, node);
    const double east_of_node = std::atan2(glm::dot(to, ninety), glm::dot(to, node)) * kRadToDeg;
    const double w = 176.630 + 350.89198226 * days;
    return WrapTwoPi((w - east_of_node) * kDegToRad) * kRadToDeg;
}

// Mallama 2007 (Icarus 192, 404) tables as used by Mallama & Hilton 2018 for Mars: magnitude
// corrections every 10 deg of effective central meridian (kMarsRotation) and of areocentric solar
// longitude Ls (kMarsOrbit), entry k at (k - 2) * 10 deg, so two entries pad each end.
constexpr double kMarsRotation[40] = {
    0.024,  0.034,  0.036,  0.045,  0.038,  0.023,  0.015,  0.011,  0.000,  -0.012,
    -0.018, -0.036, -0.044, -0.059, -0.060, -0.055, -0.043, -0.041, -0.041, -0.036,
    -0.036, -0.018, -0.038, -0.011, 0.002,  0.004,  0.018,  0.019,  0.035,  0.050,
    0.035,  0.027,  0.037,  0.048,  0.025,  0.022,  0.024,  0.034,  0.036,  0.045};
constexpr double kMarsOrbit[40] = {-0.030, -0.017, -0.029, -0.017, -0.014, -0.006, -0.018, -0.020,
                                   -0.014, -0.030, -0.008, -0.040, -0.024, -0.037, -0.036, -0.032,
                                   0.010,  0.010,  -0.001, 0.044,  0.025,  -0.004, -0.016, -0.008,
                                   0.029,  -0.054, -0.033, 0.055,  0.017,  0.052,  0.006,  0.087,
                                   0.006,  0.064,  0.030,  0.019,  -0.030, -0.017, -0.029, -0.017};

// Stirling's central-difference interpolation (fourth differences) in a 10-degree table.
double StirlingInterpolate(const double (&table)[40], double angle_deg) {
    const double x = angle_deg / 10.0;
    const int k0 = std::clamp(static_cast<int>(std::floor(x)), 0, 35) + 2;  // table index at x0
    const double p = x - (k0 - 2);
    const double fm2 = table[k0 - 2], fm1 = table[k0 - 1], f0 = table[k0], f1 = table[k0 + 1],
                 f2 = table[k0 + 2];
    const double d1 = 0.5 * (f1 - fm1);     // mean first difference
    const double d2 = f1 - 2.0 * f0 + fm1;  // second difference
    const double d3 = 0.5 * ((f2 - 3.0 * f1 + 3.0 * f0 - fm1) + (f1 - 3.0 * f0 + 3.0 * fm1 - fm2));
    const double d4 = f2 - 4.0 * f1 + 6.0 * f0 - 4.0 * fm1 + fm2;
    return f0 + p * d1 + p * p / 2.0 * d2 + p * (p * p - 1.0) / 6.0 * d3 +
           p * p * (p * p - 1.0) / 24.0 * d4;
}

// The state of the Earth shared by all planets at one instant.
struct EarthState {
    double jd_tt = 0.0;
    glm::dvec3 position{0.0};  // heliocentric, GCRS, m
    glm::dvec3 beta{0.0};      // heliocentric velocity / c
    glm::dmat3 tod_from_gcrs{1.0};
};

EarthState MakeEarthState(double jd_tt) {
    return {jd_tt, EarthHeliocentricGcrs(jd_tt), EarthVelocityGcrs(jd_tt) / kSpeedOfLight,
            TodFromGcrs(jd_tt)};
}

// The planet from the first kCoarseTerms terms of each power of its series: its distance to
// ~1e-4, enough to time the light (Compute) but not to point at it.
constexpr std::size_t kCoarseTerms = 8;

glm::dvec3 CoarseHeliocentricGcrs(Planet planet, double jd_tt) {
    const PlanetSeries s = SeriesOf(planet);
    const double tau = (jd_tt - kJ2000) / detail::kDaysPerMillennium;
    return GcrsFromEclipticJ2000() *
           FromSpherical(EvaluateVsop(s.l, tau, kCoarseTerms), EvaluateVsop(s.b, tau, kCoarseTerms),
                         EvaluateVsop(s.r, tau, kCoarseTerms) * kAstronomicalUnit);
}

PlanetPosition Compute(Planet planet, const EarthState& earth) {
    const double t = earth.jd_tt;
    // Light time in one full evaluation: tau0 from the coarse series at t and t - tau0' (its own
    // light time), the full series at t - tau0, then the exact tau1 from that position and a
    // linear step to t - tau1 with the coarse mean velocity. Measured over 20000 dates
    // 1950-2100: |tau1 - tau0| < 3.2 s (Uranus) and the emitted position within 50 m of a
    // converged iteration on the full series (16 coarse terms: 0.9 s and 3 m, for 40 % more
    // time; 50 m is 1e-5 of the truncation error). tests/geo/planets_test.cpp checks it.
    const glm::dvec3 coarse_now = CoarseHeliocentricGcrs(planet, t);
    const double tau_guess =
        glm::length(coarse_now - earth.position) / kSpeedOfLight / kSecondsPerDay;
    const glm::dvec3 coarse_then = CoarseHeliocentricGcrs(planet, t - tau_guess);
    const double tau0 = glm::length(coarse_then - earth.position) / kSpeedOfLight / kSecondsPerDay;
    const glm::dvec3 p0 = PlanetHeliocentricGcrs(planet, t - tau0);
    const double tau1 = glm::length(p0 - earth.position) / kSpeedOfLight / kSecondsPerDay;
    const glm::dvec3 velocity = (coarse_now - coarse_then) / tau_guess;  // m/day
    const glm::dvec3 planet_helio = p0 - velocity * (tau1 - tau0);

    const glm::dvec3 geometric = planet_helio - earth.position;
    const double distance = glm::length(geometric);
    glm::dvec3 p = geometric / distance;

    // Light deflection by the Sun (eraLd with bm = 1, dlim = 1e-9): q Sun->planet,
    // e Sun->Earth, both unit; the planet's own distance enters through q.
    const double earth_sun_distance = glm::length(earth.position);
    const glm::dvec3 q = glm::normalize(planet_helio);
    const glm::dvec3 e = earth.position / earth_sun_distance;
    const double qdqpe = std::max(glm::dot(q, q + e), 1e-9);
    const double w = kSunSchwarzschildRadius / earth_sun_distance / qdqpe;
    p += w * glm::cross(p, glm::cross(e, q));

    // Annual aberration, Lorentz transformation (SOFA/ERFA ab without its gravitational term,
    // which the deflection above replaces).
    const double inverse_gamma = std::sqrt(1.0 - glm::dot(earth.beta, earth.beta));
    const double p_dot_beta = glm::dot(p, earth.beta);
    const glm::dvec3 apparent =
        glm::normalize(inverse_gamma * p + (1.0 + p_dot_beta / (1.0 + inverse_gamma)) * earth.beta);

    PlanetPosition out;
    out.planet = planet;
    out.geocentric_tod = earth.tod_from_gcrs * apparent * distance;
    const glm::dvec3 u = glm::normalize(out.geocentric_tod);
    out.right_ascension = WrapTwoPi(std::atan2(u.y, u.x));
    out.declination = std::asin(std::clamp(u.z, -1.0, 1.0));

    const double r = glm::length(planet_helio);
    out.distance_au = distance / kAstronomicalUnit;
    out.heliocentric_distance_au = r / kAstronomicalUnit;
    out.phase_angle = AngleBetween(-planet_helio, earth.position - planet_helio);
    out.illuminated_fraction = 0.5 * (1.0 + std::cos(out.phase_angle));
    out.elongation = AngleBetween(-earth.position, geometric);
    out.angular_diameter_arcsec =
        2.0 * std::asin(PlanetEquatorialRadius(planet) / distance) / kArcsecToRad;

    PlanetMagnitudeAspect aspect;
    const double centuries = (t - kJ2000) / kDaysPerCentury;
    aspect.year = 2000.0 + (t - kJ2000) / 365.25;
    const glm::dvec3 to_sun = -planet_helio / r;
    const glm::dvec3 to_earth = -geometric / distance;
    if (planet == Planet::kSaturn) {
        const glm::dvec3 pole = SaturnPole(centuries);
        aspect.sub_sun_latitude_deg = LatitudeDeg(pole, to_sun);
        aspect.sub_earth_latitude_deg = LatitudeDeg(pole, to_earth);
    } else if (planet == Planet::kUranus) {
        // Planetocentric -> planetographic: tan(graphic) = tan(centric) / (1 - f)^2, with
        // f = 1 - 24973 / 25559 (IAU 2015 polar and equatorial radii).
        constexpr double kOneMinusFSquared = (24973.0 / 25559.0) * (24973.0 / 25559.0);
        const auto graphic = [](double centric_deg) {
            return std::atan(std::tan(centric_deg * kDegToRad) / kOneMinusFSquared) * kRadToDeg;
        };
        const glm::dvec3 pole = UranusPole();
        aspect.sub_sun_latitude_deg = graphic(LatitudeDeg(pole, to_sun));
        aspect.sub_earth_latitude_deg = graphic(LatitudeDeg(pole, to_earth));
    } else if (planet == Planet::kMars) {
        const glm::dvec3 pole = MarsPole(centuries);
        const double days = t - tau1 - kJ2000;  // Mars's rotation when the light left
        aspect.mars_sub_earth_longitude_deg = MarsWestLongitudeDeg(pole, to_earth, days);
        aspect.mars_sub_sun_longitude_deg = MarsWestLongitudeDeg(pole, to_sun, days);
        const glm::dvec3 ecliptic = glm::transpose(GcrsFromEclipticJ2000()) * planet_helio;
        aspect.mars_heliocentric_longitude_deg =
            WrapTwoPi(std::atan2(ecliptic.y, ecliptic.x)) * kRadToDeg;
    }
    out.magnitude_v = PlanetMagnitudeV(planet, out.heliocentric_distance_au, out.distance_au,
                                       out.phase_angle * kRadToDeg, aspect);
    return out;
}

}  // namespace

std::string_view PlanetName(Planet planet) {
    switch (planet) {
        case Planet::kMercury:
            return "mercury";
        case Planet::kVenus:
            return "venus";
        case Planet::kEarth:
            return "earth";
        case Planet::kMars:
            return "mars";
        case Planet::kJupiter:
            return "jupiter";
        case Planet::kSaturn:
            return "saturn";
        case Planet::kUranus:
            return "uranus";
        case Planet::kNeptune:
            return "neptune";
    }
    return "unknown";
}

double PlanetEquatorialRadius(Planet planet) {
    switch (planet) {
        case Planet::kMercury:
            return 2440530.0;
        case Planet::kVenus:
            return 6051800.0;
        case Planet::kEarth:
            return 6378137.0;
        case Planet::kMars:
            return 3396190.0;
        case Planet::kJupiter:
            return 71492000.0;
        case Planet::kSaturn:
            return 60268000.0;
        case Planet::kUranus:
            return 25559000.0;
        case Planet::kNeptune:
            return 24764000.0;
    }
    return 0.0;
}

glm::dvec3 PlanetHeliocentricGcrs(Planet planet, double jd_tt) {
    if (planet == Planet::kEarth) return EarthHeliocentricGcrs(jd_tt);
    const PlanetSeries s = SeriesOf(planet);
    const double tau = (jd_tt - kJ2000) / detail::kDaysPerMillennium;
    return GcrsFromEclipticJ2000() * FromSpherical(EvaluateVsop(s.l, tau), EvaluateVsop(s.b, tau),
                                                   EvaluateVsop(s.r, tau) * kAstronomicalUnit);
}

std::optional<PlanetPosition> PlanetGeocentric(Planet planet, double jd_tt) {
    if (planet == Planet::kEarth || !PlanetSeriesValid(jd_tt)) return std::nullopt;
    return Compute(planet, MakeEarthState(jd_tt));
}

std::vector<PlanetPosition> PlanetsTopocentric(const Time& t, const Observer& observer,
                                               bool diurnal_aberration) {
    std::vector<PlanetPosition> out;
    if (!PlanetSeriesValid(t.jd_tt)) return out;
    const EarthState earth = MakeEarthState(t.jd_tt);
    const glm::dmat3 ecef_from_tod = EcefFromTod(t);
    out.reserve(kSkyPlanets.size());
    for (Planet planet : kSkyPlanets) {
        PlanetPosition p = Compute(planet, earth);
        p.topocentric = TopocentricFromGeocentricTod(p.geocentric_tod, ecef_from_tod, observer,
                                                     diurnal_aberration);
        p.elevation = p.topocentric.horizontal.elevation;
        out.push_back(p);
    }
    return out;
}

double PlanetMagnitudeV(Planet planet, double r_au, double delta_au, double phase_angle_deg,
                        const PlanetMagnitudeAspect& aspect) {
    const double a = phase_angle_deg;
    const double distance_term = 5.0 * std::log10(r_au * delta_au);
    switch (planet) {
        case Planet::kMercury:  // eq. 2 (2-170 deg)
            return -0.613 + distance_term +
                   a * (6.3280e-02 +
                        a * (-1.6336e-03 +
                             a * (3.3644e-05 +
                                  a * (-3.4265e-07 + a * (1.6893e-09 + a * -3.0334e-12)))));
        case Planet::kVenus:  // eqs. 3 (< 163.7 deg) and 4 (beyond, forward scattering)
            if (a < 163.7) {
                return -4.384 + distance_term +
                       a * (-1.044e-03 + a * (3.687e-04 + a * (-2.814e-06 + a * 8.938e-09)));
            }
            return 236.05828 + distance_term + a * (-2.81914 + a * 8.39034e-03);
        case Planet::kEarth:  // eq. 5
            return -3.99 + distance_term + a * (-1.060e-03 + a * 2.054e-04);
        case Planet::kMars: {  // eqs. 6 (<= 50 deg) and 7, plus the Mallama 2007 corrections
            double v = a <= 50.0 ? -1.601 + a * (2.267e-02 - 1.302e-04 * a)
                                 : -0.367 + a * (-0.02573 + 3.445e-04 * a);
            if (aspect.mars_sub_earth_longitude_deg && aspect.mars_sub_sun_longitude_deg) {
                const double e = *aspect.mars_sub_earth_longitude_deg;
                const double s = *aspect.mars_sub_sun_longitude_deg;
                // Effective central meridian: the mean of the two longitudes, on the short arc.
                double cm = 0.5 * (e + s);
                if (std::abs(e - s) > 180.0) cm += 180.0;
                cm = std::fmod(cm, 360.0);
                v += StirlingInterpolate(kMarsRotation, cm);
            }
            if (aspect.mars_heliocentric_longitude_deg) {
                // Ls from the heliocentric ecliptic longitude (Mallama & Hilton's offset).
                double ls = std::fmod(*aspect.mars_heliocentric_longitude_deg - 85.0, 360.0);
                if (ls < 0.0) ls += 360.0;
                v += StirlingInterpolate(kMarsOrbit, ls);
            }
            return v + distance_term;
        }
        case Planet::kJupiter:  // eqs. 8 (<= 12 deg) and 9
            if (a <= 12.0) return -9.395 + distance_term + a * (-3.7e-04 + a * 6.16e-04);
            {
                const double x = a / 180.0;
                const double f =
                    1.0 + x * (-1.507 + x * (-0.363 + x * (-0.062 + x * (2.809 + x * -1.876))));
                return -9.428 + distance_term - 2.5 * std::log10(std::max(f, 1e-6));
            }
        case Planet::kSaturn: {
            // Ring tilt: geometric mean of the saturnicentric latitudes of the Sun and the
            // Earth, zero when they are on opposite sides of the ring plane.
            const double product = aspect.sub_sun_latitude_deg * aspect.sub_earth_latitude_deg;
            const double beta = product > 0.0 ? std::sqrt(product) : 0.0;
            const double sin_beta = std::sin(beta * kDegToRad);
            if (!aspect.saturn_rings) {
                if (a <= 6.5) return -8.95 + distance_term + a * (-3.7e-04 + a * 6.16e-04);
                return -8.94 + distance_term +
                       a * (2.446e-04 + a * (2.672e-04 + a * (-1.506e-06 + a * 4.767e-09)));
            }
            // eq. 10, fitted for phase angles <= 6.5 deg and ring tilts <= 27 deg (all that is
            // seen from the Earth).
            return -8.914 + distance_term - 1.825 * sin_beta + 0.026 * a -
                   0.378 * sin_beta * std::exp(-2.25 * a);
        }
        case Planet::kUranus: {  // eqs. 14 (<= 3.1 deg) and 15
            const double latitude = 0.5 * (std::abs(aspect.sub_sun_latitude_deg) +
                                           std::abs(aspect.sub_earth_latitude_deg));
            double v = -7.110 + distance_term - 8.4e-04 * latitude;
            if (a > 3.1) v += a * (6.587e-03 + a * 1.045e-04);
            return v;
        }
        case Planet::kNeptune: {  // eq. 16 (secular), eq. 17 beyond 1.9 deg
            const double v0 = std::clamp(-6.89 - 0.0054 * (aspect.year - 1980.0), -7.00, -6.89);
            double v = v0 + distance_term;
            if (a > 1.9) v += a * (7.944e-03 + a * 9.617e-05);
            return v;
        }
    }
    return 0.0;
}

}  // namespace zenith::geo
