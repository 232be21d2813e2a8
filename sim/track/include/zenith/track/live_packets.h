// What a running simulator sends over UDP, read one datagram at a time, and the clock rebuilt
// from it (`zenith live`, zenith/sim/live.h):
//
//   FlightGear's native FDM packet (--native-fdm=socket,out,HZ,HOST,PORT,udp): the FGNetFDM
//     struct of FlightGear's src/Network/net_fdm.hxx, FG_NET_FDM_VERSION 24 (FlightGear
//     2017.1 to 2020.3 and later, Debian 12's 2020.3.16), 408 bytes, every field big-endian
//     (network byte order), no padding but the explicit word after the version. Read here:
//     version (offset 0), longitude, latitude (radians, doubles at 8, 16), altitude (metres
//     above FlightGear's sea level, double at 24), phi, theta, psi (roll, pitch, true heading,
//     radians, floats at 36, 40, 44), num_engines / num_tanks / num_wheels (at 120, 284, 304,
//     checked against their arrays), cur_time (whole POSIX seconds with the warp included,
//     uint32 at 356) and warp (int32 at 360). FlightGear has no geoid: its sea level is the
//     WGS84 ellipsoid, so the altitude is an ellipsoidal height.
//   FlightGear's generic protocol with data/flightgear/zenith.xml (--generic=socket,out,HZ,
//     HOST,PORT,udp,zenith): one text line, seven comma-separated fields: /sim/time/gmt
//     (YYYY-MM-DDTHH:MM:SS, whole seconds), latitude and longitude (degrees), altitude (feet
//     above FlightGear's sea level, the ellipsoid), heading, pitch and roll (degrees).
//   X-Plane's UDP output (versions 9 to 12): "DATA" + one byte, then records of 36 bytes (an
//     int32 index and eight float32, little-endian): index 17 pitch, roll, true heading
//     (degrees), index 20 latitude, longitude (degrees), altitude (feet above mean sea level);
//     -999 marks an unused value; other indices are skipped. Or "RPOS" + one byte and 64 bytes
//     (little-endian): longitude, latitude, elevation (doubles; degrees, metres above mean sea
//     level), height above the ground, pitch, true heading, roll (floats; metres, degrees), the
//     velocities and rates (not used). X-Plane sends no time: the clock is the receiver's.
//
// Every parser either returns a fix or throws PacketError naming what is wrong (the size, the
// version, a value and its range); nothing a packet holds chooses how much memory or time a
// parser takes (sizes are fixed or bounded by kMaxPacketBytes, X-Plane's records by the size).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>

#include "zenith/base/error.h"
#include "zenith/geo/frames.h"
#include "zenith/track/flight_log.h"

namespace zenith::track {

// A datagram that cannot be used; the message names the field, the value and what was expected.
// kind() is what was wrong, for counting: "size", "version", "header", "fields", "lines",
// "indices", or the field whose value is wrong ("latitude", "gmt", "num_engines", ...).
class PacketError : public InputError {
  public:
    PacketError(std::string kind, const std::string& message)
        : InputError(message), kind_(std::move(kind)) {}
    const std::string& kind() const { return kind_; }

  private:
    std::string kind_;
};

enum class LiveProtocol { kFlightGearNative, kFlightGearGeneric, kXPlane };
std::string_view LiveProtocolName(LiveProtocol protocol);

inline constexpr std::uint32_t kFlightGearNetFdmVersion = 24;
inline constexpr std::size_t kFlightGearNetFdmBytes = 408;
// Larger datagrams are refused unread (X-Plane's DATA with every index is ~5 kB).
inline constexpr std::size_t kMaxPacketBytes = 8192;
inline constexpr std::size_t kXPlaneDataRecordBytes = 36;
inline constexpr std::size_t kXPlaneRposBytes = 69;  // "RPOS", one byte, 64 bytes of values
inline constexpr std::size_t kGenericFields = 7;

// What one datagram says about the aircraft. A packet may carry only part of it (an X-Plane
// DATA packet with index 17 and not 20): the receiver keeps the last of each.
struct LiveFix {
    std::optional<double> lat_deg;  // with lon_deg and height_m: all three or none
    std::optional<double> lon_deg;  // [-180, 180]
    std::optional<double> height_m;
    AltitudeKind altitude_kind = AltitudeKind::kEllipsoid;  // FlightGear; X-Plane: kMsl
    std::optional<geo::Attitude> attitude;
    // The simulator's UTC in whole POSIX seconds (FlightGear: cur_time, /sim/time/gmt), the
    // time warp included; X-Plane sends none.
    std::optional<double> utc_whole_s;
    bool has_position() const { return lat_deg.has_value(); }
};

// Each throws PacketError for a datagram that is not of its kind or holds values out of range.
LiveFix ParseFlightGearNative(std::span<const std::byte> packet);
LiveFix ParseFlightGearGeneric(std::span<const std::byte> packet);
LiveFix ParseXPlane(std::span<const std::byte> packet);
LiveFix ParseLivePacket(LiveProtocol protocol, std::span<const std::byte> packet);

// The simulator's clock from whole seconds and the receiver's own (steady) clock at arrival:
// if the simulator stamps floor(T) at its time T = t + C (t: arrival on the receiver's clock,
// latency aside), every packet bounds the offset, floor(T) - t <= C < floor(T) + 1 - t, and the
// packet in which the second turns over gives C to within the packets' spacing. The estimate is
// the tightest lower bound, so it only grows: the rebuilt time t + C is monotonic while the
// simulator's time runs at the receiver's rate. A packet that contradicts the bounds by more
// than kResetTolerance:
//   - later than the clock allows (the simulator's time was set forward or warped): the clock
//     starts over from it at once (it jumps forward);
//   - earlier (a packet that waited in a stalled simulator: FlightGear stamps its time at the
//     start of a frame and sends at the end; a real run had two in a row, 4 s apart, 1.7 and
//     2.4 s late): it is set aside and counted as late; only when such packets keep coming, at
//     least kLatePacketsToReset of them over kLateResetSeconds (the time was set back), does
//     the clock start over from them.
// resets() counts the restarts.
class WholeSecondClock {
  public:
    static constexpr double kResetTolerance = 0.5;    // s of contradiction
    static constexpr double kLateResetSeconds = 2.0;  // s of only earlier packets: set back
    static constexpr int kLatePacketsToReset = 5;     // and at least this many of them

    // A packet stamped utc_whole_s (whole seconds) arrived at arrival_s (receiver seconds,
    // not decreasing). Returns true when it restarted the clock.
    bool Observe(double utc_whole_s, double arrival_s);
    bool valid() const { return valid_; }
    // The simulator's UTC (POSIX seconds) at receiver time t; requires valid().
    double UtcAt(double receiver_s) const { return receiver_s + lower_; }
    // How far the offset is known: upper - lower bound, seconds (1 after one packet).
    double uncertainty_s() const { return upper_ - lower_; }
    int resets() const { return resets_; }
    // Packets set aside as late (earlier than the clock by more than kResetTolerance).
    int late_packets() const { return late_packets_; }

  private:
    void Restart(double lower, double upper);

    bool valid_ = false;
    double lower_ = 0.0;  // max(whole - arrival)
    double upper_ = 0.0;  // min(whole + 1 - arrival), kept >= lower_
    int resets_ = 0;
    int late_packets_ = 0;
    // The run of late packets since the last consistent one.
    bool late_ = false;
    double late_since_ = 0.0;
    double late_lower_ = 0.0;
    double late_upper_ = 0.0;
    int late_run_ = 0;
};

}  // namespace zenith::track
