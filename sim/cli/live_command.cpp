// `zenith live`: follow a running simulator over UDP and write its sky as frames
// (zenith/sim/live.h).
#include <fmt/format.h>

#include <atomic>
#include <memory>
#include <optional>
#include <string>

#include "commands.h"
#include "zenith/base/error.h"
#include "zenith/sim/live.h"
#include "zenith/sim/render_frame.h"

namespace zenith::cli {

Command AddLiveCommand(CLI::App& app) {
    struct Args {
        sim::LiveRequest live;
        std::optional<int> fg_native, fg_generic, xplane;
        std::string size = "640x360", exposure = "auto", format = "png", out = "live";
        std::optional<std::size_t> frames;
        std::optional<double> duration;
    };
    const auto args = std::make_shared<Args>();
    CLI::App* cmd = app.add_subcommand(
        "live",
        "Follow a running simulator over UDP (FlightGear native FDM or generic protocol, "
        "X-Plane DATA/RPOS) and write its sky as frames");
    auto* native = cmd->add_option("--fg-native", args->fg_native,
                                   "UDP port of FlightGear's --native-fdm=socket,out,HZ,HOST,"
                                   "PORT,udp (FGNetFDM version 24); 0: any free port");
    auto* generic = cmd->add_option("--fg-generic", args->fg_generic,
                                    "UDP port of FlightGear's --generic=socket,out,HZ,HOST,PORT,"
                                    "udp,zenith (data/flightgear/zenith.xml)");
    auto* xplane = cmd->add_option("--xplane", args->xplane,
                                   "UDP port of X-Plane's data output (DATA 17 and 20, or RPOS)");
    native->excludes(generic, xplane);
    generic->excludes(xplane);
    cmd->add_option("--bind", args->live.bind_address, "IPv4 address to listen on")
        ->capture_default_str();
    cmd->add_option("--out", args->out, "folder for frame_NNNNNN.png/.exr, live.csv, packets.csv")
        ->capture_default_str();
    cmd->add_option("--every", args->live.every_s, "seconds between frames")->capture_default_str();
    cmd->add_option("--frames", args->frames, "stop after this many frames");
    cmd->add_option("--duration", args->duration, "stop after this many seconds");
    cmd->add_option("--delay", args->live.delay_s,
                    "draw this many seconds behind the newest packet (interpolation)")
        ->capture_default_str();
    cmd->add_option("--size", args->size, "frame size WxH")->capture_default_str();
    cmd->add_option("--fov", args->live.fov_deg, "vertical field of view, degrees")
        ->capture_default_str();
    cmd->add_option("--exposure", args->exposure, "EV100 for PNG frames, or auto")
        ->capture_default_str();
    cmd->add_option("--format", args->format, "png, exr or both")->capture_default_str();
    cmd->add_option("--preset", args->live.preset, "atmosphere preset or JSON file")
        ->capture_default_str();
    cmd->add_option("--weather", args->live.weather, "clouds: a weather preset or JSON file")
        ->capture_default_str();
    return {
        cmd, [args] {
            sim::LiveRequest request = args->live;
            if (args->fg_native) {
                request.protocol = track::LiveProtocol::kFlightGearNative;
                request.port = *args->fg_native;
            } else if (args->fg_generic) {
                request.protocol = track::LiveProtocol::kFlightGearGeneric;
                request.port = *args->fg_generic;
            } else if (args->xplane) {
                request.protocol = track::LiveProtocol::kXPlane;
                request.port = *args->xplane;
            } else {
                throw ArgumentError("protocol",
                                    "no simulator given (expected --fg-native PORT, "
                                    "--fg-generic PORT or --xplane PORT)");
            }
            request.out_dir = args->out;
            request.size = sim::ParseFrameSize(args->size);
            request.exposure = sky::ExposureFromString(args->exposure);
            if (args->format != "png" && args->format != "exr" && args->format != "both") {
                throw ArgumentError("format", "format = " + args->format +
                                                  " is not known (expected png, exr or both)");
            }
            request.write_png = args->format != "exr";
            request.write_exr = args->format != "png";
            request.max_frames = args->frames;
            request.duration_s = args->duration;
            // Ctrl-C or SIGTERM: stop after the frame in progress (every written frame is
            // whole); exit 128 + the signal, as `zenith replay` does.
            const std::atomic<bool>& stop = StopOnSignals();
            const sim::LiveResult result = sim::RunLive(request, stop, [&](int port) {
                fmt::print(stderr, "zenith live: listening for {} on udp {}:{}\n",
                           track::LiveProtocolName(request.protocol), request.bind_address, port);
            });
            fmt::print(
                stderr,
                "zenith live: {} frames into {} ({:.3f} s per frame); {} packets, {} "
                "used, {} malformed, {} in bursts not interpolated through; clock reset {} times, "
                "{} late packets set aside\n",
                result.frames, request.out_dir.string(),
                result.frames ? result.render_seconds / static_cast<double>(result.frames) : 0.0,
                result.packets, result.used, result.malformed, result.bunched, result.clock_resets,
                result.late_packets);
            for (const auto& [kind, count] : result.malformed_by_kind) {
                fmt::print(stderr, "zenith live: warning: {} malformed packets: {}\n", count, kind);
            }
            for (const std::string& problem : result.first_problems) {
                fmt::print(stderr, "zenith live: warning: {}\n", problem);
            }
            if (result.interrupted) {
                fmt::print(stderr, "zenith live: stopped; every written frame is complete\n");
                return StoppedExitCode();
            }
            return 0;
        }};
}

}  // namespace zenith::cli
