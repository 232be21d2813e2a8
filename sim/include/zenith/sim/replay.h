// Offscreen replay of a recorded flight into frames (EXR and/or PNG) and, when ffmpeg is
// installed, an MP4. Long runs lose nothing: each frame is written under a temporary name and
// renamed when complete, a rerun skips finished frames, Ctrl-C stops after the current frame,
// and a shard K/N renders the interleaved frames i with i mod N = K so a scheduler can spread the
// work (Slurm job arrays: SLURM_ARRAY_TASK_ID / SLURM_ARRAY_TASK_COUNT).
#pragma once

#include <atomic>
#include <cstddef>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>

#include <glm/glm.hpp>

#include "zenith/sky/image_io.h"

namespace zenith::sim {

enum class ReplayCamera { kCockpit, kChase, kGround };
ReplayCamera ParseReplayCamera(const std::string& text);  // cockpit | chase | ground

struct Shard {
    int index = 0;  // K, 0-based
    int count = 1;  // N
};
// "K/N" (0 <= K < N); throws std::invalid_argument naming --shard.
Shard ParseShard(const std::string& text);
// From SLURM_ARRAY_TASK_ID and SLURM_ARRAY_TASK_COUNT when both are set (task ids counted from
// SLURM_ARRAY_TASK_MIN, default 0).
std::optional<Shard> ShardFromEnvironment();

struct ReplayRequest {
    std::filesystem::path flight;  // .igc .gpx .kml .csv
    std::filesystem::path out_dir = "replay";
    double fps = 10.0;
    glm::ivec2 size{640, 360};
    ReplayCamera camera = ReplayCamera::kCockpit;
    double fov_deg = 60.0;  // vertical
    sky::Exposure exposure;
    bool write_exr = false;
    bool write_png = true;
    double time_offset_s = 0.0;  // added to the log's times for the sky
    double time_warp = 1.0;      // sky time runs this much faster than flight time
    std::optional<double> start_s;  // flight seconds after the first sample (default: start)
    std::optional<double> end_s;    // (default: the end)
    std::string preset = "earth";
    // Clouds: weather preset or JSON file, anchored at the flight's first point and its wind
    // started at the flight's start. Each frame is traced at full resolution in cloud_passes
    // jittered passes of its own (no history from other frames), so a frame's pixels do not
    // depend on which frames were rendered before it: resumed and sharded runs match a whole one.
    std::string weather = "clear";
    int cloud_passes = 2;
    Shard shard;
    std::filesystem::path video;  // MP4 to encode at the end (empty: none)
};

struct ReplayProgress {
    std::size_t done = 0;      // frames of this shard handled so far (rendered or skipped)
    std::size_t total = 0;     // frames of this shard
    std::size_t rendered = 0;  // rendered in this run
    std::size_t skipped = 0;   // already complete
    double seconds = 0.0;      // wall time so far
};

struct ReplayResult {
    ReplayProgress progress;
    std::size_t frames_in_flight = 0;  // all shards
    bool interrupted = false;
    std::string log_summary;  // what the reader used and skipped, and trajectory notes
    std::string video_status;
};

// Throws std::invalid_argument (bad request, naming the option) or the readers' errors.
ReplayResult RunReplay(const ReplayRequest& request, const std::atomic<bool>& stop,
                       const std::function<void(const ReplayProgress&)>& on_progress = {});

// Frame file name for frame index i and an extension ("png", "exr").
std::string ReplayFrameName(std::size_t index, const std::string& extension);

}  // namespace zenith::sim
