// libFuzzer harness for the simulators' UDP datagrams (zenith/track/live_packets.h): the first
// byte chooses the protocol (mod 3), the rest is the datagram. Each parser must return a fix
// whose values are finite and in range, or throw PacketError; and the rebuilt clock must stay
// monotonic for whatever whole seconds the packets carry at increasing arrival times.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>

#include "zenith/track/live_packets.h"

namespace {

void Check(bool ok) {
    if (!ok) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace zenith::track;
    if (size == 0) return 0;
    const auto protocol = static_cast<LiveProtocol>(data[0] % 3);
    const std::span<const std::byte> packet(reinterpret_cast<const std::byte*>(data + 1), size - 1);
    try {
        const LiveFix fix = ParseLivePacket(protocol, packet);
        Check(fix.lat_deg.has_value() == fix.lon_deg.has_value() &&
              fix.lat_deg.has_value() == fix.height_m.has_value());
        if (fix.has_position()) {
            Check(std::abs(*fix.lat_deg) <= 90.0 && std::abs(*fix.lon_deg) <= 180.0);
            Check(*fix.height_m >= kMinLogAltitude && *fix.height_m <= kMaxLogAltitude);
        }
        if (fix.attitude) {
            Check(std::isfinite(fix.attitude->heading_rad) &&
                  std::abs(fix.attitude->pitch_rad) <= 1.5708 &&
                  std::abs(fix.attitude->roll_rad) <= 3.1416);
        }
        if (fix.utc_whole_s) Check(std::isfinite(*fix.utc_whole_s));
        if (!fix.has_position() && !fix.attitude) Check(protocol != LiveProtocol::kXPlane);
    } catch (const PacketError&) {
    }
    // The clock: whole seconds from the bytes, arrivals 50 ms apart. Between resets the
    // rebuilt time never goes back.
    WholeSecondClock clock;
    double previous = 0.0;
    int resets = 0;
    for (std::size_t i = 0; i + 1 < size && i < 256; ++i) {
        const double arrival = 0.05 * static_cast<double>(i);
        const double whole = 1.7e9 + static_cast<double>(data[i + 1] % 8);
        const bool reset = clock.Observe(whole, arrival);
        const double now = clock.UtcAt(arrival);
        Check(std::isfinite(now));
        if (reset) ++resets;
        if (i > 0 && !reset) Check(now >= previous);
        previous = now;
    }
    Check(resets == clock.resets());
    return 0;
}
