// What the first frame costs, with and without SkySystem::Prepare: one process per case (GL
// drivers keep compiled shaders per process). Run with the Mesa disk cache off for a cold start:
//
//   MESA_SHADER_CACHE_DISABLE=true build/tests/bench/first_frame_report [cold|prepare] [weather]
//       [linear|display]
//
// prints creation, Prepare, and each of the first frames (Update + Render + read-back) in ms.
// With "display", the display output (metered) into an RGBA8 target, waited for with glFinish.
#include <glad/gl.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <glm/gtc/constants.hpp>
#include <string>

#include "zenith/sim/sky_system.h"

namespace {
double MsSince(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}
}  // namespace

int main(int argc, char** argv) try {
    using namespace zenith;
    std::string mode = "cold";
    std::string weather = "clear";
    std::string output = "linear";
    CLI::App app{"The first frame's cost with and without SkySystem::Prepare"};
    app.add_option("mode", mode, "cold, or prepare: SkySystem::Prepare before the first frame")
        ->check(CLI::IsMember({"cold", "prepare"}));
    app.add_option("weather", weather, "a weather preset");
    app.add_option("output", output, "linear, or display: the metered display output")
        ->check(CLI::IsMember({"linear", "display"}));
    CLI11_PARSE(app, argc, argv);
    const bool prepare = mode == "prepare";
    const bool display = output == "display";
    const glm::ivec2 size(1280, 720);
    auto t0 = std::chrono::steady_clock::now();
    sim::SkySystemSettings settings;
    settings.weather = weather;
    if (display) settings.display.output = sky::DisplaySettings::Output::kDisplay;
    settings.clouds.noise_cache_directory =
        std::filesystem::path(ZENITH_BINARY_DIR) / "cloud-noise-cache";
    auto sky = sim::SkySystem::CreateHeadless(settings);
    const double create_ms = MsSince(t0);
    sky->SetTime(geo::TimeFromIso8601("2024-06-21T17:00:00Z"));
    sky->SetGeodetic(47.45, 8.56, 3000.0);
    sky->SetAttitude(glm::radians(270.0), 0.05, 0.0);
    sky->SetProjection(1.0, double(size.x) / size.y);
    double prepare_ms = 0.0;
    if (prepare) {
        t0 = std::chrono::steady_clock::now();
        sky->Prepare(size);
        prepare_ms = MsSince(t0);
    }
    GLuint texture = 0, framebuffer = 0;
    if (display) {
        glCreateTextures(GL_TEXTURE_2D, 1, &texture);
        glTextureStorage2D(texture, 1, GL_RGBA8, size.x, size.y);
        glCreateFramebuffers(1, &framebuffer);
        glNamedFramebufferTexture(framebuffer, GL_COLOR_ATTACHMENT0, texture, 0);
    }
    std::printf("%-8s %-7s weather %-18s create %7.1f ms  prepare %7.1f ms  frames",
                prepare ? "prepare" : "cold", display ? "display" : "linear", weather.c_str(),
                create_ms, prepare_ms);
    for (int frame = 0; frame < 4; ++frame) {
        t0 = std::chrono::steady_clock::now();
        sky->AdvanceTime(0.04);
        sky->Update();
        if (display) {
            sky->Render(framebuffer, {0, 0, size.x, size.y});
            glFinish();
        } else {
            sky->RenderOffscreen(size);  // the read-back waits for the GPU
        }
        std::printf(" %7.1f", MsSince(t0));
    }
    std::printf(" ms\n");
    return 0;
} catch (const std::exception& e) {
    std::fprintf(stderr, "first_frame_report: %s\n", e.what());
    return 1;
}
