// What the two Monte Carlo references (the atmosphere's path_tracer.cpp and the clouds'
// cloud_path_tracer.cpp) share that is not transport: random streams, directions about an
// axis and a deterministic parallel loop. Each tracer keeps its own transport on purpose.
#pragma once

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <glm/glm.hpp>
#include <thread>
#include <vector>

namespace zenith::sky::reference::monte_carlo {

inline std::uint64_t SplitMix64(std::uint64_t& state) {
    std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

// Independent stream seed for (seed, index): one SplitMix64 step over a key mixed with `salt`.
// Each tracer has its own salt, so its recorded figures stay reproducible.
inline std::uint64_t StreamSeed(std::uint64_t seed, std::uint64_t index, std::uint64_t salt) {
    std::uint64_t state = seed ^ (index * 0xd1342543de82ef95ULL + salt);
    SplitMix64(state);
    return SplitMix64(state);
}

// Orthonormal basis around a unit vector (Duff et al. 2017, "Building an orthonormal basis,
// revisited"): no branch on a near-zero component, no loss of precision near the poles.
inline void OrthonormalBasis(const glm::dvec3& n, glm::dvec3& b1, glm::dvec3& b2) {
    const double sign = std::copysign(1.0, n.z);
    const double a = -1.0 / (sign + n.z);
    const double b = n.x * n.y * a;
    b1 = glm::dvec3(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
    b2 = glm::dvec3(b, sign + n.y * n.y * a, -n.y);
}

// The unit direction at polar cosine cos_theta and azimuth phi about `axis` (unit).
inline glm::dvec3 DirectionAround(const glm::dvec3& axis, double cos_theta, double phi) {
    glm::dvec3 b1, b2;
    OrthonormalBasis(axis, b1, b2);
    const double sin_theta = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
    return glm::normalize(cos_theta * axis + sin_theta * (std::cos(phi) * b1 + std::sin(phi) * b2));
}

// Runs task(i) for i in [0, count) on `threads` threads (0: hardware concurrency).
template <class Task>
void ParallelFor(std::int64_t count, int threads, const Task& task) {
    int n = threads > 0 ? threads : static_cast<int>(std::thread::hardware_concurrency());
    n = static_cast<int>(std::clamp<std::int64_t>(n, 1, std::max<std::int64_t>(count, 1)));
    std::atomic<std::int64_t> next{0};
    const auto worker = [&] {
        for (std::int64_t i = next++; i < count; i = next++) task(i);
    };
    std::vector<std::thread> pool;
    for (int i = 1; i < n; ++i) pool.emplace_back(worker);
    worker();
    for (std::thread& thread : pool) thread.join();
}

}  // namespace zenith::sky::reference::monte_carlo
