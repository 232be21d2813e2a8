// The cost of the display pass (zenith/sky/display.h) at 1280x720 against the clear-sky frame
// in the same run: the frame alone (Update + Render into the renderer's RGBA32F
// target), the frame followed by the pass into an RGBA8 target (a given EV100; metered with the
// night adaptation), and the pass alone on an already rendered frame. glFinish ends each
// iteration, so the times are the GPU's (llvmpipe's) as well as the CPU's.
#include <benchmark/benchmark.h>
#include <glad/gl.h>

#include <memory>

#include "daytime_frame.h"
#include "zenith/sky/atmosphere_renderer.h"
#include "zenith/sky/display.h"
#include "zenith/sky/gl/context.h"

namespace {

using namespace zenith::sky;

struct Fixture : bench::DaytimeFrame {
    DisplayPass display;
    GLuint colour = 0, framebuffer = 0;

    Fixture() {
        glCreateTextures(GL_TEXTURE_2D, 1, &colour);
        glTextureStorage2D(colour, 1, GL_RGBA8, 1280, 720);
        glCreateFramebuffers(1, &framebuffer);
        glNamedFramebufferTexture(framebuffer, GL_COLOR_ATTACHMENT0, colour, 0);
    }
    void Frame() {
        renderer.Update(scene, view);
        renderer.Render(target);
    }
    void Display(bool metered) {
        DisplaySettings settings;
        settings.output = DisplaySettings::Output::kDisplay;
        if (!metered) settings.ev100 = 15.0;
        display.Run(renderer.frame_texture(), framebuffer, {0, 0, 1280, 720}, settings, 1.0 / 60);
    }
};

Fixture& Shared() { return bench::Shared<Fixture>(); }

void BM_ClearSkyFrame720p(benchmark::State& state) {
    Fixture& f = Shared();
    for (auto _ : state) {
        f.Frame();
        glFinish();
    }
}
BENCHMARK(BM_ClearSkyFrame720p)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_FrameAndDisplayGivenEv(benchmark::State& state) {
    Fixture& f = Shared();
    for (auto _ : state) {
        f.Frame();
        f.Display(false);
        glFinish();
    }
}
BENCHMARK(BM_FrameAndDisplayGivenEv)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_FrameAndDisplayMetered(benchmark::State& state) {
    Fixture& f = Shared();
    for (auto _ : state) {
        f.Frame();
        f.Display(true);
        glFinish();
    }
}
BENCHMARK(BM_FrameAndDisplayMetered)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_DisplayOnlyGivenEv(benchmark::State& state) {
    Fixture& f = Shared();
    f.Frame();
    glFinish();
    for (auto _ : state) {
        f.Display(false);
        glFinish();
    }
}
BENCHMARK(BM_DisplayOnlyGivenEv)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_DisplayOnlyMetered(benchmark::State& state) {
    Fixture& f = Shared();
    f.Frame();
    glFinish();
    for (auto _ : state) {
        f.Display(true);
        glFinish();
    }
}
BENCHMARK(BM_DisplayOnlyMetered)->Unit(benchmark::kMillisecond)->UseRealTime();

// exposure_ev100() after a metered pass: the read-back (a sync) a host pays when it asks.
void BM_DisplayMeteredAndReadExposure(benchmark::State& state) {
    Fixture& f = Shared();
    f.Frame();
    glFinish();
    for (auto _ : state) {
        f.Display(true);
        benchmark::DoNotOptimize(f.display.exposure_ev100());
    }
}
BENCHMARK(BM_DisplayMeteredAndReadExposure)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
