// `zenith replay`: a recorded flight into frames and video; resumable, shardable.
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "commands.h"
#include "zenith/base/error.h"
#include "zenith/sim/replay.h"

namespace zenith::cli {
namespace {

int RunReplayCommand(sim::ReplayRequest request, const std::string& size,
                     const std::string& exposure, const std::string& format,
                     const std::string& camera, const std::string& shard) {
    request.size = sim::ParseFrameSize(size);
    request.exposure = sky::ExposureFromString(exposure);
    request.camera = sim::ParseReplayCamera(camera);
    if (format != "png" && format != "exr" && format != "both") {
        throw ArgumentError("format",
                            "format = " + format + " is not known (expected png, exr or both)");
    }
    request.write_png = format != "exr";
    request.write_exr = format != "png";
    if (!shard.empty()) {
        request.shard = sim::ParseShard(shard);
    } else if (const auto from_slurm = sim::ShardFromEnvironment()) {
        request.shard = *from_slurm;
    }
    // Ctrl-C (or a scheduler's SIGTERM) stops after the frame in progress; rerun to resume.
    const std::atomic<bool>& stop = StopOnSignals();
    const bool tty = isatty(STDERR_FILENO) != 0;
    std::size_t last_line = 0;
    auto on_progress = [&](const sim::ReplayProgress& p) {
        const double rate = p.seconds > 0.0 ? static_cast<double>(p.rendered) / p.seconds : 0.0;
        const double eta = rate > 0.0 ? static_cast<double>(p.total - p.done) / rate : 0.0;
        if (tty) {
            constexpr int kWidth = 30;
            const int filled =
                static_cast<int>(kWidth * p.done / std::max<std::size_t>(p.total, 1));
            fmt::print(stderr,
                       "\r[{:<{}}] {}/{} frames ({} skipped)  {:.2f} fps  ETA {:02d}:{:02d}",
                       std::string(static_cast<std::size_t>(filled), '='), kWidth, p.done, p.total,
                       p.skipped, rate, static_cast<int>(eta) / 60, static_cast<int>(eta) % 60);
        } else if (p.done == p.total ||
                   p.done >= last_line + std::max<std::size_t>(p.total / 10, 1)) {
            last_line = p.done;
            fmt::print(stderr,
                       "zenith replay: {}/{} frames ({} skipped), {:.2f} fps, ETA {:.0f} s\n",
                       p.done, p.total, p.skipped, rate, eta);
        }
    };
    fmt::print(stderr, "zenith replay: {} (shard {}/{})\n", request.flight.string(),
               request.shard.index, request.shard.count);
    const sim::ReplayResult result = sim::RunReplay(request, stop, on_progress);
    if (tty) fmt::print(stderr, "\n");
    fmt::print(stderr, "{}\n", result.log_summary);
    fmt::print(stderr,
               "zenith replay: rendered {}, skipped {} of this shard's {} frames ({} in "
               "the flight) into {}\n",
               result.progress.rendered, result.progress.skipped, result.progress.total,
               result.frames_in_flight, request.out_dir.string());
    if (!result.notes.empty()) fmt::print(stderr, "{}", result.notes);
    if (!request.metar_file.empty()) {
        fmt::print(stderr,
                   "zenith replay: METAR weather set {} times (clouds) and {} (visibility) for {} "
                   "frames, {:.2f} s\n",
                   result.weather_sets, result.visibility_sets, result.progress.rendered,
                   result.weather_seconds);
    }
    if (!result.video_status.empty())
        fmt::print(stderr, "zenith replay: {}\n", result.video_status);
    if (result.interrupted) {
        fmt::print(stderr,
                   "zenith replay: stopped; every written frame is complete; run the same "
                   "command again to resume\n");
        // The shell's convention: 128 + the signal (130 for SIGINT, 143 for SIGTERM).
        return StoppedExitCode();
    }
    return 0;
}

}  // namespace

Command AddReplayCommand(CLI::App& app) {
    struct Args {
        sim::ReplayRequest replay;
        std::string replay_size = "640x360", replay_exposure = "auto", replay_format = "png",
                    replay_camera = "cockpit", replay_shard, replay_flight, replay_out = "replay",
                    replay_video, replay_metar_file;
        std::optional<double> replay_start, replay_end;
        std::optional<std::string> replay_icao24, replay_callsign;
        std::optional<std::vector<double>> replay_observer;
    };
    const auto args = std::make_shared<Args>();
    sim::ReplayRequest& replay = args->replay;
    CLI::App* replay_cmd = app.add_subcommand(
        "replay",
        "Render a recorded flight (IGC, GPX, KML gx:Track, CSV) into frames and video; "
        "resumable, shardable");
    replay_cmd->add_option("flight", args->replay_flight, "flight log (.igc .gpx .kml .csv)")
        ->required();
    replay_cmd->add_option("--out", args->replay_out, "output directory for frame_NNNNNN.png/.exr")
        ->capture_default_str();
    replay_cmd->add_option("--fps", replay.fps, "frames per second of flight time")
        ->capture_default_str();
    replay_cmd->add_option("--size", args->replay_size, "frame size WxH")->capture_default_str();
    replay_cmd->add_option("--camera", args->replay_camera, "cockpit, chase or ground")
        ->capture_default_str();
    replay_cmd->add_option("--fov", replay.fov_deg, "vertical field of view, degrees")
        ->capture_default_str();
    replay_cmd->add_option("--exposure", args->replay_exposure, "EV100 for PNG frames, or auto")
        ->capture_default_str();
    replay_cmd->add_option("--format", args->replay_format, "png, exr or both")
        ->capture_default_str();
    replay_cmd
        ->add_option("--time-offset", replay.time_offset_s,
                     "seconds added to the log's times for the sky")
        ->capture_default_str();
    replay_cmd->add_option("--time-warp", replay.time_warp, "sky time per flight time")
        ->capture_default_str();
    replay_cmd->add_option("--start", args->replay_start, "flight seconds to start at");
    replay_cmd->add_option("--end", args->replay_end, "flight seconds to end at");
    replay_cmd
        ->add_option("--weather", replay.weather,
                     "clouds: clear, scattered_cumulus, broken, overcast_stratus, "
                     "cumulonimbus, cirrus or a weather JSON file")
        ->capture_default_str();
    auto* metar_file = replay_cmd->add_option(
        "--metar-file", args->replay_metar_file,
        "weather along the flight from METAR reports: a CSV (station,valid,lon,lat,metar) or "
        "one report per line; the nearest station, blended in time and across stations");
    replay_cmd
        ->add_option("--station-elevation", replay.station_elevation_m,
                     "the METAR stations' elevation above mean sea level, metres (default: the "
                     "ground under them, 0 m)")
        ->needs(metar_file);
    replay_cmd->add_option("--preset", replay.preset, "atmosphere preset or JSON file")
        ->capture_default_str();
    replay_cmd->add_option("--shard", args->replay_shard,
                           "K/N: render frames i with i mod N = K (default: Slurm array task "
                           "variables, else all)");
    replay_cmd->add_option("--video", args->replay_video,
                           "encode the PNG frames to this MP4 (ffmpeg)");
    replay_cmd->add_option("--icao24", args->replay_icao24,
                           "the aircraft to replay from a log of several (OpenSky CSV)");
    replay_cmd->add_option("--callsign", args->replay_callsign,
                           "the aircraft to replay from a log of several, by callsign");
    replay_cmd
        ->add_option("--observer", args->replay_observer,
                     "the ground camera at LAT,LON,H (degrees, metres above the WGS84 "
                     "ellipsoid); default: on the ground under the first fix")
        ->delimiter(',')
        ->expected(3);
    return {replay_cmd, [args] {
                const Args& a = *args;
                sim::ReplayRequest request = a.replay;
                request.flight = a.replay_flight;
                request.out_dir = a.replay_out;
                request.video = a.replay_video;
                request.metar_file = a.replay_metar_file;
                request.start_s = a.replay_start;
                request.end_s = a.replay_end;
                request.read.icao24 = a.replay_icao24;
                request.read.callsign = a.replay_callsign;
                if (a.replay_observer) {
                    const std::vector<double>& o = *a.replay_observer;
                    request.observer = glm::dvec3(o[0], o[1], o[2]);
                }
                return RunReplayCommand(request, a.replay_size, a.replay_exposure, a.replay_format,
                                        a.replay_camera, a.replay_shard);
            }};
}

}  // namespace zenith::cli
