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
#include "zenith/sky/sky_state.h"

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

// A solar eclipse's frame against the same frame without it (issue 18 §4): Chicago at the
// 2024-04-08 maximum (93.9 % covered), looking toward the Sun 52 deg up, 60 deg field. The
// eclipse marches every Sky-View column (the Moon's shadow has no mirror symmetry), evaluates
// the shadow per sample and draws the corona's box.
struct EclipseFrame {
    SkyState eclipsed, clear;
    EclipseFrame() {
        const zenith::geo::Observer chicago(41.8781, -87.6298, 180.0);
        zenith::geo::EphemerisOptions options;
        options.planets = false;
        const zenith::geo::SkyEphemeris e = zenith::geo::Ephemeris().Compute(
            zenith::geo::TimeFromIso8601("2024-04-08T19:07:41Z"), chicago, options);
        eclipsed =
            MakeSkyState(e, chicago, Atmosphere{}, {e.sun.topocentric.horizontal.azimuth, 0.3, 0.0},
                         1.0472, 16.0 / 9.0);
        clear = eclipsed;
        clear.scene.lights.sun_illuminance = clear.scene.lights.eclipse.unobscured_illuminance;
        clear.scene.lights.eclipse = {};
    }
};
void FullFrameOf(benchmark::State& state, bool eclipse) {
    Fixture& f = Shared();
    static const EclipseFrame frames;
    const SkyState& s = eclipse ? frames.eclipsed : frames.clear;
    for (auto _ : state) {
        f.renderer.Update(s.scene, s.view);
        f.renderer.Render(f.target);
        glFinish();
    }
    ReportPassTimes(state, Inspect(f.renderer).LastPassTimes());
}
void BM_FullFrame720pBesideEclipse(benchmark::State& state) { FullFrameOf(state, false); }
void BM_FullFrame720pSolarEclipse(benchmark::State& state) { FullFrameOf(state, true); }
BENCHMARK(BM_FullFrame720pBesideEclipse)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_FullFrame720pSolarEclipse)->Unit(benchmark::kMillisecond)->UseRealTime();

// MakeSkyState (CPU, per frame) at the eclipse's maximum and a day later (no eclipse: the
// overlap test only); no stars, no planets.
void MakeSkyStateAt(benchmark::State& state, const char* utc) {
    const zenith::geo::Observer chicago(41.8781, -87.6298, 180.0);
    zenith::geo::EphemerisOptions options;
    options.planets = false;
    const zenith::geo::SkyEphemeris e =
        zenith::geo::Ephemeris().Compute(zenith::geo::TimeFromIso8601(utc), chicago, options);
    for (auto _ : state) {
        benchmark::DoNotOptimize(MakeSkyState(e, chicago, Atmosphere{}, {}, 1.0472, 16.0 / 9.0));
    }
}
void BM_MakeSkyStateNoEclipse(benchmark::State& state) {
    MakeSkyStateAt(state, "2024-04-09T19:07:41Z");
}
void BM_MakeSkyStateSolarEclipse(benchmark::State& state) {
    MakeSkyStateAt(state, "2024-04-08T19:07:41Z");
}
void BM_MakeSkyStateLunarEclipse(benchmark::State& state) {
    MakeSkyStateAt(state, "2022-11-08T10:59:08Z");
}
BENCHMARK(BM_MakeSkyStateNoEclipse)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_MakeSkyStateSolarEclipse)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_MakeSkyStateLunarEclipse)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
