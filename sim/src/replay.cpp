#include "zenith/sim/replay.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include <fmt/format.h>
#include <glm/gtc/quaternion.hpp>

#include "zenith/geo/observer.h"
#include "zenith/track/flight_log.h"
#include "zenith/sim/sky_system.h"
#include "zenith/track/trajectory.h"

namespace zenith::sim {
namespace {

namespace fs = std::filesystem;

// Chase camera: behind and above the aircraft, looking at it.
constexpr double kChaseDistance = 60.0;  // m
constexpr double kChaseHeight = 15.0;    // m
// Ground observer: at the first point of the flight, eye height above the ellipsoid there.
constexpr double kGroundEyeHeight = 2.0;  // m

// Columns right, up, backward of a camera looking along `forward` with `up_hint` up.
glm::dmat3 LookAlong(const glm::dvec3& forward, const glm::dvec3& up_hint) {
    const glm::dvec3 f = glm::normalize(forward);
    glm::dvec3 right = glm::cross(f, up_hint);
    if (glm::length(right) < 1e-9) right = glm::cross(f, glm::dvec3(0.0, 1.0, 0.0));
    right = glm::normalize(right);
    return glm::dmat3(right, glm::cross(right, f), -f);
}

bool CompleteFrame(const fs::path& path) {
    std::error_code error;
    return fs::is_regular_file(path, error) && fs::file_size(path, error) > 0;
}

}  // namespace

ReplayCamera ParseReplayCamera(const std::string& text) {
    if (text == "cockpit") return ReplayCamera::kCockpit;
    if (text == "chase") return ReplayCamera::kChase;
    if (text == "ground") return ReplayCamera::kGround;
    throw std::invalid_argument("--camera = " + text + " is not known (expected cockpit, chase "
                                "or ground)");
}

Shard ParseShard(const std::string& text) {
    int k = -1, n = 0;
    char slash = 0, extra = 0;
    if (std::sscanf(text.c_str(), "%d%c%d%c", &k, &slash, &n, &extra) != 3 || slash != '/' ||
        !(n >= 1 && k >= 0 && k < n)) {
        throw std::invalid_argument("--shard = " + text +
                                    " is not a shard (expected K/N with 0 <= K < N, e.g. 2/8)");
    }
    return {k, n};
}

std::optional<Shard> ShardFromEnvironment() {
    const char* id = std::getenv("SLURM_ARRAY_TASK_ID");
    const char* count = std::getenv("SLURM_ARRAY_TASK_COUNT");
    if (id == nullptr || count == nullptr) return std::nullopt;
    const char* min = std::getenv("SLURM_ARRAY_TASK_MIN");
    const int first = min != nullptr ? std::atoi(min) : 0;
    return ParseShard(fmt::format("{}/{}", std::atoi(id) - first, std::atoi(count)));
}

std::string ReplayFrameName(std::size_t index, const std::string& extension) {
    return fmt::format("frame_{:06d}.{}", index, extension);
}

ReplayResult RunReplay(const ReplayRequest& r, const std::atomic<bool>& stop,
                       const std::function<void(const ReplayProgress&)>& on_progress) {
    if (!(r.fps > 0.0 && r.fps <= 1000.0)) {
        throw std::invalid_argument(fmt::format("--fps = {} is out of range (expected 0 < fps "
                                                "<= 1000)", r.fps));
    }
    if (!(r.time_warp > 0.0 && std::isfinite(r.time_warp))) {
        throw std::invalid_argument(fmt::format("--time-warp = {} is out of range (expected a "
                                                "finite factor > 0)", r.time_warp));
    }
    if (!(std::isfinite(r.time_offset_s))) {
        throw std::invalid_argument("--time-offset must be a finite number of seconds");
    }
    if (!(r.fov_deg > 0.0 && r.fov_deg < 180.0)) {
        throw std::invalid_argument(fmt::format("--fov = {} is out of range (expected 0 < fov < "
                                                "180 degrees)", r.fov_deg));
    }
    if (!r.write_exr && !r.write_png) {
        throw std::invalid_argument("--format: choose png, exr or both");
    }

    const track::FlightLog log = track::ReadFlightLog(r.flight);
    const track::Trajectory trajectory(log);
    ReplayResult result;
    result.log_summary = log.summary.ToString();
    for (const std::string& note : trajectory.notes()) result.log_summary += "\n" + note;

    const double begin = trajectory.start_time_s() + r.start_s.value_or(0.0);
    const double end = r.end_s ? trajectory.start_time_s() + *r.end_s : trajectory.end_time_s();
    if (!(end >= begin)) {
        throw std::invalid_argument(fmt::format(
            "--start/--end select nothing: the flight lasts {:.0f} s", trajectory.end_time_s() -
                                                                          trajectory.start_time_s()));
    }
    result.frames_in_flight = static_cast<std::size_t>(std::floor((end - begin) * r.fps)) + 1;
    for (std::size_t i = 0; i < result.frames_in_flight; ++i) {
        if (static_cast<int>(i % static_cast<std::size_t>(r.shard.count)) == r.shard.index) {
            ++result.progress.total;
        }
    }
    fs::create_directories(r.out_dir);

    // The ground observer stands under the first valid point.
    const track::TrajectoryState first = trajectory.At(trajectory.start_time_s());
    const geo::Observer ground(first.lat_deg, first.lon_deg, first.height + kGroundEyeHeight);

    SkySystemSettings settings;
    settings.preset = r.preset;
    settings.weather = r.weather;
    settings.clouds.block = 1;
    auto sky = SkySystem::CreateHeadless(settings);
    sky->SetWeatherOrigin(first.lat_deg, first.lon_deg);
    sky->SetWeatherEpoch(geo::TimeFromUtc(geo::CivilFromUnixSeconds(
        trajectory.start_time_s() + r.time_offset_s)));
    sky->SetProjection(r.fov_deg * 0.017453292519943295, double(r.size.x) / r.size.y);
    const auto started = std::chrono::steady_clock::now();
    ReplayProgress& progress = result.progress;
    for (std::size_t i = 0; i < result.frames_in_flight; ++i) {
        if (static_cast<int>(i % static_cast<std::size_t>(r.shard.count)) != r.shard.index) {
            continue;
        }
        if (stop.load()) {
            result.interrupted = true;
            break;
        }
        const fs::path png = r.out_dir / ReplayFrameName(i, "png");
        const fs::path exr = r.out_dir / ReplayFrameName(i, "exr");
        const bool done = (!r.write_png || CompleteFrame(png)) && (!r.write_exr || CompleteFrame(exr));
        const double t = begin + static_cast<double>(i) / r.fps;
        const track::TrajectoryState aircraft = trajectory.At(t);
        if (done) {
            ++progress.skipped;
        } else if (aircraft.valid) {
            const double sky_time = trajectory.start_time_s() + r.time_offset_s +
                                    (t - trajectory.start_time_s()) * r.time_warp;
            sky->SetTime(geo::TimeFromUtc(geo::CivilFromUnixSeconds(sky_time)));
            glm::dvec3 camera_ecef = aircraft.ecef;
            glm::dmat3 ecef_from_view;
            if (r.camera == ReplayCamera::kCockpit) {
                // Body x forward, y right, z down -> view right = y, up = -z, backward = -x.
                const glm::dmat3 ecef_from_body = glm::mat3_cast(aircraft.ecef_from_body);
                ecef_from_view = glm::dmat3(ecef_from_body[1], -ecef_from_body[2],
                                            -ecef_from_body[0]);
            } else if (r.camera == ReplayCamera::kChase) {
                const geo::Observer here(aircraft.lat_deg, aircraft.lon_deg, aircraft.height);
                const glm::dvec3 up = here.ecef_from_enu()[2];
                glm::dvec3 forward = aircraft.velocity_ecef - up * glm::dot(aircraft.velocity_ecef, up);
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
            const geo::Observer camera = geo::Observer::FromEcef(camera_ecef);
            sky->SetViewFromEnu(camera.enu_from_ecef() * ecef_from_view);
            sky->ResetCloudHistory();
            sky->Update();
            sky::LutImage frame = sky->RenderOffscreen(r.size);
            for (int pass = 1; pass < r.cloud_passes && sky->has_clouds(); ++pass) {
                frame = sky->RenderOffscreen(r.size);
            }
            sky::Image image(r.size.x, r.size.y);
            for (int y = 0; y < r.size.y; ++y) {
                for (int x = 0; x < r.size.x; ++x) image.at(x, y) = frame.at(x, r.size.y - 1 - y);
            }
            if (r.write_exr) sky::WriteImage(exr, image, {});
            if (r.write_png) {
                sky::ImageWriteOptions options;
                options.exposure = r.exposure;
                sky::WriteImage(png, image, options);
            }
            ++progress.rendered;
        } else {
            ++progress.skipped;  // inside a gap of the log: no frame (the summary says why)
        }
        ++progress.done;
        progress.seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
        if (on_progress) on_progress(progress);
    }

    if (!r.video.empty() && !result.interrupted) {
        if (r.shard.count > 1) {
            result.video_status = "video not encoded: run without --shard (or once all shards "
                                  "are done) to encode it";
        } else if (std::system("command -v ffmpeg >/dev/null 2>&1") != 0) {
            result.video_status = "video not encoded: ffmpeg is not installed (apt-get install "
                                  "ffmpeg)";
        } else if (!r.write_png) {
            result.video_status = "video not encoded: it is made from the PNG frames (--format "
                                  "png or both)";
        } else {
            const fs::path partial = r.video.string() + ".partial.mp4";
            const std::string command = fmt::format(
                "ffmpeg -y -loglevel error -framerate {} -i '{}' -c:v libx264 -pix_fmt yuv420p "
                "'{}'",
                r.fps, (r.out_dir / "frame_%06d.png").string(), partial.string());
            if (std::system(command.c_str()) == 0) {
                fs::rename(partial, r.video);
                result.video_status = "video: " + r.video.string();
            } else {
                std::error_code error;
                fs::remove(partial, error);
                result.video_status = "video not encoded: ffmpeg failed (" + command + ")";
            }
        }
    }
    return result;
}

}  // namespace zenith::sim
