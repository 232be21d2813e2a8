// Soak: many frames through one SkySystem, as a host's loop would drive it (time advancing, the
// aircraft moving and turning, clouds), with the process's resident memory read after a warm-up
// and at the end. A leak per frame shows as growth; see BENCHMARKS.md for the recorded run.
// Usage: soak_report [frames=10000] [weather=scattered_cumulus] [size=64]
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#include "zenith/geo/time.h"
#include "zenith/sim/sky_system.h"

namespace {

// Resident set size in MiB, from /proc/self/statm (pages).
double ResidentMiB() {
    std::ifstream statm("/proc/self/statm");
    long size_pages = 0;
    long resident_pages = 0;
    statm >> size_pages >> resident_pages;
    return static_cast<double>(resident_pages) * static_cast<double>(::sysconf(_SC_PAGESIZE)) /
           (1024.0 * 1024.0);
}

}  // namespace

int main(int argc, char** argv) {
    int frames = 10000;
    std::string weather = "scattered_cumulus";
    int size = 64;
    CLI::App app{"SkySystem over a week of simulated flight: memory and frame time"};
    app.add_option("frames", frames)->check(CLI::Range(200, 100000000));
    app.add_option("weather", weather, "a weather preset");
    app.add_option("size", size, "frame width and height in pixels")->check(CLI::Range(8, 4096));
    CLI11_PARSE(app, argc, argv);
    zenith::sim::SkySystemSettings settings;
    settings.weather = weather;
    auto sky = zenith::sim::SkySystem::CreateHeadless(settings);
    sky->SetTime(zenith::geo::TimeFromUtc(zenith::geo::ParseIso8601("2024-06-21T04:00:00Z")));
    sky->SetProjection(60.0 * M_PI / 180.0, 16.0 / 9.0);

    double warm_mib = 0.0;
    const auto start = std::chrono::steady_clock::now();
    for (int i = 0; i < frames; ++i) {
        // A circuit at 3 km that climbs to 12 km and back, turning, over 10,000 frames of a
        // minute of sky time each (a week of days and nights).
        const double t = static_cast<double>(i);
        sky->AdvanceTime(1.0 / 60.0, 3600.0);
        sky->SetGeodetic(47.0 + 0.5 * std::sin(t * 1e-3), 8.0 + 0.5 * std::cos(t * 1e-3),
                         3000.0 + 9000.0 * 0.5 * (1.0 - std::cos(t * 6e-4)));
        sky->SetAttitude(std::fmod(t * 0.01, 2.0 * M_PI), 0.2 * std::sin(t * 0.003),
                         0.3 * std::sin(t * 0.002));
        sky->Update();
        (void)sky->RenderOffscreen({size, size * 9 / 16});
        if (i == 99) warm_mib = ResidentMiB();
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double end_mib = ResidentMiB();
    std::printf("frames %d, weather %s, %dx%d: %.1f s (%.2f ms/frame)\n", frames, weather.c_str(),
                size, size * 9 / 16, seconds, 1e3 * seconds / frames);
    std::printf(
        "resident memory after 100 frames %.1f MiB, after %d frames %.1f MiB "
        "(growth %+.1f MiB, %+.2f KiB/frame)\n",
        warm_mib, frames, end_mib, end_mib - warm_mib,
        (end_mib - warm_mib) * 1024.0 / (frames - 100));
    return 0;
}
