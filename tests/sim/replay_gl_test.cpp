// Replay's promises: frames are complete or absent, a rerun resumes without redoing finished
// frames, an interruption loses nothing, and shards partition the frames exactly.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <string>

#include "zenith/sim/replay.h"
#include "zenith/sky/image_io.h"

namespace zenith::sim {
namespace {

namespace fs = std::filesystem;

ReplayRequest SmallReplay(const fs::path& out) {
    ReplayRequest r;
    r.flight = fs::path(ZENITH_SOURCE_DIR) / "data/flights/sunset_approach_sfo.kml";
    r.out_dir = out;
    r.fps = 0.04;  // one frame every 25 s of the 8-minute approach: 19 frames
    r.size = {32, 18};
    return r;
}

// The frame files in a folder (not its settings file).
std::set<std::string> Files(const fs::path& dir) {
    std::set<std::string> names;
    if (!fs::exists(dir)) return names;
    for (const auto& entry : fs::directory_iterator(dir)) {
        const std::string name = entry.path().filename().string();
        if (name != kReplayManifest) names.insert(name);
    }
    return names;
}

fs::path ScratchDir(const std::string& name) {
    const fs::path dir = fs::path(ZENITH_BINARY_DIR) / "replay_test" / name;
    fs::remove_all(dir);
    return dir;
}

TEST(Replay, ResumesWithoutRedoingFinishedFramesAndLosesNothingOnInterrupt) {
    const fs::path dir = ScratchDir("resume");
    std::atomic<bool> stop{false};
    // Interrupted after 5 frames (as Ctrl-C would, after the frame in progress).
    const ReplayResult first = RunReplay(SmallReplay(dir), stop, [&](const ReplayProgress& p) {
        if (p.rendered == 5) stop.store(true);
    });
    EXPECT_TRUE(first.interrupted);
    EXPECT_EQ(first.progress.rendered, 5u);
    EXPECT_EQ(Files(dir).size(), 5u);  // five complete frames, no partial file
    stop.store(false);

    // Resume: the rest only.
    const ReplayResult second = RunReplay(SmallReplay(dir), stop);
    EXPECT_FALSE(second.interrupted);
    EXPECT_EQ(second.progress.skipped, 5u);
    EXPECT_EQ(second.progress.rendered, second.frames_in_flight - 5);
    EXPECT_EQ(Files(dir).size(), second.frames_in_flight);

    // A lost frame and a stale partial file (as a crash mid-write leaves): only that frame is
    // redone, and the partial is replaced by the complete frame.
    fs::remove(dir / ReplayFrameName(7, "png"));
    std::ofstream(dir / (ReplayFrameName(7, "png") + ".partial")) << "half a frame";
    const ReplayResult third = RunReplay(SmallReplay(dir), stop);
    EXPECT_EQ(third.progress.rendered, 1u);
    EXPECT_EQ(Files(dir).size(), third.frames_in_flight);
    for (const std::string& name : Files(dir)) {
        EXPECT_EQ(name.find(".partial"), std::string::npos) << name;
        EXPECT_GT(fs::file_size(dir / name), 100u) << name;
    }
}

TEST(Replay, ShardsPartitionTheFrames) {
    std::set<std::string> all;
    std::size_t total = 0;
    std::size_t in_flight = 0;
    for (int k = 0; k < 3; ++k) {
        const fs::path dir = ScratchDir("shard" + std::to_string(k));
        ReplayRequest r = SmallReplay(dir);
        r.shard = {k, 3};
        std::atomic<bool> stop{false};
        const ReplayResult result = RunReplay(r, stop);
        in_flight = result.frames_in_flight;
        for (const std::string& name : Files(dir)) {
            EXPECT_TRUE(all.insert(name).second) << name << " rendered by two shards";
        }
        total += result.progress.rendered;
    }
    EXPECT_EQ(total, in_flight);
    EXPECT_EQ(all.size(), in_flight);
    for (std::size_t i = 0; i < in_flight; ++i) {
        EXPECT_TRUE(all.count(ReplayFrameName(i, "png"))) << "frame " << i << " missing";
    }
}

// With clouds a frame is rendered from its own passes only: a shard's frame (rendered after a
// different frame than in the whole run) has the same pixels.
TEST(Replay, CloudyShardsMatchAWholeRun) {
    const auto request = [](const fs::path& dir) {
        ReplayRequest r = SmallReplay(dir);
        r.weather = "broken";
        r.fps = 0.01;  // 5 frames
        r.write_png = false;
        r.write_exr = true;
        return r;
    };
    std::atomic<bool> stop{false};
    const fs::path whole = ScratchDir("cloudy_whole");
    const fs::path shard = ScratchDir("cloudy_shard");
    RunReplay(request(whole), stop);
    ReplayRequest second = request(shard);
    second.shard = {1, 2};
    const ReplayResult result = RunReplay(second, stop);
    ASSERT_GE(result.progress.rendered, 2u);
    double cloudy = 0.0;
    for (const std::string& name : Files(shard)) {
        const sky::Image a = sky::ReadExr(shard / name), b = sky::ReadExr(whole / name);
        ASSERT_EQ(a.pixels.size(), b.pixels.size());
        for (std::size_t i = 0; i < a.pixels.size(); ++i) {
            ASSERT_EQ(a.pixels[i], b.pixels[i]) << name << " pixel " << i;
        }
        cloudy += 1.0;
    }
    EXPECT_EQ(cloudy, static_cast<double>(result.progress.rendered));
}

TEST(Replay, BadRequestsNameTheFieldAndCreateNothing) {
    std::atomic<bool> stop{false};
    const fs::path dir = ScratchDir("bad");
    const auto field_of = [&](const ReplayRequest& r) {
        try {
            RunReplay(r, stop);
        } catch (const ArgumentError& e) {
            return e.field() + ": " + e.what();
        }
        return std::string("(nothing thrown)");
    };
    ReplayRequest r = SmallReplay(dir);
    r.fps = 0.0;
    EXPECT_EQ(field_of(r), "fps: fps = 0 is out of range (expected (0, 1000])");
    r = SmallReplay(dir);
    r.size = {0, 0};
    EXPECT_EQ(field_of(r).substr(0, 17), "size: size = 0x0 ");
    r.size = {100000, 100000};
    EXPECT_EQ(field_of(r).substr(0, 22), "size: size = 100000x10");
    r = SmallReplay(dir);
    r.end_s = 1e12;  // spun for hours
    EXPECT_EQ(field_of(r).substr(0, 29), "end_s: end_s = 1000000000000 ");
    r.end_s = std::numeric_limits<double>::infinity();  // an undefined cast gave one frame
    EXPECT_EQ(field_of(r).substr(0, 18), "end_s: end_s = inf");
    r.end_s = 1e300;
    EXPECT_EQ(field_of(r).substr(0, 6), "end_s:");
    r = SmallReplay(dir);
    r.fps = 1000.0;  // four hours at the highest rate: 14.4 M frames
    r.end_s.reset();
    r.flight = fs::path(ZENITH_BINARY_DIR) / "replay_test" / "four_hours.csv";
    {
        std::ofstream log(r.flight);
        log << "time,lat_deg,lon_deg,alt_wgs84_m\n"
               "2024-06-24T00:00:00Z,67.89,21.10,400\n"
               "2024-06-24T02:00:00Z,67.90,21.10,400\n"
               "2024-06-24T04:00:00Z,67.91,21.10,400\n";
    }
    EXPECT_NE(field_of(r).find("more than 10000000 in one replay"), std::string::npos)
        << field_of(r);
    EXPECT_FALSE(fs::exists(dir)) << "a refused request left a folder";

    EXPECT_THROW(ParseShard("3/3"), ArgumentError);
    EXPECT_THROW(ParseShard("1-2"), ArgumentError);
    EXPECT_EQ(ParseShard("2/8").index, 2);
    EXPECT_THROW(ParseReplayCamera("wing"), ArgumentError);
    try {
        ParseShard("5/2");
        FAIL();
    } catch (const ArgumentError& e) {
        EXPECT_EQ(e.field(), "shard");
        EXPECT_NE(std::string(e.what()).find("shard = 5/2"), std::string::npos) << e.what();
    }
}

TEST(Replay, SlurmVariablesAreReadStrictly) {
    setenv("SLURM_ARRAY_TASK_ID", "abc", 1);
    setenv("SLURM_ARRAY_TASK_COUNT", "4", 1);
    try {
        ShardFromEnvironment();
        FAIL() << "abc became a shard";
    } catch (const ArgumentError& e) {
        EXPECT_NE(std::string(e.what()).find("SLURM_ARRAY_TASK_ID = 'abc'"), std::string::npos);
    }
    setenv("SLURM_ARRAY_TASK_ID", "7", 1);
    setenv("SLURM_ARRAY_TASK_MIN", "5", 1);
    const std::optional<Shard> shard = ShardFromEnvironment();
    ASSERT_TRUE(shard);
    EXPECT_EQ(shard->index, 2);
    EXPECT_EQ(shard->count, 4);
    setenv("SLURM_ARRAY_TASK_ID", "9", 1);  // outside 5..8
    EXPECT_THROW(ShardFromEnvironment(), ArgumentError);
    unsetenv("SLURM_ARRAY_TASK_ID");
    unsetenv("SLURM_ARRAY_TASK_COUNT");
    unsetenv("SLURM_ARRAY_TASK_MIN");
    EXPECT_FALSE(ShardFromEnvironment());
}

// A rerun into a folder of other settings is refused before anything is written; broken frames
// are found by decoding them and rendered again.
TEST(Replay, TheFolderRemembersItsSettingsAndBrokenFramesAreRedone) {
    const fs::path dir = ScratchDir("manifest");
    std::atomic<bool> stop{false};
    ReplayRequest r = SmallReplay(dir);
    r.fps = 0.02;
    r.write_exr = true;  // both formats
    const ReplayResult whole = RunReplay(r, stop);
    ASSERT_GE(whole.progress.rendered, 5u);

    ReplayRequest bigger = r;
    bigger.size = {64, 36};
    try {
        RunReplay(bigger, stop);
        FAIL() << "frames of two sizes would mix";
    } catch (const ReplayError& e) {
        EXPECT_NE(std::string(e.what()).find("size: \"32x18\" in the folder, \"64x36\" now"),
                  std::string::npos)
            << e.what();
    }
    ReplayRequest chase = r;
    chase.camera = ReplayCamera::kChase;
    EXPECT_THROW(RunReplay(chase, stop), ReplayError);

    // A truncated PNG, a corrupted EXR and a frame of the wrong size.
    fs::resize_file(dir / ReplayFrameName(1, "png"), 100);
    {
        std::fstream exr(dir / ReplayFrameName(2, "exr"),
                         std::ios::in | std::ios::out | std::ios::binary);
        exr.seekp(static_cast<std::streamoff>(fs::file_size(dir / ReplayFrameName(2, "exr")) / 2));
        exr << "garbage in the middle of the pixels";
    }
    sky::WritePng(dir / ReplayFrameName(3, "png"), sky::Image(8, 8), 10.0);
    const ReplayResult again = RunReplay(r, stop);
    EXPECT_EQ(again.progress.rendered, 3u);
    EXPECT_EQ(again.progress.repaired, 3u);
    EXPECT_NE(again.notes.find("8x8 instead of 32x18"), std::string::npos) << again.notes;
    for (std::size_t i = 1; i <= 3; ++i) {
        EXPECT_EQ(sky::ReadPng(dir / ReplayFrameName(i, "png")).width, 32);
        EXPECT_EQ(sky::ReadExr(dir / ReplayFrameName(i, "exr")).width, 32);
    }
}

// A log whose first fix stands alone before a gap: the ground observer stands under it (never at
// 0 N 0 E, where every frame was black), and a lone fix renders.
TEST(Replay, TheGroundObserverStandsUnderTheFirstFix) {
    const fs::path dir = ScratchDir("ground");
    const fs::path log = dir.parent_path() / "lone_first_fix.csv";
    fs::create_directories(dir.parent_path());
    {
        std::ofstream csv(log);
        csv << "time,lat,lon,alt_msl_m\n"
            << "2024-06-21T19:00:00Z,47.45,8.56,3000\n";  // 3 km up, then a 10-minute gap
        for (int i = 0; i < 20; ++i) {
            csv << "2024-06-21T19:10:" << fmt::format("{:02}", i) << "Z,47.46," << 8.56 + 0.001 * i
                << ",3000\n";
        }
    }
    std::atomic<bool> stop{false};
    ReplayRequest r = SmallReplay(dir);
    r.flight = log;
    r.camera = ReplayCamera::kGround;
    r.fps = 0.1;
    r.write_png = false;
    r.write_exr = true;
    const ReplayResult result = RunReplay(r, stop);
    EXPECT_NE(result.notes.find("ground observer at 47.45000, 8.56000, 2.0 m above the ellipsoid"),
              std::string::npos)
        << result.notes;
    // The lone fix at 0 s, and 600 s and 610 s within the fixes from 600 to 619 s.
    EXPECT_EQ(result.progress.rendered, 3u);
    EXPECT_GT(result.progress.in_gaps, 0u);
    const sky::Image first = sky::ReadExr(dir / ReplayFrameName(0, "exr"));
    double sum = 0.0;
    for (const glm::vec4& p : first.pixels) sum += p.g;
    EXPECT_GT(sum / static_cast<double>(first.pixels.size()), 100.0);  // a sunset sky, not black
}

}  // namespace
}  // namespace zenith::sim
