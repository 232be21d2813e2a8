// GPU (OSMesa llvmpipe, float) vs CPU (the same functions.glsl compiled as C++, double) for each
// LUT and the final image, under named tolerances: the shaders and the reference cannot drift.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include "draw_frame.h"
#include "gl_test_support.h"
#include "luminance.h"
#include "reference/atmosphere_functions.h"
#include "shader_parameters.h"
#include "zenith/sky/atmosphere_renderer.h"
#include "zenith/sky/inspection.h"
#include "zenith/sky/reference/atmosphere_reference.h"
#include "zenith/sky/sky_state.h"

namespace zenith::sky {
namespace {

using test::Luminance;

struct Difference {
    double max_absolute = 0.0;
    double max_relative = 0.0;  // relative to max(|reference|, floor)
};

Difference Compare(const LutImage& gpu, const LutImage& cpu, double floor, int channels = 3) {
    EXPECT_EQ(gpu.size, cpu.size);
    Difference d;
    const std::size_t n = std::min(gpu.texels.size(), cpu.texels.size());
    for (std::size_t i = 0; i < n; ++i) {
        for (int c = 0; c < channels; ++c) {
            const double a = gpu.texels[i][c], b = cpu.texels[i][c];
            const double diff = std::abs(a - b);
            d.max_absolute = std::max(d.max_absolute, diff);
            d.max_relative = std::max(d.max_relative, diff / std::max(std::abs(b), floor));
        }
    }
    return d;
}

class AtmosphereGlTest : public gl::test::HeadlessGlTest {};

Lights MorningLights() {
    Lights lights;
    lights.sun_direction = glm::normalize(glm::dvec3(0.8, 0.1, 0.25));
    return lights;
}

Camera CameraAt(double altitude) {
    Camera camera;
    camera.position = glm::dvec3(0.0, 0.0, 6360e3 + altitude);
    // Looking toward +x (the sun's azimuth), up = +z.
    camera.world_from_view =
        glm::dmat3(glm::dvec3(0, 1, 0), glm::dvec3(0, 0, 1), glm::dvec3(-1, 0, 0));
    camera.vertical_fov = 1.2;
    camera.aspect = 16.0 / 9.0;
    return camera;
}

TEST_F(AtmosphereGlTest, StaticLutsMatchTheCpuReference) {
    const Atmosphere earth;
    const AtmosphereRenderer gpu(earth);
    const reference::AtmosphereReference cpu(earth);
    const RendererInspection inspect(gpu);
    const Difference t = Compare(inspect.ReadTransmittance(), cpu.transmittance(), 1e-3);
    const Difference ms =
        Compare(inspect.ReadMultipleScattering(), cpu.multiple_scattering(), 1e-4);
    const Difference e = Compare(inspect.ReadGroundIrradiance(), cpu.ground_irradiance(), 1e-3);
    std::printf(
        "GPU vs CPU: transmittance max |d| %.2e; multiple scattering max rel %.2e; "
        "irradiance max rel %.2e\n",
        t.max_absolute, ms.max_relative, e.max_relative);
    // Float evaluation of the same code: transmittance to 1e-4 absolute (it is in [0, 1]); the
    // scattering LUTs to 0.5 % relative (float exp/log over long sums).
    EXPECT_LT(t.max_absolute, 1e-4);
    EXPECT_LT(ms.max_relative, 5e-3);
    EXPECT_LT(e.max_relative, 5e-3);
}

TEST_F(AtmosphereGlTest, FrameLutsMatchTheCpuReference) {
    const Atmosphere earth;
    AtmosphereRenderer gpu(earth);
    const reference::AtmosphereReference cpu(earth);
    const Lights lights = MorningLights();
    for (double altitude : {2.0, 9000.0}) {
        const Camera camera = CameraAt(altitude);
        gpu.Update(test::LightsOnly(lights), {camera});
        const Difference sky =
            Compare(Inspect(gpu).ReadSkyView(), cpu.SkyView(camera.position, lights), 1e-1);
        const Difference ap = Compare(Inspect(gpu).ReadAerialPerspective(),
                                      cpu.AerialPerspective(camera, lights), 1e-1, 4);
        std::printf(
            "GPU vs CPU at %.0f m: Sky-View max rel %.2e; aerial perspective max rel "
            "%.2e\n",
            altitude, sky.max_relative, ap.max_relative);
        // 2 m is a camera on a runway: float must hold there too (hence the exact camera
        // altitude and the cancellation-free step integral in functions.glsl).
        EXPECT_LT(sky.max_relative, 5e-3) << altitude;
        EXPECT_LT(ap.max_relative, 5e-3) << altitude;
    }
}

// Luminance (Rec.709 Y) of a frame's texel.

double RelativeRmse(const LutImage& a, const LutImage& b) {
    double sum_sq = 0.0, sum = 0.0;
    for (std::size_t i = 0; i < a.texels.size(); ++i) {
        const double d = Luminance(a.texels[i]) - Luminance(b.texels[i]);
        sum_sq += d * d;
        sum += Luminance(b.texels[i]);
    }
    const double n = static_cast<double>(a.texels.size());
    return std::sqrt(sum_sq / n) / (sum / n);
}

TEST_F(AtmosphereGlTest, FrameMatchesTheCpuSkyViewLookup) {
    const Atmosphere earth;
    AtmosphereRenderer gpu(earth);
    const reference::AtmosphereReference cpu(earth);
    const Lights lights = MorningLights();
    const Camera camera = CameraAt(1500.0);
    const glm::ivec2 size(64, 36);
    const LutImage frame = test::DrawFrame(gpu, test::LightsOnly(lights, false), {camera}, size);
    const LutImage sky_view = cpu.SkyView(camera.position, lights);
    double worst = 0.0;
    for (int y = 0; y < size.y; ++y) {
        for (int x = 0; x < size.x; ++x) {
            const glm::dvec3 direction =
                camera.Direction(2.0 * (x + 0.5) / size.x - 1.0, 2.0 * (y + 0.5) / size.y - 1.0);
            const glm::dvec3 expected =
                cpu.SampleSkyView(sky_view, camera.position, lights.sun_direction, direction);
            const double e = Luminance(expected);
            worst = std::max(worst, std::abs(Luminance(frame.at(x, y)) - e) / std::max(e, 1.0));
        }
    }
    std::printf("frame vs CPU Sky-View lookup: max relative %.2e\n", worst);
    EXPECT_LT(worst, 1e-2);
}

TEST_F(AtmosphereGlTest, SwitchFromSkyViewToRayMarchingIsInvisible) {
    // Hillaire 2020 §7: above the atmosphere the renderer ray marches each pixel. Just below the
    // top both paths are valid, so their images there measure the jump at the switch.
    const Atmosphere earth;
    AtmosphereRenderer gpu(earth);
    const Lights lights = MorningLights();
    for (double altitude : {1000.0, 99000.0}) {
        Camera camera = CameraAt(altitude);
        // Look 20 deg down so the horizon, the limb and the ground are all in view.
        const double pitch = -0.35;
        camera.world_from_view =
            glm::dmat3(glm::dvec3(0, 1, 0), glm::dvec3(std::sin(-pitch), 0, std::cos(pitch)),
                       glm::dvec3(-std::cos(pitch), 0, std::sin(-pitch)));
        const SkyScene scene = test::LightsOnly(lights, false);
        const LutImage sky_view = test::DrawFrame(gpu, scene, {camera}, {160, 90});
        const LutImage marched = test::DrawFrame(gpu, scene, {camera, true, 64}, {160, 90});
        const double rmse = RelativeRmse(sky_view, marched);
        std::printf("Sky-View vs per-pixel ray march at %.0f m: relative RMSE %.4f\n", altitude,
                    rmse);
        EXPECT_LT(rmse, 0.02) << altitude;
    }
}

// Sum of luminance times pixel solid angle over a frame: its illuminance at the camera.
double FrameIlluminance(const LutImage& frame, const Camera& camera) {
    const double tan_y = std::tan(0.5 * camera.vertical_fov), tan_x = tan_y * camera.aspect;
    const double dx = 2.0 * tan_x / frame.size.x, dy = 2.0 * tan_y / frame.size.y;
    double sum = 0.0;
    for (int y = 0; y < frame.size.y; ++y) {
        for (int x = 0; x < frame.size.x; ++x) {
            const double u = ((x + 0.5) / frame.size.x * 2.0 - 1.0) * tan_x;
            const double v = ((y + 0.5) / frame.size.y * 2.0 - 1.0) * tan_y;
            sum += Luminance(frame.at(x, y)) * dx * dy / std::pow(1.0 + u * u + v * v, 1.5);
        }
    }
    return sum;
}

// From space, looking away from the planet: nothing attenuates, so what is drawn must integrate
// to the light's illuminance exactly (energy conservation of the disk and of the splat).
Camera SpaceCameraLookingAt(const glm::dvec3& direction, double fov) {
    Camera camera;
    camera.position = glm::dvec3(0.0, 0.0, 6460e3 + 2000e3);
    const glm::dvec3 forward = glm::normalize(direction);
    const glm::dvec3 right = glm::normalize(glm::cross(forward, glm::dvec3(1, 0, 0)));
    camera.world_from_view = glm::dmat3(right, glm::cross(right, forward), -forward);
    camera.vertical_fov = fov;
    camera.aspect = 1.0;
    return camera;
}

TEST_F(AtmosphereGlTest, SunDiskAndStarsIntegrateToTheirIlluminance) {
    AtmosphereRenderer gpu(Atmosphere{});
    Lights lights;
    lights.sun_direction = glm::normalize(glm::dvec3(0.0, 0.3, 1.0));
    const double sun_y = Luminance(glm::vec4(glm::vec3(lights.sun_illuminance), 0.0f));
    const glm::ivec2 size(256, 256);
    // Resolved disk: 2 deg field, the Sun 0.27 deg across 34 pixels in radius.
    Camera camera = SpaceCameraLookingAt(lights.sun_direction, 2.0 * 0.017453292519943295);
    const double disk =
        FrameIlluminance(test::DrawFrame(gpu, test::LightsOnly(lights), {camera}, size), camera) /
        sun_y;
    // Below a pixel (90 deg field): splatted as a point.
    camera = SpaceCameraLookingAt(lights.sun_direction, 1.5707963267948966);
    const double point =
        FrameIlluminance(test::DrawFrame(gpu, test::LightsOnly(lights), {camera}, size), camera) /
        sun_y;
    // A star elsewhere in the field (the Sun turned off by pointing it away).
    Lights dark = lights;
    dark.sun_direction = camera.world_from_view[2];  // behind the camera
    SkyScene starry = test::LightsOnly(dark);
    starry.stars = {{glm::normalize(-camera.world_from_view[2] + 0.1 * camera.world_from_view[0]),
                     glm::dvec3(2e-6)}};
    const double star =
        FrameIlluminance(test::DrawFrame(gpu, starry, {camera}, size), camera) / 2e-6;
    std::printf("integrated / true illuminance: sun disk %.4f, sun point %.6f, star %.6f\n", disk,
                point, star);
    EXPECT_NEAR(disk, 1.0, 0.01);  // pixelisation of the disk edge
    EXPECT_NEAR(point, 1.0, 1e-5);
    EXPECT_NEAR(star, 1.0, 1e-5);
}

TEST_F(AtmosphereGlTest, OffAxisSunDiskIsDrawnWhole) {
    // The disks are drawn inside a scissor box computed on the CPU; off-axis in a wide field the
    // perspective stretches a disk most, so a box too tight would clip it. A 2 deg Sun 50 deg off
    // the axis of a 100 deg field, 8.7 pixels in radius: all of its light must be in the frame.
    Atmosphere atmosphere;
    atmosphere.sun_angular_radius = 2.0 * 0.017453292519943295;
    AtmosphereRenderer gpu(atmosphere);
    Camera camera = SpaceCameraLookingAt(glm::dvec3(0.0, 0.3, 1.0), 100.0 * 0.017453292519943295);
    const glm::dvec3 diagonal =
        glm::normalize(camera.world_from_view[0] + camera.world_from_view[1]);
    const double off_axis = 50.0 * 0.017453292519943295;
    Lights lights;
    lights.sun_direction = glm::normalize(-camera.world_from_view[2] * std::cos(off_axis) +
                                          diagonal * std::sin(off_axis));
    const LutImage frame = test::DrawFrame(gpu, test::LightsOnly(lights), {camera}, {512, 512});
    const double sun_y = Luminance(glm::vec4(glm::vec3(lights.sun_illuminance), 0.0f));
    const double ratio = FrameIlluminance(frame, camera) / sun_y;
    std::printf("off-axis sun disk: integrated / true illuminance %.4f\n", ratio);
    EXPECT_NEAR(ratio, 1.0, 0.01);
}

// A planet's disk wider than a pixel (ResolveDisks) in the daytime sky: an extended source,
// drawn whatever the eye's threshold for points, and all of its light there: the frame with it
// minus the frame without integrates to its illuminance through the air (Venus at -4.3 mag, a
// 60" crescent, 20 pixels across in a 0.1 deg field, 30 deg up).
TEST_F(AtmosphereGlTest, ResolvedPlanetIsDrawnWholeInDaylight) {
    AtmosphereRenderer gpu(Atmosphere{});
    const glm::dvec3 toward = glm::normalize(glm::dvec3(0.0, std::cos(0.52), std::sin(0.52)));
    Camera camera;
    camera.position = glm::dvec3(0.0, 0.0, 6360e3 + 2.0);
    const glm::dvec3 right = glm::normalize(glm::cross(toward, glm::dvec3(0.0, 0.0, 1.0)));
    camera.world_from_view = glm::dmat3(right, glm::cross(right, toward), -toward);
    camera.vertical_fov = glm::radians(0.1);
    camera.aspect = 1.0;
    const Lights lights = MorningLights();
    SkyScene scene = test::LightsOnly(lights, false);
    const LutImage sky = test::DrawFrame(gpu, scene, {camera}, {128, 128});
    StarPoint venus;
    venus.direction = toward;
    venus.illuminance = glm::dvec3(1.1e-4);  // lux, -4.3 mag
    venus.angular_radius = glm::radians(30.0 / 3600.0);
    venus.sunward = glm::normalize(lights.sun_direction - toward);
    scene.stars = {venus};
    const LutImage with = test::DrawFrame(gpu, scene, {camera}, {128, 128});
    const double drawn = FrameIlluminance(with, camera) - FrameIlluminance(sky, camera);
    const auto a = MakeShaderParameters<ref::AtmosphereParameters>(Atmosphere{});
    const double transmittance = glm::dot(
        ref::ComputeTransmittanceToTopAtmosphereBoundary(a, a.bottom_radius + 0.002, toward.z, 500),
        glm::dvec3(0.2126, 0.7152, 0.0722));  // of a grey source's luminance
    std::printf("resolved Venus in daylight: drawn %.4g lux, expected %.4g (T %.3f)\n", drawn,
                1.1e-4 * transmittance, transmittance);
    EXPECT_NEAR(drawn / (1.1e-4 * transmittance), 1.0, 0.005);
}

TEST_F(AtmosphereGlTest, MoonIsLitOnTheSideFacingTheSun) {
    // A half Moon with the Sun 90 deg to its right in the image: the lit half is the right one.
    AtmosphereRenderer gpu(Atmosphere{});
    const glm::dvec3 forward = glm::normalize(glm::dvec3(0.0, 1.0, 0.3));
    Camera camera = SpaceCameraLookingAt(forward, 0.02);
    const glm::dvec3 right = camera.world_from_view[0];
    Lights lights;
    lights.sun_direction = right;  // perpendicular to the line of sight: quarter phase
    SkyScene scene = test::LightsOnly(lights, false);
    scene.moon.enabled = true;
    scene.moon.direction = forward;
    scene.moon.angular_radius = 0.0045;
    const LutImage frame = test::DrawFrame(gpu, scene, {camera}, {128, 128});
    double left_sum = 0.0, right_sum = 0.0;
    for (int y = 0; y < 128; ++y) {
        for (int x = 0; x < 128; ++x) (x < 64 ? left_sum : right_sum) += Luminance(frame.at(x, y));
    }
    EXPECT_GT(right_sum, 0.0);
    EXPECT_LT(left_sum, 1e-3 * right_sum);
}

// The setting Sun through refraction (geo::RefractionTable on the ground): its disk drawn
// around the apparent elevation, squeezed vertically by the table's scale, its width kept.
// Measured on the frame: the disk's rows and columns above half the peak luminance, in a clear
// atmosphere (the air's transmittance would dim the lower limb more and move the edge).
TEST_F(AtmosphereGlTest, RefractedSunIsLiftedAndSqueezed) {
    Atmosphere clear;
    clear.rayleigh_scattering = glm::dvec3(1e-12);
    clear.mie_scattering = glm::dvec3(1e-12);
    clear.mie_absorption = glm::dvec3(0.0);
    clear.absorption_extinction = glm::dvec3(0.0);
    AtmosphereRenderer gpu(clear);
    constexpr double kDeg = 0.017453292519943295;
    Camera camera = CameraAt(2.0);  // looking along +x at the horizon
    camera.vertical_fov = 2.0 * kDeg;
    camera.aspect = 1.0;
    const geo::RefractionTable refraction(geo::RefractionAir{}, 2.0, 6360e3);
    const double geometric = 0.1 * kDeg;
    Lights lights;
    lights.sun_direction = glm::dvec3(std::cos(geometric), 0.0, std::sin(geometric));
    SkyScene scene = test::LightsOnly(lights);
    scene.sun_apparent = ApparentPlace{ApparentDirection(refraction, lights.sun_direction),
                                       refraction.VerticalScale(geometric)};
    constexpr int kSize = 512;
    const LutImage frame = test::DrawFrame(gpu, scene, {camera}, {kSize, kSize});
    double peak = 0.0;
    for (int y = 0; y < kSize; ++y) {
        for (int x = 0; x < kSize; ++x) peak = std::max(peak, Luminance(frame.at(x, y)));
    }
    int top = kSize, bottom = -1, left = kSize, right = -1;
    for (int y = 0; y < kSize; ++y) {
        for (int x = 0; x < kSize; ++x) {
            if (Luminance(frame.at(x, y)) < 0.5 * peak) continue;
            top = std::min(top, y);
            bottom = std::max(bottom, y);
            left = std::min(left, x);
            right = std::max(right, x);
        }
    }
    ASSERT_GE(bottom, top);
    const double pixel = camera.vertical_fov / kSize;  // rad, near the centre
    // Row 0 is the bottom of the frame (GL's origin): elevation of a row's centre.
    const double centre = (0.5 * (top + bottom) + 0.5 - 0.5 * kSize) * pixel;
    const double height = (bottom - top + 1) * pixel;
    const double width = (right - left + 1) * pixel;
    const double apparent = *refraction.Apparent(geometric);
    const double scale = refraction.VerticalScale(geometric);
    std::printf(
        "refracted Sun: centre %.4f deg (apparent %.4f, geometric %.4f), height / width "
        "%.3f (scale %.3f)\n",
        centre / kDeg, apparent / kDeg, geometric / kDeg, height / width, scale);
    EXPECT_GT(apparent - geometric, 0.4 * kDeg);  // ~0.45 deg on the horizon
    EXPECT_NEAR(centre, apparent, 0.5 * pixel);
    EXPECT_NEAR(height / width, scale, 0.02);
    EXPECT_LT(scale, 0.9);
}

TEST_F(AtmosphereGlTest, MobileSettingsRenderTheSameSky) {
    // Hillaire 2020 Table 2's iPhone column (Sky-View 96x50 with 8 steps, aerial perspective
    // 32x32x16 with 8 steps) against the PC column, on the same frames: "visual differences ...
    // are not noticeable" (§7). Measured as relative RMSE of luminance: 3.8 % on the ground (the
    // 50-texel-high Sky-View LUT is coarser at the horizon), 0.8 % at 10 km; the bound, 5 %, is
    // about 0.07 EV, below what an exposure change shows.
    AtmosphereRenderer pc(Atmosphere{});
    AtmosphereRenderer mobile(Atmosphere{}, LutSettings::Mobile());
    const Lights lights = MorningLights();
    for (double altitude : {2.0, 10000.0}) {
        const Camera camera = CameraAt(altitude);
        const SkyScene scene = test::LightsOnly(lights, false);
        const double rmse = RelativeRmse(test::DrawFrame(mobile, scene, {camera}, {160, 90}),
                                         test::DrawFrame(pc, scene, {camera}, {160, 90}));
        std::printf("mobile vs PC settings at %.0f m: relative RMSE %.4f\n", altitude, rmse);
        EXPECT_LT(rmse, 0.05) << altitude;
    }
}

TEST_F(AtmosphereGlTest, LutMemoryIsAsDocumented) {
    const AtmosphereRenderer gpu(Atmosphere{});
    // RGBA32F: 16 bytes per texel; 256x64 + (3 tiles of 128x32) + 256x1 + 200x100 + 32^3.
    EXPECT_EQ(Inspect(gpu).LutMemoryBytes(),
              16u * (256 * 64 + 3 * 128 * 32 + 256 + 200 * 100 + 32 * 32 * 32));
}

}  // namespace
}  // namespace zenith::sky
