// Atmosphere passes on the headless GL context (llvmpipe here; a GPU with ZENITH_GL=egl), each
// iteration ending in glFinish so wall time is GPU time. The Sky-View path and per-pixel ray
// marching of the same 1280x720 scene run side by side for their ratio (Hillaire 2020 §5.3, §7).
#include <benchmark/benchmark.h>
#include <glad/gl.h>

#include <memory>

#include "daytime_frame.h"
#include "zenith/sky/atmosphere_renderer.h"
#include "zenith/sky/gl/context.h"
#include "zenith/sky/inspection.h"

namespace {

using namespace zenith::sky;

using Fixture = bench::DaytimeFrame;
using bench::Shared;

void ReportPassTimes(benchmark::State& state, const PassTimes& t) {
    state.counters["transmittance_ms"] = t.transmittance;
    state.counters["multiple_scattering_ms"] = t.multiple_scattering;
    state.counters["irradiance_ms"] = t.irradiance;
    state.counters["sky_view_ms"] = t.sky_view;
    state.counters["aerial_perspective_ms"] = t.aerial_perspective;
    state.counters["render_ms"] = t.render;
}

// Transmittance + multiple scattering + ground irradiance: after an atmosphere change.
void BM_StaticLutRebuild(benchmark::State& state) {
    Fixture& f = Shared();
    for (auto _ : state) {
        f.renderer.SetAtmosphere(f.earth);
        glFinish();
    }
    ReportPassTimes(state, Inspect(f.renderer).LastPassTimes());
}
BENCHMARK(BM_StaticLutRebuild)->Unit(benchmark::kMillisecond)->UseRealTime();

// Sky-View + aerial perspective: every frame.
void BM_FrameLuts(benchmark::State& state) {
    Fixture& f = Shared();
    for (auto _ : state) {
        f.renderer.Update(f.scene, f.view);
        glFinish();
    }
    ReportPassTimes(state, Inspect(f.renderer).LastPassTimes());
}
BENCHMARK(BM_FrameLuts)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_CompositeSkyView720p(benchmark::State& state) {
    Fixture& f = Shared();
    f.renderer.Update(f.scene, f.view);
    for (auto _ : state) {
        f.renderer.Render(f.target);
        glFinish();
    }
}
BENCHMARK(BM_CompositeSkyView720p)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_CompositeRayMarch720p(benchmark::State& state) {
    Fixture& f = Shared();
    SkyView marched = f.view;
    marched.force_ray_march = true;
    marched.ray_march_steps = static_cast<int>(state.range(0));
    f.renderer.Update(f.scene, marched);
    for (auto _ : state) {
        f.renderer.Render(f.target);
        glFinish();
    }
}
BENCHMARK(BM_CompositeRayMarch720p)->Arg(32)->Unit(benchmark::kMillisecond)->UseRealTime();

// The whole clear-sky frame: per-frame LUTs and the composite (the issue's <= 20 ms goal).
void BM_FullFrame720p(benchmark::State& state) {
    Fixture& f = Shared();
    for (auto _ : state) {
        f.renderer.Update(f.scene, f.view);
        f.renderer.Render(f.target);
        glFinish();
    }
    ReportPassTimes(state, Inspect(f.renderer).LastPassTimes());
}
BENCHMARK(BM_FullFrame720p)->Unit(benchmark::kMillisecond)->UseRealTime();

// The same frame at dusk with the Moon up: two lights, so the Sky-View LUT has no mirror
// symmetry and every texel is marched for both (by day the Moon is left out, MakeLightSet).
void BM_FullFrame720pTwoLights(benchmark::State& state) {
    Fixture& f = Shared();
    SkyScene dusk = f.scene;
    dusk.lights.sun_direction = glm::normalize(glm::dvec3(0.99, 0.0, -0.14));  // 8 deg below
    dusk.lights.moon_enabled = true;
    dusk.lights.moon_direction = glm::normalize(glm::dvec3(-0.5, 0.6, 0.6));
    dusk.lights.moon_illuminance = dusk.lights.sun_illuminance * 2e-6;
    for (auto _ : state) {
        f.renderer.Update(dusk, f.view);
        f.renderer.Render(f.target);
        glFinish();
    }
    ReportPassTimes(state, Inspect(f.renderer).LastPassTimes());
}
BENCHMARK(BM_FullFrame720pTwoLights)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
