// Trajectory: Hermite positions in ECEF, derived or logged attitude slerped between samples,
// heights on the WGS84 ellipsoid. See trajectory.h for the method and its limits.
#include "zenith/track/trajectory.h"

#include <fmt/format.h>

#include <GeographicLib/Geocentric.hpp>
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <numbers>

namespace zenith::track {

namespace {

constexpr double kRadPerDeg = std::numbers::pi / 180.0;
// Below this ground speed the course is noise (a glider on the ground, a balloon in calm air):
// heading is held from a neighbour and pitch and bank are zero.
constexpr double kMinCourseSpeed = 1.0;  // m/s
// Three points whose circle is wider than this are a straight line (curvature below GNSS noise).
constexpr double kMaxTurnRadius = 1.0e7;  // m

const GeographicLib::Geocentric& Wgs84() { return GeographicLib::Geocentric::WGS84(); }

glm::dvec3 EcefFromGeodetic(double lat_deg, double lon_deg, double height) {
    double x, y, z;
    Wgs84().Forward(lat_deg, lon_deg, height, x, y, z);
    return {x, y, z};
}

struct Derived {
    bool has_course;
    double heading, pitch, roll;
};

// Attitude at point `at` (0, 1 or 2) of three time-ordered points, from the circle through
// them in the horizontal plane at that point. heights are above the ellipsoid.
Derived DeriveAttitude(const std::array<glm::dvec3, 3>& ecef, const std::array<double, 3>& t,
                       const std::array<double, 3>& heights, std::size_t at, double lat_deg,
                       double lon_deg) {
    const glm::dmat3 enu_from_ecef = glm::transpose(geo::EcefFromNed(lat_deg, lon_deg));
    // rows of enu_from_ecef as NED: use north (x) and east (y) as horizontal axes.
    std::array<glm::dvec2, 3> p;  // (north, east), metres, relative to the point `at`
    for (std::size_t k = 0; k < 3; ++k) {
        const glm::dvec3 ned = enu_from_ecef * (ecef[k] - ecef[at]);
        p[k] = {ned.x, ned.y};
    }
    const double span_s = t[2] - t[0];
    // Vertical speed at t[at]: derivative of the quadratic through the three heights.
    const double h0 = t[1] - t[0], h1 = t[2] - t[1];
    const double d01 = (heights[1] - heights[0]) / h0, d12 = (heights[2] - heights[1]) / h1;
    const double curvature2 = (d12 - d01) / (h0 + h1);  // half the second derivative
    const double vertical_speed = d01 + curvature2 * (2.0 * t[at] - t[0] - t[1]);

    const glm::dvec2 a = p[1] - p[0], b = p[2] - p[1];
    const double cross = a.x * b.y - a.y * b.x;  // > 0: clockwise seen from above (N, E axes)
    const double chord = glm::length(p[2] - p[0]);
    double speed = chord / span_s;
    glm::dvec2 direction = chord > 0.0 ? (p[2] - p[0]) / chord : glm::dvec2(0.0);
    double turn_rate = 0.0;
    const double la = glm::length(a), lb = glm::length(b);
    // Circumradius R = abc / (4 area) = abc / (2 |cross|).
    const double radius = std::abs(cross) > 0.0 ? la * lb * chord / (2.0 * std::abs(cross))
                                                : std::numeric_limits<double>::infinity();
    if (radius < kMaxTurnRadius && la > 0.0 && lb > 0.0) {
        // Circumcentre relative to p[0] (N, E plane).
        const glm::dvec2 q1 = p[1] - p[0], q2 = p[2] - p[0];
        const double d = 2.0 * (q1.x * q2.y - q1.y * q2.x);
        const glm::dvec2 c = p[0] + glm::dvec2(q2.y * glm::dot(q1, q1) - q1.y * glm::dot(q2, q2),
                                               q1.x * glm::dot(q2, q2) - q2.x * glm::dot(q1, q1)) /
                                        d;
        auto angle = [&](const glm::dvec2& u, const glm::dvec2& v) {
            return std::abs(std::atan2(u.x * v.y - u.y * v.x, glm::dot(u, v)));
        };
        const double arc = angle(p[0] - c, p[1] - c) + angle(p[1] - c, p[2] - c);
        speed = radius * arc / span_s;
        const double sign = cross > 0.0 ? 1.0 : -1.0;
        turn_rate = sign * speed / radius;
        // Tangent at the point: radius vector turned 90 degrees in the direction of motion.
        const glm::dvec2 r = (p[at] - c) / radius;
        direction = sign > 0.0 ? glm::dvec2(-r.y, r.x) : glm::dvec2(r.y, -r.x);
    }
    if (!(speed >= kMinCourseSpeed)) return {false, 0.0, 0.0, 0.0};
    return {true, std::atan2(direction.y, direction.x), std::atan2(vertical_speed, speed),
            CoordinatedTurnBank(speed, turn_rate)};
}

std::string Clock(double time_s) {
    const geo::CivilTime t = geo::CivilFromUnixSeconds(time_s);
    return fmt::format("{:02}:{:02}:{:02.0f}", t.hour, t.minute, std::floor(t.second));
}

}  // namespace

double CoordinatedTurnBank(double speed, double turn_rate) {
    return std::atan(speed * turn_rate / kStandardGravity);
}

double GeometricFromGeopotential(double geopotential_height) {
    return kIsaEarthRadius * geopotential_height / (kIsaEarthRadius - geopotential_height);
}

// Ellipsoidal height of every sample (nullopt: none can be had), per fix: the requested kind
// only; or by default each fix's best measurement: GNSS ellipsoidal height, else GNSS height
// above the geoid plus the undulation, else pressure altitude through ISA plus the undulation
// plus the offset between GNSS and pressure heights measured at the nearest fixes that have
// both (interpolated in time), so a fix without GNSS (an IGC 'V' fix) stays on the track its
// neighbours draw. Notes say what each fix used.
std::vector<std::optional<double>> Trajectory::Heights(const FlightLog& log,
                                                       const TrajectoryOptions& options) {
    const std::vector<FlightSample>& samples = log.samples;
    const std::size_t n = samples.size();
    const bool any_below_ellipsoid =
        std::any_of(samples.begin(), samples.end(), [&](const auto& x) {
            return !x.ellipsoid_height && (x.msl_altitude || x.pressure_altitude);
        });
    const geo::GeoidGrid* geoid = nullptr;
    if (any_below_ellipsoid && options.altitude != AltitudeKind::kEllipsoid) {
        if (!options.ignore_geoid)
            geoid = options.geoid ? options.geoid : geo::GeoidGrid::Default();
        notes_.push_back(
            geoid ? fmt::format("MSL -> ellipsoid: geoid undulation from {}", geoid->source())
                  : std::string("no geoid grid (install Debian proj-data or set "
                                "ZENITH_GEOID_GTX): MSL heights are used as ellipsoidal "
                                "heights, off by the geoid undulation (-107..+85 m)"));
    }
    const auto undulation = [&](const FlightSample& x) {
        return geoid ? geoid->UndulationAt(x.lat_deg, x.lon_deg) : 0.0;
    };
    const auto geometric = [&](const FlightSample& x) -> std::optional<double> {
        if (x.ellipsoid_height) return *x.ellipsoid_height;
        if (x.msl_altitude) return *x.msl_altitude + undulation(x);
        return std::nullopt;
    };
    const auto from_pressure = [&](const FlightSample& x) {
        const double h =
            options.pressure_height
                ? options.pressure_height(x.time_s, x.lat_deg, x.lon_deg, *x.pressure_altitude)
                : *x.pressure_altitude;
        return GeometricFromGeopotential(h) + undulation(x);
    };
    std::vector<std::optional<double>> heights(n);
    std::array<std::size_t, 3> used{};  // ellipsoid, MSL, pressure
    if (options.altitude) {
        altitude_kind_ = *options.altitude;
        for (std::size_t i = 0; i < n; ++i) {
            const std::optional<double> h = samples[i].Altitude(altitude_kind_);
            if (!h) continue;
            heights[i] = altitude_kind_ == AltitudeKind::kEllipsoid ? *h
                         : altitude_kind_ == AltitudeKind::kMsl     ? *h + undulation(samples[i])
                                                                    : from_pressure(samples[i]);
            ++used[static_cast<std::size_t>(altitude_kind_ == AltitudeKind::kEllipsoid ? 0
                                            : altitude_kind_ == AltitudeKind::kMsl     ? 1
                                                                                       : 2)];
        }
    } else {
        // GNSS minus pressure height where a fix has both, carried to the fixes with pressure
        // only: linear in time between the nearest two, held beyond them.
        std::vector<std::optional<double>> offset(n);
        for (std::size_t i = 0; i < n; ++i) {
            const std::optional<double> g = geometric(samples[i]);
            if (g && samples[i].pressure_altitude) offset[i] = *g - from_pressure(samples[i]);
        }
        std::vector<std::size_t> previous(n, n), next(n, n);
        for (std::size_t i = 0, last = n; i < n; ++i) {
            if (offset[i]) last = i;
            previous[i] = last;
        }
        for (std::size_t i = n, last = n; i-- > 0;) {
            if (offset[i]) last = i;
            next[i] = last;
        }
        bool pressure_only_log = true;
        for (std::size_t i = 0; i < n; ++i) {
            const FlightSample& x = samples[i];
            if (x.ellipsoid_height) {
                heights[i] = *x.ellipsoid_height;
                ++used[0];
                pressure_only_log = false;
            } else if (x.msl_altitude) {
                heights[i] = *x.msl_altitude + undulation(x);
                ++used[1];
                pressure_only_log = false;
            } else if (x.pressure_altitude) {
                double correction = 0.0;
                const std::size_t p = previous[i], q = next[i];
                if (p < n && q < n && samples[q].time_s > samples[p].time_s) {
                    const double f =
                        (x.time_s - samples[p].time_s) / (samples[q].time_s - samples[p].time_s);
                    correction = *offset[p] + f * (*offset[q] - *offset[p]);
                } else if (p < n || q < n) {
                    correction = *offset[p < n ? p : q];
                }
                heights[i] = from_pressure(x) + correction;
                ++used[2];
            }
        }
        altitude_kind_ = used[0] >= std::max(used[1], used[2]) ? AltitudeKind::kEllipsoid
                         : used[1] >= used[2]                  ? AltitudeKind::kMsl
                                                               : AltitudeKind::kPressure;
        if (used[2] > 0 && !pressure_only_log) {
            notes_.push_back(fmt::format(
                "{} fixes without a GNSS height use pressure altitude through ISA plus the "
                "GNSS - pressure difference of the nearest fixes that have both",
                used[2]));
        }
    }
    std::string what;
    constexpr std::array<AltitudeKind, 3> kKinds = {AltitudeKind::kEllipsoid, AltitudeKind::kMsl,
                                                    AltitudeKind::kPressure};
    for (std::size_t k = 0; k < 3; ++k) {
        if (used[k] == 0) continue;
        what += fmt::format("{}{} for {} fixes", what.empty() ? "" : ", ",
                            AltitudeKindName(kKinds[k]), used[k]);
    }
    if (!what.empty()) notes_.push_back("altitude used: " + what);
    if (used[2] > 0 && used[0] + used[1] == 0 && !options.pressure_height) {
        notes_.push_back(
            "pressure altitude -> height: ISA (1013.25 hPa, 15 C at MSL) with no QNH "
            "or temperature known; off by ~30 ft per hPa of QNH near the ground and "
            "by 4% per 10 K of temperature deviation aloft");
    }
    return heights;
}

Trajectory::Trajectory(const FlightLog& log, const TrajectoryOptions& options) {
    if (!(options.max_gap_s > 0.0) || !(options.attitude_half_window_s >= 0.0)) {
        throw FlightLogError(
            fmt::format("trajectory options: max_gap_s {} must be > 0 and "
                        "attitude_half_window_s {} >= 0",
                        options.max_gap_s, options.attitude_half_window_s));
    }
    struct Point {
        const FlightSample* sample;
        double height;
        glm::dvec3 ecef;
    };
    std::vector<Point> points;
    points.reserve(log.samples.size());
    const std::vector<std::optional<double>> heights = Heights(log, options);
    for (std::size_t i = 0; i < log.samples.size(); ++i) {
        if (!heights[i]) continue;
        const FlightSample& s = log.samples[i];
        points.push_back({&s, *heights[i], EcefFromGeodetic(s.lat_deg, s.lon_deg, *heights[i])});
    }
    if (points.empty()) {
        throw FlightLogError(
            fmt::format("{}: no sample has {}", log.source,
                        options.altitude ? AltitudeKindName(*options.altitude) : "an altitude"));
    }
    if (points.size() < log.samples.size()) {
        notes_.push_back(
            fmt::format("{} of {} samples have no {} and are not used",
                        log.samples.size() - points.size(), log.samples.size(),
                        options.altitude ? AltitudeKindName(*options.altitude) : "altitude"));
    }

    // Segments split at gaps.
    std::vector<int> segment(points.size(), 0);
    for (std::size_t i = 1; i < points.size(); ++i) {
        const double dt = points[i].sample->time_s - points[i - 1].sample->time_s;
        segment[i] = segment[i - 1] + (dt > options.max_gap_s || points[i].sample->discontinuity);
        if (dt > options.max_gap_s) {
            notes_.push_back(
                fmt::format("{}:{}: gap of {:.0f} s > {:.0f} s: not interpolated "
                            "(trajectory invalid from {} to {})",
                            log.source, points[i].sample->line, dt, options.max_gap_s,
                            Clock(points[i - 1].sample->time_s), Clock(points[i].sample->time_s)));
        }
    }

    knots_.resize(points.size());
    int derived = 0;
    for (std::size_t i = 0; i < points.size(); ++i) {
        Knot& k = knots_[i];
        const FlightSample& s = *points[i].sample;
        k.time_s = s.time_s;
        k.ecef = points[i].ecef;
        k.height = points[i].height;
        k.segment = segment[i];
        const bool prev = i > 0 && segment[i - 1] == segment[i];
        const bool next = i + 1 < points.size() && segment[i + 1] == segment[i];
        if (prev && next) {
            const double h0 = s.time_s - points[i - 1].sample->time_s;
            const double h1 = points[i + 1].sample->time_s - s.time_s;
            k.tangent = ((points[i + 1].ecef - k.ecef) * (h0 / h1) +
                         (k.ecef - points[i - 1].ecef) * (h1 / h0)) /
                        (h0 + h1);
        } else if (next && i + 2 < points.size() && segment[i + 2] == segment[i]) {
            // Segment start: slope of the quadratic through the first three points.
            const double h0 = points[i + 1].sample->time_s - s.time_s;
            const double h1 = points[i + 2].sample->time_s - points[i + 1].sample->time_s;
            k.tangent = -(2 * h0 + h1) / (h0 * (h0 + h1)) * k.ecef +
                        (h0 + h1) / (h0 * h1) * points[i + 1].ecef -
                        h0 / (h1 * (h0 + h1)) * points[i + 2].ecef;
        } else if (prev && i >= 2 && segment[i - 2] == segment[i]) {
            // Segment end: the same from the last three.
            const double h0 = points[i - 1].sample->time_s - points[i - 2].sample->time_s;
            const double h1 = s.time_s - points[i - 1].sample->time_s;
            k.tangent = h1 / (h0 * (h0 + h1)) * points[i - 2].ecef -
                        (h0 + h1) / (h0 * h1) * points[i - 1].ecef +
                        (2 * h1 + h0) / (h1 * (h0 + h1)) * k.ecef;
        } else if (next) {
            k.tangent = (points[i + 1].ecef - k.ecef) / (points[i + 1].sample->time_s - s.time_s);
        } else if (prev) {
            k.tangent = (k.ecef - points[i - 1].ecef) / (s.time_s - points[i - 1].sample->time_s);
        } else {
            k.tangent = glm::dvec3(0.0);
        }
    }

    // Attitude: logged, or derived from three points about attitude_half_window_s apart.
    std::vector<std::optional<geo::Attitude>> attitude(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
        const FlightSample& s = *points[i].sample;
        knots_[i].attitude_from_log = s.attitude.has_value();
        if (s.attitude) {
            attitude[i] = *s.attitude;
            continue;
        }
        // Three points in the same segment, about the half window apart where the log allows:
        // i in the middle, or at the start/end of its segment.
        auto step = [&](std::size_t from, int dir) {
            std::size_t j = from;
            const double t0 = points[from].sample->time_s;
            while (true) {
                const std::size_t n = dir < 0 ? j - 1 : j + 1;
                if ((dir < 0 && j == 0) || n >= points.size() || segment[n] != segment[i]) break;
                j = n;
                if (std::abs(points[j].sample->time_s - t0) >= options.attitude_half_window_s) {
                    break;
                }
            }
            return j;
        };
        std::size_t lo = step(i, -1), mid = i, hi = step(i, +1);
        std::size_t at = 1;
        if (lo == i) {
            mid = hi;
            hi = step(mid, +1);
            at = 0;
        } else if (hi == i) {
            mid = lo;
            lo = step(mid, -1);
            at = 2;
        }
        if (lo == mid || mid == hi) continue;  // fewer than three points in the segment
        ++derived;
        const std::array<std::size_t, 3> idx{lo, mid, hi};
        std::array<glm::dvec3, 3> e;
        std::array<double, 3> t, h;
        for (std::size_t j = 0; j < 3; ++j) {
            e[j] = points[idx[j]].ecef;
            t[j] = points[idx[j]].sample->time_s;
            h[j] = points[idx[j]].height;
        }
        const Derived d = DeriveAttitude(e, t, h, at, s.lat_deg, s.lon_deg);
        if (d.has_course) attitude[i] = geo::Attitude{d.heading, d.pitch, d.roll};
    }
    if (derived > 0) {
        notes_.push_back(fmt::format(
            "attitude derived for {} of {} samples: heading = course over ground (no wind "
            "known), pitch = flight-path angle, bank = coordinated turn atan(V omega / g)",
            derived, points.size()));
    }
    // Where no course could be had (slower than kMinCourseSpeed, lone points), hold the nearest
    // known heading, wings level.
    std::optional<geo::Attitude> last;
    for (std::size_t i = 0; i < points.size(); ++i) {
        if (attitude[i]) {
            last = attitude[i];
        } else if (last) {
            attitude[i] = geo::Attitude{last->heading_rad, 0.0, 0.0};
        }
    }
    last.reset();
    for (std::size_t i = points.size(); i-- > 0;) {
        if (attitude[i]) {
            last = attitude[i];
        } else {
            attitude[i] = geo::Attitude{last ? last->heading_rad : 0.0, 0.0, 0.0};
        }
    }
    for (std::size_t i = 0; i < points.size(); ++i) {
        knots_[i].ecef_from_body =
            geo::EcefFromBody(*attitude[i], points[i].sample->lat_deg, points[i].sample->lon_deg);
    }
}

TrajectoryState Trajectory::At(double time_s) const {
    TrajectoryState state;
    state.time_s = time_s;
    if (!(time_s >= start_time_s()) || !(time_s <= end_time_s())) return state;
    // The first knot at or after time_s; at a knot's own time that knot alone, so a lone sample
    // (a segment of one) is valid at its time.
    const auto it = std::lower_bound(knots_.begin(), knots_.end(), time_s,
                                     [](const Knot& k, double t) { return k.time_s < t; });
    const auto i1 = static_cast<std::size_t>(it - knots_.begin());
    const std::size_t i0 = knots_[i1].time_s == time_s ? i1 : i1 - 1;
    const Knot& k0 = knots_[i0];
    const Knot& k1 = knots_[i1];
    if (k0.segment != k1.segment) return state;  // inside a gap

    if (i0 == i1) {
        state.ecef = k0.ecef;
        state.velocity_ecef = k0.tangent;
        state.ecef_from_body = k0.ecef_from_body;
        state.attitude_from_log = k0.attitude_from_log;
    } else {
        // Cubic Hermite on [k0, k1].
        const double h = k1.time_s - k0.time_s;
        const double s = (time_s - k0.time_s) / h;
        const double s2 = s * s, s3 = s2 * s;
        const double h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s;
        const double h01 = -2 * s3 + 3 * s2, h11 = s3 - s2;
        state.ecef = h00 * k0.ecef + h10 * h * k0.tangent + h01 * k1.ecef + h11 * h * k1.tangent;
        const double d00 = 6 * s2 - 6 * s, d10 = 3 * s2 - 4 * s + 1;
        const double d01 = -6 * s2 + 6 * s, d11 = 3 * s2 - 2 * s;
        state.velocity_ecef =
            (d00 * k0.ecef + d01 * k1.ecef) / h + d10 * k0.tangent + d11 * k1.tangent;
        state.ecef_from_body = glm::normalize(glm::slerp(k0.ecef_from_body, k1.ecef_from_body, s));
        state.attitude_from_log = k0.attitude_from_log && k1.attitude_from_log;
    }
    Wgs84().Reverse(state.ecef.x, state.ecef.y, state.ecef.z, state.lat_deg, state.lon_deg,
                    state.height);
    state.attitude =
        geo::AttitudeFromEcefFromBody(state.ecef_from_body, state.lat_deg, state.lon_deg);
    state.valid = true;
    return state;
}

std::vector<std::pair<double, double>> Trajectory::ValidIntervals() const {
    std::vector<std::pair<double, double>> out;
    for (std::size_t i = 0; i < knots_.size(); ++i) {
        if (i == 0 || knots_[i].segment != knots_[i - 1].segment) {
            out.emplace_back(knots_[i].time_s, knots_[i].time_s);
        } else {
            out.back().second = knots_[i].time_s;
        }
    }
    return out;
}

}  // namespace zenith::track
