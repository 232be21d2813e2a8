// `zenith live` (zenith/sim/live.h): a UDP receiver thread, the rebuilt clock, interpolation
// with track::Trajectory and offscreen frames through SkySystem's public API.
#include "zenith/sim/live.h"

#include <arpa/inet.h>
#include <fmt/format.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <deque>
#include <fstream>
#include <memory>
#include <mutex>
#include <thread>

#include "zenith/base/atomic_file.h"
#include "zenith/base/error.h"
#include "zenith/base/units.h"
#include "zenith/geo/frames.h"
#include "zenith/geo/observer.h"
#include "zenith/geo/time.h"
#include "zenith/sim/render_frame.h"
#include "zenith/sim/replay.h"
#include "zenith/sim/sky_system.h"
#include "zenith/track/trajectory.h"

namespace zenith::sim {
namespace {

namespace fs = std::filesystem;
using SteadyClock = std::chrono::steady_clock;

class Socket {
  public:
    explicit Socket(int fd) : fd_(fd) {}
    ~Socket() {
        if (fd_ >= 0) close(fd_);
    }
    Socket(const Socket&) = delete;
    Socket& operator=(const Socket&) = delete;
    int fd() const { return fd_; }

  private:
    int fd_;
};

std::unique_ptr<Socket> BindUdp(const std::string& address, int port, int* bound_port) {
    sockaddr_in where{};
    where.sin_family = AF_INET;
    where.sin_port = htons(static_cast<std::uint16_t>(port));
    if (inet_pton(AF_INET, address.c_str(), &where.sin_addr) != 1) {
        throw ArgumentError("bind_address", "bind_address = " + address +
                                                " is not an IPv4 address (expected a.b.c.d)");
    }
    auto socket_fd = std::make_unique<Socket>(socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0));
    if (socket_fd->fd() < 0) throw Error(fmt::format("socket: {}", std::strerror(errno)));
    if (bind(socket_fd->fd(), reinterpret_cast<const sockaddr*>(&where), sizeof where) != 0) {
        throw Error(
            fmt::format("cannot listen on UDP {}:{}: {}", address, port, std::strerror(errno)));
    }
    socklen_t length = sizeof where;
    getsockname(socket_fd->fd(), reinterpret_cast<sockaddr*>(&where), &length);
    *bound_port = ntohs(where.sin_port);
    return socket_fd;
}

struct TimedFix {
    double arrival_s;  // receiver's steady clock, seconds since the run started
    double lat_deg, lon_deg, height_m;
    track::AltitudeKind kind;
    std::optional<geo::Attitude> attitude;
};

// What the receiver thread shares with the renderer.
struct Shared {
    std::mutex mutex;
    std::deque<TimedFix> window;
    track::WholeSecondClock clock;
    LiveResult counts;
};

void NotePacketProblem(LiveResult& r, const std::string& kind, const std::string& message) {
    ++r.malformed;
    ++r.malformed_by_kind[kind];
    if (r.first_problems.size() < kLiveProblemsKept) r.first_problems.push_back(message);
}

void Receive(const Socket& socket, track::LiveProtocol protocol, SteadyClock::time_point start,
             const std::atomic<bool>& quit, Shared& shared, std::ofstream& packet_log) {
    std::vector<std::byte> buffer(track::kMaxPacketBytes + 1);
    // What the packets said last (an X-Plane DATA packet may carry only part of it).
    std::optional<TimedFix> last;
    while (!quit.load()) {
        pollfd p{socket.fd(), POLLIN, 0};
        if (poll(&p, 1, 50) <= 0) continue;
        // MSG_TRUNC: the datagram's real length, though at most the buffer is copied.
        const ssize_t n = recv(socket.fd(), buffer.data(), buffer.size(), MSG_TRUNC);
        const double arrival = std::chrono::duration<double>(SteadyClock::now() - start).count();
        if (n < 0) continue;
        const auto size = static_cast<std::size_t>(n);
        std::lock_guard lock(shared.mutex);
        ++shared.counts.packets;
        if (size > track::kMaxPacketBytes) {
            NotePacketProblem(
                shared.counts, "size",
                fmt::format("{} packet: size {} bytes (expected at most {})",
                            track::LiveProtocolName(protocol), size, track::kMaxPacketBytes));
            continue;
        }
        track::LiveFix fix;
        try {
            fix = track::ParseLivePacket(protocol, std::span(buffer.data(), size));
        } catch (const track::PacketError& e) {
            NotePacketProblem(shared.counts, e.kind(), e.what());
            continue;
        }
        ++shared.counts.used;
        if (fix.utc_whole_s) {
            shared.clock.Observe(*fix.utc_whole_s, arrival);
        }
        TimedFix timed = last.value_or(TimedFix{arrival, 0.0, 0.0, 0.0, fix.altitude_kind, {}});
        timed.arrival_s = arrival;
        if (fix.has_position()) {
            timed.lat_deg = *fix.lat_deg;
            timed.lon_deg = *fix.lon_deg;
            timed.height_m = *fix.height_m;
            timed.kind = fix.altitude_kind;
        }
        if (fix.attitude) timed.attitude = fix.attitude;
        if (!fix.has_position() && !last) continue;  // no position yet
        last = timed;
        // A fix that arrives within kLiveMinSpacing of the last one kept (a burst: the
        // simulator or this machine was stalled) is not interpolated through: its arrival time
        // says nothing of when it was sent, and the trajectory's tangents would divide its
        // displacement by that tiny interval (kilometres of overshoot under load).
        const bool kept =
            shared.window.empty() || arrival >= shared.window.back().arrival_s + kLiveMinSpacing;
        if (kept) {
            shared.window.push_back(timed);
            while (shared.window.size() > kLiveWindow) shared.window.pop_front();
        } else {
            ++shared.counts.bunched;
        }
        const geo::Attitude a = timed.attitude.value_or(geo::Attitude{});
        packet_log << fmt::format("{:.6f},{},{:.9f},{:.9f},{:.3f},{:.4f},{:.4f},{:.4f},{}\n",
                                  arrival, fix.utc_whole_s ? FormatValue(*fix.utc_whole_s) : "",
                                  timed.lat_deg, timed.lon_deg, timed.height_m,
                                  Degrees(a.heading_rad), Degrees(a.pitch_rad), Degrees(a.roll_rad),
                                  kept ? 1 : 0);
    }
}

track::FlightLog LogOf(const std::deque<TimedFix>& window) {
    track::FlightLog log;
    log.source = "live";
    const bool attitude = std::all_of(window.begin(), window.end(),
                                      [](const TimedFix& f) { return f.attitude.has_value(); });
    for (const TimedFix& f : window) {
        track::FlightSample s;
        s.time_s = f.arrival_s;
        s.lat_deg = f.lat_deg;
        s.lon_deg = f.lon_deg;
        (f.kind == track::AltitudeKind::kMsl ? s.msl_altitude : s.ellipsoid_height) = f.height_m;
        if (attitude) s.attitude = f.attitude;
        s.line = static_cast<int>(log.samples.size()) + 1;
        log.samples.push_back(s);
    }
    log.summary.records = log.summary.used = static_cast<int>(log.samples.size());
    return log;
}

}  // namespace

track::LiveProtocol ParseLiveProtocol(const std::string& text) {
    if (text == "fg-native") return track::LiveProtocol::kFlightGearNative;
    if (text == "fg-generic") return track::LiveProtocol::kFlightGearGeneric;
    if (text == "xplane") return track::LiveProtocol::kXPlane;
    throw ArgumentError("protocol", "protocol = " + text +
                                        " is not known (expected fg-native, fg-generic or xplane)");
}

void ValidateLiveRequest(const LiveRequest& r) {
    Require("port", r.port, "", Range::Closed(0, 65535));
    Require("every_s", r.every_s, "s", Range::LeftOpen(0.0, 86400.0));
    Require("delay_s", r.delay_s, "s", Range::Closed(0.0, 60.0));
    Require("fov_deg", r.fov_deg, "deg", Range::Open(0.0, 180.0));
    if (r.duration_s) Require("duration_s", *r.duration_s, "s", Range::LeftOpen(0.0, 1e7));
    if (r.max_frames) {
        Require("frames", static_cast<double>(*r.max_frames), "",
                Range::Closed(1, static_cast<double>(kMaxLiveFrames)));
    }
    for (int side : {r.size.x, r.size.y}) {
        Require("size", side, "px", Range::Closed(1, kMaxFrameSide));
    }
    if (!r.write_png && !r.write_exr) {
        throw ArgumentError("format", "no frame format chosen (expected png, exr or both)");
    }
    if (r.out_dir.empty()) throw ArgumentError("out", "out is empty (expected a folder)");
}

LiveResult RunLive(const LiveRequest& r, const std::atomic<bool>& stop,
                   const std::function<void(int port)>& on_listening) {
    ValidateLiveRequest(r);
    SkySystemSettings settings;
    settings.preset = r.preset;
    settings.refraction = PresetRefraction(r.preset);
    settings.weather = r.weather;
    settings.clouds.block = 1;
    auto sky = SkySystem::CreateHeadless(settings);
    sky->SetProjection(Radians(r.fov_deg), static_cast<double>(r.size.x) / r.size.y);
    sky->Prepare(r.size);  // the first frame then costs what any frame costs
    fs::create_directories(r.out_dir);

    int port = 0;
    const auto socket = BindUdp(r.bind_address, r.port, &port);
    if (on_listening) on_listening(port);

    std::ofstream packet_log(r.out_dir / "packets.csv", std::ios::trunc);
    packet_log << "arrival_s,utc_whole_s,lat_deg,lon_deg,height_m,heading_deg,pitch_deg,"
                  "roll_deg,kept\n";
    std::ofstream frame_log(r.out_dir / "live.csv", std::ios::trunc);
    frame_log << "frame,receiver_s,utc_s,lat_deg,lon_deg,height_m,heading_deg,pitch_deg,"
                 "roll_deg,newest_packet_s,render_s\n";
    if (!packet_log || !frame_log) {
        throw FileError("cannot write packets.csv and live.csv in " + r.out_dir.string());
    }

    const auto start = SteadyClock::now();
    const double unix_at_start =
        std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
    Shared shared;
    std::atomic<bool> quit{false};
    std::thread receiver(Receive, std::cref(*socket), r.protocol, start, std::cref(quit),
                         std::ref(shared), std::ref(packet_log));
    struct Join {
        std::atomic<bool>& quit;
        std::thread& thread;
        ~Join() {
            quit.store(true);
            if (thread.joinable()) thread.join();
        }
    } join{quit, receiver};

    LiveResult result;
    result.port = port;
    auto now_s = [&] { return std::chrono::duration<double>(SteadyClock::now() - start).count(); };
    double next_frame = 0.0;
    track::TrajectoryOptions options;
    options.max_gap_s = 10.0;
    while (true) {
        if (stop.load()) {
            result.interrupted = true;
            break;
        }
        if (r.duration_s && now_s() >= *r.duration_s) break;
        if (r.max_frames && result.frames >= *r.max_frames) break;
        if (now_s() < next_frame) {
            std::this_thread::sleep_for(std::chrono::milliseconds(
                std::clamp(static_cast<int>((next_frame - now_s()) * 1000.0), 1, 50)));
            continue;
        }
        std::deque<TimedFix> window;
        track::WholeSecondClock clock;
        {
            std::lock_guard lock(shared.mutex);
            window = shared.window;
            clock = shared.clock;
        }
        const bool needs_clock = r.protocol != track::LiveProtocol::kXPlane;
        if (window.size() < 2 || (needs_clock && !clock.valid())) {
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
            continue;
        }
        const double frame_started = now_s();
        const track::Trajectory trajectory(LogOf(window), options);
        const double t = std::clamp(frame_started - r.delay_s, trajectory.start_time_s(),
                                    trajectory.end_time_s());
        track::TrajectoryState state = trajectory.At(t);
        if (!state.valid) state = trajectory.At(trajectory.end_time_s());
        const double utc = needs_clock ? clock.UtcAt(t) : unix_at_start + t;
        sky->SetTime(geo::TimeFromUnixSeconds(utc));
        sky->SetEcef(state.ecef);
        sky->SetViewFromEnu(geo::Observer::FromEcef(state.ecef).enu_from_ecef() *
                            glm::mat3_cast(state.ecef_from_body) * geo::BodyFromView());
        // Frames are every_s apart: nothing to reproject from the last one (as in replay).
        sky->ResetCloudHistory();
        sky->Update();
        const sky::LutImage frame = sky->RenderOffscreen(r.size);
        sky::Image image(r.size.x, r.size.y);
        for (int y = 0; y < r.size.y; ++y) {
            for (int x = 0; x < r.size.x; ++x) image.at(x, y) = frame.at(x, r.size.y - 1 - y);
        }
        if (r.write_exr) sky::WriteImage(r.out_dir / ReplayFrameName(result.frames, "exr"), image);
        if (r.write_png) {
            sky::ImageWriteOptions write;
            write.exposure = r.exposure;
            sky::WriteImage(r.out_dir / ReplayFrameName(result.frames, "png"), image, write);
        }
        const double render_s = now_s() - frame_started;
        result.render_seconds += render_s;
        const geo::Attitude a =
            geo::AttitudeFromEcefFromBody(state.ecef_from_body, state.lat_deg, state.lon_deg);
        frame_log << fmt::format(
            "{},{:.6f},{:.6f},{:.9f},{:.9f},{:.3f},{:.4f},{:.4f},{:.4f},{:.6f},"
            "{:.4f}\n",
            result.frames, t, utc, state.lat_deg, state.lon_deg, state.height,
            Degrees(a.heading_rad), Degrees(a.pitch_rad), Degrees(a.roll_rad),
            window.back().arrival_s, render_s);
        frame_log.flush();
        ++result.frames;
        // The next slot; slots missed while this frame was drawn are skipped.
        next_frame += r.every_s;
        if (next_frame <= frame_started) next_frame = frame_started + r.every_s;
    }
    quit.store(true);
    receiver.join();
    {
        std::lock_guard lock(shared.mutex);
        result.packets = shared.counts.packets;
        result.used = shared.counts.used;
        result.malformed = shared.counts.malformed;
        result.malformed_by_kind = shared.counts.malformed_by_kind;
        result.bunched = shared.counts.bunched;
        result.first_problems = shared.counts.first_problems;
        result.clock_resets = shared.clock.resets();
        result.late_packets = shared.clock.late_packets();
    }
    return result;
}

}  // namespace zenith::sim
