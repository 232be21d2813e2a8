// A flight log as a continuous trajectory for replay: position, velocity and attitude at any
// time, with heights converted to the WGS84 ellipsoid.
//
// Positions: cubic Hermite in ECEF (GeographicLib::Geocentric) through the samples, tangents
// from the non-uniform three-point derivative (exact for a quadratic path; Catmull-Rom for even
// spacing), one-sided at the ends of a segment. C1, exact at the samples, and free of the
// longitude wrap and the pole, which exist only in geodetic coordinates.
//
// Attitude: from the log where it has one; otherwise derived at each sample from the track
// through it and its neighbours (about attitude_half_window_s either side), in the local
// horizontal plane: heading = course over ground (no wind is known, so heading = track), pitch =
// flight-path angle atan(vertical speed / ground speed), bank for a coordinated turn
// tan(phi) = V omega / g, with V and omega from the circle through the three points, exact for a
// constant-speed turn. Between samples the ECEF-from-body rotation is slerped, so the attitude
// stays continuous over a pole where heading is not.
//
// Gaps: samples more than max_gap_s apart, or across a discontinuity the reader found (a jump
// faster than any aircraft), start a new segment; At() is invalid inside a gap and outside
// [start_time_s(), end_time_s()], and valid at the time of every sample, even a lone one.
//
// Heights, chosen per fix (a single fix cannot change how the others are read): GNSS height
// above the ellipsoid, else GNSS height above the geoid plus the undulation N from a GTX grid
// (EGM96 15' from Debian's proj-data, /usr/share/proj/egm96_15.gtx, or $ZENITH_GEOID_GTX;
// without one N = 0 and notes() says so, |N| <= ~107 m), else pressure altitude as ISA
// geopotential height converted to geometric height above MSL, plus N, plus the GNSS - pressure
// difference measured at the nearest fixes that have both (so an IGC 'V' fix among 'A' fixes
// stays on the GNSS track). A log of pressure altitudes only is pure ISA with no QNH and no
// temperature known (notes() says so; off by hundreds of metres aloft). TrajectoryOptions::
// altitude forces one kind, dropping the fixes without it.
#pragma once

#include <functional>
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "zenith/geo/geoid.h"
#include "zenith/track/flight_log.h"

namespace zenith::track {

inline constexpr double kStandardGravity = 9.80665;   // m/s^2 (ISA, CGPM 1901)
inline constexpr double kIsaEarthRadius = 6356766.0;  // m, for geopotential height (ISO 2533)

// ISA pressure altitude (geopotential metres) -> geometric height above MSL, metres:
// z = R H / (R - H), R = kIsaEarthRadius. Valid where ISA is defined (up to 80 km).
double GeometricFromGeopotential(double geopotential_height);

struct TrajectoryOptions {
    // Use only this kind of altitude; default: each fix's best (see the file comment).
    std::optional<AltitudeKind> altitude;
    double max_gap_s = 120.0;
    double attitude_half_window_s = 1.0;
    // Geoid for MSL -> ellipsoid; nullptr: GeoidGrid::Default(). ignore_geoid: use N = 0.
    const geo::GeoidGrid* geoid = nullptr;
    bool ignore_geoid = false;
    // The geopotential height above mean sea level of a fix's pressure altitude (ISA, 1013.25 hPa
    // datum) at its time (POSIX s) and place: the air's QNH and temperature
    // (zenith::weather::HeightFromPressureAltitude; `zenith replay --metar-file`). Null: ISA,
    // the pressure altitude itself.
    std::function<double(double time_s, double lat_deg, double lon_deg, double pressure_altitude_m)>
        pressure_height;
};

struct TrajectoryState {
    bool valid = false;  // false outside the flight or inside a gap; other fields unset then
    double time_s = 0.0;
    glm::dvec3 ecef{0.0};           // m, WGS84
    glm::dvec3 velocity_ecef{0.0};  // m/s
    double lat_deg = 0.0;
    double lon_deg = 0.0;
    double height = 0.0;     // m above the WGS84 ellipsoid
    geo::Attitude attitude;  // in the local NED frame at this position
    glm::dquat ecef_from_body{1.0, 0.0, 0.0, 0.0};
    bool attitude_from_log = false;  // both neighbouring samples carried a logged attitude
};

class Trajectory {
  public:
    // Throws FlightLogError when no sample has the requested (or any) altitude.
    explicit Trajectory(const FlightLog& log, const TrajectoryOptions& options = {});

    TrajectoryState At(double time_s) const;

    double start_time_s() const { return knots_.front().time_s; }
    double end_time_s() const { return knots_.back().time_s; }
    // The kind most fixes use.
    AltitudeKind altitude_kind() const { return altitude_kind_; }
    // How the heights and attitudes were made (altitude kind, geoid, ISA, derived attitude).
    const std::vector<std::string>& notes() const { return notes_; }
    std::size_t size() const { return knots_.size(); }
    // [start, end] of each stretch where At() is valid, in time order.
    std::vector<std::pair<double, double>> ValidIntervals() const;

  private:
    struct Knot {
        double time_s;
        glm::dvec3 ecef;
        glm::dvec3 tangent;  // m/s
        glm::dquat ecef_from_body;
        double height;  // m above the ellipsoid
        bool attitude_from_log;
        int segment;
    };
    std::vector<Knot> knots_;
    std::vector<std::optional<double>> Heights(const FlightLog& log,
                                               const TrajectoryOptions& options);

    AltitudeKind altitude_kind_ = AltitudeKind::kEllipsoid;
    std::vector<std::string> notes_;
};

// Bank angle (radians, right wing down for a right turn) of a coordinated level turn at
// ground speed V (m/s) and turn rate omega (rad/s, clockwise from above positive).
double CoordinatedTurnBank(double speed, double turn_rate);

}  // namespace zenith::track
