// live_check — checks what `zenith live` wrote while a recorded packet stream was replayed into
// it (tests/live/live_replay_test.sh):
//   - every datagram of the recording parses (a recording from a real simulator has no bad one)
//     and packets.csv holds exactly those fixes, in order (nothing lost or reordered on
//     loopback);
//   - live.csv has at least MIN_FRAMES frames, each with its frame file, decodable, of the size;
//   - each frame's position lies on the path between the two packets around its time (within
//     kPositionTolerance or kChordFraction of the chord: the trajectory is a cubic through the
//     packets) and its
//     attitude between theirs (within kAngleTolerance);
//   - the frames' UTC never goes back, and, once the stream has run kClockSettle seconds, the
//     clock's offset from the receiver's is within kClockTolerance of the best bound the whole
//     stream gives (max over packets of whole second - arrival) and never above it.
// Usage: live_check PROTOCOL RECORDING|- OUT_DIR MIN_FRAMES WIDTH HEIGHT
// Prints what it measured; exits 1 naming the first failed check.
#include <fmt/format.h>

#include <GeographicLib/Geocentric.hpp>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "zenith/base/text_lines.h"
#include "zenith/sim/live.h"
#include "zenith/sim/replay.h"
#include "zenith/sky/image_io.h"
#include "zenith/track/live_packets.h"

namespace {

// Off the chord between the two packets: 5 m, or 5 % of the chord, the sagitta L^2 / 8R of a
// turn of radius R = 2.5 L (a cubic through a turn's points bulges like its arc). The 5 m is
// what FlightGear's stalls on llvmpipe cost: packets 0.88 s apart in arrival that moved 4.7 m
// (the simulator's time had stalled, at 45 m/s) give a cubic, its tangents from the neighbouring
// packets, that leaves their chord by 2.3 m; arrival time is all the native packet gives.
constexpr double kPositionTolerance = 5.0;  // m
constexpr double kChordFraction = 0.05;
constexpr double kAngleTolerance = 0.5;   // deg
constexpr double kClockTolerance = 0.05;  // s
constexpr double kClockSettle = 5.0;      // s of packets before the clock is checked

[[noreturn]] void Fail(const std::string& message) {
    fmt::print(stderr, "live_check: FAILED: {}\n", message);
    std::exit(1);
}

std::vector<std::vector<double>> ReadCsv(const std::filesystem::path& path) {
    std::ifstream in(path);
    if (!in) Fail("cannot read " + path.string());
    std::vector<std::vector<double>> rows;
    std::string line;
    std::getline(in, line);  // header
    std::vector<std::string> fields;
    while (std::getline(in, line)) {
        if (!zenith::SplitCsvLine(line, fields)) Fail("bad line in " + path.string());
        std::vector<double> row;
        for (const std::string& f : fields) row.push_back(f.empty() ? NAN : std::stod(f));
        rows.push_back(row);
    }
    return rows;
}

glm::dvec3 Ecef(double lat, double lon, double h) {
    double x, y, z;
    GeographicLib::Geocentric::WGS84().Forward(lat, lon, h, x, y, z);
    return {x, y, z};
}

double DistanceToSegment(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b) {
    const glm::dvec3 ab = b - a;
    const double length2 = glm::dot(ab, ab);
    const double s = length2 > 0.0 ? std::clamp(glm::dot(p - a, ab) / length2, 0.0, 1.0) : 0.0;
    return glm::length(p - (a + s * ab));
}

// How far `angle` lies outside the shorter arc from a to b, degrees (0 inside).
double OutsideArc(double angle, double a, double b) {
    auto wrap = [](double d) { return std::remainder(d, 360.0); };
    const double span = wrap(b - a);
    const double along = wrap(angle - a);
    const double lo = std::min(0.0, span), hi = std::max(0.0, span);
    if (along >= lo && along <= hi) return 0.0;
    return std::min(std::abs(along - lo), std::abs(along - hi));
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 7) {
        fmt::print(stderr, "usage: live_check PROTOCOL RECORDING OUT_DIR MIN_FRAMES W H\n");
        return 2;
    }
    const auto protocol = zenith::sim::ParseLiveProtocol(argv[1]);
    const std::filesystem::path recording = argv[2], out = argv[3];
    const auto min_frames = static_cast<std::size_t>(std::stoul(argv[4]));
    const int width = std::stoi(argv[5]), height = std::stoi(argv[6]);

    // The recording, parsed.
    // RECORDING "-": a live run with no recording (a real simulator): packets.csv is taken as
    // what arrived, and the frames are checked against it.
    std::vector<zenith::track::LiveFix> fixes;
    if (recording != "-") {
        std::ifstream in(recording);
        if (!in) Fail("cannot read " + recording.string());
        std::string line;
        while (std::getline(in, line)) {
            if (line.empty() || line[0] == '#') continue;
            std::istringstream fields(line);
            double t;
            std::string hex;
            fields >> t >> hex;
            std::vector<std::byte> bytes;
            for (std::size_t k = 0; k + 1 < hex.size(); k += 2) {
                bytes.push_back(std::byte(std::stoul(hex.substr(k, 2), nullptr, 16)));
            }
            try {
                fixes.push_back(zenith::track::ParseLivePacket(protocol, bytes));
            } catch (const zenith::track::PacketError& e) {
                Fail(fmt::format("datagram {} of the recording: {}", fixes.size(), e.what()));
            }
        }
    }
    // packets.csv: arrival_s,utc_whole_s,lat_deg,lon_deg,height_m,heading_deg,pitch_deg,roll_deg,
    // kept (0: within kLiveMinSpacing of the last kept, not interpolated through)
    const auto packets = ReadCsv(out / "packets.csv");
    if (recording == "-") {
        for (const auto& p : packets) {
            zenith::track::LiveFix f;
            f.lat_deg = p[2];
            f.lon_deg = p[3];
            f.height_m = p[4];
            if (!std::isnan(p[1])) f.utc_whole_s = p[1];
            fixes.push_back(f);
        }
    }
    if (packets.size() != fixes.size()) {
        Fail(fmt::format("packets.csv has {} fixes, the recording {}", packets.size(),
                         fixes.size()));
    }
    for (std::size_t i = 0; i < fixes.size(); ++i) {
        const auto& f = fixes[i];
        const auto& p = packets[i];
        const bool same =
            std::abs(p[2] - *f.lat_deg) < 1e-8 && std::abs(p[3] - *f.lon_deg) < 1e-8 &&
            std::abs(p[4] - *f.height_m) < 1e-3 && (!f.utc_whole_s || p[1] == *f.utc_whole_s);
        if (!same) Fail(fmt::format("packets.csv line {} is not datagram {}", i + 2, i));
        if (i > 0 && !(p[0] >= packets[i - 1][0])) Fail("packets.csv arrivals go back");
    }
    // The frames are checked against the fixes the trajectory went through.
    std::vector<std::vector<double>> kept;
    for (const auto& p : packets) {
        if (p.size() < 9 || p[8] != 0.0) kept.push_back(p);
    }
    fmt::print("live_check: {} of {} fixes kept for interpolation\n", kept.size(), packets.size());
    // live.csv: frame,receiver_s,utc_s,lat_deg,lon_deg,height_m,heading_deg,pitch_deg,
    // roll_deg,newest_packet_s,render_s
    const auto frames = ReadCsv(out / "live.csv");
    if (frames.size() < min_frames) {
        Fail(fmt::format("{} frames (expected at least {})", frames.size(), min_frames));
    }
    double worst_position = 0.0, worst_angle = 0.0, worst_clock = 0.0, previous_utc = -1e300;
    double render_sum = 0.0;
    // The simulator stamps floor(T) at T = arrival + C - latency, so C >= stamp - arrival for
    // every packet: the largest is the best bound the stream gives (late packets, from
    // FlightGear's frame stalls, only lower their own bound).
    bool has_clock = false;
    double best_offset = -1e300;
    for (const auto& q : packets) {
        if (std::isnan(q[1])) continue;
        has_clock = true;
        best_offset = std::max(best_offset, q[1] - q[0]);
    }
    std::size_t clock_frames = 0;
    for (std::size_t k = 0; k < frames.size(); ++k) {
        const auto& f = frames[k];
        const auto index = static_cast<std::size_t>(f[0]);
        if (index != k)
            Fail(fmt::format("live.csv line {}: frame {} (expected {})", k + 2, index, k));
        const auto png = out / zenith::sim::ReplayFrameName(index, "png");
        const zenith::sky::Srgb8Image image = zenith::sky::ReadPng(png);
        if (image.width != width || image.height != height) {
            Fail(fmt::format("{} is {}x{} (expected {}x{})", png.string(), image.width,
                             image.height, width, height));
        }
        const double t = f[1], utc = f[2];
        if (utc < previous_utc)
            Fail(fmt::format("frame {}: UTC {} before {}", k, utc, previous_utc));
        previous_utc = utc;
        render_sum += f[10];
        // The packets around t.
        std::size_t after = 0;
        while (after < kept.size() && kept[after][0] < t) ++after;
        const std::size_t a = after == 0 ? 0 : after - 1;
        const std::size_t b = std::min(after, kept.size() - 1);
        const glm::dvec3 p = Ecef(f[3], f[4], f[5]);
        const double position = DistanceToSegment(p, Ecef(kept[a][2], kept[a][3], kept[a][4]),
                                                  Ecef(kept[b][2], kept[b][3], kept[b][4]));
        const double chord = glm::length(Ecef(kept[b][2], kept[b][3], kept[b][4]) -
                                         Ecef(kept[a][2], kept[a][3], kept[a][4]));
        const double allowed = std::max(kPositionTolerance, kChordFraction * chord);
        worst_position = std::max(worst_position, position / allowed);
        for (std::size_t c = 6; c <= 8; ++c) {
            worst_angle = std::max(worst_angle, OutsideArc(f[c], kept[a][c - 1], kept[b][c - 1]));
        }
        // The clock, once the stream has run kClockSettle seconds: the offset it used against
        // the best lower bound the whole stream gives.
        if (has_clock && f[9] >= packets.front()[0] + kClockSettle) {
            const double offset = utc - t;
            worst_clock = std::max(worst_clock, std::abs(offset - best_offset));
            if (offset > best_offset + 1e-5) {  // the CSV has microseconds
                Fail(fmt::format("frame {}: clock offset {} above every packet's bound {}", k,
                                 offset, best_offset));
            }
            ++clock_frames;
        }
    }
    fmt::print(
        "live_check: {} datagrams, {} frames; position off the packets' chord <= {:.3f} of the "
        "tolerance, "
        "attitude outside theirs <= {:.3f} deg, clock within {:.3f} s of "
        "the stream's bound ({} frames); {:.3f} s per frame\n",
        fixes.size(), frames.size(), worst_position, worst_angle, worst_clock, clock_frames,
        render_sum / static_cast<double>(frames.size()));
    if (worst_position > 1.0) Fail(fmt::format("position {} of the tolerance", worst_position));
    if (worst_angle > kAngleTolerance) Fail(fmt::format("attitude {} deg", worst_angle));
    if (worst_clock > kClockTolerance) Fail(fmt::format("clock {} s", worst_clock));
    if (has_clock && clock_frames == 0) Fail("no frame late enough to check the clock");
    return 0;
}
