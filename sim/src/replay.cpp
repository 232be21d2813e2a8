#include "zenith/sim/replay.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>
#include <xxhash.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <glm/gtc/quaternion.hpp>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "video_encoder.h"
#include "zenith/base/atomic_file.h"
#include "zenith/base/units.h"
#include "zenith/geo/observer.h"
#include "zenith/sim/sky_system.h"
#include "zenith/sky/atmosphere.h"
#include "zenith/sky/clouds/weather.h"
#include "zenith/sky/sky_state.h"
#include "zenith/track/flight_log.h"
#include "zenith/track/trajectory.h"
#include "zenith/version.h"
#include "zenith/weather/altimetry.h"
#include "zenith/weather/cloud_weather.h"
#include "zenith/weather/metar_file.h"
#include "zenith/weather/metar_timeline.h"

namespace zenith::sim {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

// Chase camera: behind and above the aircraft, looking at it.
constexpr double kChaseDistance = 60.0;  // m
constexpr double kChaseHeight = 15.0;    // m
constexpr int kMaxShards = 100000;

// Columns right, up, backward of a camera looking along `forward` with `up_hint` up.
glm::dmat3 LookAlong(const glm::dvec3& forward, const glm::dvec3& up_hint) {
    const glm::dvec3 f = glm::normalize(forward);
    glm::dvec3 right = glm::cross(f, up_hint);
    if (glm::length(right) < 1e-9) right = glm::cross(f, glm::dvec3(0.0, 1.0, 0.0));
    right = glm::normalize(right);
    return glm::dmat3(right, glm::cross(right, f), -f);
}

// --- the folder's settings ------------------------------------------------------------------

std::string Hex128(const XXH128_hash_t& h) {
    return fmt::format("{:016x}{:016x}", h.high64, h.low64);
}

std::string HashText(std::string_view text) {
    return Hex128(XXH3_128bits(text.data(), text.size()));
}

// XXH3-128 of a file's bytes, read in chunks.
std::string HashFile(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw ReplayError(fmt::format("{}: cannot open to hash it", path.string()));
    XXH3_state_t* state = XXH3_createState();
    XXH3_128bits_reset(state);
    std::vector<char> buffer(1 << 20);
    while (in) {
        in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
        XXH3_128bits_update(state, buffer.data(), static_cast<std::size_t>(in.gcount()));
    }
    const XXH128_hash_t hash = XXH3_128bits_digest(state);
    XXH3_freeState(state);
    return Hex128(hash);
}

// Everything about the weather that changes a frame, as text: each layer's values, and the
// bytes of a map file.
std::string WeatherFingerprint(const sky::clouds::Weather& weather) {
    std::string text;
    for (const sky::clouds::CloudLayer& l : weather.layers) {
        text += fmt::format(
            "{}|{}|{}|{}|{}|{}|{}|{}|{}|{}|{}|{}|{}|{}|{}|{}|{}|{}|{};", l.base_altitude,
            l.top_altitude, l.coverage, l.cloud_type, l.precipitation, l.wind_speed, l.wind_from,
            l.shear, l.extinction_scale, l.ground_fog, l.snow, l.map_period,
            static_cast<int>(l.map.kind), l.map.seed, l.map.cells_per_tile, l.map.variation,
            l.map.size, l.map.file.string(),
            l.map.kind == sky::clouds::WeatherMapSource::Kind::kFile ? HashFile(l.map.file) : "");
    }
    return HashText(text);
}

// How METAR reports become each frame's weather: part of the manifest, so that a folder made
// under other rules is not resumed with these.
constexpr const char* kMetarRule =
    "nearest station (great circle), 20 km blend band; log-visibility and per-layer linear "
    "blends in 1/128 steps; wind of the first fix held";

bool IsCsv(const fs::path& path) {
    std::string ext = path.extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return ext == ".csv";
}

// The settings every frame in a folder must share (not the shard, not the video).
Json Manifest(const ReplayRequest& r, const sky::Atmosphere& atmosphere,
              const sky::clouds::Weather& weather) {
    Json j;
    j["zenith"] = kVersion;
    j["log"] = {{"file", r.flight.filename().string()},
                {"bytes", fs::file_size(r.flight)},
                {"xxh3_128", HashFile(r.flight)},
                {"icao24", r.read.icao24.value_or("")},
                {"callsign", r.read.callsign.value_or("")}};
    j["fps"] = r.fps;
    j["size"] = fmt::format("{}x{}", r.size.x, r.size.y);
    j["camera"] = r.camera == ReplayCamera::kCockpit ? "cockpit"
                  : r.camera == ReplayCamera::kChase ? "chase"
                                                     : "ground";
    j["observer"] = r.observer
                        ? fmt::format("{},{},{}", r.observer->x, r.observer->y, r.observer->z)
                        : "first fix";
    j["fov_deg"] = r.fov_deg;
    j["exposure"] = r.exposure.automatic ? "auto" : fmt::format("{}", r.exposure.ev100);
    j["format"] = r.write_png && r.write_exr ? "both" : r.write_png ? "png" : "exr";
    j["time_offset_s"] = r.time_offset_s;
    j["time_warp"] = r.time_warp;
    j["start_s"] = r.start_s ? Json(*r.start_s) : Json("start");
    j["end_s"] = r.end_s ? Json(*r.end_s) : Json("end");
    j["preset"] = {{"name", r.preset}, {"xxh3_128", HashText(sky::AtmosphereToJson(atmosphere))}};
    j["weather"] = {{"name", r.weather}, {"xxh3_128", WeatherFingerprint(weather)}};
    j["cloud_passes"] = r.cloud_passes;
    // Only with a METAR file, so that the folders of runs without one keep their manifest.
    if (!r.metar_file.empty()) {
        j["metar"] = {
            {"file", r.metar_file.filename().string()},
            {"bytes", fs::file_size(r.metar_file)},
            {"xxh3_128", HashFile(r.metar_file)},
            {"format", IsCsv(r.metar_file) ? "csv" : "lines"},
            {"station_elevation_m", r.station_elevation_m ? Json(*r.station_elevation_m)
                                                          : Json("ground under the station (0 m)")},
            {"rule", kMetarRule}};
    }
    return j;
}

// "size: 640x360 in the folder, 1280x720 now; ..." for every key that differs.
std::string Differences(const Json& folder, const Json& now, const std::string& prefix = "") {
    std::string out;
    for (const auto& [key, value] : now.items()) {
        const auto it = folder.find(key);
        if (it != folder.end() && value.is_object() && it->is_object()) {
            out += Differences(*it, value, prefix + key + ".");
        } else if (it == folder.end() || *it != value) {
            out += fmt::format("{}{}{}: {} in the folder, {} now", out.empty() ? "" : "; ", prefix,
                               key, it == folder.end() ? "(none)" : it->dump(), value.dump());
        }
    }
    // Settings the folder has and this run does not (a METAR file given before, not now).
    for (const auto& [key, value] : folder.items()) {
        if (!now.contains(key)) {
            out += fmt::format("{}{}{}: {} in the folder, (none) now", out.empty() ? "" : "; ",
                               prefix, key, value.dump());
        }
    }
    return out;
}

std::string HostName() {
    char name[256] = {};
    if (::gethostname(name, sizeof name - 1) != 0) return "host";
    return name;
}

// Removes the manifest candidates (".replay.HOST.PID.json", and its ".partial") that runs on
// this host left when they were killed between writing and removing them; a candidate of a
// running process or of another host (shards on a shared folder) is left alone.
void RemoveStaleCandidates(const fs::path& dir, const std::string& host) {
    const std::string prefix = ".replay." + host + ".";
    std::error_code error;
    for (const auto& entry : fs::directory_iterator(dir, error)) {
        const std::string name = entry.path().filename().string();
        if (name.rfind(prefix, 0) != 0) continue;
        const std::string rest = name.substr(prefix.size());
        char* end = nullptr;
        const long pid = std::strtol(rest.c_str(), &end, 10);
        if (pid <= 0 || end == rest.c_str() ||
            (std::string_view(end) != ".json" && std::string_view(end) != ".json.partial")) {
            continue;
        }
        if (::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH) continue;
        std::error_code ignored;
        fs::remove(entry.path(), ignored);
    }
}

// Creates the folder's manifest, or checks that the one there describes this run. Shards that
// start together race to create it: the first link() wins and the others compare with it.
void ClaimFolder(const fs::path& dir, const Json& manifest) {
    const fs::path path = dir / kReplayManifest;
    const std::string text = manifest.dump(2) + "\n";
    const std::string host = HostName();
    RemoveStaleCandidates(dir, host);
    const fs::path candidate = dir / fmt::format(".replay.{}.{}.json", host, ::getpid());
    WriteFileAtomically(candidate, text);
    const bool created = ::link(candidate.c_str(), path.c_str()) == 0;
    std::error_code ignored;
    fs::remove(candidate, ignored);
    if (created) return;
    std::ifstream in(path);
    Json folder;
    try {
        folder = Json::parse(in);
    } catch (const Json::exception&) {
        throw ReplayError(
            fmt::format("{}: not a replay settings file; the folder is not a "
                        "replay's (choose another output folder)",
                        path.string()));
    }
    if (folder != manifest) {
        throw ReplayError(fmt::format(
            "{} holds the frames of a replay with other settings ({}); choose another output "
            "folder, or remove it to start over",
            dir.string(), Differences(folder, manifest)));
    }
}

// Why the frame file cannot be kept (empty when it decodes whole at the right size).
std::string FrameProblem(const fs::path& path, glm::ivec2 size) {
    std::error_code error;
    if (!fs::is_regular_file(path, error)) return "missing";
    try {
        glm::ivec2 found;
        if (path.extension() == ".png") {
            const sky::Srgb8Image image = sky::ReadPng(path);
            found = {image.width, image.height};
        } else {
            const sky::Image image = sky::ReadExr(path);
            found = {image.width, image.height};
        }
        if (found != size)
            return fmt::format("{}x{} instead of {}x{}", found.x, found.y, size.x, size.y);
    } catch (const std::exception& e) {
        return e.what();
    }
    return {};
}

}  // namespace

ReplayCamera ParseReplayCamera(const std::string& text) {
    if (text == "cockpit") return ReplayCamera::kCockpit;
    if (text == "chase") return ReplayCamera::kChase;
    if (text == "ground") return ReplayCamera::kGround;
    throw ArgumentError("camera",
                        "camera = " + text + " is not known (expected cockpit, chase or ground)");
}

Shard ParseShard(const std::string& text) {
    int k = -1, n = 0;
    char slash = 0, extra = 0;
    if (std::sscanf(text.c_str(), "%d%c%d%c", &k, &slash, &n, &extra) != 3 || slash != '/' ||
        !(n >= 1 && n <= kMaxShards && k >= 0 && k < n)) {
        throw ArgumentError("shard", fmt::format("shard = {} is not a shard (expected K/N with "
                                                 "0 <= K < N <= {}, e.g. 2/8)",
                                                 text, kMaxShards));
    }
    return {k, n};
}

std::optional<Shard> ShardFromEnvironment() {
    const char* id = std::getenv("SLURM_ARRAY_TASK_ID");
    const char* count = std::getenv("SLURM_ARRAY_TASK_COUNT");
    if (id == nullptr || count == nullptr) return std::nullopt;
    const char* min = std::getenv("SLURM_ARRAY_TASK_MIN");
    const auto whole = [](const char* name, const char* text) {
        char* end = nullptr;
        errno = 0;
        const long value = std::strtol(text, &end, 10);
        if (end == text || *end != '\0' || errno != 0 || value < 0 || value > 100000000) {
            throw ArgumentError(name, fmt::format("{} = '{}' is not a task number (expected a "
                                                  "whole number >= 0)",
                                                  name, text));
        }
        return value;
    };
    const long task = whole("SLURM_ARRAY_TASK_ID", id);
    const long tasks = whole("SLURM_ARRAY_TASK_COUNT", count);
    const long first = min != nullptr ? whole("SLURM_ARRAY_TASK_MIN", min) : 0;
    if (!(task >= first && task - first < tasks && tasks <= kMaxShards)) {
        throw ArgumentError("SLURM_ARRAY_TASK_ID",
                            fmt::format("SLURM_ARRAY_TASK_ID = {} is outside the array ({} tasks "
                                        "from {}; at most {})",
                                        task, tasks, first, kMaxShards));
    }
    return Shard{static_cast<int>(task - first), static_cast<int>(tasks)};
}

std::string ReplayFrameName(std::size_t index, const std::string& extension) {
    return fmt::format("frame_{:06d}.{}", index, extension);
}

ReplayResult RunReplay(const ReplayRequest& r, const std::atomic<bool>& stop,
                       const std::function<void(const ReplayProgress&)>& on_progress) {
    // Everything the request says is checked before anything is read or written.
    Require("fps", r.fps, "", Range::LeftOpen(0.0, 1000.0));
    Require("time_warp", r.time_warp, "", Range::LeftOpen(0.0, 1e6));
    Require("time_offset_s", r.time_offset_s, "s", Range::Closed(-1e10, 1e10));
    Require("cloud_passes", r.cloud_passes, "", Range::Closed(1, 64));
    ParseFrameSize(fmt::format("{}x{}", r.size.x, r.size.y));
    sky::ValidateProjection(Radians(r.fov_deg), static_cast<double>(r.size.x) / r.size.y);
    if (r.shard.count < 1 || r.shard.count > kMaxShards || r.shard.index < 0 ||
        r.shard.index >= r.shard.count) {
        ParseShard(fmt::format("{}/{}", r.shard.index, r.shard.count));
    }
    if (!r.write_exr && !r.write_png) {
        throw ArgumentError("format", "format: choose png, exr or both");
    }
    if (!r.video.empty() && !r.write_png) {
        throw ArgumentError("video", "video: it is made from the PNG frames (format png or both)");
    }
    if (!r.metar_file.empty() && r.weather != "clear") {
        throw ArgumentError("weather",
                            "weather = " + r.weather + " and a METAR file: give one of them");
    }
    if (r.metar_file.empty() && r.station_elevation_m) {
        throw ArgumentError("station_elevation",
                            "station_elevation: it places a METAR file's heights (give "
                            "--metar-file too)");
    }
    if (r.station_elevation_m) {
        Require("station_elevation", *r.station_elevation_m, "m", Range::Closed(-500.0, 9000.0));
    }
    if (r.observer) {
        // Validates, naming the value.
        static_cast<void>(geo::Observer(r.observer->x, r.observer->y, r.observer->z));
    }

    const track::FlightLog log = track::ReadFlightLog(r.flight, r.read);
    ReplayResult result;
    // The flight's first and last fix, for the reports' times.
    const auto [first_fix, last_fix] =
        std::minmax_element(log.samples.begin(), log.samples.end(),
                            [](const track::FlightSample& a, const track::FlightSample& b) {
                                return a.time_s < b.time_s;
                            });
    const double flight_start = log.samples.empty() ? 0.0 : first_fix->time_s;
    const double flight_end = log.samples.empty() ? 0.0 : last_fix->time_s;

    // Weather from METAR reports: read (bounded by the reader) before anything is written.
    std::unique_ptr<weather::MetarTimeline> timeline;
    if (!r.metar_file.empty()) {
        weather::MetarFile file = IsCsv(r.metar_file) ? weather::ReadMetarCsv(r.metar_file)
                                                      : weather::ReadMetarLines(r.metar_file);
        result.notes += file.Summary() + "\n";
        weather::TimelineOptions options;
        options.station_elevation_m = r.station_elevation_m;
        options.clear_visibility_m =
            std::log(20.0) / weather::GroundExtinctionGreen(sky::LoadAtmosphere(r.preset));
        timeline = std::make_unique<weather::MetarTimeline>(std::move(file), options, flight_start,
                                                            flight_end);
        for (const std::string& note : timeline->notes()) result.notes += "METAR: " + note + "\n";
        result.notes += fmt::format(
            "METAR: {} stations; the weather of the nearest to the aircraft at the log's time; "
            "heights above {}\n",
            timeline->stations().size(),
            r.station_elevation_m
                ? fmt::format("the stations' elevation, {} m (--station-elevation)",
                              *r.station_elevation_m)
                : std::string("the ground zenith draws under them (0 m; give "
                              "--station-elevation to place them)"));
    }

    // Pressure altitudes through the reports' QNH and temperature where there are reports.
    track::TrajectoryOptions trajectory_options;
    if (timeline) {
        trajectory_options.pressure_height = [&timeline](double t, double lat, double lon,
                                                         double pressure_altitude) {
            // Outside what altimetry takes (a corrupt fix), the pressure altitude as it is.
            if (!(pressure_altitude >= -1000.0 && pressure_altitude <= 20000.0)) {
                return pressure_altitude;
            }
            return weather::HeightFromPressureAltitude(pressure_altitude,
                                                       timeline->AirAt(t, lat, lon));
        };
    }
    const track::Trajectory trajectory(log, trajectory_options);
    result.log_summary = log.summary.ToString();
    for (const std::string& note : trajectory.notes()) result.log_summary += "\n" + note;
    if (timeline && trajectory.altitude_kind() == track::AltitudeKind::kPressure) {
        result.notes +=
            "METAR: pressure altitude -> height through the reports' QNH and temperature (nearest "
            "station, linear in time; zenith::weather::HeightFromPressureAltitude)\n";
    }
    if (stop.load()) {
        result.interrupted = true;
        return result;
    }

    // The plan, in doubles until it is known to fit.
    const double duration = trajectory.end_time_s() - trajectory.start_time_s();
    const double start = r.start_s.value_or(0.0);
    const double end = r.end_s.value_or(duration);
    Require("start_s", start, "s", Range::Closed(0.0, duration));
    Require("end_s", end, "s", Range::Closed(start, duration));
    const double frames = std::floor((end - start) * r.fps) + 1.0;
    if (!(frames <= static_cast<double>(kMaxReplayFrames))) {
        throw ArgumentError("fps", fmt::format("{:.0f} frames ({:.0f} s of flight at {} fps) is "
                                               "more than {} in one replay; lower the fps or "
                                               "choose start_s and end_s",
                                               frames, end - start, r.fps, kMaxReplayFrames));
    }
    result.frames_in_flight = static_cast<std::size_t>(frames);
    const auto count = static_cast<std::size_t>(r.shard.count);
    const auto index = static_cast<std::size_t>(r.shard.index);
    ReplayProgress& progress = result.progress;
    progress.total =
        result.frames_in_flight / count + (index < result.frames_in_flight % count ? 1 : 0);
    const double begin = trajectory.start_time_s() + start;

    // The ground observer stands on the ground zenith draws, under the first fix (the first
    // sample's own place: never a fallback).
    const track::TrajectoryState first = trajectory.At(trajectory.start_time_s());
    const geo::Observer ground =
        r.observer ? geo::Observer(r.observer->x, r.observer->y, r.observer->z)
                   : geo::Observer(first.lat_deg, first.lon_deg, kGroundEyeHeight);
    if (r.camera == ReplayCamera::kGround) {
        result.notes +=
            fmt::format("ground observer at {:.5f}, {:.5f}, {:.1f} m above the ellipsoid ({})\n",
                        ground.lat_deg(), ground.lon_deg(), ground.height_m(),
                        r.observer ? "as given" : "on the ground zenith draws under the first fix");
    }

    SkySystemSettings settings;
    settings.preset = r.preset;
    settings.refraction = PresetRefraction(r.preset);
    settings.weather = r.weather;
    settings.clouds.block = 1;
    auto sky = SkySystem::CreateHeadless(settings);
    fs::create_directories(r.out_dir);
    ClaimFolder(r.out_dir, Manifest(r, sky->atmosphere(), sky->weather()));

    const geo::Time weather_epoch =
        geo::TimeFromUnixSeconds(trajectory.start_time_s() + r.time_offset_s);
    sky->SetWeatherOrigin(first.lat_deg, first.lon_deg);
    sky->SetWeatherEpoch(weather_epoch);
    // The weather drawn now, so that it is set again only when the quantised blend changes it;
    // each frame's weather is a function of its own time and place only.
    std::optional<weather::LayerWind> wind;
    std::optional<double> visibility_drawn;
    bool fog_drawn = false;
    if (timeline) {
        wind = timeline->WindAt(trajectory.start_time_s(), first.lat_deg, first.lon_deg);
    }
    sky->SetProjection(Radians(r.fov_deg), static_cast<double>(r.size.x) / r.size.y);
    const auto started = std::chrono::steady_clock::now();
    for (std::size_t i = index; i < result.frames_in_flight; i += count) {
        if (stop.load()) {
            result.interrupted = true;
            break;
        }
        const fs::path png = r.out_dir / ReplayFrameName(i, "png");
        const fs::path exr = r.out_dir / ReplayFrameName(i, "exr");
        const double t = begin + static_cast<double>(i) / r.fps;
        const track::TrajectoryState aircraft = trajectory.At(t);
        std::string problem;
        for (const fs::path& p : {png, exr}) {
            if ((p == png ? r.write_png : r.write_exr) && problem.empty()) {
                problem = FrameProblem(p, r.size);
            }
        }
        if (!aircraft.valid) {
            ++progress.in_gaps;  // inside a gap of the log: no frame (the summary says why)
        } else if (problem.empty()) {
            ++progress.skipped;
        } else {
            if (problem != "missing") {
                ++progress.repaired;
                if (progress.repaired <= 8) {
                    result.notes +=
                        fmt::format("{}: {}; rendered again\n", ReplayFrameName(i, "*"), problem);
                }
            }
            const double sky_time = trajectory.start_time_s() + r.time_offset_s +
                                    (t - trajectory.start_time_s()) * r.time_warp;
            sky->SetTime(geo::TimeFromUnixSeconds(sky_time));
            if (timeline) {
                const auto set_started = std::chrono::steady_clock::now();
                const weather::TimelineSample sample =
                    timeline->At(t, aircraft.lat_deg, aircraft.lon_deg, wind);
                if (sample.weather.clouds.layers != sky->weather().layers) {
                    sky->SetWeather(sample.weather.clouds, settings.clouds);
                    sky->SetWeatherEpoch(weather_epoch);  // SetWeather restarts the wind
                    ++result.weather_sets;
                }
                if (settings.refraction) {
                    sky->SetRefraction(weather::RefractionAirOf(
                        timeline->AirAt(t, aircraft.lat_deg, aircraft.lon_deg)));
                }
                if (sample.weather.visibility_m != visibility_drawn ||
                    sample.weather.fog != fog_drawn) {
                    sky->SetVisibility(sample.weather.visibility_m, sample.weather.fog);
                    visibility_drawn = sample.weather.visibility_m;
                    fog_drawn = sample.weather.fog;
                    ++result.visibility_sets;
                }
                result.weather_seconds +=
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - set_started)
                        .count();
            }
            glm::dvec3 camera_ecef = aircraft.ecef;
            glm::dmat3 ecef_from_view;
            if (r.camera == ReplayCamera::kCockpit) {
                ecef_from_view = glm::mat3_cast(aircraft.ecef_from_body) * geo::BodyFromView();
            } else if (r.camera == ReplayCamera::kChase) {
                const glm::dvec3 up = geo::EcefFromEnu(aircraft.lat_deg, aircraft.lon_deg)[2];
                glm::dvec3 forward =
                    aircraft.velocity_ecef - up * glm::dot(aircraft.velocity_ecef, up);
                if (glm::length(forward) < 1.0) {
                    forward = glm::mat3_cast(aircraft.ecef_from_body)[0];
                }
                forward = glm::normalize(forward);
                camera_ecef = aircraft.ecef - forward * kChaseDistance + up * kChaseHeight;
                ecef_from_view = LookAlong(aircraft.ecef - camera_ecef, up);
            } else {
                camera_ecef = ground.ecef();
                ecef_from_view = LookAlong(aircraft.ecef - camera_ecef, ground.ecef_from_enu()[2]);
            }
            sky->SetEcef(camera_ecef);
            sky->SetViewFromEnu(geo::Observer::FromEcef(camera_ecef).enu_from_ecef() *
                                ecef_from_view);
            sky->ResetCloudHistory();
            sky->Update();
            sky::LutImage frame = sky->RenderOffscreen(r.size);
            for (int pass = 1; pass < r.cloud_passes && sky->has_clouds(); ++pass) {
                frame = sky->RenderOffscreen(r.size);
            }
            const sky::Image image = sky::ImageFromFrame(frame);
            if (r.write_exr) sky::WriteImage(exr, image, {});
            if (r.write_png) {
                sky::ImageWriteOptions options;
                options.exposure = r.exposure;
                sky::WriteImage(png, image, options);
            }
            ++progress.rendered;
        }
        ++progress.done;
        progress.seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
        if (on_progress) on_progress(progress);
    }
    if (progress.repaired > 8) {
        result.notes += fmt::format("... {} frames rendered again in all\n", progress.repaired);
    }

    if (!r.video.empty() && !result.interrupted) {
        if (r.shard.count > 1) {
            result.video_status =
                "video not encoded: run without a shard once all shards are "
                "done to encode it";
            return result;
        }
        // Frames inside gaps hold the frame before the gap (or the first one after a gap at the
        // start), so the video keeps the flight's time.
        std::vector<fs::path> sequence;
        std::optional<fs::path> held;
        std::size_t leading_gap = 0;
        for (std::size_t i = 0; i < result.frames_in_flight; ++i) {
            const fs::path png = r.out_dir / ReplayFrameName(i, "png");
            if (trajectory.At(begin + static_cast<double>(i) / r.fps).valid) {
                if (const std::string problem = FrameProblem(png, r.size); !problem.empty()) {
                    throw ReplayError(
                        fmt::format("{}: {}; the video needs every frame", png.string(), problem));
                }
                held = png;
                for (; leading_gap > 0; --leading_gap) sequence.push_back(png);
            }
            if (held) {
                sequence.push_back(*held);
            } else {
                ++leading_gap;
            }
        }
        if (sequence.empty()) throw ReplayError("no frame to make a video of");
        VideoEncoder encoder(r.video, r.fps);
        for (const fs::path& png : sequence) {
            if (stop.load()) {
                result.interrupted = true;
                result.video_status = "video not encoded: stopped";
                return result;
            }
            encoder.AddPng(png);
        }
        encoder.Finish();
        result.video_status = "video: " + r.video.string();
    }
    return result;
}

}  // namespace zenith::sim
