// Atmosphere passes on the headless GL context (llvmpipe here; a GPU with ZENITH_GL=egl), each
// iteration ending in glFinish so wall time is GPU time. The Sky-View path and per-pixel ray
// marching of the same 1280x720 scene run side by side for their ratio (Hillaire 2020 §5.3, §7).
#include <benchmark/benchmark.h>
#include <glad/gl.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <memory>
#include <vector>

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

// The same without the multiple scattering's plane-parallel column (solved on the CPU), for its
// share of the rebuild: LutSettings::multiple_scattering_column_layers = 0.
void BM_StaticLutRebuildWithoutColumn(benchmark::State& state) {
    Fixture& f = Shared();
    LutSettings settings = f.renderer.settings();
    settings.multiple_scattering_column_layers = 0;
    static AtmosphereRenderer renderer(f.earth, settings);
    for (auto _ : state) {
        renderer.SetAtmosphere(f.earth);
        glFinish();
    }
}
BENCHMARK(BM_StaticLutRebuildWithoutColumn)->Unit(benchmark::kMillisecond)->UseRealTime();

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

// Night (the Sun 30 deg down) with 4,000 stars, as before issue 18 §3 (every star drawn whole,
// no diffuse light), and with the night sky: the CPU's map of airglow, zodiacal light,
// starlight and light pollution (128 x 64 directions through the transmittance LUT), its upload,
// one more texture read per pixel and the stars' visibility against the sky. Their ratio to
// BM_FullFrame720p is the night sky's per-frame cost.
SkyScene NightScene(const SkyScene& day, bool night_sky) {
    SkyScene night = day;
    night.lights.sun_direction = glm::normalize(glm::dvec3(0.87, 0.0, -0.5));
    for (int i = 0; i < 4000; ++i) {  // a golden-angle spiral over the sphere
        const double z = 1.0 - (i + 0.5) / 2000.0;
        const double r = std::sqrt(std::max(0.0, 1.0 - z * z)), phi = 2.399963229728653 * i;
        night.stars.push_back({{r * std::cos(phi), r * std::sin(phi), z}, glm::dvec3(2e-8)});
    }
    night.star_visibility = night_sky;
    night.night_sky.enabled = night_sky;
    night.night_sky.starlight = std::make_shared<const StarlightMap>(StarlightMap::ModelOnly());
    night.night_sky.settings.artificial_zenith_brightness = 20.0;
    return night;
}

// `turning`: the sky turns 0.05 deg a frame (12 s of time), so the night sky's map is filled
// again each frame, as in a fast time warp; otherwise it is kept (AtmospherePasses).
void FullFrameAtNight(benchmark::State& state, bool night_sky, bool turning = false) {
    Fixture& f = Shared();
    SkyScene night = NightScene(f.scene, night_sky);
    const glm::dmat3 turn =
        glm::dmat3(glm::rotate(glm::dmat4(1.0), glm::radians(0.05), glm::dvec3(0.0, 0.6, 0.8)));
    for (auto _ : state) {
        if (turning) night.night_sky.icrs_from_world = night.night_sky.icrs_from_world * turn;
        f.renderer.Update(night, f.view);
        f.renderer.Render(f.target);
        glFinish();
    }
    ReportPassTimes(state, Inspect(f.renderer).LastPassTimes());
}

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

void BM_FullFrame720pNightStars(benchmark::State& state) { FullFrameAtNight(state, false); }
BENCHMARK(BM_FullFrame720pNightStars)->Unit(benchmark::kMillisecond)->UseRealTime();
void BM_FullFrame720pNightSky(benchmark::State& state) { FullFrameAtNight(state, true); }
BENCHMARK(BM_FullFrame720pNightSky)->Unit(benchmark::kMillisecond)->UseRealTime();
void BM_FullFrame720pNightSkyTurning(benchmark::State& state) {
    FullFrameAtNight(state, true, true);
}
BENCHMARK(BM_FullFrame720pNightSkyTurning)->Unit(benchmark::kMillisecond)->UseRealTime();

// The night sky's light on the ground for a host's ambient (SkySystem's SkyLighting at night):
// CPU only, per call, beside the night frame above.
void BM_NightSkyGroundIrradiance(benchmark::State& state) {
    Fixture& f = Shared();
    const SkyScene night = NightScene(f.scene, true);
    const LutImage transmittance = Inspect(f.renderer).ReadTransmittance();
    for (auto _ : state) {
        benchmark::DoNotOptimize(NightSkyGroundIrradiance(night.night_sky, Atmosphere{},
                                                          transmittance, f.view.camera.position));
    }
}
BENCHMARK(BM_NightSkyGroundIrradiance)->Unit(benchmark::kMillisecond);

// The three frames interleaved in every iteration (the clear daytime frame, the night as before,
// the night with the night sky), so that a machine whose load drifts slows all three alike: the
// medians of the per-iteration ratios are the night sky's cost.
void BM_NightSkyInterleaved(benchmark::State& state) {
    Fixture& f = Shared();
    const SkyScene before = NightScene(f.scene, false), after = NightScene(f.scene, true);
    const auto frame_ms = [&](const SkyScene& scene) {
        const auto start = std::chrono::steady_clock::now();
        f.renderer.Update(scene, f.view);
        f.renderer.Render(f.target);
        glFinish();
        return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
            .count();
    };
    std::vector<double> to_clear, to_before, clear_ms;
    for (auto _ : state) {
        const double clear = frame_ms(f.scene), old = frame_ms(before), night = frame_ms(after);
        to_clear.push_back(night / clear);
        to_before.push_back(night / old);
        clear_ms.push_back(clear);
    }
    const auto median = [](std::vector<double> v) {
        std::sort(v.begin(), v.end());
        return v.empty() ? 0.0 : v[v.size() / 2];
    };
    state.counters["night_sky_over_clear"] = median(to_clear);
    state.counters["night_sky_over_night_before"] = median(to_before);
    state.counters["clear_ms"] = median(clear_ms);
}
BENCHMARK(BM_NightSkyInterleaved)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(5.0);

}  // namespace

BENCHMARK_MAIN();
