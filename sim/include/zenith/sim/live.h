// `zenith live`: follow a running simulator over UDP and render its sky, offscreen.
//
// A receiver thread reads one UDP socket (FlightGear native FDM, FlightGear generic with
// data/flightgear/zenith.xml, or X-Plane DATA/RPOS: zenith/track/live_packets.h), stamps each
// datagram with the receiver's steady clock and parses it; a malformed one is counted, and
// its first few problems are kept, never fatal. The simulator's clock is rebuilt from its whole
// seconds and the arrival times (track::WholeSecondClock; X-Plane sends no time: the receiver's
// UTC). The aircraft is interpolated between the last kLiveWindow fixes with the replay's
// trajectory code (track::Trajectory: cubic Hermite positions, slerped attitudes), delay_s
// behind the newest packet so that a frame falls between two packets; each frame's UTC is the
// rebuilt clock at that instant, fed to SkySystem::SetTime.
//
// Every every_s seconds (receiver time) a frame is rendered and written under out_dir as
// frame_NNNNNN.png / .exr (atomically: a reader never sees half a frame); live.csv gets one
// line per frame with what it was drawn from, packets.csv one line per usable packet (and
// whether it was kept for interpolation: one within kLiveMinSpacing of the last is not). It stops
// after max_frames frames, after duration_s seconds, or when `stop` becomes true (SIGINT,
// SIGTERM), after the frame in progress.
//
// What input may cost is bounded: datagrams over track::kMaxPacketBytes are refused unread, the
// window of fixes is kLiveWindow, the lists of problems kLiveProblemsKept.
#pragma once

#include <atomic>
#include <cstddef>
#include <filesystem>
#include <functional>
#include <glm/glm.hpp>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "zenith/sky/image_io.h"
#include "zenith/track/live_packets.h"

namespace zenith::sim {

inline constexpr std::size_t kLiveWindow = 64;        // fixes kept for interpolation
inline constexpr std::size_t kLiveProblemsKept = 16;  // first problems listed in the result
inline constexpr std::size_t kMaxLiveFrames = 10'000'000;
// Fixes arriving closer than this to the last one kept are not interpolated through (a burst).
inline constexpr double kLiveMinSpacing = 0.02;  // s

// "fg-native" | "fg-generic" | "xplane"; throws ArgumentError (field "protocol").
track::LiveProtocol ParseLiveProtocol(const std::string& text);

struct LiveRequest {
    track::LiveProtocol protocol = track::LiveProtocol::kFlightGearNative;
    std::string bind_address = "127.0.0.1";  // IPv4 address to listen on (0.0.0.0: every one)
    int port = 5501;                         // 0: a free port, reported by on_listening
    std::filesystem::path out_dir = "live";
    double every_s = 1.0;  // seconds between frames (receiver's clock)
    std::optional<std::size_t> max_frames;
    std::optional<double> duration_s;  // seconds from the start
    double delay_s = 0.2;              // how far behind the newest packet frames are drawn
    glm::ivec2 size{640, 360};
    double fov_deg = 60.0;
    sky::Exposure exposure;
    bool write_png = true;
    bool write_exr = false;
    std::string preset = "earth";
    std::string weather = "clear";
};

// Throws ArgumentError naming the field for a request that cannot run.
void ValidateLiveRequest(const LiveRequest& request);

struct LiveResult {
    std::size_t frames = 0;
    std::size_t packets = 0;  // datagrams received
    std::size_t used = 0;     // parsed into a fix
    // Malformed datagrams: how many, by what was wrong (track::PacketError::kind()), and the
    // first kLiveProblemsKept messages in full.
    std::size_t malformed = 0;
    std::map<std::string, std::size_t> malformed_by_kind;
    std::vector<std::string> first_problems;
    int clock_resets = 0;
    int late_packets = 0;
    std::size_t bunched = 0;  // fixes that came within kLiveMinSpacing of the last one kept  //
                              // stamped earlier than the clock allows, set aside (WholeSecondClock)
    bool interrupted = false;
    int port = 0;
    double render_seconds = 0.0;  // rendering and writing, all frames
};

// Throws ArgumentError (a bad request), an Error when the socket cannot be bound, or the
// renderer's and writers' errors. on_listening is called with the bound port before any
// packet is read.
LiveResult RunLive(const LiveRequest& request, const std::atomic<bool>& stop,
                   const std::function<void(int port)>& on_listening = {});

}  // namespace zenith::sim
