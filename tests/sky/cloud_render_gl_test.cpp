// The cloud passes on OSMesa llvmpipe (float) against the same march compiled as C++ (double),
// from below, inside and above the layer and from orbit; coverage 0 is exactly the clear sky;
// the reduced-resolution trace with reprojection converges to a high-sample full-resolution
// render, and keeps up with a camera flying at airliner speed.
#include <glad/gl.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <memory>
#include <numbers>
#include <optional>
#include <utility>
#include <vector>

#include "bindings.h"
#include "cloud_test_support.h"
#include "colour_target.h"
#include "draw_frame.h"
#include "gl_test_support.h"
#include "luminance.h"
#include "reference/cloud_trace.h"
#include "zenith/base/error.h"
#include "zenith/sky/atmosphere_renderer.h"
#include "zenith/sky/inspection.h"
#include "zenith/sky/lighting.h"

namespace zenith::sky {
namespace {

using zenith::test::Luminance;

constexpr double kKm = 1000.0;

class CloudRenderGlTest : public gl::test::HeadlessGlTest {};

CloudSettings Settings(int block = 1) {
    CloudSettings s;
    s.block = block;
    s.noise_cache_directory = std::filesystem::path(ZENITH_BINARY_DIR) / "cloud-noise-cache";
    s.shadow_map_size = 32;
    return s;
}

clouds::Weather Cumulus(double coverage = 0.45) {
    clouds::CloudLayer layer;
    layer.name = "cumulus";
    layer.base_altitude = 1500.0;
    layer.top_altitude = 4000.0;
    layer.coverage = coverage;
    layer.cloud_type = 0.5;
    layer.map_period = 40000.0;
    layer.map.kind = clouds::WeatherMapSource::Kind::kPatches;
    layer.map.size = 128;
    layer.map.cells_per_tile = 8;
    layer.map.seed = 5;
    clouds::Weather weather;
    weather.name = "test_cumulus";
    weather.layers = {layer};
    return weather;
}

Lights Afternoon() {
    Lights lights;
    lights.sun_direction = glm::normalize(glm::dvec3(0.6, 0.3, 0.5));
    return lights;
}

// At `altitude` m, looking along heading (rad from +y = north toward +x = east) and pitch.
Camera CameraAt(double altitude, double heading, double pitch, double fov = 1.0) {
    Camera camera;
    camera.position = glm::dvec3(0.0, 0.0, 6360e3 + altitude);
    const glm::dvec3 forward(std::sin(heading) * std::cos(pitch),
                             std::cos(heading) * std::cos(pitch), std::sin(pitch));
    const glm::dvec3 right = glm::normalize(glm::cross(forward, glm::dvec3(0, 0, 1)));
    const glm::dvec3 up = glm::cross(right, forward);
    camera.world_from_view = glm::dmat3(right, up, -forward);
    camera.vertical_fov = fov;
    camera.aspect = 16.0 / 9.0;
    return camera;
}

using test::DrawFrames;
using test::FrameOptions;
using test::SceneOf;

// The Sun's disk is left out unless a test asks for it.
FrameOptions Options(glm::ivec2 size) {
    FrameOptions options;
    options.size = size;
    options.draw_sun_disk = false;
    return options;
}

LutImage RenderClouds(AtmosphereRenderer& renderer, const Camera& camera, const Lights& lights,
                      const FrameOptions& options, int frames = 1) {
    DrawFrames(renderer, camera, lights, options, frames);
    return Inspect(renderer).ReadClouds();
}

double MeanLuminance(const LutImage& image) {
    double sum = 0.0;
    for (const glm::vec4& t : image.texels) sum += (t.r + t.g + t.b) / 3.0;
    return sum / static_cast<double>(image.texels.size());
}

// Mean |a - b| of the luminance over the mean luminance of b, and mean |a - b| of the
// transmittance.
struct ImageDifference {
    double luminance = 0.0;
    double transmittance = 0.0;
};
ImageDifference Difference(const LutImage& a, const LutImage& b) {
    double l = 0.0, t = 0.0;
    for (std::size_t i = 0; i < a.texels.size(); ++i) {
        for (int c = 0; c < 3; ++c) l += std::abs(a.texels[i][c] - b.texels[i][c]) / 3.0;
        t += std::abs(a.texels[i].a - b.texels[i].a);
    }
    const double n = static_cast<double>(a.texels.size());
    return {l / n / std::max(MeanLuminance(b), 1e-9), t / n};
}

TEST_F(CloudRenderGlTest, CoverageZeroIsExactlyTheClearSky) {
    const Atmosphere earth;
    const Camera camera = CameraAt(2500.0, 0.3, 0.1);
    const Lights lights = Afternoon();
    FrameOptions options = Options({96, 54});
    options.draw_sun_disk = true;

    AtmosphereRenderer clear(earth);
    DrawFrames(clear, camera, lights, options);
    const LutImage sky = Inspect(clear).ReadFrame();

    clouds::Weather none = Cumulus(0.0);
    none.layers[0].map.kind = clouds::WeatherMapSource::Kind::kUniform;
    AtmosphereRenderer renderer(earth);
    renderer.SetWeather(none, Settings());
    DrawFrames(renderer, camera, lights, options);
    const LutImage frame = Inspect(renderer).ReadFrame();
    const LutImage layer = Inspect(renderer).ReadClouds();
    ASSERT_EQ(frame.texels.size(), sky.texels.size());
    for (std::size_t i = 0; i < frame.texels.size(); ++i) {
        ASSERT_EQ(frame.texels[i], sky.texels[i]) << "pixel " << i;
        ASSERT_EQ(layer.texels[i], glm::vec4(0.0f, 0.0f, 0.0f, 1.0f)) << "pixel " << i;
    }
    for (const glm::vec4& t : Inspect(renderer).ReadCloudShadowMap().texels) ASSERT_EQ(t.r, 1.0f);
}

std::vector<double> Everywhere(glm::ivec2 size, double eye_depth) {
    return std::vector<double>(static_cast<std::size_t>(size.x * size.y), eye_depth);
}

// The host's framebuffer after Render over geometry at eye_depths[pixel] m (rows from the
// bottom; 0: none, the far plane), filled with `colour` before: L + T colour per pixel.
std::vector<glm::vec4> RenderOverGeometry(AtmosphereRenderer& renderer, const Camera& camera,
                                          const Lights& lights, FrameOptions options,
                                          const std::vector<double>& eye_depths, float colour) {
    constexpr double kNear = 1.0, kFar = 100000.0;
    const glm::ivec2 size = options.size;
    std::vector<float> depth(eye_depths.size(), 1.0f);
    for (std::size_t i = 0; i < depth.size(); ++i) {
        if (!(eye_depths[i] > 0.0)) continue;
        const double z_ndc = (kFar + kNear - 2.0 * kNear * kFar / eye_depths[i]) / (kFar - kNear);
        depth[i] = static_cast<float>(0.5 * (z_ndc + 1.0));
    }
    const zenith::test::ColourTarget target(GL_RGBA32F, size.x, size.y);
    GLuint depth_texture = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &depth_texture);
    glTextureStorage2D(depth_texture, 1, GL_DEPTH_COMPONENT32F, size.x, size.y);
    glTextureSubImage2D(depth_texture, 0, 0, 0, size.x, size.y, GL_DEPTH_COMPONENT, GL_FLOAT,
                        depth.data());
    const float fill[4] = {colour, colour, colour, 1.0f};
    glClearNamedFramebufferfv(target.framebuffer(), GL_COLOR, 0, fill);
    renderer.Update(SceneOf(lights, options), {camera});
    renderer.Render(RenderTarget::Host(target.framebuffer(), {0, 0, size.x, size.y},
                                       SceneDepth{depth_texture, kNear, kFar}));
    glDeleteTextures(1, &depth_texture);
    return target.ReadFloat();
}

// The transmittance over the host's geometry (RenderOverGeometry): the difference of two host
// colours.
std::vector<double> TransmittanceOverGeometry(AtmosphereRenderer& renderer, const Camera& camera,
                                              const Lights& lights, const FrameOptions& options,
                                              const std::vector<double>& eye_depths) {
    const std::vector<glm::vec4> black =
        RenderOverGeometry(renderer, camera, lights, options, eye_depths, 0.0f);
    const std::vector<glm::vec4> white =
        RenderOverGeometry(renderer, camera, lights, options, eye_depths, 1000.0f);
    std::vector<double> t(black.size());
    for (std::size_t i = 0; i < t.size(); ++i) t[i] = (white[i].g - black[i].g) / 1000.0;
    return t;
}

// The composite lays the clouds, (L, T) as ReadClouds gives them, over what they hide: the
// Sun's disk shows through them times exactly T, and over a host's geometry only the clouds in
// front of it are drawn, so geometry before the clouds keeps the air's transmittance and
// geometry behind them takes T times it. With the history reset, every render of a view draws
// the same clouds.
TEST_F(CloudRenderGlTest, CompositeHidesTheSunAndOnlyGeometryBehindTheClouds) {
    const Atmosphere earth;
    // Looking at the Sun, 0.74 rad up, from 500 m, toward a cloud's edge: the clouds lie
    // 1.5-5 km away along the rays.
    const Camera camera = CameraAt(500.0, 1.9, 0.74, 0.1);
    Lights lights;
    lights.sun_direction = -camera.world_from_view[2];
    FrameOptions options = Options({96, 54});
    options.clouds.reset_history = true;

    AtmosphereRenderer clear(earth);
    AtmosphereRenderer cloudy(earth);
    cloudy.SetWeather(Cumulus(0.6), Settings());
    const auto sun_disk = [&](AtmosphereRenderer& renderer) {
        FrameOptions o = options;
        o.draw_sun_disk = true;
        DrawFrames(renderer, camera, lights, o);
        LutImage with = Inspect(renderer).ReadFrame();
        o.draw_sun_disk = false;
        DrawFrames(renderer, camera, lights, o);
        const LutImage without = Inspect(renderer).ReadFrame();
        for (std::size_t i = 0; i < with.texels.size(); ++i) with.texels[i] -= without.texels[i];
        return with;
    };
    const LutImage disk = sun_disk(clear);
    const LutImage disk_through_clouds = sun_disk(cloudy);
    const LutImage clouds = Inspect(cloudy).ReadClouds();
    int disk_pixels = 0, hidden = 0;
    for (std::size_t i = 0; i < disk.texels.size(); ++i) {
        const double expected = clouds.texels[i].a * disk.texels[i].g;
        ASSERT_NEAR(disk_through_clouds.texels[i].g, expected, 1e-5 * disk.texels[i].g + 1.0)
            << "pixel " << i;
        if (disk.texels[i].g > 0.0f) {
            ++disk_pixels;
            if (clouds.texels[i].a < 0.5f) ++hidden;
        }
    }

    int covered = 0;
    for (const double eye_depth : {1000.0, 20000.0}) {
        const std::vector<double> depths = Everywhere(options.size, eye_depth);
        const std::vector<double> air =
            TransmittanceOverGeometry(clear, camera, lights, options, depths);
        const std::vector<double> seen =
            TransmittanceOverGeometry(cloudy, camera, lights, options, depths);
        for (std::size_t i = 0; i < air.size(); ++i) {
            const double cloud = eye_depth < 2000.0 ? 1.0 : clouds.texels[i].a;
            ASSERT_NEAR(seen[i], cloud * air[i], 1e-4) << eye_depth << " m, pixel " << i;
            if (cloud < 0.5) ++covered;
        }
    }
    std::printf(
        "sun disk %d pixels, %d of them behind clouds with T < 0.5; %d pixels of "
        "geometry 20 km away behind such clouds\n",
        disk_pixels, hidden, covered);
    EXPECT_GT(disk_pixels, 10);
    EXPECT_GT(hidden, 0);
    EXPECT_GT(covered, 100);
}

// A homogeneous layer from `base` to `top` m of `extinction` /m: fog's density (ground_fog),
// flat to kCloudFogFlat of the layer, then falling to 0 at its top.
clouds::Weather FogLayer(double base, double top, double extinction) {
    clouds::CloudLayer layer;
    layer.name = "fog";
    layer.base_altitude = base;
    layer.top_altitude = top;
    layer.coverage = 1.0;
    layer.cloud_type = 0.0;
    layer.ground_fog = true;
    layer.extinction_scale = extinction / CloudSettings{}.extinction;
    layer.map_period = 20000.0;
    clouds::Weather weather;
    weather.name = "test_fog";
    weather.layers = {layer};
    return weather;
}

// Fog at the ground, 50 m deep with 200 m visibility (15 /km): the densest weather next to the
// camera.
clouds::Weather GroundFog() { return FogLayer(0.0, 50.0, 15.0e-3); }

// A peak rising out of a deck, seen from 300 m above the deck's top: geometry 2 km ahead in the
// frame's middle columns, its lower rows inside the deck, its upper rows above it. Over the
// geometry the composite must dim the host's colour by the clouds' transmittance up to it,
// exp(-tau), tau integrated here along each pixel's ray through the deck's density profile (the
// fog's: flat to kCloudFogFlat of the layer, then falling to 0 at its top). Before, each trace
// cell's one ray spoke for its 4 x 4 pixels, and the edge where the peak leaves the deck came
// out in blocks of cloud over the peak or peak through the cloud, changing with the traced pixel.
// A ridge across the whole frame has 72 cells along that edge: more than the list of cells to
// march had room for (2 / block^2 of the cells, 42), which left the rest to their cell's share
// and, on a GPU, a different rest each frame.
TEST_F(CloudRenderGlTest, GeometryRisingOutOfADeckIsSeenPixelByPixel) {
    const Atmosphere earth;
    const Lights lights = Afternoon();
    constexpr double kSigma = 5e-3;  // 1/m
    const clouds::Weather weather = FogLayer(1000.0, 1500.0, kSigma);
    const clouds::CloudLayer& deck = weather.layers[0];

    const Camera camera = CameraAt(1800.0, 0.3, -0.15);
    const glm::ivec2 size(96, 54);
    FrameOptions options = Options(size);
    options.clouds.reset_history = true;
    constexpr double kEyeDepth = 2000.0;
    const auto tau = [&](const glm::dvec3& view, double distance) {
        constexpr int kSteps = 4000;
        double sum = 0.0;
        for (int i = 0; i < kSteps; ++i) {
            const glm::dvec3 p = camera.position + view * (distance * (i + 0.5) / kSteps);
            const double h = (glm::length(p) - 6360e3 - deck.base_altitude) /
                             (deck.top_altitude - deck.base_altitude);
            if (h > 0.0 && h < 1.0)
                sum += std::clamp((1.0 - h) / (1.0 - ref::kCloudFogFlat), 0.0, 1.0);
        }
        return kSigma * sum * distance / kSteps;
    };
    AtmosphereRenderer clear(earth);
    // The geometry's columns: a peak in the middle, a ridge across the frame.
    for (const auto& [first, end] : {std::pair{30, 66}, std::pair{0, 96}}) {
        std::vector<double> depths(static_cast<std::size_t>(size.x * size.y), 0.0);
        for (int y = 0; y < size.y; ++y) {
            for (int x = first; x < end; ++x) {
                depths[static_cast<std::size_t>(y * size.x + x)] = kEyeDepth;
            }
        }
        const std::vector<double> air =
            TransmittanceOverGeometry(clear, camera, lights, options, depths);
        for (const int block : {1, 4}) {
            AtmosphereRenderer cloudy(earth);
            cloudy.SetWeather(weather, Settings(block));
            const std::vector<double> seen =
                TransmittanceOverGeometry(cloudy, camera, lights, options, depths);
            int pixels = 0, partly = 0, wrong = 0;
            double worst = 0.0;
            for (int y = 0; y < size.y; ++y) {
                for (int x = first; x < end; ++x) {
                    const std::size_t i = static_cast<std::size_t>(y * size.x + x);
                    const glm::dvec3 view = camera.Direction(2.0 * (x + 0.5) / size.x - 1.0,
                                                             2.0 * (y + 0.5) / size.y - 1.0);
                    const double distance = kEyeDepth / glm::dot(view, -camera.world_from_view[2]);
                    const double expected = std::exp(-tau(view, distance));
                    const double error = std::abs(seen[i] / air[i] - expected);
                    ++pixels;
                    if (expected > 0.05 && expected < 0.95) ++partly;
                    if (error > 0.05) ++wrong;
                    worst = std::max(worst, error);
                }
            }
            std::printf(
                "columns %d-%d, block %d: %d pixels of geometry, %d of them partly behind the "
                "deck; clouds' transmittance in front of them off by > 0.05 at %d, worst %.3f\n",
                first, end - 1, block, pixels, partly, wrong, worst);
            EXPECT_GT(partly, 36) << block;
            EXPECT_EQ(wrong, 0) << "columns " << first << "-" << end - 1 << ", block " << block;
        }
    }
}

// GPU trace (block 1, first frame: no history) vs ref::TraceClouds at every pixel, traced in
// each stage (CloudSettings::pass_stage; on llvmpipe kAuto takes the fragment stage, elsewhere
// the compute stage, so both are checked here on every machine).
struct View {
    const char* name;
    double altitude;
    double pitch;
};

// The clouds' image of `camera` at `altitude` m on the CPU, with the jitter of the GPU's first
// frame.
LutImage TraceOnTheCpu(const ref::CloudScene& scene, const Camera& camera, double altitude,
                       glm::ivec2 size) {
    LutImage traced(size.x, size.y, 1);
    const glm::dvec3 camera_km = glm::dvec3(glm::vec3(camera.position / kKm));
    for (int y = 0; y < size.y; ++y) {
        for (int x = 0; x < size.x; ++x) {
            const glm::dvec3 view =
                camera.Direction(2.0 * (x + 0.5) / size.x - 1.0, 2.0 * (y + 0.5) / size.y - 1.0);
            traced.at(x, y) = glm::vec4(ref::TraceClouds(scene, camera_km, altitude / kKm, view,
                                                         ref::CloudJitter({x, y}, 0.0)));
        }
    }
    return traced;
}

TEST_F(CloudRenderGlTest, TraceMatchesTheCpuReferenceFromBelowInsideAboveAndOrbit) {
    const Atmosphere earth;
    const Lights lights = Afternoon();
    const clouds::Weather weather = Cumulus();
    const glm::ivec2 size(48, 27);
    AtmosphereRenderer renderer(earth);
    const auto noise = clouds::test::CachedNoise();
    const View views[] = {{"ground, looking up", 300.0, 0.35},
                          {"inside the layer", 2700.0, 0.0},
                          {"12 km, looking down", 12000.0, -0.45},
                          {"orbit, 400 km", 400000.0, -1.2}};
    // The CPU's image of each view, which does not depend on the stage: traced once.
    std::vector<LutImage> cpu_images;
    for (const CloudPassStage stage : {CloudPassStage::kFragment, CloudPassStage::kCompute}) {
        CloudSettings settings = Settings();
        settings.pass_stage = stage;
        renderer.SetWeather(weather, settings);
        const char* stage_name = stage == CloudPassStage::kCompute ? "compute" : "fragment";
        for (std::size_t i = 0; i < std::size(views); ++i) {
            const View& v = views[i];
            SCOPED_TRACE(stage_name);
            const Camera camera = CameraAt(v.altitude, 0.4, v.pitch);
            FrameOptions options = Options(size);
            options.clouds.reset_history = true;
            const LutImage gpu = RenderClouds(renderer, camera, lights, options);

            const ref::CloudScene scene =
                ref::MakeCloudScene(earth, Inspect(renderer).ReadTransmittance(),
                                    Inspect(renderer).ReadMultipleScattering(),
                                    Inspect(renderer).ReadGroundIrradiance(), weather, settings,
                                    noise, camera, lights, options.clouds);
            // What the clouds do to the light beneath them (sky_shade passes vs the CPU march).
            const CloudShade shade = Inspect(renderer).ReadCloudShade();
            EXPECT_DOUBLE_EQ(shade.base_altitude, weather.layers[0].base_altitude) << v.name;
            EXPECT_NEAR(shade.direct_transmittance, scene.lights.cloud_direct, 1e-3) << v.name;
            EXPECT_NEAR(shade.sky_transmittance, scene.lights.cloud_sky, 1e-3) << v.name;
            EXPECT_NEAR(shade.ground_sky_transmittance, scene.lights.cloud_ground_sky, 1e-3)
                << v.name;
            for (int c = 0; c < 3; ++c) {
                EXPECT_NEAR(shade.luminance[c] / scene.lights.cloud_luminance[c], 1.0, 0.005)
                    << v.name;
                EXPECT_NEAR(shade.ground_luminance[c] / scene.lights.cloud_ground_luminance[c], 1.0,
                            0.005)
                    << v.name;
            }
            if (cpu_images.size() == i) {
                cpu_images.push_back(TraceOnTheCpu(scene, camera, v.altitude, size));
            }
            const LutImage& cpu = cpu_images[i];
            double cover = 0.0;
            for (const glm::vec4& t : cpu.texels) cover += 1.0 - t.a;
            cover /= static_cast<double>(cpu.texels.size());
            const ImageDifference d = Difference(gpu, cpu);
            const double mean_ratio = MeanLuminance(gpu) / MeanLuminance(cpu);
            std::printf(
                "%-8s %-22s cloud cover %.3f, mean luminance %.4g cd/m^2: GPU/CPU mean %.4f, "
                "per pixel %.2f %%, transmittance %.4f; beneath: sun %.4f/%.4f, "
                "sky %.4f/%.4f, cloud light %.1f/%.1f cd/m^2\n",
                stage_name, v.name, cover, MeanLuminance(cpu), mean_ratio, 100.0 * d.luminance,
                d.transmittance, shade.direct_transmittance, scene.lights.cloud_direct,
                shade.sky_transmittance, scene.lights.cloud_sky, shade.luminance.y,
                scene.lights.cloud_luminance.y);
            // Every view sees cloud, and not only cloud.
            EXPECT_GT(cover, 0.05) << v.name;
            EXPECT_LT(cover, 0.98) << v.name;
            // Float vs double over a march through thresholded noise (and llvmpipe's 8-bit filter
            // weights): a sample that lands on the other side of a cloud's edge moves a whole
            // step's worth of light. Measured: under 0.7 % per pixel, 0.03 % in the mean.
            EXPECT_NEAR(mean_ratio, 1.0, 0.005) << v.name;
            EXPECT_LT(d.luminance, 0.02) << v.name;
            EXPECT_LT(d.transmittance, 0.005) << v.name;
        }
    }
}

// The reduced-resolution trace (one pixel in 16 per frame, reprojected) once converged, against
// a full-resolution render with four times the steps: the 2 % goal. Cumulus from 300 m,
// and fog seen from 2 m looking 10 deg down, where the clouds' mean depth is metres: the point
// reprojected there was once camera_km + view depth in float, 6360 km from the planet's centre
// where a float's step is 0.5 m, which moved the history by degrees (speckles of 35 % and, where
// the shifted point left the view, wedges at the frame's sides that never converged).
TEST_F(CloudRenderGlTest, ReprojectionConvergesToAFullResolutionHighSampleRender) {
    const Atmosphere earth;
    const Lights lights = Afternoon();
    struct Scene {
        const char* name;
        clouds::Weather weather;
        Camera camera;
    };
    for (const Scene& v : {Scene{"cumulus from 300 m", Cumulus(), CameraAt(300.0, 0.4, 0.15)},
                           Scene{"fog from 2 m", GroundFog(), CameraAt(2.0, 0.4, -0.17)}}) {
        const FrameOptions options = Options({96, 54});
        CloudSettings reference_settings = Settings(1);
        reference_settings.max_steps = 256;
        reference_settings.min_step = 30.0;
        reference_settings.shadow_steps = 8;
        reference_settings.shadow_first_step = 40.0;
        AtmosphereRenderer reference(earth);
        reference.SetWeather(v.weather, reference_settings);
        const LutImage high = RenderClouds(reference, v.camera, lights, options, 8);
        AtmosphereRenderer renderer(earth);
        renderer.SetWeather(v.weather, Settings(4));
        const LutImage first = RenderClouds(renderer, v.camera, lights, options, 1);
        const LutImage converged = RenderClouds(renderer, v.camera, lights, options, 63);
        const double error_first = Difference(first, high).luminance;
        const double error = Difference(converged, high).luminance;
        const double mean_error = std::abs(MeanLuminance(converged) / MeanLuminance(high) - 1.0);
        std::printf(
            "%s, block 4 vs full resolution x4 steps: first frame %.2f %%, after 64 frames "
            "%.2f %% per pixel, %.2f %% in the mean luminance\n",
            v.name, 100.0 * error_first, 100.0 * error, 100.0 * mean_error);
        EXPECT_LT(mean_error, 0.02) << v.name;
        EXPECT_LT(error, error_first) << v.name;
        EXPECT_LT(error, 0.05) << v.name;
    }
}

// Flying at 250 m/s, 30 frames per second, turning at 17 deg/s: after a second the
// reprojected image follows the camera. Compared with the converged full-resolution render at
// the last camera, it is far closer than the image the camera started from (what a history
// reused in place, or smeared, would show) and not far from a camera that held still there.
TEST_F(CloudRenderGlTest, ReprojectionFollowsAFastCameraWithoutSmearing) {
    const Atmosphere earth;
    const Lights lights = Afternoon();
    const clouds::Weather weather = Cumulus();
    const FrameOptions options = Options({96, 54});
    const auto camera_at = [](int frame) {
        Camera c = CameraAt(2000.0, 0.4 + 0.01 * frame, 0.05);
        c.position.y += 250.0 / 30.0 * frame;  // north
        return c;
    };
    constexpr int kFrames = 32;

    AtmosphereRenderer reference(earth);
    reference.SetWeather(weather, Settings(1));
    const LutImage truth = RenderClouds(reference, camera_at(kFrames - 1), lights, options, 8);
    FrameOptions cut = options;
    cut.clouds.reset_history = true;
    const LutImage start = RenderClouds(reference, camera_at(0), lights, cut, 1);

    AtmosphereRenderer flying(earth);
    flying.SetWeather(weather, Settings(4));
    AtmosphereRenderer still(earth);
    still.SetWeather(weather, Settings(4));
    for (int frame = 0; frame < kFrames; ++frame) {
        RenderClouds(flying, camera_at(frame), lights, options, 1);
        RenderClouds(still, camera_at(kFrames - 1), lights, options, 1);
    }
    const double error_flying = Difference(Inspect(flying).ReadClouds(), truth).luminance;
    const double error_still = Difference(Inspect(still).ReadClouds(), truth).luminance;
    const double error_start = Difference(start, truth).luminance;
    std::printf(
        "after %d frames vs the converged full-resolution image: flying and turning "
        "%.1f %%, holding still %.1f %%, the first camera's image %.1f %%\n",
        kFrames, 100.0 * error_flying, 100.0 * error_still, 100.0 * error_start);
    EXPECT_LT(error_flying, 0.5 * error_start);
    EXPECT_LT(error_flying, error_still + 0.2);
}

// The two stages of the clouds' passes (CloudSettings::pass_stage: trace, sky shade,
// reconstruction, the ground's shadow and the light shafts, the same GLSL) make the same
// frames: 16 frames of a camera flying at 250 m/s under the cumulus' base, looking a little
// down and turning, block 4 (history, reprojection), the shade updated every 4th frame; the
// clouds alone and the composite (with the shadow on the ground and the shafts). On llvmpipe
// the compute stage once read the weather maps wrong (clouds/definitions.glsl).
TEST_F(CloudRenderGlTest, BothPassStagesMakeTheSameFramesWhileFlying) {
    const Atmosphere earth;
    const Lights lights = Afternoon();
    const FrameOptions options = Options({96, 54});
    std::vector<LutImage> frames, composites;
    std::vector<CloudShade> shades;
    for (const CloudPassStage stage : {CloudPassStage::kFragment, CloudPassStage::kCompute}) {
        CloudSettings settings = Settings(4);
        settings.pass_stage = stage;
        AtmosphereRenderer renderer(earth);
        renderer.SetWeather(Cumulus(), settings);
        for (int frame = 0; frame < 16; ++frame) {
            Camera camera = CameraAt(1000.0, 0.4 + 0.01 * frame, -0.1);
            camera.position.y += 250.0 / 30.0 * frame;
            RenderClouds(renderer, camera, lights, options, 1);
        }
        frames.push_back(Inspect(renderer).ReadClouds());
        composites.push_back(Inspect(renderer).ReadFrame());
        shades.push_back(Inspect(renderer).ReadCloudShade());
    }
    const ImageDifference d = Difference(frames[1], frames[0]);
    const ImageDifference frame = Difference(composites[1], composites[0]);
    std::printf(
        "compute vs fragment stage after 16 frames: clouds' luminance %.2e per pixel (mean "
        "%.4g cd/m^2), transmittance %.2e; the frame %.2e (mean %.4g cd/m^2); shade: sky "
        "%.6f / %.6f, cloud light %.3f / %.3f cd/m^2\n",
        d.luminance, MeanLuminance(frames[0]), d.transmittance, frame.luminance,
        MeanLuminance(composites[0]), shades[1].sky_transmittance, shades[0].sky_transmittance,
        shades[1].luminance.y, shades[0].luminance.y);
    EXPECT_GT(MeanLuminance(frames[0]), 100.0);
    EXPECT_LT(d.luminance, 1e-3);
    EXPECT_LT(d.transmittance, 1e-4);
    EXPECT_LT(frame.luminance, 1e-3);
    EXPECT_NEAR(shades[1].sky_transmittance, shades[0].sky_transmittance, 1e-5);
    EXPECT_NEAR(shades[1].luminance.y / shades[0].luminance.y, 1.0, 1e-4);
}

// What the clouds do beneath them (F16 §5.9 and Eq. 22), on our own ground: every pixel of a
// view down onto the ground under scattered cumulus against a CPU reference made without the
// Sky-View LUT or the composite: a 200-step march of the pixel's ray with the lights as the
// clouds shade them (CPU sky shade: mean sun and sky transmittance, the clouds' light), plus
// the local shadow's difference from the mean times the ground's direct light (Lambert,
// albedo E cos / pi) through the marched transmittance.
TEST_F(CloudRenderGlTest, CloudShadowAndShadeReachOurGround) {
    const Atmosphere earth;
    const Lights lights = Afternoon();
    const clouds::Weather weather = Cumulus();
    for (int block : {1, 4}) {  // the shadow worked out per pixel, or per cell and interpolated
        CloudSettings settings = Settings(block);
        settings.shadow_map_size = 64;
        AtmosphereRenderer renderer(earth);
        renderer.SetWeather(weather, settings);
        const Camera camera = CameraAt(800.0, 2.0, -0.7, 1.2);  // under the base, looking down
        const glm::ivec2 size(128, 72);
        FrameOptions options = Options(size);
        options.clouds.reset_history = true;
        const LutImage in_front = RenderClouds(renderer, camera, lights, options);
        const LutImage frame = Inspect(renderer).ReadFrame();
        const ref::Texture2D shadow_map = ref::FromImage(Inspect(renderer).ReadCloudShadowMap());

        const ref::CloudScene scene = ref::MakeCloudScene(
            earth, Inspect(renderer).ReadTransmittance(),
            Inspect(renderer).ReadMultipleScattering(), Inspect(renderer).ReadGroundIrradiance(),
            weather, settings, clouds::test::CachedNoise(), camera, lights, options.clouds);
        const ref::AtmosphereParameters& a = scene.atmosphere;
        const glm::dvec3 camera_km = camera.position / kKm;
        const double altitude = 0.8;
        const double r = glm::length(camera_km);
        double error = 0.0, reference = 0.0, lit = 0.0, shadowed = 0.0, shafts = 0.0;
        int n = 0, n_lit = 0, n_shadowed = 0;
        for (int y = 0; y < size.y; ++y) {
            for (int x = 0; x < size.x; ++x) {
                const glm::dvec3 view = camera.Direction(2.0 * (x + 0.5) / size.x - 1.0,
                                                         2.0 * (y + 0.5) / size.y - 1.0);
                const double t = ref::RaySphereDistance(r, glm::dot(camera_km, view) / r, altitude,
                                                        a.bottom_radius);
                if (t < 0.0 || in_front.at(x, y).a < 1.0f) continue;  // sky, or clouds in front
                const ref::ScatteringResult march = ref::IntegrateScatteredLuminance(
                    a, scene.transmittance, scene.multiple_scattering, scene.irradiance,
                    scene.lights, camera_km, altitude, view, 0.0, 1e9, 200, true);
                const glm::dvec3 ground = camera_km + view * t;
                const glm::dvec2 uv = ref::CloudShadowMapUv(
                    camera_km, a.bottom_radius, settings.shadow_map_extent / kKm, ground);
                const double weight = std::clamp(
                    (0.5 - std::max(std::abs(uv.x - 0.5), std::abs(uv.y - 0.5))) / 0.05, 0.0, 1.0);
                const double shadow = ref::SampleTexture2D(shadow_map, uv).r;
                const double mu_s =
                    glm::dot(glm::normalize(ground), scene.lights.light[0].direction);
                const glm::dvec3 direct =
                    scene.lights.light[0].illuminance * std::max(mu_s, 0.0) *
                    ref::GetTransmittanceToSun(a, scene.transmittance, a.bottom_radius, mu_s) *
                    a.ground_albedo / ref::kPi * march.transmittance;
                // The light shafts in the air in front of the ground, with the samples where the
                // GPU puts them in the pixel's cell (interpolated between cells on the GPU).
                const glm::dvec3 air = glm::dvec3(
                    ref::CloudAirShadowCorrection(
                        a, scene.transmittance, shadow_map, scene.lights,
                        scene.lights.light[0].direction, scene.lights.cloud_base,
                        settings.shadow_map_extent / kKm, camera_km, altitude, view, 1e9,
                        settings.light_shaft_steps,
                        ref::CloudJitter(glm::ivec2(x, y) / (kCloudLightShaftCell * block), 0.0))
                        .part[3]);
                const glm::dvec3 expected =
                    march.luminance + weight * (shadow - scene.lights.cloud_direct) * direct + air;
                shafts += std::abs(Luminance(air));
                const glm::dvec3 actual(frame.at(x, y));
                const double y_expected = Luminance(expected);
                const double y_actual = Luminance(actual);
                error += std::abs(y_actual - y_expected);
                reference += y_expected;
                ++n;
                if (weight == 1.0 && shadow > 0.9) lit += y_actual, ++n_lit;
                if (weight == 1.0 && shadow < 0.1) shadowed += y_actual, ++n_shadowed;
            }
        }
        ASSERT_GT(n, size.x * size.y / 2);
        ASSERT_GT(n_lit, 20);
        ASSERT_GT(n_shadowed, 20);
        const double relative = error / reference;
        const CloudShade shade = Inspect(renderer).ReadCloudShade();
        std::printf(
            "ground under scattered cumulus, block %d, %d pixels: GPU vs CPU reference %.2f "
            "%% (mean |difference| / mean); sunlit ground %.0f cd/m^2, in cloud shadow %.0f "
            "cd/m^2 (beneath: sun %.3f, sky %.3f, cloud light %.0f cd/m^2); light shafts in "
            "front of it %.2f %% of the luminance (mean |shaft|)\n",
            block, n, 100.0 * relative, lit / n_lit, shadowed / n_shadowed,
            shade.direct_transmittance, shade.sky_transmittance, shade.luminance.y,
            100.0 * shafts / reference);
        // Measured 0.01 % per pixel and 1.5 % interpolated between 4x4-pixel cells (shadow edges
        // softened over a cell); 61 % without the shadow term.
        EXPECT_LT(relative, block == 1 ? 0.005 : 0.03) << block;
        EXPECT_LT(shadowed / n_shadowed, 0.6 * lit / n_lit) << block;  // shadows show
    }
}

// The light shafts in front of a host's geometry: what they add there (the frame with shafts
// minus the frame without) against the CPU twin's correction up to the geometry's distance, which
// the composite interpolates from each cell's profile (a quarter, half, three quarters, whole).
TEST_F(CloudRenderGlTest, LightShaftsReachTheHostsGeometry) {
    const Atmosphere earth;
    const Lights lights = Afternoon();
    const clouds::Weather weather = Cumulus();
    const Camera camera = CameraAt(800.0, 2.0, -0.7, 1.2);  // under the base, looking down
    const glm::ivec2 size(96, 54);
    FrameOptions options = Options(size);
    options.clouds.reset_history = true;
    CloudSettings settings = Settings(1);
    settings.shadow_map_size = 64;
    AtmosphereRenderer with(earth);
    with.SetWeather(weather, settings);
    settings.light_shaft_steps = 0;
    AtmosphereRenderer without(earth);
    without.SetWeather(weather, settings);
    const double eye_depth = 700.0;  // m: in front of the ground, 1.0-1.6 km along the rays
    const std::vector<glm::vec4> shafted =
        RenderOverGeometry(with, camera, lights, options, Everywhere(size, eye_depth), 0.0f);
    const std::vector<glm::vec4> plain =
        RenderOverGeometry(without, camera, lights, options, Everywhere(size, eye_depth), 0.0f);

    settings.light_shaft_steps = CloudSettings{}.light_shaft_steps;
    const ref::Texture2D shadow_map = ref::FromImage(Inspect(with).ReadCloudShadowMap());
    const ref::CloudScene scene = ref::MakeCloudScene(
        earth, Inspect(with).ReadTransmittance(), Inspect(with).ReadMultipleScattering(),
        Inspect(with).ReadGroundIrradiance(), weather, settings, clouds::test::CachedNoise(),
        camera, lights, options.clouds);
    const glm::dvec3 camera_km = camera.position / kKm;
    double error = 0.0, total = 0.0, whole = 0.0;
    for (int y = 0; y < size.y; ++y) {
        for (int x = 0; x < size.x; ++x) {
            const glm::dvec3 view =
                camera.Direction(2.0 * (x + 0.5) / size.x - 1.0, 2.0 * (y + 0.5) / size.y - 1.0);
            const glm::dvec3 forward = -camera.world_from_view[2];
            const double distance_km = eye_depth / glm::dot(view, forward) / kKm;
            const auto shafts = [&](double limit) {
                return glm::dvec3(ref::CloudAirShadowCorrection(
                                      scene.atmosphere, scene.transmittance, shadow_map,
                                      scene.lights, scene.lights.light[0].direction,
                                      scene.lights.cloud_base, settings.shadow_map_extent / kKm,
                                      camera_km, 0.8, view, limit, 256, 0.5)
                                      .part[3]);
            };
            const glm::dvec3 expected = shafts(distance_km);
            const std::size_t i = static_cast<std::size_t>(y * size.x + x);
            const glm::dvec3 actual = glm::dvec3(shafted[i]) - glm::dvec3(plain[i]);
            error += std::abs(Luminance(actual) - Luminance(expected));
            total += std::abs(Luminance(expected));
            whole += std::abs(Luminance(shafts(1e9)) - Luminance(expected));
        }
    }
    std::printf(
        "light shafts in front of geometry 1.0-1.6 km away: GPU vs CPU %.1f %% (mean |difference| "
        "/ mean |shafts|); the whole ray's shafts would be %.0f %% off\n",
        100.0 * error / total, 100.0 * whole / total);
    EXPECT_GT(total, 0.0);
    EXPECT_LT(error, 0.05 * total);  // 1.2 % measured
    EXPECT_LT(error, 0.25 * whole);
}

// The host's sunlight through the clouds (CloudTransmittance): from the ground it is the shadow
// map's march (ref::CloudShadowMapTexel at the camera's ground point, same steps); from higher
// on the same ray less cloud lies ahead; above the clouds nothing; and it converges in the
// step count.
TEST_F(CloudRenderGlTest, CloudTransmittanceIsTheShadowMapsMarchFromAnyHeight) {
    const Atmosphere earth;
    const clouds::Weather weather = Cumulus(0.6);
    const CloudSettings settings = Settings();
    // Looking at the Sun through a cloud's edge (as in the composite test), from 500 m.
    const Camera camera = CameraAt(500.0, 1.9, 0.74, 0.1);
    Lights lights;
    lights.sun_direction = -camera.world_from_view[2];
    CloudView view;
    view.time = 600.0;  // the wind has moved the clouds
    AtmosphereRenderer renderer(earth);
    EXPECT_EQ(renderer.CloudTransmittance(camera.position, lights.sun_direction, view), 1.0);
    renderer.SetWeather(weather, settings);
    EXPECT_THROW(renderer.CloudTransmittance(camera.position, lights.sun_direction, view, 0),
                 zenith::ArgumentError);

    const glm::dvec3 ground = glm::dvec3(0.0, 0.0, earth.bottom_radius);
    const ref::CloudScene scene = ref::MakeCloudScene(
        earth, Inspect(renderer).ReadTransmittance(), Inspect(renderer).ReadMultipleScattering(),
        Inspect(renderer).ReadGroundIrradiance(), weather, settings, clouds::test::CachedNoise(),
        camera, lights, view);
    const double shadow_map_texel =
        ref::CloudShadowMapTexel(scene, settings, camera.position / kKm, glm::dvec2(0.5));
    const double from_ground =
        renderer.CloudTransmittance(ground, lights.sun_direction, view, settings.shadow_map_steps);
    EXPECT_NEAR(from_ground, shadow_map_texel, 1e-12);

    const auto along_sun = [&](double metres) { return ground + lights.sun_direction * metres; };
    const double exact = renderer.CloudTransmittance(ground, lights.sun_direction, view, 4096);
    const double coarse = renderer.CloudTransmittance(ground, lights.sun_direction, view);
    const double inside =
        renderer.CloudTransmittance(along_sun(2500.0), lights.sun_direction, view, 4096);
    const double above = renderer.CloudTransmittance(along_sun(8000.0), lights.sun_direction, view);
    std::printf(
        "sun through cumulus from the ground: %.4f (64 steps), %.4f (4096); from 2.5 km "
        "up the same ray %.4f; from above the clouds %.4f\n",
        coarse, exact, inside, above);
    EXPECT_LT(exact, 0.5);  // the Sun is behind the cloud
    EXPECT_NEAR(std::log(coarse) / std::log(exact), 1.0, 0.05);
    EXPECT_GT(inside, exact);
    EXPECT_LT(inside, 1.0);
    EXPECT_EQ(above, 1.0);
}

// The far sun-depth volume the GPU builds level by level, each level reading the one above it
// through the sampler (clouds/sun_depth.comp), against the CPU's chain in double
// (ref::CloudSunDepthVolume): tall clouds, 1.5-9 km, under a Sun 10 deg up, whose ways cross
// several texels each; the frame that reads it against the CPU's trace; and without a volume,
// one texel the march never reads.
TEST_F(CloudRenderGlTest, SunDepthVolumeMatchesTheCpu) {
    const Atmosphere earth;
    clouds::Weather weather = Cumulus(0.6);
    weather.layers[0].top_altitude = 9000.0;
    weather.layers[0].cloud_type = 1.0;
    CloudSettings settings = Settings();
    settings.sun_depth_size = 32;
    settings.sun_depth_levels = 10;
    settings.sun_depth_extent = 60000.0;
    const double e = 10.0 * ref::kPi / 180.0;
    Lights lights;
    lights.sun_direction = glm::dvec3(0.8 * std::cos(e), 0.6 * std::cos(e), std::sin(e));
    const Camera camera = CameraAt(300.0, 0.4, 0.2);
    AtmosphereRenderer renderer(earth);
    renderer.SetWeather(weather, settings);
    FrameOptions options = Options(glm::ivec2(32, 18));
    options.clouds.reset_history = true;
    const LutImage frame = RenderClouds(renderer, camera, lights, options);
    const LutImage gpu = Inspect(renderer).ReadCloudSunDepth();
    const ref::CloudScene scene = ref::MakeCloudScene(
        earth, Inspect(renderer).ReadTransmittance(), Inspect(renderer).ReadMultipleScattering(),
        Inspect(renderer).ReadGroundIrradiance(), weather, settings, clouds::test::CachedNoise(),
        camera, lights, options.clouds);
    ASSERT_EQ(gpu.size, glm::ivec3(32, 32, 10));
    ASSERT_EQ(scene.sun_depth.size(), glm::ivec3(32, 32, 10));
    double sum_gpu = 0.0, sum_cpu = 0.0, difference = 0.0, top = 0.0;
    for (int z = 0; z < 10; ++z) {
        for (int y = 0; y < 32; ++y) {
            for (int x = 0; x < 32; ++x) {
                const double g = gpu.at(x, y, z).r, c = scene.sun_depth.at(x, y, z).r;
                sum_gpu += g;
                sum_cpu += c;
                difference += std::abs(g - c);
                if (z == 9) top += g;
            }
        }
    }
    const double n = 32.0 * 32.0 * 10.0;
    std::printf(
        "sun-depth volume 32x32x10, Sun 10 deg up: mean optical depth GPU %.4f, CPU %.4f, mean "
        "|difference| %.4f\n",
        sum_gpu / n, sum_cpu / n, difference / n);
    EXPECT_GT(sum_cpu / n, 1.0);  // the clouds are there
    EXPECT_NEAR(sum_gpu / sum_cpu, 1.0, 0.005);
    EXPECT_LT(difference / sum_cpu, 0.01);
    EXPECT_EQ(top, 0.0);

    const LutImage cpu = TraceOnTheCpu(scene, camera, 300.0, options.size);
    const ImageDifference d = Difference(frame, cpu);
    std::printf("its frame: GPU/CPU mean %.4f, per pixel %.2f %%\n",
                MeanLuminance(frame) / MeanLuminance(cpu), 100.0 * d.luminance);
    EXPECT_NEAR(MeanLuminance(frame) / MeanLuminance(cpu), 1.0, 0.005);
    EXPECT_LT(d.luminance, 0.02);

    settings.sun_depth_size = 0;
    renderer.SetWeather(weather, settings);
    const LutImage without = RenderClouds(renderer, camera, lights, options);
    EXPECT_EQ(Inspect(renderer).ReadCloudSunDepth().size, glm::ivec3(1));
    // What the volume adds darkens the clouds lit from beyond the march's reach.
    std::printf("without the volume the frame is %.3f of the one with it\n",
                MeanLuminance(without) / MeanLuminance(frame));
    EXPECT_GT(MeanLuminance(without) / MeanLuminance(frame), 1.02);
}

// Rain lit by the light beneath the clouds (clouds/march.glsl, CloudLightBeneathClouds): the
// shade reaches the cloud passes through the cloud block (CloudPasses::CopyShade), the CPU twin
// through CopyCloudShade. From 300 m under raining cumulus, looking level into the shafts, the
// GPU against the CPU; and the CPU's frame with the shade left out of the cloud lights (the rain
// lit through its cloud's slab, as the shade's own trace lights it), which differs by 4 % here:
// a GPU whose cloud block lost the shade would be as far from the CPU. Measured: 1.0001 in the
// mean, 0.04 % per pixel (1.5 % in the mean while the CPU's shade took the shaft's base, the
// ground, for the clouds', so that its aerial perspective saw no clouds above).
TEST_F(CloudRenderGlTest, RainLitBeneathTheCloudsMatchesTheCpu) {
    const Atmosphere earth;
    clouds::Weather weather = Cumulus(0.7);
    weather.layers[0].precipitation = 0.6;
    const CloudSettings settings = Settings();
    const Lights lights = Afternoon();
    const Camera camera = CameraAt(300.0, 0.4, 0.05);
    AtmosphereRenderer renderer(earth);
    renderer.SetWeather(weather, settings);
    FrameOptions options = Options(glm::ivec2(32, 18));
    options.clouds.reset_history = true;
    const LutImage gpu = RenderClouds(renderer, camera, lights, options);
    ref::CloudScene scene = ref::MakeCloudScene(
        earth, Inspect(renderer).ReadTransmittance(), Inspect(renderer).ReadMultipleScattering(),
        Inspect(renderer).ReadGroundIrradiance(), clouds::WithPrecipitationShafts(weather),
        settings, clouds::test::CachedNoise(), camera, lights, options.clouds);
    ASSERT_EQ(scene.layers.size(), 2u);
    EXPECT_EQ(scene.cloud_lights.cloud_shaded, 1.0);
    const LutImage cpu = TraceOnTheCpu(scene, camera, 300.0, options.size);
    const ImageDifference d = Difference(gpu, cpu);
    scene.cloud_lights.cloud_shaded = 0.0;
    const LutImage slab = TraceOnTheCpu(scene, camera, 300.0, options.size);
    std::printf(
        "rain from 300 m: GPU/CPU mean %.4f, per pixel %.2f %%; lit through the slab "
        "instead %.3f of it\n",
        MeanLuminance(gpu) / MeanLuminance(cpu), 100.0 * d.luminance,
        MeanLuminance(slab) / MeanLuminance(cpu));
    EXPECT_NEAR(MeanLuminance(gpu) / MeanLuminance(cpu), 1.0, 0.005);
    EXPECT_LT(d.luminance, 0.02);
    EXPECT_GT(std::abs(MeanLuminance(slab) / MeanLuminance(cpu) - 1.0), 0.02);
}

// Under a uniformly raining deck the shaft is homogeneous: the host's precipitation query is
// Beer's law with clouds::PrecipitationExtinction, in any horizontal direction and over any
// distance; 1 without weather or rain, and over no distance.
TEST_F(CloudRenderGlTest, PrecipitationTransmittanceIsTheShaftsExtinction) {
    const Atmosphere earth;
    clouds::Weather weather = Cumulus(1.0);
    clouds::CloudLayer& deck = weather.layers[0];
    deck.map.kind = clouds::WeatherMapSource::Kind::kUniform;
    deck.precipitation = 0.6;
    const glm::dvec3 position(0.0, 0.0, earth.bottom_radius + 300.0);
    const glm::dvec3 east(1.0, 0.0, 0.0);
    const CloudView view;
    AtmosphereRenderer renderer(earth);
    EXPECT_EQ(renderer.PrecipitationTransmittance(position, east, 3000.0, view), 1.0);
    renderer.SetWeather(weather, Settings());
    for (const double distance : {500.0, 3000.0, 10000.0}) {
        const double expected = std::exp(-clouds::PrecipitationExtinction(0.6, false) * distance);
        EXPECT_NEAR(renderer.PrecipitationTransmittance(position, east, distance, view) / expected,
                    1.0, 2e-3)
            << distance;
        EXPECT_NEAR(renderer.PrecipitationTransmittance(position, glm::dvec3(0.6, -0.8, 0.0),
                                                        distance, view) /
                        expected,
                    1.0, 2e-3)
            << distance;
    }
    EXPECT_EQ(renderer.PrecipitationTransmittance(position, east, 0.0, view), 1.0);
    EXPECT_THROW(renderer.PrecipitationTransmittance(position, east, -1.0, view),
                 zenith::ArgumentError);
    // The whole column below the deck: the rain's optical depth adds to the deck's.
    const glm::dvec3 up(0.0, 0.0, 1.0);
    EXPECT_NEAR(renderer.PrecipitationTransmittance(position, up, 1200.0, view),
                std::exp(-clouds::PrecipitationExtinction(0.6, false) * 1200.0), 2e-3);
    weather.layers[0].precipitation = 0.0;
    renderer.SetWeather(weather, Settings());
    EXPECT_EQ(renderer.PrecipitationTransmittance(position, east, 3000.0, view), 1.0);
}

// Snow at the camera (moderate, under a uniform deck) drawn as streaks: where the frame shows
// the ground, each pixel changed by alpha (L_flake - L_behind), alpha the flakes' cover. Summed
// over those pixels the cover is the closed form's: along a ray the flakes cover sigma / 2 per
// metre (their cross-section; the shaft's sigma counts diffraction too) from 0.1 m to the side
// of the 3 m sphere of flakes around the camera; L_flake is a white Lambertian (0.9) under the
// shade's light on the ground.
TEST_F(CloudRenderGlTest, SnowAtTheCameraCoversWhatItsExtinctionSays) {
    const Atmosphere earth;
    clouds::Weather weather = Cumulus(1.0);
    clouds::CloudLayer& deck = weather.layers[0];
    deck.base_altitude = 800.0;
    deck.map.kind = clouds::WeatherMapSource::Kind::kUniform;
    deck.precipitation = 0.6;
    deck.snow = true;
    Camera camera = CameraAt(2.0, 0.0, -0.35, 1.2);  // looking down at the ground
    const Lights lights = Afternoon();
    AtmosphereRenderer renderer(earth);
    CloudSettings settings = Settings();
    constexpr glm::ivec2 kSize(320, 180);
    const auto frame = [&](bool streaks) {
        settings.precipitation_streaks = streaks;
        renderer.SetWeather(weather, settings);
        for (int i = 0; i < 3; ++i)
            test::DrawFrame(renderer, test::LightsOnly(lights), {camera}, kSize);
        return test::DrawFrame(renderer, test::LightsOnly(lights), {camera}, kSize);
    };
    const LutImage without = frame(false);
    const LutImage with = frame(true);
    const std::optional<CloudShade> shade = renderer.LatestCloudShade();
    ASSERT_TRUE(shade);
    const glm::dvec3 clear =
        lights.sun_illuminance * SampleGroundIrradiance(Inspect(renderer).ReadGroundIrradiance(),
                                                        glm::normalize(lights.sun_direction).z);
    const double flake =
        Luminance(glm::vec4(glm::vec3(0.9 *
                                      (clear * shade->ground_sky_transmittance +
                                       std::numbers::pi * shade->ground_luminance) /
                                      std::numbers::pi),
                            0.0f));
    const double sigma = clouds::PrecipitationExtinction(0.6, true);
    const double tan_y = std::tan(0.5 * camera.vertical_fov), tan_x = tan_y * camera.aspect;
    double cover = 0.0, expected = 0.0;
    for (int y = 0; y < kSize.y; ++y) {
        for (int x = 0; x < kSize.x; ++x) {
            const double behind = Luminance(without.at(x, y));
            if (!(flake - behind > 0.5 * flake)) continue;  // the dark ground: a clear contrast
            cover += (Luminance(with.at(x, y)) - behind) / (flake - behind);
            const glm::dvec3 ray =
                glm::normalize(camera.world_from_view *
                               glm::dvec3(((x + 0.5) / kSize.x * 2.0 - 1.0) * tan_x,
                                          ((y + 0.5) / kSize.y * 2.0 - 1.0) * tan_y, -1.0));
            // To the sphere of flakes or the ground, in depth along the view's axis (a pixel's
            // frustum holds z^2 of them per depth, each covering 1 / z^2 of it), from 0.1 m.
            double reach = 3.0;
            if (ray.z < 0.0) reach = std::min(reach, 2.0 / -ray.z);
            const double axial = reach * glm::dot(ray, -camera.world_from_view[2]);
            expected += 0.5 * sigma * std::max(axial - 0.1, 0.0);
        }
    }
    std::printf(
        "snow at the camera: flakes' cover summed over the ground's pixels %.2f, "
        "closed form %.2f (flake %.0f cd/m^2)\n",
        cover, expected, flake);
    ASSERT_GT(expected, 10.0);
    EXPECT_NEAR(cover / expected, 1.0, 0.06);
}

// The shadow map and the shade are worked out every shadow_map_interval frames; the frames
// between keep the last shade in the light block, which is uploaded without it every frame.
TEST_F(CloudRenderGlTest, ShadeHoldsBetweenItsUpdates) {
    const Atmosphere earth;
    const Lights lights = Afternoon();
    AtmosphereRenderer renderer(earth);
    renderer.SetWeather(Cumulus(), Settings(4));
    const Camera camera = CameraAt(300.0, 0.4, 0.15);
    const FrameOptions options = Options({48, 27});
    std::vector<CloudShade> shades;
    for (int frame = 0; frame < 6; ++frame) {
        RenderClouds(renderer, camera, lights, options);
        shades.push_back(Inspect(renderer).ReadCloudShade());
        const bool updated = Inspect(renderer).LastPassTimes().cloud_shade > 0.0;
        EXPECT_EQ(updated, frame % 4 == 0) << "frame " << frame;
    }
    EXPECT_LT(shades[0].direct_transmittance, 0.95);
    EXPECT_LT(shades[0].sky_transmittance, 0.95);
    EXPECT_GT(shades[0].luminance.y, 0.0);
    for (std::size_t frame = 1; frame < 4; ++frame) {
        EXPECT_EQ(shades[frame].direct_transmittance, shades[0].direct_transmittance);
        EXPECT_EQ(shades[frame].sky_transmittance, shades[0].sky_transmittance);
        EXPECT_EQ(shades[frame].luminance, shades[0].luminance);
    }
}

// The host's shade without a stall (issue 16): LatestCloudShade is nothing before the first
// Update, then, once the GPU has run a frame, exactly the shade ReadCloudShade waits for; it
// follows a change of weather, and without weather it is the clear sky's at once.
TEST_F(CloudRenderGlTest, LatestCloudShadeIsTheFencedCopyOfTheFramesShade) {
    const Atmosphere earth;
    const Lights lights = Afternoon();
    AtmosphereRenderer renderer(earth);
    const std::optional<CloudShade> clear = renderer.LatestCloudShade();
    ASSERT_TRUE(clear);
    EXPECT_EQ(clear->base_altitude, 0.0);
    EXPECT_EQ(clear->sky_transmittance, 1.0);
    renderer.SetWeather(Cumulus(), Settings(4));
    EXPECT_FALSE(renderer.LatestCloudShade()) << "a shade before any frame";
    const Camera camera = CameraAt(300.0, 0.4, 0.15);
    const FrameOptions options = Options({48, 27});
    DrawFrames(renderer, camera, lights, options);
    glFinish();
    const std::optional<CloudShade> latest = renderer.LatestCloudShade();
    ASSERT_TRUE(latest);
    const CloudShade read = Inspect(renderer).ReadCloudShade();
    EXPECT_EQ(latest->base_altitude, read.base_altitude);
    EXPECT_EQ(latest->direct_transmittance, read.direct_transmittance);
    EXPECT_EQ(latest->sky_transmittance, read.sky_transmittance);
    EXPECT_EQ(latest->luminance, read.luminance);
    EXPECT_LT(latest->sky_transmittance, 0.95);
    // Thicker clouds: the next frames' copies carry the new shade.
    renderer.SetWeather(clouds::LoadWeather("overcast_stratus"), Settings(4));
    for (int frame = 0; frame < 3; ++frame) DrawFrames(renderer, camera, lights, options);
    glFinish();
    const std::optional<CloudShade> overcast = renderer.LatestCloudShade();
    ASSERT_TRUE(overcast);
    EXPECT_EQ(overcast->sky_transmittance, Inspect(renderer).ReadCloudShade().sky_transmittance);
    EXPECT_LT(overcast->sky_transmittance, latest->sky_transmittance);
}

// Issue 15: the thick overcast seen from above at noon is brighter than the albedo-0.3 ground
// beside it (the octave lighting made it a third as bright). The whole frame, straight down from
// 8 km over overcast_stratus and over the clear ground, sun 65 deg high.
TEST_F(CloudRenderGlTest, OvercastStratusFromAboveIsBrighterThanTheGround) {
    const Atmosphere earth;
    AtmosphereRenderer renderer(earth);
    Lights noon;
    const double elevation = glm::radians(65.0);
    noon.sun_direction = glm::dvec3(0.0, std::cos(elevation), std::sin(elevation));
    const Camera camera = CameraAt(8000.0, 0.0, -glm::radians(90.0) + 1e-3, 0.35);
    FrameOptions options = Options({32, 18});
    const auto frame_luminance = [&](const clouds::Weather& weather) {
        renderer.SetWeather(weather, Settings());
        options.clouds.reset_history = true;
        DrawFrames(renderer, camera, noon, options);
        const LutImage frame = Inspect(renderer).ReadFrame();
        double sum = 0.0;
        for (const glm::vec4& t : frame.texels) sum += Luminance(t);
        return sum / static_cast<double>(frame.texels.size());
    };
    const double deck = frame_luminance(clouds::LoadWeather("overcast_stratus"));
    const double ground = frame_luminance(clouds::Weather{});
    // pi L / E of the deck, with E from the ground's pi L / 0.3 (its air light included).
    std::printf(
        "overcast_stratus from 8 km: %.0f cd/m^2, clear ground %.0f cd/m^2 (deck pi L / E "
        "~ %.2f)\n",
        deck, ground, 0.3 * deck / ground);
    EXPECT_GT(deck, 1.3 * ground);
}

TEST_F(CloudRenderGlTest, OvercastShadowsTheGroundAndTheSettingsAreChecked) {
    const Atmosphere earth;
    clouds::Weather overcast = Cumulus(1.0);
    overcast.layers[0].map.kind = clouds::WeatherMapSource::Kind::kUniform;
    overcast.layers[0].cloud_type = 1.0;
    AtmosphereRenderer renderer(earth);
    renderer.SetWeather(overcast, Settings());
    Lights noon;
    noon.sun_direction = glm::dvec3(0.0, 0.0, 1.0);
    const Camera camera = CameraAt(300.0, 0.0, 0.2);
    RenderClouds(renderer, camera, noon, Options({32, 18}));
    double mean = 0.0;
    const LutImage shadow = Inspect(renderer).ReadCloudShadowMap();
    for (const glm::vec4& t : shadow.texels) mean += t.r;
    mean /= static_cast<double>(shadow.texels.size());
    std::printf("overcast cumulonimbus at noon: mean sun transmittance to the ground %.3g\n", mean);
    EXPECT_LT(mean, 0.05);

    CloudSettings bad = Settings();
    bad.block = 0;
    try {
        renderer.SetWeather(overcast, bad);
        FAIL() << "block 0 accepted";
    } catch (const zenith::ArgumentError& e) {
        EXPECT_NE(std::string(e.what()).find("CloudSettings::block = 0"), std::string::npos)
            << e.what();
    }
    clouds::Weather five = Cumulus();
    five.layers.clear();
    for (int i = 0; i < 5; ++i) {
        clouds::CloudLayer layer = Cumulus().layers[0];
        layer.base_altitude = 1000.0 + 2000.0 * i;
        layer.top_altitude = layer.base_altitude + 1000.0;
        five.layers.push_back(layer);
    }
    EXPECT_THROW(renderer.SetWeather(five, Settings()), zenith::ArgumentError);
    // The failed calls left the previous weather in place.
    EXPECT_EQ(renderer.weather(), overcast);
}

}  // namespace
}  // namespace zenith::sky
