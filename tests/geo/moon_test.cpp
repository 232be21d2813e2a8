// Tests of the ELP/MPP02 Moon (geo/src/moon.cpp) against published values and ERFA, and of the
// physics the series must reproduce (distance range, lunar months).
#include "zenith/geo/moon.h"

#include <erfa.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "zenith/geo/earth_orientation.h"

namespace zenith::geo {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kArcsec = kDeg / 3600.0;
constexpr double kKm = 1000.0;

// Signed difference of two longitudes in (-pi, pi].
double AngleDiff(double a, double b) { return std::remainder(a - b, 2.0 * std::numbers::pi); }

// Angle between two directions, radians.
double Separation(const glm::dvec3& a, const glm::dvec3& b) {
    return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

glm::dvec3 Cartesian(const EclipticPosition& p) {
    const double cb = std::cos(p.latitude);
    return p.distance *
           glm::dvec3(cb * std::cos(p.longitude), cb * std::sin(p.longitude), std::sin(p.latitude));
}

// Meeus, Astronomical Algorithms (2nd ed.), Example 47.a: 1992 April 12, 0h TD. Meeus evaluates
// his truncation of ELP-2000/82 (about 10" in longitude, 4" in latitude); the difference to the
// full theory sets the tolerance, not our truncation.
constexpr double kMeeusJd = 2448724.5;
constexpr double kMeeusTolerance = 10.0 * kArcsec;
constexpr double kMeeusDistanceTolerance = 5.0 * kKm;  // his distance series keeps ~0.2 km terms

TEST(MoonTest, MeeusExample47a) {
    const EclipticPosition p = MoonGeometricEcliptic(kMeeusJd);
    EXPECT_NEAR(AngleDiff(p.longitude, 133.162655 * kDeg), 0.0, kMeeusTolerance)
        << "longitude " << p.longitude / kDeg << " deg";
    EXPECT_NEAR(p.latitude, -3.229126 * kDeg, kMeeusTolerance) << p.latitude / kDeg << " deg";
    EXPECT_NEAR(p.distance, 368409.7 * kKm, kMeeusDistanceTolerance) << p.distance / kKm << " km";

    // Apparent longitude adds nutation (Meeus: +0.004610 deg) and light time (~0.7").
    const EclipticPosition a = MoonApparentEcliptic(kMeeusJd);
    EXPECT_NEAR(AngleDiff(a.longitude, 133.167265 * kDeg), 0.0, kMeeusTolerance)
        << "apparent longitude " << a.longitude / kDeg << " deg";
}

// ERFA's eraMoon98 (Meeus' ELP-2000/82 truncation, GCRS, geometric) is an independent
// implementation of a ~10" theory; this only catches gross frame or argument errors.
constexpr double kMoon98Tolerance = 30.0 * kArcsec;
// Its distance series stops at ~1 km terms; measured max difference 10.8 km (1950-2100).
constexpr double kMoon98DistanceTolerance = 15.0 * kKm;

TEST(MoonTest, AgreesWithErfaMoon98From1950To2100) {
    double max_sep = 0.0;
    double max_dr = 0.0;
    for (double jd = 2433282.5; jd <= 2488069.5; jd += 97.3) {  // 1950-2100, incommensurate step
        double pv[2][3];
        eraMoon98(jd, 0.0, pv);
        double rm[3][3];
        eraEcm06(jd, 0.0, rm);  // GCRS -> mean ecliptic and equinox of date (IAU 2006)
        double ecl[3];
        eraRxp(rm, pv[0], ecl);
        const glm::dvec3 ref(ecl[0], ecl[1], ecl[2]);
        const glm::dvec3 ours = Cartesian(MoonGeometricEcliptic(jd));
        const double sep = Separation(ours, ref);
        const double dr = std::abs(glm::length(ours) - glm::length(ref) * kAstronomicalUnit);
        max_sep = std::max(max_sep, sep);
        max_dr = std::max(max_dr, dr);
        ASSERT_LT(sep, kMoon98Tolerance) << "JD " << jd << ": " << sep / kArcsec << "\"";
        ASSERT_LT(dr, kMoon98DistanceTolerance) << "JD " << jd << ": " << dr / kKm << " km";
    }
    std::printf("eraMoon98 vs ELP/MPP02 1950-2100: max %.2f\", max %.3f km\n", max_sep / kArcsec,
                max_dr / kKm);
}

// Perigee and apogee of the Moon stay within 356,400-406,700 km (Meeus ch. 50: extremes
// 356,375 km and 406,720 km over 1500-2500); the margins are the bounds asked of the model.
TEST(MoonTest, DistanceStaysWithinPerigeeApogeeRange) {
    double min_r = 1e300;
    double max_r = 0.0;
    for (double jd = 2433282.5; jd <= 2488069.5; jd += 0.25) {
        const double r = MoonGeometricEcliptic(jd).distance;
        min_r = std::min(min_r, r);
        max_r = std::max(max_r, r);
    }
    EXPECT_GT(min_r, 356000.0 * kKm) << min_r / kKm;
    EXPECT_LT(min_r, 357000.0 * kKm) << min_r / kKm;  // closest perigees do reach ~356,400 km
    EXPECT_LT(max_r, 407000.0 * kKm) << max_r / kKm;
    EXPECT_GT(max_r, 406000.0 * kKm) << max_r / kKm;
}

// Mean sidereal month 27.321662 d and anomalistic month 27.554550 d (Explanatory Supplement,
// 3rd ed., table 15.3). Averaged over a century the series must give them to ~1e-4 d.
constexpr double kSiderealMonth = 27.321662;
constexpr double kAnomalisticMonth = 27.554550;
constexpr double kMonthTolerance = 2e-3;  // days; epoch-to-epoch jitter of perigee times / N

TEST(MoonTest, LunarMonthsOverACentury) {
    // Sidereal: count turns of the longitude referred to the fixed J2000 equinox (subtract
    // general precession ~ 1.38 deg/century, so use the mean motion of the J2000 longitude).
    const double jd0 = 2433282.5;
    const double jd1 = jd0 + 36525.0;
    double turns = 0.0;
    double prev = MoonGeometricEcliptic(jd0).longitude;
    for (double jd = jd0 + 0.5; jd <= jd1; jd += 0.5) {
        const double lon = MoonGeometricEcliptic(jd).longitude;
        turns += AngleDiff(lon, prev) / (2.0 * std::numbers::pi);
        prev = lon;
    }
    const double precession_turns = 5028.8 / (360.0 * 3600.0);  // one century
    const double period = 36525.0 / (turns - precession_turns);
    EXPECT_NEAR(period, kSiderealMonth, kMonthTolerance) << period;

    // Anomalistic: mean interval between perigees (local distance minima), sampled hourly.
    std::vector<double> perigees;
    const double step = 1.0 / 24.0;
    double r_prev2 = MoonGeometricEcliptic(jd0 - 2 * step).distance;
    double r_prev = MoonGeometricEcliptic(jd0 - step).distance;
    for (double jd = jd0; jd <= jd0 + 3652.5; jd += step) {
        const double r = MoonGeometricEcliptic(jd).distance;
        if (r_prev < r_prev2 && r_prev <= r) perigees.push_back(jd - step);
        r_prev2 = r_prev;
        r_prev = r;
    }
    ASSERT_GT(perigees.size(), 100u);
    const double anomalistic =
        (perigees.back() - perigees.front()) / static_cast<double>(perigees.size() - 1);
    EXPECT_NEAR(anomalistic, kAnomalisticMonth, 0.05) << anomalistic;  // perigee time jitters ~1 d
}

// Light time is r/c ~ 1.2-1.35 s, so the apparent position trails the geometric one by
// (Moon's angular speed ~0.55"/s) * tau ~ 0.7" in longitude, before nutation.
TEST(MoonTest, ApparentIsGeometricAtRetardedTimePlusNutation) {
    for (double jd = 2451545.0; jd < 2451545.0 + 30.0; jd += 1.7) {
        const EclipticPosition g = MoonGeometricEcliptic(jd);
        const EclipticPosition a = MoonApparentEcliptic(jd);
        const double tau = g.distance / 299792458.0;
        EXPECT_GT(tau, 1.18);
        EXPECT_LT(tau, 1.36);
        const EclipticPosition retarded = MoonGeometricEcliptic(jd - tau / 86400.0);
        const double dpsi = Nutation2000B(jd).dpsi;
        EXPECT_NEAR(AngleDiff(a.longitude, retarded.longitude + dpsi), 0.0, 1e-3 * kArcsec);
        EXPECT_NEAR(a.latitude, retarded.latitude, 1e-3 * kArcsec);
        const double lag = AngleDiff(g.longitude + dpsi, a.longitude);
        EXPECT_GT(lag, 0.4 * kArcsec);  // the Moon moves eastward
        EXPECT_LT(lag, 0.9 * kArcsec);
    }
}

// TOD position: the apparent ecliptic longitude/latitude (true equinox) rotated by the true
// obliquity must equal MoonApparentTod; checked through ERFA's IAU 2006/2000B chain.
constexpr double kTodTolerance = 0.01 * kArcsec;

TEST(MoonTest, TodMatchesApparentEclipticThroughTrueObliquity) {
    for (double jd = 2440000.5; jd < 2480000.0; jd += 3111.1) {
        const glm::dvec3 tod = MoonApparentTod(jd);
        const EclipticPosition a = MoonApparentEcliptic(jd);
        const double eps = MeanObliquity2006(jd) + Nutation2000B(jd).deps;
        const glm::dvec3 e = Cartesian(a);
        const glm::dvec3 expected(e.x, std::cos(eps) * e.y - std::sin(eps) * e.z,
                                  std::sin(eps) * e.y + std::cos(eps) * e.z);
        EXPECT_LT(Separation(tod, expected), kTodTolerance) << "JD " << jd;
        EXPECT_NEAR(glm::length(tod), a.distance, 1.0);
    }
}

}  // namespace
}  // namespace zenith::geo
