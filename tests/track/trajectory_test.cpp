// Trajectory: attitude derivation against analytic flight (coordinated turn, straight climb),
// interpolation (exact at samples, smooth between, across 180 deg, over a pole, gaps), altitude
// kinds and the geoid.
#include "zenith/track/trajectory.h"

#include <gtest/gtest.h>

#include <GeographicLib/Geocentric.hpp>
#include <GeographicLib/LocalCartesian.hpp>
#include <cmath>
#include <numbers>
#include <optional>

namespace zenith::track {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kRadPerDeg = kPi / 180.0;
constexpr double kT0 = 1719025200.0;  // 2024-06-22T03:00:00Z
// Derived angles from exact input: what is left is the flat-plane approximation of the
// horizontal circle over a few hundred metres (~1e-5 rad).
constexpr double kAngleTolerance = 0.01 * kRadPerDeg;

TrajectoryOptions Options(std::optional<AltitudeKind> altitude, double max_gap_s = 120.0,
                          double half_window_s = 1.0, bool ignore_geoid = false) {
    TrajectoryOptions o;
    o.altitude = altitude;
    o.max_gap_s = max_gap_s;
    o.attitude_half_window_s = half_window_s;
    o.ignore_geoid = ignore_geoid;
    return o;
}

double AngleDiff(double a, double b) { return std::remainder(a - b, 2.0 * kPi); }

glm::dvec3 Ecef(double lat_deg, double lon_deg, double h) {
    double x, y, z;
    GeographicLib::Geocentric::WGS84().Forward(lat_deg, lon_deg, h, x, y, z);
    return {x, y, z};
}

FlightSample Sample(double t, double lat, double lon, double h) {
    FlightSample s;
    s.time_s = t;
    s.lat_deg = lat;
    s.lon_deg = lon;
    s.ellipsoid_height = h;
    return s;
}

// A constant-speed level circle in the tangent plane at (45 N, 7 E, 1000 m), clockwise seen from
// above when turn_sign > 0 (a right turn), sampled every dt seconds.
FlightLog Circle(double speed, double radius, double turn_sign, double dt, int n) {
    const GeographicLib::LocalCartesian enu(45.0, 7.0, 1000.0);
    FlightLog log;
    log.source = "circle";
    for (int i = 0; i < n; ++i) {
        const double t = i * dt;
        const double angle = turn_sign * speed / radius * t;  // clockwise from north
        double lat, lon, h;
        enu.Reverse(radius * std::sin(angle), radius * std::cos(angle), 0.0, lat, lon, h);
        log.samples.push_back(Sample(kT0 + t, lat, lon, h));
    }
    return log;
}

TEST(AttitudeDerivation, CoordinatedTurnBankMatchesAnalytic) {
    for (double sign : {+1.0, -1.0}) {
        for (double dt : {1.0, 4.0}) {
            const double speed = 25.0, radius = 80.0;  // glider thermalling, ~20 s a circle
            const FlightLog log = Circle(speed, radius, sign, dt, 40);
            const Trajectory trajectory(log, Options(std::nullopt, 120.0, 0.0));
            const double omega = sign * speed / radius;
            const double bank = std::atan(speed * omega / kStandardGravity);
            EXPECT_NEAR(CoordinatedTurnBank(speed, omega), bank, 1e-15);
            EXPECT_NEAR(std::abs(bank), 38.54 * kRadPerDeg, 0.01 * kRadPerDeg);
            for (int i = 1; i < 39; ++i) {
                const TrajectoryState s = trajectory.At(kT0 + i * dt);
                ASSERT_TRUE(s.valid);
                EXPECT_FALSE(s.attitude_from_log);
                EXPECT_NEAR(s.attitude.roll_rad, bank, kAngleTolerance) << "sample " << i;
                EXPECT_NEAR(s.attitude.pitch_rad, 0.0, kAngleTolerance) << "sample " << i;
                // Heading is tangent to the circle: 90 deg right of the radius for a right turn.
                const double expected_heading = sign * speed / radius * i * dt + sign * kPi / 2;
                EXPECT_NEAR(AngleDiff(s.attitude.heading_rad, expected_heading), 0.0,
                            kAngleTolerance)
                    << "sample " << i;
            }
        }
    }
}

TEST(AttitudeDerivation, StraightClimbPitchIsFlightPathAngle) {
    // Due north along a meridian at 60 m/s ground speed, climbing 8 m/s, every 2 s.
    const double ground_speed = 60.0, climb = 8.0;
    FlightLog log;
    double lat = 10.0;
    for (int i = 0; i < 30; ++i) {
        const double h = 500.0 + climb * 2.0 * i;
        log.samples.push_back(Sample(kT0 + 2.0 * i, lat, 20.0, h));
        // Meridian arc per degree at this latitude and height.
        const double s = std::sin(lat * kRadPerDeg);
        const double e2 =
            GeographicLib::Constants::WGS84_f() * (2 - GeographicLib::Constants::WGS84_f());
        const double m =
            GeographicLib::Constants::WGS84_a() * (1 - e2) / std::pow(1 - e2 * s * s, 1.5);
        lat += ground_speed * 2.0 / (m + h) / kRadPerDeg;
    }
    const Trajectory trajectory(log);
    for (int i = 0; i < 30; ++i) {
        const TrajectoryState s = trajectory.At(kT0 + 2.0 * i);
        EXPECT_NEAR(s.attitude.pitch_rad, std::atan(climb / ground_speed), kAngleTolerance) << i;
        EXPECT_NEAR(s.attitude.roll_rad, 0.0, kAngleTolerance) << i;
        EXPECT_NEAR(AngleDiff(s.attitude.heading_rad, 0.0), 0.0, kAngleTolerance) << i;
    }
}

TEST(AttitudeDerivation, SlowSamplesHoldHeadingWingsLevel) {
    FlightLog log;
    for (int i = 0; i < 5; ++i) log.samples.push_back(Sample(kT0 + i, 10.0, 20.0, 100.0 + i));
    const Trajectory trajectory(log);
    const TrajectoryState s = trajectory.At(kT0 + 2.0);
    // Wings level (to rounding: the attitude goes through an ECEF quaternion).
    EXPECT_NEAR(s.attitude.roll_rad, 0.0, 1e-12);
    EXPECT_NEAR(s.attitude.pitch_rad, 0.0, 1e-12);
}

TEST(Interpolation, ExactAtSamplesSmoothBetween) {
    const double speed = 60.0, radius = 600.0, dt = 2.0;
    const FlightLog log = Circle(speed, radius, 1.0, dt, 30);
    const Trajectory trajectory(log);
    for (const FlightSample& s : log.samples) {
        const TrajectoryState st = trajectory.At(s.time_s);
        EXPECT_LT(glm::length(st.ecef - Ecef(s.lat_deg, s.lon_deg, *s.ellipsoid_height)), 1e-6);
        EXPECT_NEAR(st.height, *s.ellipsoid_height, 1e-6);
    }
    // Between samples the Hermite curve stays on the circle to a few centimetres (the chord
    // would be 0.8 m inside it) and the velocity is continuous.
    const GeographicLib::LocalCartesian enu(45.0, 7.0, 1000.0);
    double worst = 0.0;
    for (double t = 2.0; t < 56.0; t += 0.25) {
        const TrajectoryState st = trajectory.At(kT0 + t);
        double x, y, z;
        enu.Forward(st.lat_deg, st.lon_deg, st.height, x, y, z);
        worst = std::max(worst, std::abs(std::hypot(x, y) - radius));
        EXPECT_NEAR(glm::length(st.velocity_ecef), speed, 0.01 * speed) << t;
    }
    EXPECT_LT(worst, 0.05);
    for (int i = 2; i < 28; ++i) {
        const double t = kT0 + i * dt;
        const glm::dvec3 before = trajectory.At(t - 1e-6).velocity_ecef;
        const glm::dvec3 after = trajectory.At(t + 1e-6).velocity_ecef;
        EXPECT_LT(glm::length(before - after), 1e-3) << i;
    }
    EXPECT_FALSE(trajectory.At(kT0 - 1.0).valid);
    EXPECT_FALSE(trajectory.At(kT0 + 100.0).valid);
}

TEST(Interpolation, AcrossTheAntimeridian) {
    // East along the equator at 250 m/s from 179.98 E to 179.98 W.
    FlightLog log;
    const double deg_per_s = 250.0 / (GeographicLib::Constants::WGS84_a() + 11000.0) / kRadPerDeg;
    for (int i = 0; i <= 20; ++i) {
        double lon = 179.98 + deg_per_s * 4.0 * i;
        if (lon >= 180.0) lon -= 360.0;
        log.samples.push_back(Sample(kT0 + 4.0 * i, 0.0, lon, 11000.0));
    }
    const Trajectory trajectory(log);
    for (double t = 0.0; t <= 80.0; t += 0.5) {
        const TrajectoryState s = trajectory.At(kT0 + t);
        ASSERT_TRUE(s.valid);
        EXPECT_NEAR(glm::length(s.velocity_ecef), 250.0, 0.1) << t;
        EXPECT_NEAR(s.height, 11000.0, 1e-3) << t;
        EXPECT_NEAR(s.lat_deg, 0.0, 1e-9);
        // Continuous in longitude modulo 360.
        const double expected_lon = 179.98 + deg_per_s * t;
        EXPECT_NEAR(std::remainder(s.lon_deg - expected_lon, 360.0), 0.0, 1e-8) << t;
        EXPECT_NEAR(AngleDiff(s.attitude.heading_rad, kPi / 2), 0.0, kAngleTolerance) << t;
    }
}

TEST(Interpolation, OverTheNorthPole) {
    // Along meridian 0 up to the pole and down meridian 180, 200 m/s, 10 000 m.
    FlightLog log;
    const double step_deg = 0.01;
    for (int i = -10; i <= 10; ++i) {
        const double lat = 90.0 - std::abs(i) * step_deg;
        log.samples.push_back(Sample(kT0 + 10.0 * (i + 10), lat, i <= 0 ? 0.0 : 180.0, 10000.0));
    }
    const Trajectory trajectory(log);
    const TrajectoryState at_pole = trajectory.At(kT0 + 100.0);
    EXPECT_NEAR(at_pole.lat_deg, 90.0, 1e-9);
    double previous_speed = -1.0;
    glm::dquat previous_q{1, 0, 0, 0};
    for (double t = 10.0; t <= 190.0; t += 1.0) {
        const TrajectoryState s = trajectory.At(kT0 + t);
        ASSERT_TRUE(s.valid);
        EXPECT_NEAR(s.height, 10000.0, 0.05) << t;
        const double speed = glm::length(s.velocity_ecef);
        if (previous_speed > 0) {
            EXPECT_NEAR(speed, previous_speed, 0.5) << t;
        }
        previous_speed = speed;
        // The body rotation in ECEF turns smoothly over the pole (slowly: the flight path bends
        // with the Earth), although heading jumps from 0 to 180 deg there.
        if (t > 10.0) {
            const double turned =
                2.0 * std::acos(std::min(1.0, std::abs(glm::dot(previous_q, s.ecef_from_body))));
            EXPECT_LT(turned, 0.01 * kRadPerDeg) << t;
        }
        previous_q = s.ecef_from_body;
        if (t < 95.0) {
            EXPECT_NEAR(AngleDiff(s.attitude.heading_rad, 0.0), 0.0, 1e-3) << t;
        }
    }
}

TEST(Interpolation, GapsAreInvalidAndLoggedAttitudeIsSlerped) {
    FlightLog log;
    for (double t : {0.0, 1.0, 2.0, 300.0, 301.0}) {
        FlightSample s = Sample(kT0 + t, 45.0, 7.0 + t * 1e-4, 1000.0);
        s.attitude = geo::Attitude{(t == 1.0 ? 10.0 : 350.0) * kRadPerDeg, 0.0, 0.0};
        log.samples.push_back(s);
    }
    const Trajectory trajectory(log, Options(std::nullopt, 60.0));
    EXPECT_FALSE(trajectory.At(kT0 + 100.0).valid);
    const auto intervals = trajectory.ValidIntervals();
    ASSERT_EQ(intervals.size(), 2u);
    EXPECT_DOUBLE_EQ(intervals[0].second, kT0 + 2.0);
    EXPECT_DOUBLE_EQ(intervals[1].first, kT0 + 300.0);
    // Halfway between heading 350 and 10 is north, not south.
    const TrajectoryState mid = trajectory.At(kT0 + 0.5);
    EXPECT_TRUE(mid.attitude_from_log);
    EXPECT_NEAR(AngleDiff(mid.attitude.heading_rad, 0.0), 0.0, 1e-3);
    EXPECT_TRUE(std::any_of(
        trajectory.notes().begin(), trajectory.notes().end(),
        [](const std::string& n) { return n.find("gap of 298 s") != std::string::npos; }));
}

// --- altitudes ----------------------------------------------------------------------------------

TEST(Altitude, KindsStayApartAndConvertAsDocumented) {
    FlightLog log;
    for (int i = 0; i < 3; ++i) {
        FlightSample s;
        s.time_s = kT0 + i;
        s.lat_deg = 46.0;
        s.lon_deg = 8.0 + i * 1e-3;
        s.msl_altitude = 3000.0;
        s.pressure_altitude = 2900.0;
        log.samples.push_back(s);
    }
    // Default: geometric (MSL) over pressure.
    const Trajectory by_default(log, Options(std::nullopt, 120.0, 1.0, true));
    EXPECT_EQ(by_default.altitude_kind(), AltitudeKind::kMsl);
    EXPECT_NEAR(by_default.At(kT0).height, 3000.0, 1e-6);
    const Trajectory pressure(log, Options(AltitudeKind::kPressure, 120.0, 1.0, true));
    EXPECT_NEAR(pressure.At(kT0).height, GeometricFromGeopotential(2900.0), 1e-6);
    EXPECT_NEAR(GeometricFromGeopotential(11000.0), 11019.07, 0.01);  // ISA tropopause
    EXPECT_THROW(Trajectory(log, Options(AltitudeKind::kEllipsoid)), FlightLogError);

    const geo::GeoidGrid* geoid = geo::GeoidGrid::Default();
    if (!geoid) GTEST_SKIP() << "no geoid grid (Debian proj-data): MSL conversion not checked";
    const Trajectory msl(log);
    const double n = geoid->UndulationAt(46.0, 8.0);
    EXPECT_GT(n, 40.0);  // Alps: ~+50 m
    EXPECT_NEAR(msl.At(kT0).height, 3000.0 + n, 1e-6);
    EXPECT_NEAR(Trajectory(log, Options(AltitudeKind::kPressure)).At(kT0).height,
                GeometricFromGeopotential(2900.0) + n, 1e-6);
}

// A log with pressure altitudes only, and the air's conversion given (replay --metar-file): each
// fix's height is that conversion at its own time and place, then geopotential -> geometric.
TEST(Altitude, PressureAltitudesThroughTheGivenAir) {
    FlightLog log;
    for (int i = 0; i < 3; ++i) {
        FlightSample s;
        s.time_s = kT0 + 60.0 * i;
        s.lat_deg = 46.0;
        s.lon_deg = 8.0 + i * 1e-2;
        s.pressure_altitude = 2000.0;
        log.samples.push_back(s);
    }
    TrajectoryOptions options = Options(std::nullopt, 120.0, 1.0, true);
    int calls = 0;
    options.pressure_height = [&calls](double t, double lat, double lon, double h) {
        ++calls;
        EXPECT_DOUBLE_EQ(lat, 46.0);
        EXPECT_DOUBLE_EQ(h, 2000.0);
        return h + 100.0 * (lon - 8.0) / 1e-2 + (t - kT0) / 60.0;  // depends on place and time
    };
    const Trajectory t(log, options);
    EXPECT_EQ(calls, 3);
    EXPECT_EQ(t.altitude_kind(), AltitudeKind::kPressure);
    for (int i = 0; i < 3; ++i) {
        EXPECT_NEAR(t.At(kT0 + 60.0 * i).height, GeometricFromGeopotential(2000.0 + 101.0 * i),
                    1e-6);
    }
}

TEST(SampleFlights, AllBecomeTrajectories) {
    for (const char* name : {"glider_sisteron.igc", "airliner_nadi_climb.gpx",
                             "sunset_approach_sfo.kml", "balloon_esrange.csv"}) {
        const FlightLog log =
            ReadFlightLog(std::string(ZENITH_SOURCE_DIR) + "/data/flights/" + name);
        const Trajectory trajectory(log);
        EXPECT_EQ(trajectory.ValidIntervals().size(), 1u) << name;
        for (double t = trajectory.start_time_s(); t <= trajectory.end_time_s(); t += 7.3) {
            const TrajectoryState s = trajectory.At(t);
            ASSERT_TRUE(s.valid) << name;
            ASSERT_TRUE(std::isfinite(s.attitude.heading_rad) &&
                        std::isfinite(s.attitude.roll_rad) && std::isfinite(s.attitude.pitch_rad))
                << name;
        }
    }
}

TEST(SampleFlights, GliderBankFromThermallingCircles) {
    const FlightLog log =
        ReadFlightLog(std::string(ZENITH_SOURCE_DIR) + "/data/flights/glider_sisteron.igc");
    const Trajectory trajectory(log);
    EXPECT_EQ(trajectory.altitude_kind(), AltitudeKind::kMsl);
    // 12:03:30 is inside the first (right-hand) thermal: 40 deg of bank in still air; the
    // 3 m/s wind and the 1.85 m position resolution of IGC move the derived value around it.
    double sum = 0.0;
    int n = 0;
    for (double t = 0; t < 60.0; t += 1.0) {
        sum += trajectory.At(log.samples.front().time_s + 210.0 + t).attitude.roll_rad;
        ++n;
    }
    EXPECT_NEAR(sum / n, 40.0 * kRadPerDeg, 4.0 * kRadPerDeg);
}

// --- issue 13 ------------------------------------------------------------------------------

TEST(Heights, OneFixWithoutGnssCannotChangeHowTheOthersAreRead) {
    // A paraglider: 199 fixes with GNSS height above the geoid 1500 m and pressure altitude
    // 1340 m (a QNH far from standard); one 'V' fix in the middle has the pressure altitude only.
    FlightLog log;
    log.source = "pg";
    for (int i = 0; i < 199; ++i) {
        FlightSample s;
        s.time_s = kT0 + i;
        s.lat_deg = 45.0;
        s.lon_deg = 6.0 + 1e-4 * i;
        s.pressure_altitude = 1340.0;
        if (i != 100) s.msl_altitude = 1500.0;
        log.samples.push_back(s);
    }
    const Trajectory trajectory(log, Options(std::nullopt, 120.0, 1.0, true));
    EXPECT_EQ(trajectory.altitude_kind(), AltitudeKind::kMsl);
    // The V fix sits on the GNSS track: its pressure height plus its neighbours' offset.
    EXPECT_NEAR(trajectory.At(kT0 + 100.0).height, 1500.0, 1e-6);
    EXPECT_NEAR(trajectory.At(kT0 + 99.5).height, 1500.0, 1e-6);
    bool noted = false;
    for (const std::string& note : trajectory.notes()) {
        noted = noted || note.find("1 fixes without a GNSS height use pressure altitude") !=
                             std::string::npos;
    }
    EXPECT_TRUE(noted);
    // Forcing pressure altitude still reads pure ISA everywhere.
    const Trajectory isa(log, Options(AltitudeKind::kPressure, 120.0, 1.0, true));
    EXPECT_NEAR(isa.At(kT0).height, GeometricFromGeopotential(1340.0), 1e-6);
}

TEST(Interpolation, ALoneFixIsValidAtItsTime) {
    FlightLog log;
    log.source = "one";
    log.samples.push_back(Sample(kT0, 45.0, 6.0, 1000.0));
    const Trajectory lone(log);
    const TrajectoryState s = lone.At(kT0);
    ASSERT_TRUE(s.valid);
    EXPECT_NEAR(s.lat_deg, 45.0, 1e-9);
    EXPECT_NEAR(s.height, 1000.0, 1e-6);

    // The first fix alone before a gap: valid at its time, never a fallback position.
    for (int i = 0; i < 5; ++i) log.samples.push_back(Sample(kT0 + 600.0 + i, 45.0, 6.001, 1000.0));
    const Trajectory gapped(log);
    const TrajectoryState first = gapped.At(kT0);
    ASSERT_TRUE(first.valid);
    EXPECT_NEAR(first.lon_deg, 6.0, 1e-9);
    EXPECT_FALSE(gapped.At(kT0 + 1.0).valid);  // inside the gap
}

TEST(Interpolation, NotAcrossADiscontinuity) {
    FlightLog log;
    log.source = "jump";
    for (int i = 0; i < 6; ++i) {
        log.samples.push_back(
            Sample(kT0 + i, 45.0, i < 3 ? 6.0 + 1e-4 * i : 12.0 + 1e-4 * i, 1000.0));
    }
    log.samples[3].discontinuity = true;
    const Trajectory trajectory(log);
    EXPECT_EQ(trajectory.ValidIntervals().size(), 2u);
    EXPECT_FALSE(trajectory.At(kT0 + 2.5).valid);
    EXPECT_TRUE(trajectory.At(kT0 + 3.5).valid);
}

}  // namespace
}  // namespace zenith::track
