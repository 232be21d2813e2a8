// Planets: heliocentric series against ERFA's eraPlan94 (Simon et al. 1994, an independent
// planetary theory) and eraEpv00, apparent places against JPL Horizons, magnitudes against the
// test cases Mallama & Hilton published with their paper, and the laws the geometry must obey.
#include "zenith/geo/planets.h"

#include <erfa.h>
#include <erfam.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <vector>

#include "zenith/geo/angles.h"
#include "zenith/geo/ephemeris.h"
#include "zenith/geo/sun.h"

namespace zenith::geo {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kKm = 1000.0;

std::vector<double> RandomDates(int n) {
    std::mt19937_64 rng(18031950);
    std::uniform_real_distribution<double> jd(kPlanetSeriesFirstJdTt, kPlanetSeriesLastJdTt);
    std::vector<double> dates(static_cast<std::size_t>(n));
    for (double& d : dates) d = jd(rng);
    return dates;
}

glm::dvec3 FromErfa(const double v[3]) { return {v[0], v[1], v[2]}; }

// Angular separation of two (RA, Dec) pairs, radians.
double Separation(double ra1, double dec1, double ra2, double dec2) {
    const glm::dvec3 a(std::cos(dec1) * std::cos(ra1), std::cos(dec1) * std::sin(ra1),
                       std::sin(dec1));
    const glm::dvec3 b(std::cos(dec2) * std::cos(ra2), std::cos(dec2) * std::sin(ra2),
                       std::sin(dec2));
    return AngleBetween(a, b);
}

// eraPlan94's own maximum errors against DE200 over 1800-2100 (its documentation, note 5:
// L, B in arcsec, R in km). Our truncated VSOP87 is within 0.2" and 120 km of the full series,
// so the comparison can only show eraPlan94's error; a bound of hypot(L, B) + 1" and R + 10 %
// fails on any error of ours larger than the reference's.
struct Plan94Case {
    Planet planet;
    int np;
    double l_arcsec, b_arcsec, r_km;
};
constexpr Plan94Case kPlan94[] = {
    {Planet::kMercury, 1, 7, 1, 500},     {Planet::kVenus, 2, 7, 1, 1100},
    {Planet::kMars, 4, 26, 1, 9000},      {Planet::kJupiter, 5, 78, 6, 82000},
    {Planet::kSaturn, 6, 87, 14, 263000}, {Planet::kUranus, 7, 86, 7, 661000},
    {Planet::kNeptune, 8, 11, 2, 248000},
};

TEST(Planets, HeliocentricMatchesErfaPlan94WithinItsStatedAccuracy) {
    const std::vector<double> dates = RandomDates(3000);
    for (const Plan94Case& c : kPlan94) {
        double max_angle = 0.0, max_dr = 0.0;
        for (double jd : dates) {
            double pv[2][3];
            ASSERT_EQ(eraPlan94(jd, 0.0, c.np, pv), 0);
            const glm::dvec3 ref = FromErfa(pv[0]) * ERFA_DAU;
            const glm::dvec3 ours = PlanetHeliocentricGcrs(c.planet, jd);
            max_angle = std::max(max_angle, AngleBetween(ref, ours) / kArcsecToRad);
            max_dr = std::max(max_dr, std::abs(glm::length(ref) - glm::length(ours)) / kKm);
        }
        std::printf("%-8s vs eraPlan94 1950-2100: max direction %.2f\", max |dR| %.0f km\n",
                    PlanetName(c.planet).data(), max_angle, max_dr);
        EXPECT_LT(max_angle, std::hypot(c.l_arcsec, c.b_arcsec) + 1.0) << PlanetName(c.planet);
        EXPECT_LT(max_dr, 1.1 * c.r_km) << PlanetName(c.planet);
    }
}

TEST(Planets, EarthMatchesErfaEpv00) {
    // eraEpv00 is fitted to DE405 (a few km); the Sun's tests bound our Earth series through the
    // apparent Sun, this bounds the heliocentric vector the planets are referred to.
    double max_angle = 0.0, max_dr = 0.0;
    for (double jd : RandomDates(3000)) {
        double pvh[2][3], pvb[2][3];
        eraEpv00(jd, 0.0, pvh, pvb);
        const glm::dvec3 ref = FromErfa(pvh[0]) * ERFA_DAU;
        const glm::dvec3 ours = PlanetHeliocentricGcrs(Planet::kEarth, jd);
        max_angle = std::max(max_angle, AngleBetween(ref, ours) / kArcsecToRad);
        max_dr = std::max(max_dr, std::abs(glm::length(ref) - glm::length(ours)) / kKm);
    }
    std::printf("earth    vs eraEpv00 1950-2100: max direction %.3f\", max |dR| %.1f km\n",
                max_angle, max_dr);
    EXPECT_LT(max_angle, 0.1);
    EXPECT_LT(max_dr, 30.0);
}

// JPL Horizons, observer table, topocentric airless apparent RA/Dec (true equator and equinox
// of date) and azimuth/elevation, 2020-03-14 16:43:22 UT, site 38.2463888888 N, 85.763611111
// W, 0 m (Louisville, Kentucky), degrees to 1e-9 (RA/Dec) and 1e-4 (az/el); as quoted in a
// public JavaScript ephemeris test. DUT1 was about -0.2 s then (IERS Bulletin A); az/el use it.
struct HorizonsCase {
    Planet planet;
    double ra_deg, dec_deg, az_deg, el_deg;
};
constexpr HorizonsCase kHorizons20200314[] = {
    {Planet::kMercury, 331.173632891, -11.329384129, 188.5413, 40.0342},
    {Planet::kVenus, 37.141793123, 17.020722349, 95.0213, 34.3682},
    {Planet::kMars, 290.450914110, -22.756951643, 224.5099, 14.5311},
    {Planet::kJupiter, 293.681748056, -21.684335302, 222.6401, 17.1504},
    {Planet::kSaturn, 301.571483161, -20.309971390, 216.8290, 22.2722},
    {Planet::kUranus, 32.185296307, 12.515877311, 102.9224, 35.5201},
    {Planet::kNeptune, 349.945528234, -5.433416185, 162.8510, 44.8948},
};
// The issue's bound is 30"; the measured errors are printed and are ~100x smaller, so the test
// asserts 2" (and 3" in az/el, given Horizons' 1e-4 deg rounding and the DUT1 estimate).
constexpr double kHorizonsRaDecTolerance = 2.0;  // arcsec
constexpr double kHorizonsAzElTolerance = 3.0;   // arcsec

TEST(Planets, TopocentricMatchesJplHorizons) {
    TimeOptions options;
    options.dut1_s = -0.2;
    const Time t = TimeFromUtc({2020, 3, 14, 16, 43, 22.0}, options);
    const Observer louisville(38.2463888888, -85.763611111111, 0.0);
    const std::vector<PlanetPosition> planets = PlanetsTopocentric(t, louisville);
    ASSERT_EQ(planets.size(), kSkyPlanets.size());
    for (const HorizonsCase& c : kHorizons20200314) {
        const auto it = std::find_if(planets.begin(), planets.end(),
                                     [&](const PlanetPosition& p) { return p.planet == c.planet; });
        ASSERT_NE(it, planets.end());
        const Topocentric& topo = it->topocentric;
        const double radec =
            Separation(topo.right_ascension, topo.declination, c.ra_deg * kDeg, c.dec_deg * kDeg) /
            kArcsecToRad;
        const double azel = Separation(topo.horizontal.azimuth, topo.horizontal.elevation,
                                       c.az_deg * kDeg, c.el_deg * kDeg) /
                            kArcsecToRad;
        std::printf("%-8s vs Horizons 2020-03-14: RA/Dec %.2f\", az/el %.2f\"\n",
                    PlanetName(c.planet).data(), radec, azel);
        EXPECT_LT(radec, kHorizonsRaDecTolerance) << PlanetName(c.planet);
        EXPECT_LT(azel, kHorizonsAzElTolerance) << PlanetName(c.planet);
    }
}

TEST(Planets, GeocentricSaturnMatchesJplHorizons) {
    // Horizons, geocentric airless apparent RA/Dec of Saturn, 2015-08-10 17:09:00 UT:
    // 236.54879, -17.89171 deg (quantities 1,2; as quoted in a public ephemeris test).
    const Time t = TimeFromUtc({2015, 8, 10, 17, 9, 0.0});
    const auto saturn = PlanetGeocentric(Planet::kSaturn, t.jd_tt);
    ASSERT_TRUE(saturn.has_value());
    const double error = Separation(saturn->right_ascension, saturn->declination, 236.54879 * kDeg,
                                    -17.89171 * kDeg) /
                         kArcsecToRad;
    std::printf("saturn   vs Horizons 2015-08-10 geocentric: %.2f\"\n", error);
    EXPECT_LT(error, kHorizonsRaDecTolerance);
}

TEST(Planets, JupiterOppositionMatchesJplHorizonsDistancesAndMagnitude) {
    // Horizons (jup341/DE431), geocentric, 2010-09-20 00:00 UT, near opposition: APmag -2.94,
    // r = 4.957786140014 au, delta = 3.95404849923145 au, phase angle 0.4689 deg.
    const Time t = TimeFromUtc({2010, 9, 20, 0, 0, 0.0});
    const auto jupiter = PlanetGeocentric(Planet::kJupiter, t.jd_tt);
    ASSERT_TRUE(jupiter.has_value());
    EXPECT_NEAR(jupiter->heliocentric_distance_au, 4.957786140014, 2e-6);
    EXPECT_NEAR(jupiter->distance_au, 3.95404849923145, 2e-6);
    // Horizons' S-T-O differs by 0.006 deg: near opposition the phase angle turns with the
    // ~20" aberration of the Earth-Jupiter direction, which its S-T-O includes and ours (the
    // geometric angle at emission, as Mallama & Hilton use) does not.
    EXPECT_NEAR(jupiter->phase_angle / kDeg, 0.4689, 0.01);
    EXPECT_NEAR(jupiter->magnitude_v, -2.94, 0.01);
}

// JPL Horizons (DE431), geocentric observer tables at 0h UT, 2010, as published in the
// cosinekitty/astronomy repository (generate/magnitude/<Planet>.txt, made 2019-04-28): the
// Sun-planet distance r at emission and the light-time-corrected range delta, au. These check
// the radial components, which the direction tests above do not see.
struct HorizonsDistanceCase {
    Planet planet;
    int month, day;
    double r_au, delta_au;
};
constexpr HorizonsDistanceCase kHorizonsDistances2010[] = {
    {Planet::kMercury, 3, 14, 0.366087123860, 1.35862674041650},
    {Planet::kMercury, 9, 20, 0.308144773413, 0.95311193942450},
    {Planet::kVenus, 1, 1, 0.727242589828, 1.70809470731038},
    {Planet::kVenus, 9, 20, 0.727894618724, 0.44809966058075},
    {Planet::kMars, 1, 29, 1.647718187727, 0.66414061396079},
    {Planet::kMars, 7, 2, 1.624365008979, 1.79987414003546},
    {Planet::kJupiter, 1, 1, 5.003380951875, 5.63740758870295},
    {Planet::kJupiter, 9, 20, 4.957786140014, 3.95404849923145},
    {Planet::kSaturn, 3, 22, 9.499204242042, 8.50380411718196},
    {Planet::kSaturn, 7, 2, 9.530004313909, 9.67743224983369},
    {Planet::kUranus, 3, 18, 20.09582428682, 21.0908706922235},
    {Planet::kUranus, 9, 20, 20.09212801278, 19.0882755777358},
    {Planet::kNeptune, 2, 14, 30.02326419043, 31.0106018619227},
    {Planet::kNeptune, 8, 19, 30.01792857067, 29.0061493790726},
};

TEST(Planets, DistancesMatchJplHorizons) {
    // Measured: < 50 km for Mercury to Mars, < 200 km for Jupiter, < 800 km for Saturn, and
    // +6000 km (Uranus) and -8400 km (Neptune) at both dates. Those last are systematic
    // offsets of the VSOP87 series (as kstars-data ships them) from DE431, not our truncation
    // (< 120 km, measured in the .inc headers); VSOP87 was fitted to DE200, and the outer
    // planets' orbits have been refined since. At 20-30 au they change the magnitude by < 1e-3
    // mag and a direction hardly at all; the bounds below are the measured differences with
    // margin, so a regression shows.
    const auto bound_km = [](Planet planet) {
        switch (planet) {
            case Planet::kJupiter:
                return 400.0;
            case Planet::kSaturn:
                return 1500.0;
            case Planet::kUranus:
            case Planet::kNeptune:
                return 12000.0;
            default:
                return 100.0;
        }
    };
    for (const HorizonsDistanceCase& c : kHorizonsDistances2010) {
        const Time t = TimeFromUtc({2010, c.month, c.day, 0, 0, 0.0});
        const auto p = PlanetGeocentric(c.planet, t.jd_tt);
        ASSERT_TRUE(p.has_value());
        const double dr_km = (p->heliocentric_distance_au - c.r_au) * kAstronomicalUnit / kKm;
        const double dd_km = (p->distance_au - c.delta_au) * kAstronomicalUnit / kKm;
        std::printf("%-8s 2010-%02d-%02d vs Horizons: dr %+8.1f km, ddelta %+8.1f km\n",
                    PlanetName(c.planet).data(), c.month, c.day, dr_km, dd_km);
        const double tolerance_au = bound_km(c.planet) * kKm / kAstronomicalUnit;
        EXPECT_NEAR(p->heliocentric_distance_au, c.r_au, tolerance_au) << PlanetName(c.planet);
        EXPECT_NEAR(p->distance_au, c.delta_au, tolerance_au) << PlanetName(c.planet);
    }
}

// Mallama & Hilton 2018, test cases of their Ap_Mag program (Ap_Mag_Output_V3.txt): r, delta
// (au), phase angle (deg), and the magnitude they computed, rounded to 0.001.
struct MagnitudeCase {
    Planet planet;
    double r_au, delta_au, phase_deg, expected;
    PlanetMagnitudeAspect aspect;
};

PlanetMagnitudeAspect Latitudes(double sun, double earth) {
    PlanetMagnitudeAspect a;
    a.sub_sun_latitude_deg = sun;
    a.sub_earth_latitude_deg = earth;
    return a;
}
PlanetMagnitudeAspect MarsAngles(double sub_earth, double sub_sun, double helio_longitude) {
    PlanetMagnitudeAspect a;
    a.mars_sub_earth_longitude_deg = sub_earth;
    a.mars_sub_sun_longitude_deg = sub_sun;
    a.mars_heliocentric_longitude_deg = helio_longitude;
    return a;
}
PlanetMagnitudeAspect Year(double year) {
    PlanetMagnitudeAspect a;
    a.year = year;
    return a;
}

const MagnitudeCase kMallamaHilton[] = {
    {Planet::kMercury, 0.310295423552, 1.32182643625754, 1.1677, -2.477, {}},
    {Planet::kMercury, 0.413629222334, 0.92644808718613, 90.1662, 0.181, {}},
    {Planet::kMercury, 0.448947624811, 0.56004973217883, 178.7284, 7.167, {}},
    {Planet::kVenus, 0.722722540169, 1.71607489554051, 1.3232, -3.917, {}},
    {Planet::kVenus, 0.721480714554, 0.37762511206278, 124.1348, -4.916, {}},
    {Planet::kVenus, 0.726166592736, 0.28889582420642, 179.1845, -3.090, {}},
    {Planet::kEarth, 0.983331936476, 1.41317594650699, 8.7897, -3.269, {}},
    {Planet::kEarth, 0.983356079811, 0.26526856764726, 4.1369, -6.909, {}},
    {Planet::kEarth, 0.983356467727, 0.62933287342927, 175.6869, 1.122, {}},
    {Planet::kMars, 1.381191244505, 0.37274381097911, 4.8948, -2.862,
     MarsAngles(329.27, 330.76, 334.4996)},
    {Planet::kMars, 1.664150453905, 2.58995164518460, 11.5877, 1.788,
     MarsAngles(76.84, 64.66, 147.3485)},
    {Planet::kMars, 1.591952180003, 3.85882552272013, 167.9000, 8.977,
     MarsAngles(29.50, 221.11, 212.8886)},
    {Planet::kJupiter, 5.446231815414, 6.44985867459088, 0.2446, -1.667, {}},
    {Planet::kJupiter, 4.957681473205, 3.95393078136013, 0.3431, -2.934, {}},
    {Planet::kJupiter, 5.227587855371, 5.23501920009381, 147.0989, 0.790, {}},
    {Planet::kSaturn, 9.014989659493, 8.03160470546889, 0.1055, -0.552, Latitudes(26.279, 26.279)},
    {Planet::kUranus, 18.321003215845, 17.3229728525108, 0.0410, 5.381, Latitudes(-20.29, -20.28)},
    {Planet::kUranus, 20.096361095266, 21.0888470145276, 0.0568, 6.025, Latitudes(1.02, 0.97)},
    {Planet::kUranus, 19.38003071775, 11.1884243801383, 161.7728, 8.318, Latitudes(-71.16, 55.11)},
    {Planet::kNeptune, 30.322109867761, 31.3091610098214, 0.0549, 7.997, Year(1970.9)},
    {Planet::kNeptune, 30.207767693725, 29.8172370857530, 1.7741, 7.827, Year(1990.32)},
    {Planet::kNeptune, 30.028181709541, 29.0158521665744, 0.0381, 7.701, Year(2009.63)},
};

TEST(Planets, MagnitudesMatchMallamaHiltonTestCases) {
    // Their values are rounded to 0.001, so 0.0006 is the tightest honest bound. Mars's tables
    // are interpolated here with Stirling's formula written from the textbook (their Fortran
    // leaves one difference of its table uninitialised), and still agree to 0.0005.
    constexpr double kTolerance = 0.0006;
    for (const MagnitudeCase& c : kMallamaHilton) {
        const double v = PlanetMagnitudeV(c.planet, c.r_au, c.delta_au, c.phase_deg, c.aspect);
        std::printf("%-8s alpha %8.4f: %7.3f (Mallama & Hilton %7.3f, diff %+.4f)\n",
                    PlanetName(c.planet).data(), c.phase_deg, v, c.expected, v - c.expected);
        EXPECT_NEAR(v, c.expected, kTolerance) << PlanetName(c.planet) << " " << c.phase_deg;
    }
}

// The same test cases end to end: Mallama & Hilton took r, delta and the phase angle from JPL
// Horizons at 0h UT on these dates, so our whole chain (positions, light time, phase angle,
// Saturn's ring tilt from the IAU pole, Mars's central meridian and Ls from the IAU rotation
// model, Neptune's epoch) must land on their magnitudes. Measured: all within 0.001 mag, the
// transits of Mercury (2003-05-07, phase 178.7 deg) and Venus (2004-06-08, 179.2 deg)
// included.
struct DatedMagnitudeCase {
    Planet planet;
    int year, month, day;
    double expected;
};
constexpr DatedMagnitudeCase kMallamaHiltonDates[] = {
    {Planet::kMercury, 2006, 5, 19, -2.477}, {Planet::kMercury, 2006, 6, 15, 0.181},
    {Planet::kMercury, 2003, 5, 7, 7.167},   {Planet::kVenus, 2006, 10, 28, -3.917},
    {Planet::kVenus, 2005, 12, 14, -4.916},  {Planet::kVenus, 2004, 6, 8, -3.090},
    {Planet::kMars, 2003, 8, 28, -2.862},    {Planet::kMars, 2004, 7, 19, 1.788},
    {Planet::kJupiter, 2004, 9, 21, -1.667}, {Planet::kJupiter, 2010, 9, 21, -2.934},
    {Planet::kSaturn, 2032, 12, 25, -0.552}, {Planet::kUranus, 1970, 3, 28, 5.381},
    {Planet::kUranus, 2008, 3, 8, 6.025},    {Planet::kNeptune, 1970, 11, 23, 7.997},
    {Planet::kNeptune, 1990, 4, 27, 7.827},  {Planet::kNeptune, 2009, 8, 17, 7.701},
};

TEST(Planets, MagnitudesEndToEndMatchMallamaHiltonAtTheirDates) {
    constexpr double kTolerance = 0.002;  // their rounding (0.0005) plus our geometry
    for (const DatedMagnitudeCase& c : kMallamaHiltonDates) {
        const Time t = TimeFromUtc({c.year, c.month, c.day, 0, 0, 0.0});
        const auto p = PlanetGeocentric(c.planet, t.jd_tt);
        ASSERT_TRUE(p.has_value());
        std::printf("%-8s %d-%02d-%02d: V %7.3f (Mallama & Hilton %7.3f, diff %+.4f)\n",
                    PlanetName(c.planet).data(), c.year, c.month, c.day, p->magnitude_v, c.expected,
                    p->magnitude_v - c.expected);
        EXPECT_NEAR(p->magnitude_v, c.expected, kTolerance)
            << PlanetName(c.planet) << " " << c.year << "-" << c.month << "-" << c.day;
    }
}

TEST(Planets, VenusGreatestBrilliancyAndJupiterOppositions) {
    // Venus at greatest brilliancy reaches about -4.6 to -4.9 (Mallama & Hilton's Table 1:
    // brightest -4.92); Jupiter at opposition from about -2.2 (aphelion) to -2.94 (perihelion);
    // 2000-2012 spans the 2005 aphelion (-2.5) and the 2010 perihelion.
    double venus_min = 10.0, venus_max = -10.0;
    for (double jd = 2458849.5; jd < 2458849.5 + 8 * 365.25; jd += 1.0) {  // 2020-2027
        const double v = PlanetGeocentric(Planet::kVenus, jd)->magnitude_v;
        venus_min = std::min(venus_min, v);
        venus_max = std::max(venus_max, v);
    }
    std::printf("venus 2020-2027: brightest %.2f, faintest %.2f\n", venus_min, venus_max);
    EXPECT_LT(venus_min, -4.6);
    EXPECT_GT(venus_min, -4.95);

    double jupiter_min = 10.0, jupiter_max_at_opposition = -10.0;
    // Magnitude at each opposition (the minimum of each 399-day synodic period), 2000-2012.
    for (int k = 0; k < 12; ++k) {
        double best = 10.0;
        for (double jd = 2451545.0 + k * 398.88; jd < 2451545.0 + (k + 1) * 398.88; jd += 1.0) {
            best = std::min(best, PlanetGeocentric(Planet::kJupiter, jd)->magnitude_v);
        }
        jupiter_min = std::min(jupiter_min, best);
        jupiter_max_at_opposition = std::max(jupiter_max_at_opposition, best);
    }
    std::printf("jupiter oppositions 2000-2012: %.2f .. %.2f\n", jupiter_min,
                jupiter_max_at_opposition);
    EXPECT_NEAR(jupiter_min, -2.94, 0.03);
    EXPECT_GT(jupiter_max_at_opposition, -2.5);
    EXPECT_LT(jupiter_max_at_opposition, -2.1);
}

TEST(Planets, GeometryObeysOrbits) {
    // Inferior planets never stray farther from the Sun than their greatest elongation; the
    // superior planets' phase angles stay below asin(1 au / r_min); illuminated fraction and
    // phase angle agree; magnitudes and diameters are finite and in their known ranges.
    double mercury_elong = 0.0, venus_elong = 0.0, jupiter_phase = 0.0, saturn_phase = 0.0;
    for (double jd : RandomDates(2000)) {
        for (Planet planet : kSkyPlanets) {
            const auto p = PlanetGeocentric(planet, jd);
            ASSERT_TRUE(p.has_value());
            EXPECT_NEAR(p->illuminated_fraction, 0.5 * (1.0 + std::cos(p->phase_angle)), 1e-12);
            EXPECT_TRUE(std::isfinite(p->magnitude_v)) << PlanetName(planet) << " " << jd;
            EXPECT_GT(p->angular_diameter_arcsec, 2.0);
            EXPECT_LT(p->angular_diameter_arcsec, 67.0);
            if (planet == Planet::kMercury) mercury_elong = std::max(mercury_elong, p->elongation);
            if (planet == Planet::kVenus) venus_elong = std::max(venus_elong, p->elongation);
            if (planet == Planet::kJupiter) jupiter_phase = std::max(jupiter_phase, p->phase_angle);
            if (planet == Planet::kSaturn) saturn_phase = std::max(saturn_phase, p->phase_angle);
        }
    }
    EXPECT_LT(mercury_elong / kDeg, 28.4);
    EXPECT_GT(mercury_elong / kDeg, 25.0);
    EXPECT_LT(venus_elong / kDeg, 47.9);
    EXPECT_GT(venus_elong / kDeg, 45.0);
    EXPECT_LT(jupiter_phase / kDeg, 12.0);
    EXPECT_LT(saturn_phase / kDeg, 6.5);
}

TEST(Planets, LightTimeIsSelfConsistent) {
    // The emitted position at t - delta/c must be the one the light-time step chose: compare
    // with a brute-force fixed-point iteration on the full heliocentric series (1e-9 au is
    // 150 m; the coarse-series shortcut in planets.cpp is measured at < 50 m).
    for (double jd : RandomDates(500)) {
        const glm::dvec3 earth = PlanetHeliocentricGcrs(Planet::kEarth, jd);
        for (Planet planet : kSkyPlanets) {
            double tau = 0.0;
            for (int i = 0; i < 6; ++i) {
                tau = glm::length(PlanetHeliocentricGcrs(planet, jd - tau) - earth) / 299792458.0 /
                      86400.0;
            }
            const double delta_au = tau * 299792458.0 * 86400.0 / kAstronomicalUnit;
            EXPECT_NEAR(PlanetGeocentric(planet, jd)->distance_au, delta_au, 1e-9)
                << PlanetName(planet);
        }
    }
}

TEST(Planets, OutsideTheSeriesWindowThereIsNoPosition) {
    EXPECT_FALSE(PlanetGeocentric(Planet::kMars, kPlanetSeriesFirstJdTt - 1.0).has_value());
    EXPECT_FALSE(PlanetGeocentric(Planet::kMars, kPlanetSeriesLastJdTt + 1.0).has_value());
    EXPECT_FALSE(PlanetGeocentric(Planet::kEarth, kJ2000).has_value());
    const Observer observer(47.26, 11.35, 3000.0);
    EXPECT_TRUE(PlanetsTopocentric(TimeFromUtc({2150, 1, 1, 0, 0, 0.0}), observer).empty());
}

TEST(Planets, SkyEphemerisCarriesThePlanets) {
    const Observer observer(47.26, 11.35, 3000.0);
    const Time t = TimeFromUtc({2024, 4, 8, 18, 18, 0.0});
    const Ephemeris ephemeris;
    const SkyEphemeris with = ephemeris.Compute(t, observer);
    ASSERT_EQ(with.planets.size(), kSkyPlanets.size());
    const std::vector<PlanetPosition> direct = PlanetsTopocentric(t, observer);
    for (std::size_t i = 0; i < direct.size(); ++i) {
        EXPECT_EQ(with.planets[i].planet, kSkyPlanets[i]);
        EXPECT_EQ(with.planets[i].elevation, direct[i].elevation);
        EXPECT_EQ(with.planets[i].magnitude_v, direct[i].magnitude_v);
    }
    EphemerisOptions refracted;
    refracted.refraction = RefractionOptions{};
    const SkyEphemeris r = ephemeris.Compute(t, observer, refracted);
    for (std::size_t i = 0; i < direct.size(); ++i) {
        EXPECT_GE(r.planets[i].elevation, direct[i].elevation);
    }
    EphemerisOptions off;
    off.planets = false;
    EXPECT_TRUE(ephemeris.Compute(t, observer, off).planets.empty());
}

}  // namespace
}  // namespace zenith::geo
