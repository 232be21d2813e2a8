// Simulator datagrams (FlightGear native FDM and generic protocol, X-Plane DATA and RPOS) and
// the clock rebuilt from whole seconds; zenith/track/live_packets.h has the layouts.
#include "zenith/track/live_packets.h"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "zenith/base/units.h"
#include "zenith/geo/time.h"

namespace zenith::track {
namespace {

// Offsets of the FGNetFDM (version 24) fields read here.
constexpr std::size_t kFdmVersion = 0;
constexpr std::size_t kFdmLongitude = 8;
constexpr std::size_t kFdmLatitude = 16;
constexpr std::size_t kFdmAltitude = 24;
constexpr std::size_t kFdmPhi = 36;
constexpr std::size_t kFdmTheta = 40;
constexpr std::size_t kFdmPsi = 44;
constexpr std::size_t kFdmNumEngines = 120;
constexpr std::size_t kFdmNumTanks = 284;
constexpr std::size_t kFdmNumWheels = 304;
constexpr std::size_t kFdmCurTime = 356;
constexpr std::size_t kFdmWarp = 360;
constexpr std::uint32_t kFdmMaxEngines = 4, kFdmMaxTanks = 4, kFdmMaxWheels = 3;

constexpr double kXPlaneUnused = -999.0;  // X-Plane's "no value" in a DATA record
constexpr std::int32_t kXPlaneAttitudeIndex = 17;
constexpr std::int32_t kXPlanePositionIndex = 20;

template <class T>
T Load(std::span<const std::byte> bytes, std::size_t offset, std::endian order) {
    static_assert(sizeof(T) == 4 || sizeof(T) == 8);
    using Bits = std::conditional_t<sizeof(T) == 4, std::uint32_t, std::uint64_t>;
    Bits bits = 0;
    for (std::size_t i = 0; i < sizeof(T); ++i) {
        const auto byte = static_cast<Bits>(std::to_integer<unsigned>(bytes[offset + i]));
        const std::size_t shift = order == std::endian::big ? 8 * (sizeof(T) - 1 - i) : 8 * i;
        bits |= byte << shift;
    }
    return std::bit_cast<T>(bits);
}

[[noreturn]] void Fail(LiveProtocol protocol, std::string_view kind, const std::string& message) {
    throw PacketError(std::string(kind),
                      fmt::format("{} packet: {}", LiveProtocolName(protocol), message));
}

double Check(LiveProtocol protocol, std::string_view field, double value, std::string_view unit,
             const Range& range) {
    if (!range.Contains(value)) Fail(protocol, field, RangeMessage(field, value, unit, range));
    return value;
}

void SetPosition(LiveProtocol protocol, LiveFix& fix, double lat_deg, double lon_deg,
                 double height_m) {
    fix.lat_deg = Check(protocol, "latitude", lat_deg, "deg", Range::Closed(-90.0, 90.0));
    fix.lon_deg = Check(protocol, "longitude", lon_deg, "deg", Range::Closed(-180.0, 180.0));
    fix.height_m =
        Check(protocol, "altitude", height_m, "m", Range::Closed(kMinLogAltitude, kMaxLogAltitude));
}

// Heading in any turn of [-360, 720] degrees (simulators send 0..360 or -180..180), pitch
// [-90, 90], roll [-180, 180] (+ a little rounding).
void SetAttitude(LiveProtocol protocol, LiveFix& fix, double heading_deg, double pitch_deg,
                 double roll_deg) {
    constexpr double kSlack = 1e-3;
    Check(protocol, "heading", heading_deg, "deg", Range::Closed(-360.0, 720.0));
    Check(protocol, "pitch", pitch_deg, "deg", Range::Closed(-90.0 - kSlack, 90.0 + kSlack));
    Check(protocol, "roll", roll_deg, "deg", Range::Closed(-180.0 - kSlack, 180.0 + kSlack));
    fix.attitude = geo::Attitude::FromDegrees(heading_deg, std::clamp(pitch_deg, -90.0, 90.0),
                                              std::clamp(roll_deg, -180.0, 180.0));
}

void SetUtc(LiveProtocol protocol, LiveFix& fix, double utc_s) {
    fix.utc_whole_s =
        Check(protocol, "time", utc_s, "s (POSIX)", Range::Closed(kMinLogTime, kMaxLogTime));
}

std::string_view Printable(std::string_view text) {
    constexpr std::size_t kShown = 40;
    return text.substr(0, std::min(text.size(), kShown));
}

double ParseNumber(LiveProtocol protocol, std::string_view field, std::string_view text) {
    std::string s(text);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\r')) s.pop_back();
    std::size_t first = s.find_first_not_of(' ');
    if (first == std::string::npos || s.size() > 64) {
        Fail(protocol, field, fmt::format("{} = '{}' is not a number", field, Printable(text)));
    }
    s = s.substr(first);
    char* end = nullptr;
    const double value = std::strtod(s.c_str(), &end);
    if (end != s.c_str() + s.size()) {
        Fail(protocol, field, fmt::format("{} = '{}' is not a number", field, Printable(text)));
    }
    return value;
}

}  // namespace

std::string_view LiveProtocolName(LiveProtocol protocol) {
    switch (protocol) {
        case LiveProtocol::kFlightGearNative:
            return "FlightGear native FDM";
        case LiveProtocol::kFlightGearGeneric:
            return "FlightGear generic (zenith.xml)";
        case LiveProtocol::kXPlane:
            return "X-Plane";
    }
    return "?";
}

LiveFix ParseFlightGearNative(std::span<const std::byte> packet) {
    constexpr LiveProtocol p = LiveProtocol::kFlightGearNative;
    if (packet.size() < 4) {
        Fail(p, "size",
             fmt::format("size {} bytes is too short for the version field", packet.size()));
    }
    const auto version = Load<std::uint32_t>(packet, kFdmVersion, std::endian::big);
    if (version != kFlightGearNetFdmVersion) {
        Fail(p, "version",
             fmt::format("version {} is not supported (expected FG_NET_FDM_VERSION {}{})", version,
                         kFlightGearNetFdmVersion,
                         Load<std::uint32_t>(packet, kFdmVersion, std::endian::little) ==
                                 kFlightGearNetFdmVersion
                             ? "; the packet is in little-endian order, not network order"
                             : ""));
    }
    if (packet.size() != kFlightGearNetFdmBytes) {
        Fail(p, "size",
             fmt::format("size {} bytes (expected {} for version {})", packet.size(),
                         kFlightGearNetFdmBytes, kFlightGearNetFdmVersion));
    }
    const struct {
        const char* name;
        std::size_t offset;
        std::uint32_t max;
    } counts[] = {{"num_engines", kFdmNumEngines, kFdmMaxEngines},
                  {"num_tanks", kFdmNumTanks, kFdmMaxTanks},
                  {"num_wheels", kFdmNumWheels, kFdmMaxWheels}};
    for (const auto& c : counts) {
        const auto n = Load<std::uint32_t>(packet, c.offset, std::endian::big);
        if (n > c.max) Fail(p, c.name, fmt::format("{} = {} (expected 0 to {})", c.name, n, c.max));
    }
    LiveFix fix;
    fix.altitude_kind = AltitudeKind::kEllipsoid;
    const double lon = Load<double>(packet, kFdmLongitude, std::endian::big);
    const double lat = Load<double>(packet, kFdmLatitude, std::endian::big);
    Check(p, "longitude", lon, "rad", Range::Closed(-kPi, kPi));
    Check(p, "latitude", lat, "rad", Range::Closed(-kPi / 2, kPi / 2));
    SetPosition(p, fix, std::clamp(Degrees(lat), -90.0, 90.0),
                std::clamp(Degrees(lon), -180.0, 180.0),
                Load<double>(packet, kFdmAltitude, std::endian::big));
    const double phi = Load<float>(packet, kFdmPhi, std::endian::big);
    const double theta = Load<float>(packet, kFdmTheta, std::endian::big);
    const double psi = Load<float>(packet, kFdmPsi, std::endian::big);
    for (const auto& [name, value] :
         {std::pair{"phi (roll)", phi}, std::pair{"theta (pitch)", theta},
          std::pair{"psi (heading)", psi}}) {
        Check(p, name, value, "rad", Range::Closed(-4.0 * kPi, 4.0 * kPi));
    }
    SetAttitude(p, fix, Degrees(psi), Degrees(theta), Degrees(phi));
    // cur_time is unsigned 32-bit POSIX time (FlightGear's own FIXME: until 2106 read as
    // unsigned); 0 before FlightGear has set its clock.
    const auto cur_time = Load<std::uint32_t>(packet, kFdmCurTime, std::endian::big);
    const auto warp = Load<std::int32_t>(packet, kFdmWarp, std::endian::big);
    Check(p, "warp", warp, "s", Range::Closed(-kMaxLogTime, kMaxLogTime));
    if (cur_time != 0) SetUtc(p, fix, static_cast<double>(cur_time));
    return fix;
}

LiveFix ParseFlightGearGeneric(std::span<const std::byte> packet) {
    constexpr LiveProtocol p = LiveProtocol::kFlightGearGeneric;
    if (packet.size() > kMaxPacketBytes) {
        Fail(p, "size",
             fmt::format("size {} bytes (expected at most {})", packet.size(), kMaxPacketBytes));
    }
    std::string_view text(reinterpret_cast<const char*>(packet.data()), packet.size());
    // One line: FlightGear ends it with "\n" (line_separator newline); "\r\n" is accepted.
    if (!text.empty() && text.back() == '\n') text.remove_suffix(1);
    if (!text.empty() && text.back() == '\r') text.remove_suffix(1);
    if (text.find_first_of(std::string_view("\n\0", 2)) != std::string_view::npos) {
        Fail(p, "lines", "more than one line, or a NUL byte (expected one line of text)");
    }
    std::vector<std::string_view> fields;
    std::size_t start = 0;
    while (fields.size() <= kGenericFields) {
        const std::size_t comma = text.find(',', start);
        fields.push_back(text.substr(
            start, comma == std::string_view::npos ? text.size() - start : comma - start));
        if (comma == std::string_view::npos) break;
        start = comma + 1;
    }
    if (fields.size() != kGenericFields) {
        Fail(p, "fields",
             fmt::format(
                 "{} fields (expected {}: gmt,lat,lon,alt_ft,heading,pitch,roll, as "
                 "data/flightgear/zenith.xml sends them)",
                 fields.size() > kGenericFields ? "more than 7" : std::to_string(fields.size()),
                 kGenericFields));
    }
    LiveFix fix;
    fix.altitude_kind = AltitudeKind::kEllipsoid;
    // /sim/time/gmt: "YYYY-MM-DDTHH:MM:SS" (FlightGear's own format: no zone, UTC).
    std::string gmt(fields[0].substr(0, std::min<std::size_t>(fields[0].size(), 32)));
    if (fields[0].size() != 19) {
        Fail(p, "gmt",
             fmt::format("gmt = '{}' (expected YYYY-MM-DDTHH:MM:SS)", Printable(fields[0])));
    }
    try {
        SetUtc(p, fix, geo::UnixSecondsFromCivil(geo::ParseIso8601(gmt + "Z")));
    } catch (const PacketError&) {
        throw;
    } catch (const Error& e) {
        Fail(p, "gmt", fmt::format("gmt = '{}': {}", gmt, e.what()));
    }
    const double lat = ParseNumber(p, "latitude", fields[1]);
    const double lon = ParseNumber(p, "longitude", fields[2]);
    const double alt_ft = ParseNumber(p, "altitude", fields[3]);
    Check(p, "altitude", alt_ft, "ft",
          Range::Closed(kMinLogAltitude / kMetresPerFoot, kMaxLogAltitude / kMetresPerFoot));
    SetPosition(p, fix, lat, lon, alt_ft * kMetresPerFoot);
    SetAttitude(p, fix, ParseNumber(p, "heading", fields[4]), ParseNumber(p, "pitch", fields[5]),
                ParseNumber(p, "roll", fields[6]));
    return fix;
}

LiveFix ParseXPlane(std::span<const std::byte> packet) {
    constexpr LiveProtocol p = LiveProtocol::kXPlane;
    if (packet.size() > kMaxPacketBytes) {
        Fail(p, "size",
             fmt::format("size {} bytes (expected at most {})", packet.size(), kMaxPacketBytes));
    }
    if (packet.size() < 5) {
        Fail(p, "size",
             fmt::format("size {} bytes is too short for a header (expected DATA or RPOS "
                         "and one byte)",
                         packet.size()));
    }
    const std::string_view head(reinterpret_cast<const char*>(packet.data()), 4);
    LiveFix fix;
    fix.altitude_kind = AltitudeKind::kMsl;
    if (head == "RPOS") {
        if (packet.size() != kXPlaneRposBytes) {
            Fail(p, "size",
                 fmt::format("RPOS size {} bytes (expected {})", packet.size(), kXPlaneRposBytes));
        }
        const double lon = Load<double>(packet, 5, std::endian::little);
        const double lat = Load<double>(packet, 13, std::endian::little);
        const double elevation = Load<double>(packet, 21, std::endian::little);
        SetPosition(p, fix, lat, lon, elevation);
        const double pitch = Load<float>(packet, 33, std::endian::little);
        const double heading = Load<float>(packet, 37, std::endian::little);
        const double roll = Load<float>(packet, 41, std::endian::little);
        SetAttitude(p, fix, heading, pitch, roll);
        return fix;
    }
    if (head != "DATA") {
        std::string shown;
        for (const char c : head) shown += (c >= 32 && c < 127) ? c : '?';
        Fail(p, "header", fmt::format("header '{}' (expected DATA or RPOS)", shown));
    }
    const std::size_t body = packet.size() - 5;
    if (body == 0 || body % kXPlaneDataRecordBytes != 0) {
        Fail(p, "size",
             fmt::format("DATA size {} bytes (expected 5 + a multiple of {})", packet.size(),
                         kXPlaneDataRecordBytes));
    }
    bool any = false;
    for (std::size_t at = 5; at < packet.size(); at += kXPlaneDataRecordBytes) {
        const auto index = Load<std::int32_t>(packet, at, std::endian::little);
        float v[8];
        for (int i = 0; i < 8; ++i) {
            v[i] =
                Load<float>(packet, at + 4 + 4 * static_cast<std::size_t>(i), std::endian::little);
        }
        auto value = [&](int i, const char* name) -> double {
            if (v[i] == kXPlaneUnused) {
                Fail(p, name, fmt::format("DATA index {}: {} is unset (-999)", index, name));
            }
            return v[i];
        };
        if (index == kXPlanePositionIndex) {
            const double lat = value(0, "latitude"), lon = value(1, "longitude");
            const double alt_ft = value(2, "altitude");
            Check(
                p, "altitude", alt_ft, "ft",
                Range::Closed(kMinLogAltitude / kMetresPerFoot, kMaxLogAltitude / kMetresPerFoot));
            SetPosition(p, fix, lat, lon, alt_ft * kMetresPerFoot);
            any = true;
        } else if (index == kXPlaneAttitudeIndex) {
            const double pitch = value(0, "pitch"), roll = value(1, "roll");
            SetAttitude(p, fix, value(2, "true heading"), pitch, roll);
            any = true;
        }
    }
    if (!any) {
        Fail(p, "indices",
             fmt::format("DATA without index {} or {} (enable 'lat, lon, altitude' and "
                         "'pitch, roll, headings' in X-Plane's Data Output)",
                         kXPlaneAttitudeIndex, kXPlanePositionIndex));
    }
    return fix;
}

LiveFix ParseLivePacket(LiveProtocol protocol, std::span<const std::byte> packet) {
    switch (protocol) {
        case LiveProtocol::kFlightGearNative:
            return ParseFlightGearNative(packet);
        case LiveProtocol::kFlightGearGeneric:
            return ParseFlightGearGeneric(packet);
        case LiveProtocol::kXPlane:
            return ParseXPlane(packet);
    }
    throw PacketError("protocol", "unknown protocol");
}

void WholeSecondClock::Restart(double lower, double upper) {
    lower_ = lower;
    upper_ = std::max(upper, lower);
    late_ = false;
}

bool WholeSecondClock::Observe(double utc_whole_s, double arrival_s) {
    const double lower = utc_whole_s - arrival_s;
    const double upper = utc_whole_s + 1.0 - arrival_s;
    if (!valid_) {
        valid_ = true;
        Restart(lower, upper);
        return false;
    }
    if (lower > upper_ + kResetTolerance) {  // later than the clock allows: set forward
        Restart(lower, upper);
        ++resets_;
        return true;
    }
    if (upper < lower_ - kResetTolerance) {  // earlier: late, or set back if it lasts
        ++late_packets_;
        if (!late_) {
            late_ = true;
            late_since_ = arrival_s;
            late_lower_ = lower;
            late_upper_ = upper;
            late_run_ = 0;
        } else {
            late_lower_ = std::max(late_lower_, lower);
            late_upper_ = std::min(late_upper_, upper);
        }
        ++late_run_;
        if (late_run_ >= kLatePacketsToReset && arrival_s - late_since_ >= kLateResetSeconds) {
            Restart(late_lower_, late_upper_);
            ++resets_;
            return true;
        }
        return false;
    }
    late_ = false;
    lower_ = std::max(lower_, lower);
    // A packet late by less than the tolerance can push the upper bound under the lower one:
    // the lower bound, from the packets that came soonest after a turn of the second, stays.
    upper_ = std::max(std::min(upper_, upper), lower_);
    return false;
}

}  // namespace zenith::track
