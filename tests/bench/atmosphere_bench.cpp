// Atmosphere passes on the headless GL context (llvmpipe here; a GPU with ZENITH_GL=egl), each
// iteration ending in glFinish so wall time is GPU time. The Sky-View path and per-pixel ray
// marching of the same 1280x720 scene run side by side for their ratio (Hillaire 2020 §5.3, §7).
#include <benchmark/benchmark.h>
#include <glad/gl.h>

#include <memory>

#include "daytime_frame.h"
#include "zenith/sky/atmosphere_renderer.h"
#include "zenith/sky/gl/context.h"

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
    ReportPassTimes(state, f.renderer.LastPassTimes());
}
BENCHMARK(BM_StaticLutRebuild)->Unit(benchmark::kMillisecond)->UseRealTime();

// Sky-View + aerial perspective: every frame.
void BM_FrameLuts(benchmark::State& state) {
    Fixture& f = Shared();
    for (auto _ : state) {
        f.renderer.UpdateFrameLuts(f.camera, f.lights);
        glFinish();
    }
    ReportPassTimes(state, f.renderer.LastPassTimes());
}
BENCHMARK(BM_FrameLuts)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_CompositeSkyView720p(benchmark::State& state) {
    Fixture& f = Shared();
    f.renderer.UpdateFrameLuts(f.camera, f.lights);
    f.options.force_ray_march = false;
    for (auto _ : state) {
        f.renderer.Render(f.camera, f.lights, f.options);
        glFinish();
    }
}
BENCHMARK(BM_CompositeSkyView720p)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_CompositeRayMarch720p(benchmark::State& state) {
    Fixture& f = Shared();
    f.options.force_ray_march = true;
    f.options.ray_march_steps = static_cast<int>(state.range(0));
    for (auto _ : state) {
        f.renderer.Render(f.camera, f.lights, f.options);
        glFinish();
    }
    f.options.force_ray_march = false;
}
BENCHMARK(BM_CompositeRayMarch720p)->Arg(32)->Unit(benchmark::kMillisecond)->UseRealTime();

// The whole clear-sky frame: per-frame LUTs and the composite (the issue's <= 20 ms goal).
void BM_FullFrame720p(benchmark::State& state) {
    Fixture& f = Shared();
    f.options.force_ray_march = false;
    for (auto _ : state) {
        f.renderer.UpdateFrameLuts(f.camera, f.lights);
        f.renderer.Render(f.camera, f.lights, f.options);
        glFinish();
    }
    ReportPassTimes(state, f.renderer.LastPassTimes());
}
BENCHMARK(BM_FullFrame720p)->Unit(benchmark::kMillisecond)->UseRealTime();

// The same frame at dusk with the Moon up: two lights, so the Sky-View LUT has no mirror
// symmetry and every texel is marched for both (by day the Moon is left out, MakeLightSet).
void BM_FullFrame720pTwoLights(benchmark::State& state) {
    Fixture& f = Shared();
    Lights dusk = f.lights;
    dusk.sun_direction = glm::normalize(glm::dvec3(0.99, 0.0, -0.14));  // 8 deg below
    dusk.moon_enabled = true;
    dusk.moon_direction = glm::normalize(glm::dvec3(-0.5, 0.6, 0.6));
    dusk.moon_illuminance = dusk.sun_illuminance * 2e-6;
    f.options.force_ray_march = false;
    for (auto _ : state) {
        f.renderer.UpdateFrameLuts(f.camera, dusk);
        f.renderer.Render(f.camera, dusk, f.options);
        glFinish();
    }
    ReportPassTimes(state, f.renderer.LastPassTimes());
}
BENCHMARK(BM_FullFrame720pTwoLights)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
