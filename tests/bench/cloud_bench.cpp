// Clouds at 1280x720 on the headless GL context (llvmpipe here), scattered cumulus, looking at
// the horizon from the ground, inside the layer and from 12 km: whole frames (frame LUTs, sky,
// clouds; glFinish) with the reduced-resolution trace and reprojection (block 4, the default,
// and 8) and with every pixel traced each frame (block 1), beside the clear-sky frame as the
// baseline; the converged image against a full-resolution render with four times the steps;
// the image after a fast turning flight against the converged truth; the CPU march of the
// host's sunlight through the clouds; and the cost of setting the weather.
#include <benchmark/benchmark.h>
#include <glad/gl.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "colour_target.h"
#include "draw_frame.h"
#include "zenith/sky/atmosphere_renderer.h"
#include "zenith/sky/gl/context.h"
#include "zenith/sky/inspection.h"

namespace {

using namespace zenith::sky;

struct View {
    const char* name;
    double altitude;
    double pitch;
};
constexpr View kViews[] = {
    {"ground", 2.0, 0.05}, {"inside", 2700.0, 0.0}, {"12km", 12000.0, -0.03}};

struct Fixture {
    std::unique_ptr<gl::HeadlessContext> context = gl::CreateHeadlessContextFromEnvironment();
    Atmosphere earth;
    clouds::Weather weather = clouds::LoadWeather("scattered_cumulus");
    AtmosphereRenderer renderer{earth};
    Lights lights;

    Fixture() { lights.sun_direction = glm::normalize(glm::dvec3(0.6, 0.3, 0.5)); }

    Camera CameraFor(const View& v) const {
        Camera camera;
        camera.position = glm::dvec3(0.0, 0.0, earth.bottom_radius + v.altitude);
        const glm::dvec3 forward(std::cos(v.pitch), 0.0, std::sin(v.pitch));  // east
        const glm::dvec3 right = glm::normalize(glm::cross(forward, glm::dvec3(0, 0, 1)));
        camera.world_from_view = glm::dmat3(right, glm::cross(right, forward), -forward);
        camera.vertical_fov = 1.0471975511965976;
        camera.aspect = 16.0 / 9.0;
        return camera;
    }
};

Fixture& Shared() {
    static Fixture fixture;
    return fixture;
}

CloudSettings Settings(int block) {
    CloudSettings s;
    s.block = block;
    return s;
}

using zenith::test::FrameOptions;  // 1280x720 with the Sun's disk

void Frame(Fixture& f, const Camera& camera, const FrameOptions& options) {
    zenith::test::DrawFrames(f.renderer, camera, f.lights, options);
}

// A first frame (noise upload, history), then one each iteration, each waited for; the last
// frame's pass times.
PassTimes TimeFrames(benchmark::State& state, Fixture& f, const Camera& camera) {
    const FrameOptions options;
    Frame(f, camera, options);
    glFinish();
    for (auto _ : state) {
        Frame(f, camera, options);
        glFinish();
    }
    return Inspect(f.renderer).LastPassTimes();
}

// args: view, block (0: no clouds, the baseline)
void BM_Frame720p(benchmark::State& state) {
    Fixture& f = Shared();
    const View& view = kViews[state.range(0)];
    const int block = static_cast<int>(state.range(1));
    f.renderer.SetWeather(block == 0 ? clouds::Weather{} : f.weather, Settings(std::max(block, 1)));
    const PassTimes t = TimeFrames(state, f, f.CameraFor(view));
    state.counters["sky_view_ms"] = t.sky_view;
    state.counters["composite_ms"] = t.render;
    state.counters["cloud_shadow_ms"] = t.cloud_shadow_map;
    state.counters["cloud_shade_ms"] = t.cloud_shade;
    state.counters["cloud_trace_ms"] = t.cloud_trace;
    state.counters["cloud_reconstruct_ms"] = t.cloud_reconstruct;
    state.counters["cloud_ground_shadow_ms"] = t.cloud_ground_shadow;
    state.counters["cloud_light_shafts_ms"] = t.cloud_light_shafts;
    state.SetLabel(std::string(view.name) +
                   (block == 0 ? " clear" : " block " + std::to_string(block)));
}
BENCHMARK(BM_Frame720p)
    ->ArgsProduct({{0, 1, 2}, {0, 4, 8, 1}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(2.0);

// The block-4 frames without the far sun-depth volume (CloudSettings::sun_depth_size 0, its
// pass and its reads skipped) and with it (the default), in the same run. The shadow map's
// time, every shadow_map_interval frames, includes the volume's levels. args: view (kViews),
// 0 without, 1 with.
void BM_SunDepth720p(benchmark::State& state) {
    Fixture& f = Shared();
    const View& view = kViews[state.range(0)];
    CloudSettings settings = Settings(4);
    if (state.range(1) == 0) settings.sun_depth_size = 0;
    f.renderer.SetWeather(f.weather, settings);
    const PassTimes t = TimeFrames(state, f, f.CameraFor(view));
    state.counters["cloud_shadow_ms"] = t.cloud_shadow_map;
    state.counters["cloud_trace_ms"] = t.cloud_trace;
    state.SetLabel(std::string(view.name) + (state.range(1) == 1 ? " volume" : " no volume"));
}
BENCHMARK(BM_SunDepth720p)
    ->ArgsProduct({{0, 1, 2}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(2.0);

// The same frames at block 4 with the clouds' per-cell and per-pixel passes in each GL
// stage (CloudSettings::pass_stage; the default picks one by the driver). args: view (kViews),
// 0 fragment, 1 compute.
void BM_PassStage720p(benchmark::State& state) {
    Fixture& f = Shared();
    const View& view = kViews[state.range(0)];
    CloudSettings settings = Settings(4);
    settings.pass_stage =
        state.range(1) == 1 ? CloudPassStage::kCompute : CloudPassStage::kFragment;
    f.renderer.SetWeather(f.weather, settings);
    const PassTimes t = TimeFrames(state, f, f.CameraFor(view));
    state.counters["cloud_shade_ms"] = t.cloud_shade;
    state.counters["cloud_trace_ms"] = t.cloud_trace;
    state.counters["cloud_reconstruct_ms"] = t.cloud_reconstruct;
    state.SetLabel(std::string(view.name) + (state.range(1) == 1 ? " compute" : " fragment"));
}
BENCHMARK(BM_PassStage720p)
    ->ArgsProduct({{0, 1, 2}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(2.0);

// The composite over a host's geometry in the clouds: a ridge 8 km away fills the frame's lower
// part up to a line that rises and falls by 10 % of the height, rendered into the host's
// framebuffer with its depth. From inside the cumulus layer the ridge's edge and face meet the
// clouds' edges (where MarchToGeometry marches pixels on their own rays); from the ground the
// clouds lie behind it. args: view (kViews), 0 the far plane everywhere (no geometry) or 1 the
// ridge.
void BM_HostGeometryInClouds720p(benchmark::State& state) {
    Fixture& f = Shared();
    f.renderer.SetWeather(f.weather, Settings(4));
    constexpr int kWidth = 1280, kHeight = 720;
    constexpr double kNear = 1.0, kFar = 100000.0, kEyeDepth = 8000.0;
    const float ridge_depth = static_cast<float>(
        0.5 * ((kFar + kNear - 2.0 * kNear * kFar / kEyeDepth) / (kFar - kNear) + 1.0));
    std::vector<float> depth(static_cast<std::size_t>(kWidth * kHeight), 1.0f);
    for (int y = 0; y < kHeight && state.range(1) == 1; ++y) {
        for (int x = 0; x < kWidth; ++x) {
            if (y < kHeight * (0.45 + 0.1 * std::sin(x / 60.0))) {
                depth[static_cast<std::size_t>(y * kWidth + x)] = ridge_depth;
            }
        }
    }
    const zenith::test::ColourTarget target(GL_RGBA16F, kWidth, kHeight);
    GLuint depth_texture = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &depth_texture);
    glTextureStorage2D(depth_texture, 1, GL_DEPTH_COMPONENT32F, kWidth, kHeight);
    glTextureSubImage2D(depth_texture, 0, 0, 0, kWidth, kHeight, GL_DEPTH_COMPONENT, GL_FLOAT,
                        depth.data());
    const RenderTarget host = RenderTarget::Host(target.framebuffer(), {0, 0, kWidth, kHeight},
                                                 SceneDepth{depth_texture, kNear, kFar});
    const View& view = kViews[state.range(0)];
    f.renderer.Update(zenith::test::SceneOf(f.lights, {}), {f.CameraFor(view)});
    f.renderer.Render(host);
    glFinish();
    for (auto _ : state) {
        f.renderer.Render(host);
        glFinish();
    }
    glDeleteTextures(1, &depth_texture);
    const PassTimes t = Inspect(f.renderer).LastPassTimes();
    state.counters["composite_ms"] = t.render;
    state.counters["cloud_trace_ms"] = t.cloud_trace;
    state.counters["cloud_geometry_ms"] = t.cloud_geometry;
    state.SetLabel(std::string(view.name) +
                   (state.range(1) == 0 ? ", no geometry" : ", ridge at 8 km"));
}
BENCHMARK(BM_HostGeometryInClouds720p)
    ->ArgsProduct({{0, 1}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(2.0);

// The precipitation's cost (clouds::WithPrecipitationShafts, and the streaks of the rain at the
// camera): the overcast deck dry and raining moderately (0.6), whole frames at block 4 from the
// ground. args: 0 dry, 1 raining without streaks, 2 raining with them (the default)
void BM_PrecipitationShaft720p(benchmark::State& state) {
    Fixture& f = Shared();
    clouds::Weather deck = clouds::LoadWeather("overcast_stratus");
    deck.layers[0].precipitation = state.range(0) == 0 ? 0.0 : 0.6;
    CloudSettings settings = Settings(4);
    settings.precipitation_streaks = state.range(0) == 2;
    f.renderer.SetWeather(deck, settings);
    const PassTimes t = TimeFrames(state, f, f.CameraFor(kViews[0]));
    state.counters["cloud_trace_ms"] = t.cloud_trace;
    state.SetLabel(state.range(0) == 0   ? "ground, dry deck"
                   : state.range(0) == 1 ? "ground, raining deck, no streaks"
                                         : "ground, raining deck, streaks");
}
BENCHMARK(BM_PrecipitationShaft720p)
    ->Arg(0)
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(2.0);

// The light shafts' cost (CloudSettings::light_shaft_steps, 0 = none): whole frames at block 4
// from the ground and from 12 km, with the shafts' pass timed on its own. args: view, shaft steps
void BM_LightShafts720p(benchmark::State& state) {
    Fixture& f = Shared();
    const View& view = kViews[state.range(0)];
    CloudSettings settings = Settings(4);
    settings.light_shaft_steps = static_cast<int>(state.range(1));
    f.renderer.SetWeather(f.weather, settings);
    const PassTimes t = TimeFrames(state, f, f.CameraFor(view));
    state.counters["light_shafts_ms"] = t.cloud_light_shafts;
    state.counters["cloud_trace_ms"] = t.cloud_trace;
    state.SetLabel(std::string(view.name) + ", " + std::to_string(state.range(1)) + " steps");
}
BENCHMARK(BM_LightShafts720p)
    ->ArgsProduct({{0, 2}, {0, 24}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(2.0);

// The environment cube map and its harmonics (zenith/sky/environment.h) on top of whole frames
// from the ground, clear and at block 4: args: clouds (0/1), faces a side (0: none), faces per
// frame. environment_ms is the environment's GPU time per frame averaged over every frame (with
// one face a frame the faces differ, and every sixth frame adds the round's projection).
void BM_Environment720p(benchmark::State& state) {
    Fixture& f = Shared();
    const bool clouds = state.range(0) != 0;
    f.renderer.SetWeather(clouds ? f.weather : clouds::Weather{}, Settings(4));
    EnvironmentSettings environment;
    environment.size = static_cast<int>(state.range(1));
    environment.faces_per_frame = static_cast<int>(state.range(2));
    f.renderer.SetEnvironment(environment);
    const Camera camera = f.CameraFor(kViews[0]);
    const zenith::test::FrameOptions options;
    Frame(f, camera, options);
    glFinish();
    double environment_ms = 0.0;
    for (auto _ : state) {
        Frame(f, camera, options);
        glFinish();
        environment_ms += Inspect(f.renderer).LastPassTimes().environment;
    }
    f.renderer.SetEnvironment({});
    state.counters["environment_ms"] =
        environment_ms /
        static_cast<double>(std::max<benchmark::IterationCount>(state.iterations(), 1));
    state.SetLabel(std::string(clouds ? "block 4" : "clear") + ", " +
                   std::to_string(environment.size) + "^2 x 6, " +
                   std::to_string(environment.faces_per_frame) + " a frame");
}
BENCHMARK(BM_Environment720p)
    ->Args({0, 0, 1})
    ->Args({0, 64, 1})
    ->Args({0, 64, 6})
    ->Args({1, 0, 1})
    ->Args({1, 32, 1})
    ->Args({1, 64, 1})
    ->Args({1, 64, 6})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(2.0);

// The host's sunlight at the aircraft (SkySystem::Update calls it for the Sun and the Moon): the
// CPU march toward the Sun through scattered cumulus, 64 samples per layer, from the ground
// and from inside the layer.
void BM_CloudTransmittanceCpu(benchmark::State& state) {
    Fixture& f = Shared();
    f.renderer.SetWeather(f.weather, Settings(4));
    const Camera camera = f.CameraFor(kViews[state.range(0)]);
    CloudView view;
    double sum = 0.0;
    for (auto _ : state) {
        sum += f.renderer.CloudTransmittance(camera.position, f.lights.sun_direction, view);
    }
    benchmark::DoNotOptimize(sum);
    state.SetLabel(kViews[state.range(0)].name);
}
BENCHMARK(BM_CloudTransmittanceCpu)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

// The host's air queries (AtmosphereRenderer::SkyLuminance, AirInScattering to 4 km: the
// shared ray march on the CPU, 64 steps, over the renderer's own LUTs) from the ground under
// scattered cumulus, after an Update. args: 0 sky luminance, 1 air to 4 km
void BM_AirQueryCpu(benchmark::State& state) {
    Fixture& f = Shared();
    f.renderer.SetWeather(f.weather, Settings(4));
    const Camera camera = f.CameraFor(kViews[0]);
    zenith::test::DrawFrames(f.renderer, camera, f.lights, zenith::test::FrameOptions{});
    const glm::dvec3 direction = -camera.world_from_view[2];
    double sum = 0.0;
    for (auto _ : state) {
        sum += state.range(0) == 0
                   ? f.renderer.SkyLuminance(camera.position, direction).g
                   : f.renderer.AirInScattering(camera.position, direction, 4000.0).a;
    }
    benchmark::DoNotOptimize(sum);
    state.SetLabel(state.range(0) == 0 ? "sky luminance" : "air to 4 km");
}
BENCHMARK(BM_AirQueryCpu)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

// SetWeather with scattered cumulus (noise from the cache, weather map, GL programs, the CPU
// copy for CloudTransmittance): on a new renderer, which also compiles the six sky programs
// that composite the clouds, and again on the same renderer.
// args: 1 = a new renderer each time
void BM_SetWeather(benchmark::State& state) {
    Fixture& f = Shared();
    std::unique_ptr<AtmosphereRenderer> fresh;
    for (auto _ : state) {
        state.PauseTiming();
        if (state.range(0) == 1) fresh = std::make_unique<AtmosphereRenderer>(f.earth);
        AtmosphereRenderer& renderer = state.range(0) == 1 ? *fresh : f.renderer;
        renderer.SetWeather(clouds::Weather{}, Settings(4));
        glFinish();
        state.ResumeTiming();
        renderer.SetWeather(f.weather, Settings(4));
        glFinish();
    }
    state.SetLabel(state.range(0) == 1 ? "new renderer" : "same renderer");
}
BENCHMARK(BM_SetWeather)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->Iterations(5);

double MeanLuminance(const LutImage& image) {
    double sum = 0.0;
    for (const glm::vec4& t : image.texels) sum += (t.r + t.g + t.b) / 3.0;
    return sum / static_cast<double>(image.texels.size());
}

// The mean |image - reference| of the luminance, relative to the reference's mean.
double PixelDifference(const LutImage& image, const LutImage& reference) {
    double sum = 0.0;
    for (std::size_t i = 0; i < reference.texels.size(); ++i) {
        for (int c = 0; c < 3; ++c) {
            sum += std::abs(image.texels[i][c] - reference.texels[i][c]) / 3.0;
        }
    }
    return sum / static_cast<double>(reference.texels.size()) / MeanLuminance(reference);
}

// The reduced-resolution clouds after 4 block^2 static frames (each pixel traced four times)
// against a full-resolution render with 4x the steps and 8 jittered passes: mean luminance
// difference and mean per-pixel difference, both relative to the reference's mean.
// args: view, block
void BM_ConvergedVsReference720p(benchmark::State& state) {
    Fixture& f = Shared();
    const View& view = kViews[state.range(0)];
    const int block = static_cast<int>(state.range(1));
    const Camera camera = f.CameraFor(view);
    const FrameOptions options;
    double mean_difference = 0.0, pixel_difference = 0.0;
    for (auto _ : state) {
        CloudSettings high = Settings(1);
        high.max_steps = 256;
        high.min_step = 30.0;
        high.shadow_steps = 8;
        high.shadow_first_step = 40.0;
        f.renderer.SetWeather(f.weather, high);
        for (int i = 0; i < 8; ++i) Frame(f, camera, options);
        const LutImage reference = Inspect(f.renderer).ReadClouds();
        f.renderer.SetWeather(f.weather, Settings(block));
        for (int i = 0; i < 4 * block * block; ++i) Frame(f, camera, options);
        const LutImage converged = Inspect(f.renderer).ReadClouds();
        mean_difference = MeanLuminance(converged) / MeanLuminance(reference) - 1.0;
        pixel_difference = PixelDifference(converged, reference);
    }
    state.counters["mean_luminance_diff_pct"] = 100.0 * mean_difference;
    state.counters["per_pixel_diff_pct"] = 100.0 * pixel_difference;
    state.SetLabel(std::string(view.name) + " block " + std::to_string(block));
}
BENCHMARK(BM_ConvergedVsReference720p)
    ->ArgsProduct({{0, 1, 2}, {4, 8}})
    ->Unit(benchmark::kSecond)
    ->UseRealTime()
    ->Iterations(1);

// Motion at 1280x720: flying at 250 m/s, 30 frames per second, turning at 17 deg/s, 2 km up
// in the layer's base (the flight test of CloudRenderGlTest at full size). After 32 frames, the
// mean per-pixel difference to the converged full-resolution image at the last camera, for the
// flying camera, for one that held still there, and for the first camera's image (what a
// history that did not follow would show), relative to the truth's mean luminance.
// args: block
void BM_FlightVsTruth720p(benchmark::State& state) {
    Fixture& f = Shared();
    const int block = static_cast<int>(state.range(0));
    const auto camera_at = [&](int frame) {
        Camera c = f.CameraFor({"flight", 2000.0, 0.05});
        const double turn = 0.01 * frame;  // about the local vertical
        const glm::dmat3 yaw(glm::dvec3(std::cos(turn), std::sin(turn), 0.0),
                             glm::dvec3(-std::sin(turn), std::cos(turn), 0.0),
                             glm::dvec3(0.0, 0.0, 1.0));
        c.world_from_view = yaw * c.world_from_view;
        c.position.y += 250.0 / 30.0 * frame;  // north
        return c;
    };
    constexpr int kFrames = 32;
    const FrameOptions options;
    double flying = 0.0, still = 0.0, start = 0.0;
    for (auto _ : state) {
        f.renderer.SetWeather(f.weather, Settings(1));
        for (int i = 0; i < 8; ++i) Frame(f, camera_at(kFrames - 1), options);
        const LutImage truth = Inspect(f.renderer).ReadClouds();
        FrameOptions cut = options;
        cut.clouds.reset_history = true;
        Frame(f, camera_at(0), cut);
        const LutImage first = Inspect(f.renderer).ReadClouds();
        f.renderer.SetWeather(f.weather, Settings(block));
        for (int i = 0; i < kFrames; ++i) Frame(f, camera_at(i), options);
        const LutImage flown = Inspect(f.renderer).ReadClouds();
        f.renderer.SetWeather(f.weather, Settings(block));
        for (int i = 0; i < kFrames; ++i) Frame(f, camera_at(kFrames - 1), options);
        const LutImage held = Inspect(f.renderer).ReadClouds();
        flying = PixelDifference(flown, truth);
        still = PixelDifference(held, truth);
        start = PixelDifference(first, truth);
    }
    state.counters["flying_pct"] = 100.0 * flying;
    state.counters["still_pct"] = 100.0 * still;
    state.counters["first_camera_pct"] = 100.0 * start;
    state.SetLabel("block " + std::to_string(block));
}
BENCHMARK(BM_FlightVsTruth720p)
    ->Arg(4)
    ->Arg(8)
    ->Unit(benchmark::kSecond)
    ->UseRealTime()
    ->Iterations(1);

// Denser clouds converge more slowly in the step count: cumulonimbus from 12 km, 10 deg down,
// 160x90, four passes per setting; the mean cloud luminance at the default 64 steps and at 256,
// relative to 1024 (min_step scaled with the count, so every crossing gets that many steps).
void BM_StepConvergenceCumulonimbus(benchmark::State& state) {
    Fixture& f = Shared();
    const Camera camera = f.CameraFor({"12km", 12000.0, -0.17});
    FrameOptions options;
    options.size = {160, 90};
    const clouds::Weather cumulonimbus = clouds::LoadWeather("cumulonimbus");
    std::vector<double> means;
    for (auto _ : state) {
        means.clear();
        for (const int steps : {64, 256, 1024}) {
            CloudSettings s = Settings(1);
            s.max_steps = steps;
            s.min_step = 120.0 * 64.0 / steps;
            f.renderer.SetWeather(cumulonimbus, s);
            for (int i = 0; i < 4; ++i) Frame(f, camera, options);
            means.push_back(MeanLuminance(Inspect(f.renderer).ReadClouds()));
        }
    }
    state.counters["steps64_vs_1024_pct"] = 100.0 * (means[0] / means[2] - 1.0);
    state.counters["steps256_vs_1024_pct"] = 100.0 * (means[1] / means[2] - 1.0);
}
BENCHMARK(BM_StepConvergenceCumulonimbus)->Unit(benchmark::kSecond)->UseRealTime()->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
