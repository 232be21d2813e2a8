// Accuracy of the LUT renderer against the path tracer in the scenarios of Hillaire 2020 §6, as a
// markdown table (BENCHMARKS.md, "sky: accuracy against the path tracer"). Not a Google Benchmark:
// a plain main, built by tests/bench/CMakeLists.txt's glob.
//
//   accuracy_report [--width W] [--height H] [--samples N] [--thick-samples N] [--threads T]
//                   [--seed S] [--only NAME]
//
// Defaults (96x64, 1024 paths per pixel, 256 for the 50x atmosphere whose paths scatter hundreds
// of times) take several minutes on 2 cores.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "zenith/sky/reference/accuracy.h"

namespace {

using zenith::sky::reference::AccuracyOptions;
using zenith::sky::reference::AccuracyResult;
using zenith::sky::reference::AccuracyScenario;

// RGB triple as "a, b, c" scaled by `scale`, `digits` after the point.
std::string Triple(const glm::dvec3& v, double scale, int digits) {
    char text[96];
    std::snprintf(text, sizeof(text), "%.*f, %.*f, %.*f", digits, v.x * scale, digits, v.y * scale,
                  digits, v.z * scale);
    return text;
}

[[noreturn]] void Usage(const char* message) {
    std::fprintf(stderr,
                 "accuracy_report: %s\nusage: accuracy_report [--width W] [--height H] "
                 "[--samples N] [--thick-samples N] [--threads T] [--seed S] [--only NAME]\n",
                 message);
    std::exit(2);
}

long long ParseInteger(const char* flag, const char* text, long long low, long long high) {
    char* end = nullptr;
    const long long value = std::strtoll(text, &end, 10);
    if (end == text || *end != '\0' || value < low || value > high) {
        Usage((std::string(flag) + " " + text + " is out of range [" + std::to_string(low) + ", " +
               std::to_string(high) + "]")
                  .c_str());
    }
    return value;
}

}  // namespace

int main(int argc, char** argv) {
    AccuracyOptions options;
    options.width = 96;
    options.height = 64;
    options.samples = 1024;
    std::int64_t thick_samples = 256;
    std::string only;
    for (int i = 1; i < argc; ++i) {
        const char* flag = argv[i];
        if (i + 1 >= argc) Usage((std::string("missing value after ") + flag).c_str());
        const char* value = argv[++i];
        if (!std::strcmp(flag, "--width")) {
            options.width = static_cast<int>(ParseInteger(flag, value, 1, 4096));
        } else if (!std::strcmp(flag, "--height")) {
            options.height = static_cast<int>(ParseInteger(flag, value, 1, 4096));
        } else if (!std::strcmp(flag, "--samples")) {
            options.samples = ParseInteger(flag, value, 2, 1 << 24);
        } else if (!std::strcmp(flag, "--thick-samples")) {
            thick_samples = ParseInteger(flag, value, 2, 1 << 24);
        } else if (!std::strcmp(flag, "--threads")) {
            options.threads = static_cast<int>(ParseInteger(flag, value, 0, 1024));
        } else if (!std::strcmp(flag, "--seed")) {
            options.seed = static_cast<std::uint64_t>(ParseInteger(flag, value, 0, 1LL << 62));
        } else if (!std::strcmp(flag, "--only")) {
            only = value;
        } else {
            Usage((std::string("unknown option ") + flag).c_str());
        }
    }

    std::printf(
        "%dx%d pixels, %lld paths per pixel (%lld for thick_daytime), seed %llu, LUTs: "
        "LutSettings::Pc(), %d ray-marching steps from space\n\n",
        options.width, options.height, static_cast<long long>(options.samples),
        static_cast<long long>(thick_samples), static_cast<unsigned long long>(options.seed),
        options.ray_march_steps);
    std::printf(
        "| scenario | path | relative RMSE (R, G, B) | reference noise, relative | RMSE - noise, "
        "relative | mean bias (R, G, B) | absolute RMSE ×10⁻³ /sr | paper (O) ×10⁻³ | "
        "noise ×10⁻³ /sr | time LUT / PT |\n");
    std::printf("|---|---|---|---|---|---|---|---|---|---|\n");
    std::fflush(stdout);
    double total_seconds = 0.0;
    for (const AccuracyScenario& scenario : zenith::sky::reference::PaperScenarios()) {
        if (!only.empty() && scenario.name != only) continue;
        AccuracyOptions scenario_options = options;
        if (scenario.name == "thick_daytime") scenario_options.samples = thick_samples;
        const AccuracyResult r = MeasureAccuracy(scenario, scenario_options);
        const bool has_paper = scenario.paper_rmse != glm::dvec3(0.0);
        std::printf(
            "| %s | %s | %s | %s | %s | %s ± %s | %s | %s | %s | %.2f s / %.0f s |\n",
            scenario.name.c_str(), r.ray_marched ? "ray march" : "Sky-View",
            Triple(r.RelativeRmse(), 1.0, 4).c_str(), Triple(r.RelativeNoise(), 1.0, 4).c_str(),
            Triple(r.RelativeRmseNoiseCorrected(), 1.0, 4).c_str(),
            Triple(r.MeanBias(), 1.0, 4).c_str(), Triple(r.MeanBiasError(), 1.0, 4).c_str(),
            Triple(r.AbsoluteRmse(), 1e3, 3).c_str(),
            has_paper ? Triple(scenario.paper_rmse, 1e3, 2).c_str() : "—",
            Triple(r.AbsoluteNoise(), 1e3, 3).c_str(), r.renderer_seconds, r.reference_seconds);
        std::fflush(stdout);
        total_seconds += r.renderer_seconds + r.reference_seconds;
    }
    std::printf("\ntotal %.0f s\n", total_seconds);
    return 0;
}
