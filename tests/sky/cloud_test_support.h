// What the cloud tests share: the full-size noise through the build tree's cache, and a fresh
// scratch directory per test.
#pragma once

#include <unistd.h>

#include <filesystem>
#include <string>

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

}  // namespace zenith::sky::clouds::test
