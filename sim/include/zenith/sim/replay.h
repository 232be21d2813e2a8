// Offscreen replay of a recorded flight into frames (EXR and/or PNG) and an MP4. Long runs lose
// nothing and mix nothing:
//   - each frame is written under a temporary name and renamed when complete;
//   - the output folder records the run's settings and a hash of the log (replay.json); a run
//     with other settings into the same folder is refused, naming what differs;
//   - a rerun skips a finished frame only after decoding it and checking its size, and renders
//     it again otherwise (a truncated or corrupt file);
//   - every frame depends only on its own time and pose (the clouds are traced in passes of its
//     own, the stars' apparent places are taken at whole seconds), so resumed, sharded and whole
//     runs write the same pixels;
//   - a stop request (Ctrl-C, SIGTERM) ends the run after the frame in progress;
//   - a shard K/N renders the frames i with i mod N = K (Slurm job arrays:
//     SLURM_ARRAY_TASK_ID / SLURM_ARRAY_TASK_COUNT), all shards into one folder.
// What a run may cost is bounded: the log's limits (zenith/track/flight_log.h), at most
// kMaxReplayFrames frames of at most kMaxFrameSide pixels a side.
#pragma once

#include <atomic>
#include <cstddef>
#include <filesystem>
#include <functional>
#include <glm/glm.hpp>
#include <optional>
#include <string>

#include "zenith/base/error.h"
#include "zenith/sim/render_frame.h"
#include "zenith/sky/image_io.h"
#include "zenith/track/flight_log.h"

namespace zenith::sim {

inline constexpr std::size_t kMaxReplayFrames = 10'000'000;
// Ground observer: eye height above the ground zenith draws (the WGS84 ellipsoid).
inline constexpr double kGroundEyeHeight = 2.0;  // m

// The output folder holds frames of a run with other settings, or a frame cannot be had.
class ReplayError : public Error {
  public:
    using Error::Error;
};

enum class ReplayCamera { kCockpit, kChase, kGround };
// "cockpit" | "chase" | "ground"; throws ArgumentError (field "camera").
ReplayCamera ParseReplayCamera(const std::string& text);

struct Shard {
    int index = 0;  // K, 0-based
    int count = 1;  // N
};
// "K/N" (0 <= K < N <= 100000); throws ArgumentError (field "shard").
Shard ParseShard(const std::string& text);
// From SLURM_ARRAY_TASK_ID and SLURM_ARRAY_TASK_COUNT when both are set (task ids counted from
// SLURM_ARRAY_TASK_MIN, default 0). Throws ArgumentError naming the variable when one is not a
// whole number or the task is outside the array.
std::optional<Shard> ShardFromEnvironment();

struct ReplayRequest {
    std::filesystem::path flight;  // .igc .gpx .kml .csv
    track::ReadOptions read;       // which aircraft in a multi-aircraft log
    std::filesystem::path out_dir = "replay";
    double fps = 10.0;
    glm::ivec2 size{640, 360};
    ReplayCamera camera = ReplayCamera::kCockpit;
    // The ground camera's place (lat_deg, lon_deg, height_m above the ellipsoid); default: on
    // the ground zenith draws under the first fix, kGroundEyeHeight up.
    std::optional<glm::dvec3> observer;
    double fov_deg = 60.0;  // vertical
    sky::Exposure exposure;
    bool write_exr = false;
    bool write_png = true;
    double time_offset_s = 0.0;     // added to the log's times for the sky
    double time_warp = 1.0;         // sky time runs this much faster than flight time
    std::optional<double> start_s;  // flight seconds after the first sample (default: start)
    std::optional<double> end_s;    // (default: the end)
    std::string preset = "earth";
    // Clouds: weather preset or JSON file, anchored at the flight's first point and its wind
    // started at the flight's start. Each frame is traced at full resolution in cloud_passes
    // jittered passes of its own (no history from other frames).
    std::string weather = "clear";
    int cloud_passes = 2;
    // Weather along the flight from METAR reports (instead of `weather`): a CSV (.csv: the
    // airport-archive columns station,valid,lon,lat,metar) or one report per line. Each frame
    // draws weather::MetarTimeline::At of the log's own time (before time_offset_s and
    // time_warp: the reports describe the air the flight flew through) at the aircraft:
    // the nearest station, blended between its reports and across a change of station
    // (zenith/weather/metar_timeline.h). The report's heights are above station_elevation_m
    // (metres above mean sea level, every station), else above the ground zenith draws under
    // them (0 m), as `zenith render` does. The manifest holds the file's hash and these options.
    std::filesystem::path metar_file;
    std::optional<double> station_elevation_m;
    Shard shard;
    // MP4 to encode once every frame of the flight exists (empty: none). Frames inside gaps of
    // the log hold the last frame before the gap, so the video keeps the flight's time.
    std::filesystem::path video;
};

struct ReplayProgress {
    std::size_t done = 0;      // frames of this shard handled so far
    std::size_t total = 0;     // frames of this shard
    std::size_t rendered = 0;  // rendered in this run
    std::size_t skipped = 0;   // already complete (decoded and checked)
    std::size_t repaired = 0;  // found incomplete or corrupt, rendered again
    std::size_t in_gaps = 0;   // inside a gap of the log: no frame
    double seconds = 0.0;      // wall time so far
};

struct ReplayResult {
    ReplayProgress progress;
    std::size_t frames_in_flight = 0;  // all shards
    bool interrupted = false;
    std::string log_summary;  // what the reader used and skipped, and trajectory notes
    std::string notes;        // where the ground observer stands, frames repaired, ...
    // With a METAR file: how often the clouds and the visibility were set (only when the
    // quantised weather changed) and the wall time that took.
    std::size_t weather_sets = 0;
    std::size_t visibility_sets = 0;
    double weather_seconds = 0.0;
    std::string video_status;  // "video: path" or why none was made (a sharded run)
};

// Throws ArgumentError (a bad request, naming its field), track::FlightLogError, ReplayError
// (another run's folder; a missing frame for the video), VideoError (ffmpeg failed), or the
// renderer's and writers' errors. Frames written before an error stay complete.
ReplayResult RunReplay(const ReplayRequest& request, const std::atomic<bool>& stop,
                       const std::function<void(const ReplayProgress&)>& on_progress = {});

// Frame file name for frame index i and an extension ("png", "exr").
std::string ReplayFrameName(std::size_t index, const std::string& extension);

// The settings file a replay folder holds.
inline constexpr const char* kReplayManifest = "replay.json";

}  // namespace zenith::sim
