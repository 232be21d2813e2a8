// The cost of the GL state contract (sky/src/gl/state_guard.h): one guard that saves, sets and
// restores (~150 glGet and ~130 set calls) against one that only sets, and a whole 1280x720
// frame (UpdateFrameLuts + Render, two guards) with and without preserving the host's state.
#include <benchmark/benchmark.h>
#include <glad/gl.h>

#include <memory>

#include "gl/state_guard.h"
#include "zenith/sky/atmosphere_renderer.h"
#include "zenith/sky/gl/context.h"

namespace {

using namespace zenith::sky;

struct Fixture {
    std::unique_ptr<gl::HeadlessContext> context = gl::CreateHeadlessContextFromEnvironment();
    Atmosphere earth;
    AtmosphereRenderer renderer{earth};
    Camera camera;
    Lights lights;
    RenderOptions options;

    Fixture() {
        camera.position = glm::dvec3(0.0, 0.0, earth.bottom_radius + 1500.0);
        camera.world_from_view =
            glm::dmat3(glm::dvec3(0, 1, 0), glm::dvec3(0, 0, 1), glm::dvec3(-1, 0, 0));
        camera.vertical_fov = 1.0471975511965976;
        camera.aspect = 16.0 / 9.0;
        lights.sun_direction = glm::normalize(glm::dvec3(0.98, 0.0, 0.17));
        options.size = {1280, 720};
    }
};

Fixture& Shared() {
    static Fixture fixture;
    return fixture;
}

// Save, set and restore: what each renderer entry point costs a host on top of its passes.
void BM_GuardPreserving(benchmark::State& state) {
    Shared();
    for (auto _ : state) {
        const gl::StateGuard guard(true);
        benchmark::ClobberMemory();
    }
}
BENCHMARK(BM_GuardPreserving)->Unit(benchmark::kMicrosecond);

// Set only (SkySystemSettings::preserve_gl_state = false).
void BM_GuardSettingOnly(benchmark::State& state) {
    Shared();
    for (auto _ : state) {
        const gl::StateGuard guard(false);
        benchmark::ClobberMemory();
    }
}
BENCHMARK(BM_GuardSettingOnly)->Unit(benchmark::kMicrosecond);

void Frame(benchmark::State& state, bool preserve) {
    Fixture& f = Shared();
    f.renderer.set_preserve_gl_state(preserve);
    for (auto _ : state) {
        f.renderer.UpdateFrameLuts(f.camera, f.lights);
        f.renderer.Render(f.camera, f.lights, f.options);
        glFinish();
    }
    f.renderer.set_preserve_gl_state(true);
}
void BM_Frame720pPreserving(benchmark::State& state) { Frame(state, true); }
void BM_Frame720pSettingOnly(benchmark::State& state) { Frame(state, false); }
BENCHMARK(BM_Frame720pPreserving)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Frame720pSettingOnly)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
