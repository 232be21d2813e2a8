// geo/frames.h, geoid.h and the observer's ECEF constructor.
#include "zenith/geo/frames.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/quaternion.hpp>
#include <numbers>
#include <string>

#include "zenith/base/units.h"
#include "zenith/geo/geoid.h"
#include "zenith/geo/observer.h"
#include "zenith/geo/time.h"

namespace zenith::geo {
namespace {

constexpr double kDeg = kRadiansPerDegree;

void ExpectNear(const glm::dvec3& a, const glm::dvec3& b, double tolerance) {
    EXPECT_NEAR(glm::length(a - b), 0.0, tolerance) << a.x << " " << a.y << " " << a.z;
}

TEST(Attitude, HeadingPitchRollFollowAircraftConventions) {
    // Columns: right, up, backward; ENU axes x east, y north, z up.
    glm::dmat3 m = EnuFromView({0.0, 0.0, 0.0});
    ExpectNear(-m[2], {0, 1, 0}, 1e-12);  // looking north
    ExpectNear(m[0], {1, 0, 0}, 1e-12);   // right wing east
    ExpectNear(m[1], {0, 0, 1}, 1e-12);
    m = EnuFromView({90.0 * kDeg, 0.0, 0.0});
    ExpectNear(-m[2], {1, 0, 0}, 1e-12);  // heading 090 looks east
    m = EnuFromView({0.0, 30.0 * kDeg, 0.0});
    ExpectNear(-m[2], {0, std::cos(30 * kDeg), std::sin(30 * kDeg)}, 1e-12);  // nose up
    m = EnuFromView({0.0, 0.0, 20.0 * kDeg});
    EXPECT_LT(m[0].z, 0.0);  // positive roll: right wing down
    ExpectNear(-m[2], {0, 1, 0}, 1e-12);
    // Always a rotation.
    const glm::dmat3 r = EnuFromView({1.0, -0.4, 2.5});
    EXPECT_NEAR(glm::determinant(r), 1.0, 1e-12);
    ExpectNear(glm::transpose(r) * r[0], {1, 0, 0}, 1e-12);
}

TEST(Attitude, EulerRoundTripsThroughEcefQuaternion) {
    for (double lat : {-89.0, -30.0, 0.0, 45.0, 90.0}) {
        for (double lon : {-180.0, -60.0, 0.0, 179.5}) {
            const Attitude a{1.2, -0.3, 0.7};
            const Attitude b = AttitudeFromEcefFromBody(EcefFromBody(a, lat, lon), lat, lon);
            EXPECT_NEAR(b.heading_rad, a.heading_rad, 1e-12);
            EXPECT_NEAR(b.pitch_rad, a.pitch_rad, 1e-12);
            EXPECT_NEAR(b.roll_rad, a.roll_rad, 1e-12);
        }
    }
    // Body x (forward) at heading 90, level, on the equator at lon 0 points east: ECEF +y.
    const glm::dvec3 forward =
        glm::mat3_cast(EcefFromBody({kPi / 2, 0, 0}, 0.0, 0.0)) * glm::dvec3(1, 0, 0);
    EXPECT_NEAR(forward.y, 1.0, 1e-12);
}

TEST(Attitude, ViewFromAttitudeIsTheProductOfTheFrames) {
    for (const Attitude a :
         {Attitude{0.3, 0.2, -0.9}, Attitude::FromDegrees(250.0, -80.0, 45.0), Attitude{}}) {
        const glm::dmat3 product = EnuFromNed() * NedFromBody(a) * BodyFromView();
        const glm::dmat3 direct = EnuFromView(a);
        for (int c = 0; c < 3; ++c) ExpectNear(direct[c], product[c], 1e-15);
    }
    const Attitude d = Attitude::FromDegrees(90.0, 45.0, -30.0);
    EXPECT_DOUBLE_EQ(d.heading_rad, std::numbers::pi / 2);
    EXPECT_DOUBLE_EQ(d.pitch_rad, std::numbers::pi / 4);
    EXPECT_DOUBLE_EQ(d.roll_rad, -std::numbers::pi / 6);
}

TEST(Observer, FromEcefKeepsThePositionExactly) {
    const Observer reference(47.45, 8.56, 10000.0);
    const Observer o = Observer::FromEcef(reference.ecef());
    EXPECT_EQ(o.ecef(), reference.ecef());
    EXPECT_NEAR(o.lat_deg(), 47.45, 1e-12);
    EXPECT_NEAR(o.lon_deg(), 8.56, 1e-12);
    EXPECT_NEAR(o.height_m(), 10000.0, 1e-6);
    EXPECT_THROW(Observer::FromEcef({NAN, 0.0, 0.0}), ObserverError);
    EXPECT_THROW(Observer::FromEcef({1e12, 0.0, 0.0}), ObserverError);
}

TEST(UnixTime, RoundTripsAndRejectsTheImpossible) {
    EXPECT_DOUBLE_EQ(UnixSecondsFromCivil({1970, 1, 1, 0, 0, 0.0}), 0.0);
    EXPECT_DOUBLE_EQ(UnixSecondsFromCivil({2024, 6, 22, 3, 30, 0.0}), 1719027000.0);
    const CivilTime t = CivilFromUnixSeconds(1719027000.25);
    EXPECT_EQ(t.hour, 3);
    EXPECT_EQ(t.minute, 30);
    EXPECT_DOUBLE_EQ(t.second, 0.25);
    const Time from_unix = TimeFromUnixSeconds(1719027000.25);
    EXPECT_DOUBLE_EQ(from_unix.jd_utc, TimeFromIso8601("2024-06-22T03:30:00.25Z").jd_utc);
    EXPECT_THROW(TimeFromUnixSeconds(NAN), TimeError);
    EXPECT_THROW(TimeFromUnixSeconds(1e300), TimeError);
    EXPECT_THROW(TimeFromUnixSeconds(-1e12), TimeError);
}

TEST(Geoid, Egm96GridMatchesNgaTestPoints) {
    const GeoidGrid* geoid = GeoidGrid::Default();
    if (!geoid) GTEST_SKIP() << "no geoid grid (Debian proj-data)";
    // NGA's EGM96 test values (WW15MGH.GRD interpolation, metres).
    struct Point {
        double lat, lon, n;
    };
    for (const Point& p :
         {Point{38.6281550, 269.7791550, -31.628}, Point{-14.6212170, 305.0211140, -2.969},
          Point{46.8743190, 102.4487290, -43.575}, Point{-23.6174460, 133.8747120, 15.871},
          Point{38.6254730, 359.9995000, 50.066}, Point{-0.4667440, 0.0023000, 17.329}}) {
        // Bilinear on the 15' grid versus NGA's spline: a few centimetres.
        EXPECT_NEAR(geoid->UndulationAt(p.lat, p.lon), p.n, 0.1) << p.lat << " " << p.lon;
    }
    EXPECT_NEAR(geoid->UndulationAt(90.0, 0.0), 13.6, 0.1);  // the grid's pole row
}

TEST(Geoid, BadGridFilesSayWhy) {
    EXPECT_THROW(GeoidGrid::LoadGtx("/nonexistent.gtx"), GeoidError);
    EXPECT_THROW(GeoidGrid::LoadGtx(std::string(ZENITH_SOURCE_DIR) + "/data/flights/README.md"),
                 GeoidError);
}

}  // namespace
}  // namespace zenith::geo
