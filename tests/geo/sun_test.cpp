// The Sun's apparent place against Meeus's worked example and against an independent chain built
// from ERFA: eraEpv00 (Earth ephemeris fitted to JPL DE405, a few km), light time, eraAb
// (relativistic aberration with the barycentric velocity), eraPnm06a (IAU 2006/2000A).
#include "zenith/geo/sun.h"

#include <erfa.h>
#include <erfam.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include "zenith/geo/angles.h"
#include "zenith/geo/earth_orientation.h"

namespace zenith::geo {
namespace {

constexpr double kJd1950 = 2433282.5;  // 1950-01-01 0h
constexpr double kJd2100 = 2488069.5;  // 2100-01-01 0h
constexpr double kAuPerDayToMps = ERFA_DAU / ERFA_DAYSEC;

double Dms(double deg, double min, double sec) {
    const double sign = std::signbit(deg) ? -1.0 : 1.0;
    return sign * (std::abs(deg) + min / 60 + sec / 3600) * std::numbers::pi / 180;
}
double Hms(double h, double min, double sec) {
    return (h + min / 60 + sec / 3600) * std::numbers::pi / 12;
}

glm::dvec3 FromErfa(const double v[3]) { return {v[0], v[1], v[2]}; }

std::vector<double> RandomDates(int n) {
    std::mt19937_64 rng(19921013);
    std::uniform_real_distribution<double> jd(kJd1950, kJd2100);
    std::vector<double> dates(static_cast<std::size_t>(n));
    for (double& d : dates) d = jd(rng);
    return dates;
}

// Geocentric apparent direction of the Sun in TOD from ERFA, unit vector. TDB is taken as TT
// (they differ by < 2 ms, in which the Sun moves 1e-4").
glm::dvec3 ErfaSunApparentTod(double jd_tt) {
    double pvh[2][3], pvb[2][3];
    eraEpv00(jd_tt, 0.0, pvh, pvb);
    const glm::dvec3 earth_bary = FromErfa(pvb[0]);
    const glm::dvec3 sun_bary = earth_bary - FromErfa(pvh[0]);
    const glm::dvec3 sun_bary_velocity = FromErfa(pvb[1]) - FromErfa(pvh[1]);
    // Light time: the Sun where it was when the light left it (~ 8.3 min, ~ 6 km of solar motion).
    const double light_time_days = glm::length(sun_bary - earth_bary) * ERFA_AULT / ERFA_DAYSEC;
    const glm::dvec3 geometric = sun_bary - light_time_days * sun_bary_velocity - earth_bary;
    const double distance_au = glm::length(geometric);
    double pnat[3] = {geometric.x / distance_au, geometric.y / distance_au,
                      geometric.z / distance_au};
    double v[3];
    for (int i = 0; i < 3; ++i) v[i] = pvb[1][i] * ERFA_AULT / ERFA_DAYSEC;  // units of c
    const double bm1 = std::sqrt(1.0 - (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]));
    double apparent_gcrs[3], apparent_tod[3], rnpb[3][3];
    eraAb(pnat, v, distance_au, bm1, apparent_gcrs);
    eraPnm06a(jd_tt, 0.0, rnpb);
    eraRxp(rnpb, apparent_gcrs, apparent_tod);
    return FromErfa(apparent_tod);
}

// Meeus, Astronomical Algorithms (2nd ed.), Example 25.b, 1992-10-13 0h TD. The apparent
// alpha/delta and R are the values Meeus gives from the complete VSOP87 (the ones the example
// computes with the abridged Appendix III series are 13h13m30.763s, -7d47'01.94"; the full
// series is also reproduced by the MIT-licensed soniakeys/meeus library, solar.
// ApparentEquatorialVSOP87). R is from the full series, 0.99760852 au by direct summation.
constexpr double kJd19921013 = 2448908.5;

// Meeus uses IAU 1980 nutation and the Lieske obliquity, 0.042" above IAU 2006 (shifting delta by
// up to 0.04" sin(lambda) ~ 0.015" here); our series truncation is < 0.016" and 2000B vs 1980
// nutation < 0.01". 0.1" (0.0067 s of RA) bounds the sum with margin.
constexpr double kMeeusAngleTolerance = 0.1 * kArcsecToRad;
constexpr double kMeeusDistanceToleranceAu = 1e-7;  // truncation of R is < 7.1e-8 au (inc header)

TEST(Sun, ApparentRaDecMatchesMeeusExample25b) {
    const glm::dvec3 sun = SunApparentTod(kJd19921013);
    const double ra = std::atan2(sun.y, sun.x) + 2.0 * std::numbers::pi;
    const double dec = std::asin(sun.z / glm::length(sun));
    EXPECT_NEAR(ra * std::cos(dec), Hms(13, 13, 30.749) * std::cos(dec), kMeeusAngleTolerance);
    EXPECT_NEAR(dec, Dms(-7, 47, 1.74), kMeeusAngleTolerance);
    EXPECT_NEAR(glm::length(sun) / kAstronomicalUnit, 0.99760853, kMeeusDistanceToleranceAu);
}

TEST(Sun, ApparentEclipticMatchesMeeusExample25b) {
    // Meeus's longitude 199d54'21.818" and latitude +0.72" come from the abridged series of his
    // Appendix III, which he states is good to ~ 1"; the full-series alpha/delta above are the
    // tight check, this one guards units and signs of the ecliptic output.
    constexpr double kAbridgedTolerance = 1.0 * kArcsecToRad;
    const EclipticPosition sun = SunApparentEcliptic(kJd19921013);
    EXPECT_NEAR(sun.longitude, Dms(199, 54, 21.818), kAbridgedTolerance);
    EXPECT_NEAR(sun.latitude, 0.72 * kArcsecToRad, kAbridgedTolerance);
    EXPECT_NEAR(sun.distance / kAstronomicalUnit, 0.99760853, kMeeusDistanceToleranceAu);
}

TEST(Sun, ApparentEclipticAndTodAgree) {
    // Same apparent place through the two outputs: TOD = R1(-true obliquity) (ecliptic, true
    // equinox). Only rounding separates them.
    for (double jd : RandomDates(100)) {
        const EclipticPosition e = SunApparentEcliptic(jd);
        const double eps = MeanObliquity2006(jd) + Nutation2000B(jd).deps;
        const glm::dvec3 ecl(std::cos(e.latitude) * std::cos(e.longitude),
                             std::cos(e.latitude) * std::sin(e.longitude), std::sin(e.latitude));
        const glm::dvec3 equ(ecl.x, ecl.y * std::cos(eps) - ecl.z * std::sin(eps),
                             ecl.y * std::sin(eps) + ecl.z * std::cos(eps));
        const glm::dvec3 tod = SunApparentTod(jd);
        EXPECT_LT(AngleBetween(equ, tod), 1e-6 * kArcsecToRad) << jd;
        EXPECT_NEAR(glm::length(tod), e.distance, 1e-3);
    }
}

// Requirement: the apparent Sun within 5" of the reference over 1950-2100. The tighter bound is
// what we measured (max 0.075", RMS 0.046" over these 2000 instants) with margin, so a regression
// shows long before the requirement is broken. Contributions: VSOP87 truncation (< 0.016"), VSOP87
// (DE200-based) vs DE405 frame and theory (~ 0.02"), the Meeus FK5 correction, 2000B vs 2000A (< 1
// mas), aberration from -20.4898"/R (heliocentric, ~ 0.01").
constexpr double kSunRequirement = 5.0 * kArcsecToRad;
constexpr double kSunMeasuredBound = 0.1 * kArcsecToRad;
constexpr int kSunSamples = 2000;

TEST(Sun, ApparentTodAgreesWithErfaChain) {
    double worst = 0.0, sum_sq = 0.0, worst_jd = 0.0;
    for (double jd : RandomDates(kSunSamples)) {
        const double err = AngleBetween(SunApparentTod(jd), ErfaSunApparentTod(jd));
        sum_sq += err * err;
        if (err > worst) {
            worst = err;
            worst_jd = jd;
        }
    }
    const double rms = std::sqrt(sum_sq / kSunSamples);
    std::cout << "SunApparentTod vs ERFA (" << kSunSamples << " instants 1950-2100): max "
              << worst / kArcsecToRad << "\" at JD " << worst_jd << ", RMS " << rms / kArcsecToRad
              << "\"\n";
    RecordProperty("max_arcsec", std::to_string(worst / kArcsecToRad));
    RecordProperty("rms_arcsec", std::to_string(rms / kArcsecToRad));
    EXPECT_LT(worst, kSunRequirement);
    EXPECT_LT(worst, kSunMeasuredBound);
}

TEST(Sun, HeliocentricEarthAgreesWithErfaEpv00) {
    // Geometric position, no aberration: ours (ecliptic of date) taken to TOD, ERFA's (ICRS) by
    // eraPnm06a. The geometric position has no FK5 correction, so the VSOP87 frame offset shows
    // (measured 0.092" max); distance to the series truncation (10.6 km) plus eraEpv00's few km.
    constexpr double kDirectionTolerance = 0.15 * kArcsecToRad;
    constexpr double kDistanceTolerance = 20e3;  // m
    double worst_dir = 0.0, worst_dist = 0.0;
    for (double jd : RandomDates(kSunSamples)) {
        const EclipticPosition e = EarthHeliocentricVsop87(jd);
        const glm::dvec3 ours =
            TodFromEclipticOfDate(jd) *
            (e.distance * glm::dvec3(std::cos(e.latitude) * std::cos(e.longitude),
                                     std::cos(e.latitude) * std::sin(e.longitude),
                                     std::sin(e.latitude)));
        double pvh[2][3], pvb[2][3], rnpb[3][3], tod[3];
        eraEpv00(jd, 0.0, pvh, pvb);
        eraPnm06a(jd, 0.0, rnpb);
        eraRxp(rnpb, pvh[0], tod);
        const glm::dvec3 theirs = FromErfa(tod) * ERFA_DAU;
        worst_dir = std::max(worst_dir, AngleBetween(ours, theirs));
        worst_dist = std::max(worst_dist, std::abs(glm::length(ours) - glm::length(theirs)));
    }
    std::cout << "EarthHeliocentricVsop87 vs eraEpv00: max direction " << worst_dir / kArcsecToRad
              << "\", max distance " << worst_dist / 1e3 << " km\n";
    EXPECT_LT(worst_dir, kDirectionTolerance);
    EXPECT_LT(worst_dist, kDistanceTolerance);
}

TEST(Sun, EarthVelocityAgreesWithErfaEpv00) {
    // Heliocentric velocity: same physical quantity, so tight (1.2e-6 measured). Barycentric
    // velocity is what stellar aberration wants; the Sun's own motion about the barycentre
    // (~ 13 m/s of 30 km/s) keeps the heliocentric value within the 0.1 % the use needs.
    constexpr double kHeliocentricRelTolerance = 1e-5;
    constexpr double kBarycentricRelTolerance = 1e-3;
    double worst_helio = 0.0, worst_bary = 0.0;
    for (double jd : RandomDates(kSunSamples)) {
        double pvh[2][3], pvb[2][3];
        eraEpv00(jd, 0.0, pvh, pvb);
        const glm::dvec3 ours = EarthVelocityGcrs(jd);
        const glm::dvec3 helio = FromErfa(pvh[1]) * kAuPerDayToMps;
        const glm::dvec3 bary = FromErfa(pvb[1]) * kAuPerDayToMps;
        worst_helio = std::max(worst_helio, glm::length(ours - helio) / glm::length(helio));
        worst_bary = std::max(worst_bary, glm::length(ours - bary) / glm::length(bary));
    }
    std::cout << "EarthVelocityGcrs vs eraEpv00: max relative error heliocentric " << worst_helio
              << ", barycentric " << worst_bary << "\n";
    EXPECT_LT(worst_helio, kHeliocentricRelTolerance);
    EXPECT_LT(worst_bary, kBarycentricRelTolerance);
}

TEST(Sun, OutputsAreInRange) {
    // Physical bounds: perihelion/aphelion 0.9833/1.0167 au, |beta| < 2" for the Sun, |dec| <=
    // true obliquity, longitude in [0, 2 pi).
    for (double jd : RandomDates(500)) {
        const EclipticPosition e = SunApparentEcliptic(jd);
        EXPECT_GE(e.longitude, 0.0);
        EXPECT_LT(e.longitude, 2.0 * std::numbers::pi);
        EXPECT_LT(std::abs(e.latitude), 2.0 * kArcsecToRad);
        EXPECT_GT(e.distance / kAstronomicalUnit, 0.983);
        EXPECT_LT(e.distance / kAstronomicalUnit, 1.017);
        const glm::dvec3 tod = SunApparentTod(jd);
        EXPECT_LE(std::abs(std::asin(tod.z / glm::length(tod))),
                  MeanObliquity2006(jd) + Nutation2000B(jd).deps + 2.0 * kArcsecToRad);
    }
}

// Low-level math: finite Julian dates expected (validated in time.h); NaN propagates.
TEST(Sun, NanInputPropagates) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    EXPECT_TRUE(std::isnan(EarthHeliocentricVsop87(nan).longitude));
    EXPECT_TRUE(std::isnan(SunApparentEcliptic(nan).longitude));
    EXPECT_TRUE(std::isnan(SunApparentTod(nan).x));
    EXPECT_TRUE(std::isnan(EarthVelocityGcrs(nan).x));
}

}  // namespace
}  // namespace zenith::geo
