// Replay's promises: frames are complete or absent, a rerun resumes without redoing finished
// frames, an interruption loses nothing, and shards partition the frames exactly.
#include "zenith/sim/replay.h"

#include <atomic>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include <gtest/gtest.h>

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

std::set<std::string> Files(const fs::path& dir) {
    std::set<std::string> names;
    if (!fs::exists(dir)) return names;
    for (const auto& entry : fs::directory_iterator(dir)) {
        names.insert(entry.path().filename().string());
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

TEST(Replay, BadRequestsNameTheOption) {
    std::atomic<bool> stop{false};
    ReplayRequest r = SmallReplay(ScratchDir("bad"));
    r.fps = 0.0;
    EXPECT_THROW(RunReplay(r, stop), std::invalid_argument);
    EXPECT_THROW(ParseShard("3/3"), std::invalid_argument);
    EXPECT_THROW(ParseShard("1-2"), std::invalid_argument);
    EXPECT_EQ(ParseShard("2/8").index, 2);
    EXPECT_THROW(ParseReplayCamera("wing"), std::invalid_argument);
    try {
        ParseShard("5/2");
        FAIL();
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("--shard = 5/2"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace zenith::sim
