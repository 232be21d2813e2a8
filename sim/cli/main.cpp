// zenith — command-line front end: `zenith ephemeris`, `zenith info`.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <unistd.h>

#include <atomic>
#include <csignal>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "zenith/base/error.h"
#include "zenith/geo/ephemeris.h"
#include "zenith/sim/ephemeris_report.h"
#include "zenith/sim/render_frame.h"
#include "zenith/sim/replay.h"
#include "zenith/sky/gl/context.h"
#include "zenith/sky/gl/error.h"
#include "zenith/version.h"

namespace {

namespace fs = std::filesystem;
using namespace zenith;

// Built-in default observer: the Royal Observatory, Greenwich (WGS84).
constexpr double kDefaultLatDeg = 51.476852;
constexpr double kDefaultLonDeg = -0.000500;
constexpr double kDefaultHeightM = 46.0;

struct EphemerisArgs {
    std::optional<std::string> utc;
    double lat_deg = kDefaultLatDeg;
    double lon_deg = kDefaultLonDeg;
    double height_m = kDefaultHeightM;
    std::optional<double> dut1_s;
    std::optional<double> delta_t_s;
    bool refraction = false;
    double pressure_hpa = 1010.0;
    double temperature_c = 10.0;
    bool json = false;
    std::size_t stars = 10;
    double mag_limit = 6.5;
    std::string batch_in;
    std::string batch_out;
};

int RunBatch(const EphemerisArgs& a) {
    std::ifstream in(a.batch_in);
    if (!in) {
        fmt::print(stderr, "zenith ephemeris: cannot open --batch file '{}'\n", a.batch_in);
        return 2;
    }
    // Written under a temporary name and renamed when complete, so OUT is never half-written.
    const fs::path out_path = a.batch_out;
    const fs::path tmp_path = out_path.string() + ".partial";
    std::ofstream out(tmp_path, std::ios::trunc);
    if (!out) {
        fmt::print(stderr, "zenith ephemeris: cannot write --out file '{}'\n", a.batch_out);
        return 2;
    }
    const sim::BatchSummary summary = sim::RunEphemerisBatch(in, out);
    out.close();
    if (!out) {
        fmt::print(stderr, "zenith ephemeris: write error on '{}'\n", tmp_path.string());
        return 2;
    }
    fs::rename(tmp_path, out_path);
    if (summary.failed > 0) {
        fmt::print(stderr,
                   "zenith ephemeris: {} of {} lines failed (first: {}); their output lines hold "
                   "{{\"line\": N, \"error\": ...}}\n",
                   summary.failed, summary.lines, summary.first_error);
        return 1;
    }
    fmt::print(stderr, "zenith ephemeris: {} lines written to {}\n", summary.lines, a.batch_out);
    return 0;
}

int RunSingle(const EphemerisArgs& a) {
    geo::TimeOptions time_options{a.dut1_s, a.delta_t_s};
    const geo::Time t = a.utc ? geo::TimeFromIso8601(*a.utc, time_options)
                              : geo::TimeNow(time_options);
    const geo::Observer observer(a.lat_deg, a.lon_deg, a.height_m);
    geo::EphemerisOptions options;
    if (a.refraction) options.refraction = geo::RefractionOptions{a.pressure_hpa, a.temperature_c};

    std::optional<geo::StarCatalog> catalog;
    if (a.stars > 0) {
        try {
            catalog = geo::StarCatalog::Load(a.mag_limit);
        } catch (const geo::CatalogError& e) {
            fmt::print(stderr, "zenith ephemeris: stars not shown: {}\n", e.what());
        }
    }
    const geo::Ephemeris ephemeris(catalog ? &*catalog : nullptr);
    const geo::SkyEphemeris e = ephemeris.Compute(t, observer, options);
    if (a.json) {
        nlohmann::json j = sim::EphemerisRecord(e);
        j["utc"] = geo::FormatIso8601(geo::CivilFromJulianDate(t.jd_utc));
        j["lat_deg"] = observer.lat_deg();
        j["lon_deg"] = observer.lon_deg();
        j["height_m"] = observer.height_m();
        j["tt_minus_ut1_s"] = t.DeltaT();
        j["refraction"] = a.refraction;
        if (a.refraction) {
            j["sun_el_deg"] = e.sun.elevation * 57.29577951308232;
            j["moon_el_deg"] = e.moon.elevation * 57.29577951308232;
        }
        j["moon_waxing"] = e.moon_phase.waxing;
        j["moon_bright_limb_from_zenith_deg"] = e.moon_phase.bright_limb_from_zenith * 57.29577951308232;
        nlohmann::json stars = nlohmann::json::array();
        for (std::size_t i = 0; i < e.stars.size() && i < a.stars; ++i) {
            const auto& s = e.stars[i];
            stars.push_back({{"name", s.star->name},
                             {"hd", s.star->hd},
                             {"mag_v", s.star->magnitude_v},
                             {"b_minus_v", s.star->b_minus_v},
                             {"az_deg", s.horizontal.azimuth * 57.29577951308232},
                             {"el_deg", s.horizontal.elevation * 57.29577951308232},
                             {"illuminance_lux", s.illuminance_lux}});
        }
        j["stars"] = stars;
        std::cout << j.dump(2) << '\n';
    } else {
        std::cout << sim::EphemerisTable(e, observer, a.stars);
    }
    return 0;
}

int RunRender(sim::FrameRequest request, const std::string& size, const std::string& exposure,
              const std::string& quality) {
    request.size = sim::ParseFrameSize(size);
    request.exposure = sky::ExposureFromString(exposure);
    if (quality == "mobile") {
        request.lut_settings = sky::LutSettings::Mobile();
    } else if (quality != "pc") {
        throw ArgumentError("quality", "quality = " + quality + " is not known (expected pc or mobile)");
    }
    std::string warning;
    const sim::FrameResult result = sim::RenderFrame(request, &warning);
    if (!warning.empty()) fmt::print(stderr, "zenith render: {}\n", warning);
    fmt::print(stderr,
               "zenith render: {} ({}x{}, sun elevation {:.2f} deg, {} stars, EV100 {:.2f}) "
               "on {}\n",
               request.out.string(), request.size.x, request.size.y, result.sun_elevation_deg,
               result.stars_drawn, result.ev100, result.gl_description);
    return 0;
}

// The command-line option of a library field named in an ArgumentError ("" if none).
std::string FlagForField(const std::string& field) {
    static const std::map<std::string, std::string> kFlags = {
        {"size", "--size"},
        {"fps", "--fps"},
        {"fov_deg", "--fov"},
        {"time_warp", "--time-warp"},
        {"time_offset_s", "--time-offset"},
        {"start_s", "--start"},
        {"end_s", "--end"},
        {"camera", "--camera"},
        {"format", "--format"},
        {"video", "--video"},
        {"shard", "--shard"},
        {"cloud_passes", "--cloud-passes"},
        {"exposure", "--exposure"},
        {"quality", "--quality"},
        {"lat_deg", "--lat"},
        {"lon_deg", "--lon"},
        {"height_m", "--height"},
        {"heading_deg", "--heading"},
        {"pitch_deg", "--pitch"},
        {"roll_deg", "--roll"},
        {"out", "--out"},
    };
    const auto it = kFlags.find(field);
    return it == kFlags.end() ? std::string() : it->second;
}

std::atomic<bool> g_stop{false};
std::atomic<int> g_signal{0};
extern "C" void OnInterrupt(int signal) {
    g_signal.store(signal);
    g_stop.store(true);
}

int RunReplayCommand(sim::ReplayRequest request, const std::string& size,
                     const std::string& exposure, const std::string& format,
                     const std::string& camera, const std::string& shard) {
    request.size = sim::ParseFrameSize(size);
    request.exposure = sky::ExposureFromString(exposure);
    request.camera = sim::ParseReplayCamera(camera);
    if (format != "png" && format != "exr" && format != "both") {
        throw ArgumentError("format", "format = " + format +
                                          " is not known (expected png, exr or both)");
    }
    request.write_png = format != "exr";
    request.write_exr = format != "png";
    if (!shard.empty()) {
        request.shard = sim::ParseShard(shard);
    } else if (const auto from_slurm = sim::ShardFromEnvironment()) {
        request.shard = *from_slurm;
    }
    // Ctrl-C (or a scheduler's SIGTERM) stops after the frame in progress; rerun to resume.
    std::signal(SIGINT, OnInterrupt);
    std::signal(SIGTERM, OnInterrupt);
    const bool tty = isatty(STDERR_FILENO) != 0;
    std::size_t last_line = 0;
    auto on_progress = [&](const sim::ReplayProgress& p) {
        const double rate = p.seconds > 0.0 ? static_cast<double>(p.rendered) / p.seconds : 0.0;
        const double eta = rate > 0.0 ? static_cast<double>(p.total - p.done) / rate : 0.0;
        if (tty) {
            constexpr int kWidth = 30;
            const int filled = static_cast<int>(kWidth * p.done / std::max<std::size_t>(p.total, 1));
            fmt::print(stderr, "\r[{:<{}}] {}/{} frames ({} skipped)  {:.2f} fps  ETA {:02d}:{:02d}",
                       std::string(static_cast<std::size_t>(filled), '='), kWidth, p.done, p.total,
                       p.skipped, rate, static_cast<int>(eta) / 60, static_cast<int>(eta) % 60);
        } else if (p.done == p.total || p.done >= last_line + std::max<std::size_t>(p.total / 10, 1)) {
            last_line = p.done;
            fmt::print(stderr, "zenith replay: {}/{} frames ({} skipped), {:.2f} fps, ETA {:.0f} s\n",
                       p.done, p.total, p.skipped, rate, eta);
        }
    };
    fmt::print(stderr, "zenith replay: {} (shard {}/{})\n", request.flight.string(),
               request.shard.index, request.shard.count);
    const sim::ReplayResult result = sim::RunReplay(request, g_stop, on_progress);
    if (tty) fmt::print(stderr, "\n");
    fmt::print(stderr, "{}\n", result.log_summary);
    fmt::print(stderr, "zenith replay: rendered {}, skipped {} of this shard's {} frames ({} in "
               "the flight) into {}\n", result.progress.rendered, result.progress.skipped,
               result.progress.total, result.frames_in_flight, request.out_dir.string());
    if (!result.notes.empty()) fmt::print(stderr, "{}", result.notes);
    if (!result.video_status.empty()) fmt::print(stderr, "zenith replay: {}\n", result.video_status);
    if (result.interrupted) {
        fmt::print(stderr, "zenith replay: stopped; every written frame is complete; run the same "
                   "command again to resume\n");
        // The shell's convention: 128 + the signal (130 for SIGINT, 143 for SIGTERM).
        return 128 + (g_signal.load() != 0 ? g_signal.load() : SIGINT);
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"zenith — flight-simulator sky: ephemeris, atmosphere, clouds"};
    app.require_subcommand(1);
    app.set_version_flag("--version", std::string("zenith ") + kVersion);

    EphemerisArgs eph;
    CLI::App* ephemeris = app.add_subcommand(
        "ephemeris", "Sun, Moon and star positions for a UTC instant and a WGS84 position");
    ephemeris->add_option("--utc", eph.utc,
                          "UTC instant, ISO 8601 (2024-04-08T18:18:00Z, offsets allowed); "
                          "default: now");
    ephemeris->add_option("--lat", eph.lat_deg, "geodetic latitude, degrees (north +)")
        ->capture_default_str();
    ephemeris->add_option("--lon", eph.lon_deg, "longitude, degrees (east +)")
        ->capture_default_str();
    ephemeris->add_option("--height", eph.height_m, "height above the WGS84 ellipsoid, metres")
        ->capture_default_str();
    ephemeris->add_option("--dut1", eph.dut1_s, "UT1 - UTC, seconds (default 0)");
    ephemeris->add_option("--delta-t", eph.delta_t_s,
                          "override TT - UT1, seconds (default: leap seconds + 32.184 s)");
    ephemeris->add_flag("--refraction", eph.refraction,
                        "apply atmospheric refraction to elevations (default: geometric)");
    ephemeris->add_option("--pressure", eph.pressure_hpa, "pressure for refraction, hPa")
        ->capture_default_str();
    ephemeris->add_option("--temperature", eph.temperature_c,
                          "temperature for refraction, degrees C")
        ->capture_default_str();
    ephemeris->add_option("--stars", eph.stars, "how many of the brightest stars to list")
        ->capture_default_str();
    ephemeris->add_option("--mag-limit", eph.mag_limit, "faintest star magnitude loaded")
        ->capture_default_str();
    ephemeris->add_flag("--json", eph.json, "print JSON instead of a table");
    auto* batch = ephemeris->add_option(
        "--batch", eph.batch_in,
        "JSON-lines input: {utc, lat_deg, lon_deg, height_m} per line (needs --out)");
    auto* batch_out =
        ephemeris->add_option("--out", eph.batch_out, "JSON-lines output for --batch");
    batch->needs(batch_out);
    batch_out->needs(batch);
    batch->check(CLI::ExistingFile);

    sim::FrameRequest frame;
    std::string size = "1280x720", exposure = "auto", quality = "pc", out = "zenith.png";
    CLI::App* render = app.add_subcommand(
        "render",
        "Render one frame of sky offscreen to EXR (linear cd/m^2) or PNG (exposed, tone mapped); "
        "with no options, a built-in scene: sunset over Zurich at 10 km");
    render->add_option("--utc", frame.utc, "UTC instant, ISO 8601")->capture_default_str();
    render->add_option("--lat", frame.lat_deg, "geodetic latitude, degrees")->capture_default_str();
    render->add_option("--lon", frame.lon_deg, "longitude, degrees")->capture_default_str();
    render->add_option("--height", frame.height_m, "height above the WGS84 ellipsoid, metres")
        ->capture_default_str();
    render->add_option("--heading", frame.heading_deg, "degrees from true north, clockwise")
        ->capture_default_str();
    render->add_option("--pitch", frame.pitch_deg, "degrees, nose up positive")
        ->capture_default_str();
    render->add_option("--roll", frame.roll_deg, "degrees, right wing down positive")
        ->capture_default_str();
    render->add_option("--fov", frame.fov_deg, "vertical field of view, degrees")
        ->capture_default_str();
    render->add_option("--size", size, "image size WxH")->capture_default_str();
    render->add_option("--weather", frame.weather,
                       "clouds: clear, scattered_cumulus, broken, overcast_stratus, "
                       "cumulonimbus or a weather JSON file")
        ->capture_default_str();
    render->add_option("--preset", frame.preset, "atmosphere: earth, mars, thick or a JSON file")
        ->capture_default_str();
    render->add_option("--exposure", exposure, "EV100 for PNG output, or auto")
        ->capture_default_str();
    render->add_option("--quality", quality, "LUT sizes and steps: pc or mobile (Hillaire 2020 "
                                             "Table 2)")
        ->capture_default_str();
    render->add_flag("--ray-march", frame.force_ray_march,
                     "ray march every pixel instead of using the Sky-View LUT");
    render->add_option("--out", out, "output file, .exr or .png")->capture_default_str();

    sim::ReplayRequest replay;
    std::string replay_size = "640x360", replay_exposure = "auto", replay_format = "png",
                replay_camera = "cockpit", replay_shard, replay_flight, replay_out = "replay",
                replay_video;
    std::optional<double> replay_start, replay_end;
    CLI::App* replay_cmd = app.add_subcommand(
        "replay", "Render a recorded flight (IGC, GPX, KML gx:Track, CSV) into frames and video; "
                  "resumable, shardable");
    replay_cmd->add_option("flight", replay_flight, "flight log (.igc .gpx .kml .csv)")
        ->required();
    replay_cmd->add_option("--out", replay_out, "output directory for frame_NNNNNN.png/.exr")
        ->capture_default_str();
    replay_cmd->add_option("--fps", replay.fps, "frames per second of flight time")
        ->capture_default_str();
    replay_cmd->add_option("--size", replay_size, "frame size WxH")->capture_default_str();
    replay_cmd->add_option("--camera", replay_camera, "cockpit, chase or ground")
        ->capture_default_str();
    replay_cmd->add_option("--fov", replay.fov_deg, "vertical field of view, degrees")
        ->capture_default_str();
    replay_cmd->add_option("--exposure", replay_exposure, "EV100 for PNG frames, or auto")
        ->capture_default_str();
    replay_cmd->add_option("--format", replay_format, "png, exr or both")->capture_default_str();
    replay_cmd->add_option("--time-offset", replay.time_offset_s,
                           "seconds added to the log's times for the sky")
        ->capture_default_str();
    replay_cmd->add_option("--time-warp", replay.time_warp, "sky time per flight time")
        ->capture_default_str();
    replay_cmd->add_option("--start", replay_start, "flight seconds to start at");
    replay_cmd->add_option("--end", replay_end, "flight seconds to end at");
    replay_cmd->add_option("--weather", replay.weather,
                           "clouds: clear, scattered_cumulus, broken, overcast_stratus, "
                           "cumulonimbus or a weather JSON file")
        ->capture_default_str();
    replay_cmd->add_option("--preset", replay.preset, "atmosphere preset or JSON file")
        ->capture_default_str();
    replay_cmd->add_option("--shard", replay_shard,
                           "K/N: render frames i with i mod N = K (default: Slurm array task "
                           "variables, else all)");
    replay_cmd->add_option("--video", replay_video, "encode the PNG frames to this MP4 (ffmpeg)");
    std::optional<std::string> replay_icao24, replay_callsign;
    std::optional<std::vector<double>> replay_observer;
    replay_cmd->add_option("--icao24", replay_icao24,
                           "the aircraft to replay from a log of several (OpenSky CSV)");
    replay_cmd->add_option("--callsign", replay_callsign,
                           "the aircraft to replay from a log of several, by callsign");
    replay_cmd->add_option("--observer", replay_observer,
                           "the ground camera at LAT,LON,H (degrees, metres above the WGS84 "
                           "ellipsoid); default: on the ground under the first fix")
        ->delimiter(',')
        ->expected(3);

    CLI::App* info = app.add_subcommand(
        "info", "Versions, the headless GL context (ZENITH_GL=osmesa|egl), star catalogue");

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e);
    }

    try {
        if (*ephemeris) return eph.batch_in.empty() ? RunSingle(eph) : RunBatch(eph);
        if (*replay_cmd) {
            replay.flight = replay_flight;
            replay.out_dir = replay_out;
            replay.video = replay_video;
            replay.start_s = replay_start;
            replay.end_s = replay_end;
            replay.read.icao24 = replay_icao24;
            replay.read.callsign = replay_callsign;
            if (replay_observer) {
                replay.observer =
                    glm::dvec3((*replay_observer)[0], (*replay_observer)[1], (*replay_observer)[2]);
            }
            return RunReplayCommand(replay, replay_size, replay_exposure, replay_format,
                                    replay_camera, replay_shard);
        }
        if (*render) {
            frame.out = out;
            return RunRender(frame, size, exposure, quality);
        }
        if (*info) {
            fmt::print("zenith {}\n", kVersion);
            try {
                const auto context = sky::gl::CreateHeadlessContextFromEnvironment();
                fmt::print("GL context: {}\n", context->description());
            } catch (const sky::gl::GlError& e) {
                fmt::print("GL context: unavailable: {}\n", e.what());
            }
            try {
                const auto catalog = geo::StarCatalog::Load();
                fmt::print("star catalogue: {} stars to magnitude {:.1f}\n",
                           catalog.stars().size(), catalog.magnitude_limit());
            } catch (const geo::CatalogError& e) {
                fmt::print("star catalogue: unavailable: {}\n", e.what());
            }
            return 0;
        }
    } catch (const ArgumentError& e) {
        // The library names its fields; say which option it was.
        const std::string flag = FlagForField(e.field());
        fmt::print(stderr, "zenith: error: {}{}\n", flag.empty() ? "" : flag + ": ", e.what());
        return 2;
    } catch (const std::exception& e) {
        fmt::print(stderr, "zenith: error: {}\n", e.what());
        return 2;
    }
    return 0;
}
