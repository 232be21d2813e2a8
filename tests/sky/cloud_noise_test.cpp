// Laws the cloud noise (clouds/noise.h) must obey: periodic primitives, volumes that tile
// seamlessly on every axis and channel, determinism from the seed (independent of threads),
// value ranges and statistics of real noise with frequencies that increase across the channels,
// a divergence-free curl field, and a cache that round-trips, survives corruption and is fast.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>

#include "cloud_test_support.h"
#include "zenith/base/error.h"
#include "zenith/sky/clouds/noise.h"

namespace zenith::sky::clouds {
namespace {

TEST(CloudNoisePrimitives, PerlinAndWorleyRepeatWithTheirPeriod) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const glm::ivec3 period(4, 2, 8);
    for (int i = 0; i < 2000; ++i) {
        const glm::dvec3 p(u(rng) * 4.0, u(rng) * 2.0, u(rng) * 8.0);
        for (int axis = 0; axis < 3; ++axis) {
            glm::dvec3 shifted = p;
            shifted[axis] += period[axis] * (1 + i % 3);
            ASSERT_NEAR(TileablePerlin(p, period, 7), TileablePerlin(shifted, period, 7), 1e-12);
            ASSERT_NEAR(TileableWorley(p, period, 7), TileableWorley(shifted, period, 7), 1e-12);
        }
    }
}

TEST(CloudNoisePrimitives, PerlinVanishesOnTheLatticeAndWorleyIsADistance) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    double largest = 0.0;
    for (int i = 0; i < 5000; ++i) {
        const glm::dvec3 p(u(rng) * 8.0, u(rng) * 8.0, u(rng) * 8.0);
        EXPECT_EQ(TileablePerlin(glm::floor(p), glm::ivec3(8), 9), 0.0);
        const double f1 = TileableWorley(p, glm::ivec3(8), 9);
        // One feature point per cell: the nearest is within the cell's diagonal.
        EXPECT_GE(f1, 0.0);
        EXPECT_LE(f1, std::sqrt(3.0));
        largest = std::max(largest, std::abs(TileablePerlin(p, glm::ivec3(8), 9)));
    }
    EXPECT_GT(largest, 0.4);
    EXPECT_LE(largest, 1.5);
}

// Mean and largest |difference| between neighbours along `axis`, inside the volume and across
// the wrap (last slice to first).
struct Seams {
    double interior_mean = 0.0, interior_max = 0.0, wrap_mean = 0.0, wrap_max = 0.0;
};

Seams MeasureSeams(const NoiseVolume& v, int axis, int c) {
    Seams s;
    long long interior = 0, wrap = 0;
    for (int z = 0; z < v.size.z; ++z) {
        for (int y = 0; y < v.size.y; ++y) {
            for (int x = 0; x < v.size.x; ++x) {
                glm::ivec3 p(x, y, z), q = p;
                q[axis] = (p[axis] + 1) % v.size[axis];
                if (v.size[axis] == 1) continue;
                const double d = std::abs(v.Value(p.x, p.y, p.z, c) - v.Value(q.x, q.y, q.z, c));
                if (q[axis] == 0) {
                    s.wrap_mean += d, s.wrap_max = std::max(s.wrap_max, d), ++wrap;
                } else {
                    s.interior_mean += d, s.interior_max = std::max(s.interior_max, d), ++interior;
                }
            }
        }
    }
    s.interior_mean /= static_cast<double>(std::max(interior, 1LL));
    s.wrap_mean /= static_cast<double>(std::max(wrap, 1LL));
    return s;
}

void ExpectTiles(const NoiseVolume& v, const char* name) {
    for (int c = 0; c < v.channels; ++c) {
        for (int axis = 0; axis < 3; ++axis) {
            if (v.size[axis] == 1) continue;
            const Seams s = MeasureSeams(v, axis, c);
            SCOPED_TRACE(std::string(name) + " channel " + "RGBA"[c] + " axis " + "xyz"[axis]);
            // The wrap is one more pair of neighbours: no larger than the interior's largest
            // step, and on average like any other slice (a non-tiling volume has wrap
            // differences of random pairs, ~10x the interior mean).
            EXPECT_LE(s.wrap_max, s.interior_max);
            EXPECT_LE(s.wrap_mean, 1.3 * s.interior_mean + 1.0 / 255.0)
                << "interior mean " << s.interior_mean;
            EXPECT_GT(s.interior_mean, 0.0);
        }
    }
}

TEST(CloudNoiseVolumes, OppositeFacesContinueSmoothly) {
    const CloudNoise& noise = test::CachedNoise();
    ExpectTiles(noise.shape, "shape");
    ExpectTiles(noise.detail, "detail");
    ExpectTiles(noise.curl, "curl");
}

TEST(CloudNoiseVolumes, SizesAndChannelsAreThoseOfTable41) {
    const CloudNoise& noise = test::CachedNoise();
    EXPECT_EQ(noise.shape.size, glm::ivec3(128, 32, 128));
    EXPECT_EQ(noise.shape.channels, 4);
    EXPECT_EQ(noise.detail.size, glm::ivec3(32, 32, 32));
    EXPECT_EQ(noise.detail.channels, 3);
    EXPECT_EQ(noise.curl.size, glm::ivec3(128, 128, 1));
    EXPECT_EQ(noise.curl.channels, 2);
}

TEST(CloudNoiseVolumes, StatisticsAreThoseOfRealNoiseWithRisingFrequency) {
    const CloudNoise& noise = test::CachedNoise();
    for (const NoiseVolume* v : {&noise.shape, &noise.detail}) {
        double previous_roughness = 0.0;
        for (int c = 0; c < v->channels; ++c) {
            double sum = 0.0, sum2 = 0.0;
            int low = 0, high = 0;
            const std::size_t n = v->texels.size() / static_cast<std::size_t>(v->channels);
            for (std::size_t i = 0; i < n; ++i) {
                const double x = v->texels[i * static_cast<std::size_t>(v->channels) +
                                           static_cast<std::size_t>(c)] /
                                 255.0;
                sum += x, sum2 += x * x;
                low += x<0.1, high += x> 0.9;
            }
            const double mean = sum / static_cast<double>(n);
            const double sd = std::sqrt(std::max(sum2 / static_cast<double>(n) - mean * mean, 0.0));
            SCOPED_TRACE(std::string("channel ") + "RGBA"[c]);
            EXPECT_GT(mean, 0.25);
            EXPECT_LT(mean, 0.8);
            EXPECT_GT(sd, 0.05);
            EXPECT_LT(sd, 0.3);
            // The channels after R are Worley octaves at rising frequency: rougher each time.
            const double roughness = MeasureSeams(*v, 0, c).interior_mean;
            if (c >= (v == &noise.shape ? 2 : 1)) {
                EXPECT_GT(roughness, 1.3 * previous_roughness);
            }
            previous_roughness = roughness;
        }
    }
}

TEST(CloudNoiseVolumes, CurlFieldIsDivergenceFree) {
    const NoiseVolume& curl = test::CachedNoise().curl;
    const int n = curl.size.x;
    const auto v = [&](int x, int y, int c) {
        return 2.0 * curl.Value((x + n) % n, (y + n) % n, 0, c) - 1.0;
    };
    double divergence = 0.0, gradient = 0.0, largest = 0.0;
    for (int y = 0; y < n; ++y) {
        for (int x = 0; x < n; ++x) {
            // The same central differences the generator took of the potential: they commute,
            // so only 8-bit rounding is left.
            divergence += std::abs(0.5 * (v(x + 1, y, 0) - v(x - 1, y, 0)) +
                                   0.5 * (v(x, y + 1, 1) - v(x, y - 1, 1)));
            gradient += std::abs(0.5 * (v(x + 1, y, 0) - v(x - 1, y, 0)));
            largest = std::max(largest, std::hypot(v(x, y, 0), v(x, y, 1)));
        }
    }
    EXPECT_LT(divergence, 0.3 * gradient);
    EXPECT_GT(largest, 0.95);  // normalised to |v| <= 1
    EXPECT_LE(largest, 1.0 + 2.0 / 255.0);
}

TEST(CloudNoiseGeneration, SameSeedSameBytesWhateverTheThreads) {
    CloudNoiseSettings small;
    small.shape_size = {32, 8, 32};
    small.detail_size = 16;
    small.curl_size = 32;
    small.threads = 1;
    const CloudNoise one = GenerateCloudNoise(small);
    small.threads = 2;
    EXPECT_TRUE(GenerateCloudNoise(small) == one);
    small.threads = 5;
    EXPECT_TRUE(GenerateCloudNoise(small) == one);
    small.seed = 2;
    const CloudNoise other = GenerateCloudNoise(small);
    EXPECT_NE(other.shape.texels, one.shape.texels);
    EXPECT_NE(other.detail.texels, one.detail.texels);
    EXPECT_NE(other.curl.texels, one.curl.texels);
}

TEST(CloudNoiseGeneration, RejectsSizesThatCannotTile) {
    EXPECT_THROW(GenerateShapeNoise(1, {128, 20, 128}), zenith::ArgumentError);
    EXPECT_THROW(GenerateShapeNoise(1, {0, 32, 128}), zenith::ArgumentError);
    EXPECT_THROW(GenerateDetailNoise(1, 0), zenith::ArgumentError);
    try {
        GenerateShapeNoise(1, {128, 20, 128});
    } catch (const zenith::ArgumentError& e) {
        EXPECT_NE(std::string(e.what()).find("128x20x128"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("axis y"), std::string::npos) << e.what();
    }
}

TEST(CloudNoiseCache, GeneratesOnceThenLoadsAndTimesBoth) {
    const std::filesystem::path dir = test::TempDir("noise-cache");
    const CloudNoiseSettings settings;
    const CloudNoiseLoad first = LoadOrGenerateCloudNoise(settings, dir);
    EXPECT_FALSE(first.from_cache);
    EXPECT_EQ(first.cache_problem, "");
    EXPECT_TRUE(std::filesystem::exists(first.cache_file));
    EXPECT_EQ(first.cache_file.filename(), NoiseCacheFileName(settings));
    const CloudNoiseLoad second = LoadOrGenerateCloudNoise(settings, dir);
    EXPECT_TRUE(second.from_cache) << second.cache_problem;
    EXPECT_TRUE(second.noise == first.noise);
    EXPECT_TRUE(first.noise == test::CachedNoise());  // the build tree's cache, from another run
    std::printf(
        "cloud noise (shape 128x32x128, detail 32^3, curl 128^2, %d threads): "
        "generated + cached in %.3f s, loaded from cache in %.4f s\n",
        settings.threads, first.seconds, second.seconds);
    EXPECT_LT(second.seconds, first.seconds);
    // Only the cache file is left: no temporary from the atomic write.
    int files = 0;
    for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir)) ++files;
    EXPECT_EQ(files, 1);
    std::filesystem::remove_all(dir);
}

TEST(CloudNoiseCache, CorruptTruncatedOrForeignFilesAreRegenerated) {
    const std::filesystem::path dir = test::TempDir("noise-corrupt");
    CloudNoiseSettings settings;
    settings.shape_size = {32, 8, 32};
    settings.detail_size = 16;
    settings.curl_size = 32;
    const CloudNoise expected = GenerateCloudNoise(settings);
    const std::filesystem::path file = dir / NoiseCacheFileName(settings);

    const auto expect_regenerated = [&](const char* cause) {
        const CloudNoiseLoad load = LoadOrGenerateCloudNoise(settings, dir);
        EXPECT_FALSE(load.from_cache) << cause;
        EXPECT_NE(load.cache_problem.find(cause), std::string::npos) << load.cache_problem;
        EXPECT_TRUE(load.noise == expected);
        EXPECT_TRUE(LoadOrGenerateCloudNoise(settings, dir).from_cache) << "rewritten";
    };

    WriteNoiseCache(file, settings, expected);
    {  // one flipped payload byte
        std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
        f.seekp(100);
        char byte = 0;
        f.seekg(100);
        f.read(&byte, 1);
        byte = static_cast<char>(byte ^ 0x5a);
        f.seekp(100);
        f.write(&byte, 1);
    }
    expect_regenerated("checksum");
    std::filesystem::resize_file(file, std::filesystem::file_size(file) - 10);
    expect_regenerated("truncated");
    {
        std::ofstream(file, std::ios::binary)
            << "not a cache at all, but long enough to read a header from it";
    }
    expect_regenerated("not a noise cache");
    // The same file name for other settings cannot happen; reading it with other settings fails.
    CloudNoiseSettings other = settings;
    other.seed = 99;
    std::string problem;
    EXPECT_FALSE(ReadNoiseCache(file, other, &problem).has_value());
    EXPECT_NE(problem.find("other settings"), std::string::npos) << problem;
    std::filesystem::remove_all(dir);
}

TEST(CloudNoiseCache, UnwritableDirectoryStillGivesTheNoise) {
    CloudNoiseSettings settings;
    settings.shape_size = {16, 4, 16};
    settings.detail_size = 8;
    settings.curl_size = 16;
    const CloudNoiseLoad load = LoadOrGenerateCloudNoise(settings, "/proc/zenith-no-such-dir");
    EXPECT_FALSE(load.from_cache);
    EXPECT_NE(load.cache_problem, "");
    EXPECT_EQ(load.noise.shape.size, glm::ivec3(16, 4, 16));
}

TEST(CloudNoiseCache, FileNameKeysEveryInput) {
    CloudNoiseSettings a;
    EXPECT_EQ(NoiseCacheFileName(a), "cloud-noise-v" + std::to_string(kCloudNoiseFormatVersion) +
                                         "-seed1-shape128x32x128-detail32-curl128.bin");
    CloudNoiseSettings b = a;
    b.threads = 7;  // not an input of the result
    EXPECT_EQ(NoiseCacheFileName(a), NoiseCacheFileName(b));
    b.seed = 2;
    EXPECT_NE(NoiseCacheFileName(a), NoiseCacheFileName(b));
}

}  // namespace
}  // namespace zenith::sky::clouds
