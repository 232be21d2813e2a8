// What the cloud tests share: the full-size noise through the build tree's cache, a fresh
// scratch directory per test, and a cumulus layer in the shaders' units.
#pragma once

#include <unistd.h>

#include <filesystem>
#include <string>

#include "reference/cloud_functions.h"
#include "zenith/sky/clouds/noise.h"

namespace zenith::sky::clouds::test {

// The noise of Table 4.1 (CloudNoiseSettings{}), through the cache in the build tree: ctest runs
// every test in its own process, and only the first generates it.
inline const CloudNoise& CachedNoise() {
    static const CloudNoise noise =
        LoadOrGenerateCloudNoise(CloudNoiseSettings{},
                                 std::filesystem::path(ZENITH_BINARY_DIR) / "cloud-noise-cache")
            .noise;
    return noise;
}

// A fresh, empty directory under the build tree for one test (named per process).
inline std::filesystem::path TempDir(const std::string& name) {
    const std::filesystem::path dir = std::filesystem::path(ZENITH_BINARY_DIR) / "test-tmp" /
                                      (name + "-" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

// A cumulus layer 1.5-4 km, weather tile 40 km, shape noise 10 km (2.5 km in altitude), detail
// 2 km: both noises tile a whole number of times per weather tile. The wind has carried the
// weather map by -(wind_x, wind_y) km.
inline ref::CloudLayerParameters CumulusLayer(double wind_x = 0.0, double wind_y = 0.0) {
    ref::CloudLayerParameters p{};
    p.bottom_radius = 6360.0;
    p.base_altitude = 1.5;
    p.top_altitude = 4.0;
    p.weather_period = 40.0;
    p.shape_period = 10.0;
    p.shape_period_y = 2.5;
    p.detail_period = 2.0;
    p.erosion_strength = 0.5;
    p.wind_offset_x = wind_x;
    p.wind_offset_y = wind_y;
    p.cloud_top_altitude = p.top_altitude;  // a bound for any map (CloudTopFraction is tighter)
    p.extinction_scale = 1.0;               // water droplets
    return p;
}

}  // namespace zenith::sky::clouds::test
