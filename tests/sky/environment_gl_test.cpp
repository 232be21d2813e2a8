// The environment cube map and its spherical harmonics (zenith/sky/environment.h) on the GPU:
// the faces' orientation against frames the renderer draws along the same directions, the GPU's
// projection against the CPU's of the same atlas, the rounds and the read-back that never
// waits, and the irradiance they give against what the renderer's other passes work out for a
// horizontal surface: the ground-irradiance LUT in a clear sky and the clouds' sky shade under
// an overcast deck.
#include <glad/gl.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>

#include "draw_frame.h"
#include "gl_test_support.h"
#include "luminance.h"
#include "zenith/base/error.h"
#include "zenith/sky/atmosphere_renderer.h"
#include "zenith/sky/clouds/weather.h"
#include "zenith/sky/environment.h"
#include "zenith/sky/inspection.h"
#include "zenith/sky/lighting.h"

namespace zenith::sky {
namespace {

using zenith::test::Luminance;

class EnvironmentGlTest : public gl::test::HeadlessGlTest {};

constexpr double kPi = 3.14159265358979323846;

// The Sun 8 deg up, 30 deg east of north: a sky that is different in every direction.
Lights LowSun() {
    Lights lights;
    const double el = 8.0 * kPi / 180.0, az = 30.0 * kPi / 180.0;
    lights.sun_direction =
        glm::dvec3(std::sin(az) * std::cos(el), std::cos(az) * std::cos(el), std::sin(el));
    return lights;
}

Lights HighSun() {
    Lights lights;
    lights.sun_direction = glm::normalize(glm::dvec3(0.3, 0.4, 0.8));
    return lights;
}

// A camera at `altitude` m looking along `forward` (world frame, x east, y north, z up).
Camera Looking(const glm::dvec3& forward, double altitude, double fov = 0.01) {
    Camera camera;
    camera.position = glm::dvec3(0.0, 0.0, 6360e3 + altitude);
    const glm::dvec3 f = glm::normalize(forward);
    const glm::dvec3 helper = std::abs(f.z) > 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(0, 0, 1);
    const glm::dvec3 right = glm::normalize(glm::cross(f, helper));
    camera.world_from_view = glm::dmat3(right, glm::cross(right, f), -f);
    camera.vertical_fov = fov;
    camera.aspect = 1.0;
    return camera;
}

EnvironmentSettings Environment(int size, int faces_per_frame = 6) {
    EnvironmentSettings s;
    s.size = size;
    s.faces_per_frame = faces_per_frame;
    return s;
}

// Update until a round is done and its harmonics have come back (glFinish: the fence is then
// signalled).
SphericalHarmonics9 RoundSh(AtmosphereRenderer& renderer, const SkyScene& scene,
                            const Camera& camera) {
    const long long rounds = renderer.environment_rounds();
    while (renderer.environment_rounds() == rounds) renderer.Update(scene, {camera});
    glFinish();
    const std::optional<SphericalHarmonics9> sh = renderer.LatestEnvironmentSh();
    EXPECT_TRUE(sh.has_value());
    return sh.value_or(SphericalHarmonics9{});
}

double Mean(const glm::dvec3& v) { return (v.r + v.g + v.b) / 3.0; }

// The integral of L(d) weight(d) dOmega over the atlas' texels, each at its centre's direction.
glm::dvec3 AtlasIntegral(const LutImage& atlas,
                         const std::function<double(const glm::dvec3&)>& weight) {
    const int n = atlas.size.x;
    glm::dvec3 sum(0.0);
    for (int face = 0; face < 6; ++face) {
        for (int y = 0; y < n; ++y) {
            for (int x = 0; x < n; ++x) {
                const glm::dvec3 d = CubeFaceDirection(face, (x + 0.5) / n, (y + 0.5) / n);
                sum += glm::dvec3(glm::vec3(atlas.at(x, face * n + y))) * weight(d) *
                       CubeTexelSolidAngle(x, y, n);
            }
        }
    }
    return sum;
}

// The irradiance on a surface of unit normal `normal`: the integral L(d) max(d.n, 0) dOmega
// that the harmonics approximate.
glm::dvec3 AtlasIrradiance(const LutImage& atlas, const glm::dvec3& normal) {
    return AtlasIntegral(atlas,
                         [&](const glm::dvec3& d) { return std::max(glm::dot(d, normal), 0.0); });
}

// Each face's texels lie where OpenGL's cube map convention puts them: a texel off the face's
// centre and off its diagonals (so a flipped or transposed face would be elsewhere) holds what
// a frame of the renderer shows along that texel's direction. The cube's level 0 is the atlas.
TEST_F(EnvironmentGlTest, FacesAreWhereOpenGlSamplesThem) {
    const Atmosphere earth;
    AtmosphereRenderer renderer(earth);
    constexpr int kSize = 32;
    renderer.SetEnvironment(Environment(kSize));
    const SkyScene scene = test::LightsOnly(LowSun(), false);
    renderer.Update(scene, {Looking({0, 1, 0}, 300.0)});
    const LutImage atlas = Inspect(renderer).ReadEnvironmentAtlas();
    const LutImage cube = Inspect(renderer).ReadEnvironmentCube();
    ASSERT_EQ(atlas.texels.size(), cube.texels.size());
    for (std::size_t i = 0; i < atlas.texels.size(); ++i)
        ASSERT_EQ(atlas.texels[i], cube.texels[i]);

    constexpr int kX = 7, kY = 20;
    for (int face = 0; face < 6; ++face) {
        const glm::dvec3 d = CubeFaceDirection(face, (kX + 0.5) / kSize, (kY + 0.5) / kSize);
        const LutImage frame = test::DrawFrame(renderer, scene, {Looking(d, 300.0)}, {2, 2});
        double seen = 0.0;
        for (const glm::vec4& t : frame.texels) seen += Luminance(t) / 4.0;
        const double texel = Luminance(atlas.at(kX, face * kSize + kY));
        // The same direction mirrored in either of the face's axes, for scale: what a flipped
        // face would show.
        const double flipped_s = Luminance(atlas.at(kSize - 1 - kX, face * kSize + kY));
        const double flipped_t = Luminance(atlas.at(kX, face * kSize + kSize - 1 - kY));
        std::printf("face %d: texel %.1f cd/m^2, frame %.1f (%+.3f %%), flipped %.1f / %.1f\n",
                    face, texel, seen, 100.0 * (texel / seen - 1.0), flipped_s, flipped_t);
        EXPECT_NEAR(texel / seen, 1.0, 0.003) << "face " << face;
        // Below (face 5, -z) the ground is the same in every direction: nothing to tell there.
        if (face != 5) {
            EXPECT_GT(std::abs(flipped_s / seen - 1.0) + std::abs(flipped_t / seen - 1.0), 0.03)
                << "face " << face << ": the test could not tell a flipped face";
        }
    }
}

// The GPU's projection (environment_sh.comp, float) is the CPU's (ProjectToSh, double) of the
// atlas it read.
TEST_F(EnvironmentGlTest, GpuProjectionIsTheCpuOne) {
    const Atmosphere earth;
    AtmosphereRenderer renderer(earth);
    renderer.SetEnvironment(Environment(48));
    const SkyScene scene = test::LightsOnly(LowSun(), false);
    const SphericalHarmonics9 gpu = RoundSh(renderer, scene, Looking({0, 1, 0}, 1000.0));
    const SphericalHarmonics9 cpu = ProjectToSh(Inspect(renderer).ReadEnvironmentAtlas());
    const double scale = Mean(cpu.coefficients[0]);
    double worst = 0.0;
    for (std::size_t i = 0; i < 9; ++i) {
        for (int c = 0; c < 3; ++c) {
            worst = std::max(worst, std::abs(gpu.coefficients[i][c] - cpu.coefficients[i][c]));
        }
    }
    std::printf("L00 %.1f cd/m^2 sr; largest GPU - CPU difference %.2e of it\n", scale,
                worst / scale);
    EXPECT_LT(worst / scale, 1e-5);
}

// One face a frame: no harmonics until the sixth face is drawn, then the round's (read back
// behind a fence: LatestEnvironmentSh never waits, and after glFinish it has them).
TEST_F(EnvironmentGlTest, RoundsOfFacesAndAReadBackThatNeverWaits) {
    const Atmosphere earth;
    AtmosphereRenderer renderer(earth);
    EXPECT_EQ(renderer.environment_texture(), 0u);
    EXPECT_FALSE(renderer.LatestEnvironmentSh().has_value());
    renderer.SetEnvironment(Environment(16, 1));
    EXPECT_NE(renderer.environment_texture(), 0u);
    EXPECT_NE(renderer.environment_sh_buffer(), 0u);
    const SkyScene scene = test::LightsOnly(HighSun(), false);
    const Camera camera = Looking({0, 1, 0}, 500.0);
    for (int frame = 0; frame < 5; ++frame) {
        renderer.Update(scene, {camera});
        EXPECT_EQ(renderer.environment_rounds(), 0);
    }
    glFinish();
    EXPECT_FALSE(renderer.LatestEnvironmentSh().has_value());
    renderer.Update(scene, {camera});
    EXPECT_EQ(renderer.environment_rounds(), 1);
    glFinish();
    ASSERT_TRUE(renderer.LatestEnvironmentSh().has_value());
    EXPECT_GT(Mean(renderer.LatestEnvironmentSh()->coefficients[0]), 0.0);
    // The mip chain reaches one texel per face: the face's mean (a box filter).
    const LutImage top = Inspect(renderer).ReadEnvironmentCube(4);
    EXPECT_EQ(top.size, glm::ivec3(1, 6, 1));

    EXPECT_THROW(renderer.SetEnvironment(Environment(2000)), ArgumentError);
    EXPECT_EQ(renderer.environment_settings().size, 16);  // kept
    renderer.SetEnvironment(EnvironmentSettings{});
    EXPECT_EQ(renderer.environment_texture(), 0u);
    EXPECT_THROW(Inspect(renderer).ReadEnvironmentAtlas(), std::logic_error);
}

// A clear sky: the cube's irradiance on a horizontal surface at the ground (its texels' sum)
// against the ground-irradiance LUT, which integrates the sky over the hemisphere in its own pass
// (irradiance.comp: its own directions, its own march); and the harmonics' irradiance against
// the cube's on the ground, walls and facing down (what L2 leaves out).
TEST_F(EnvironmentGlTest, ClearSkyIrradianceMatchesTheGroundIrradianceLut) {
    const Atmosphere earth;
    AtmosphereRenderer renderer(earth);
    renderer.SetEnvironment(Environment(64));
    for (const Lights& lights : {HighSun(), LowSun()}) {
        const SkyScene scene = test::LightsOnly(lights, false);
        const SphericalHarmonics9 sh = RoundSh(renderer, scene, Looking({0, 1, 0}, 1.0));
        const LutImage atlas = Inspect(renderer).ReadEnvironmentAtlas();
        const glm::dvec3 exact = AtlasIrradiance(atlas, {0, 0, 1});
        const glm::dvec3 lut = lights.sun_illuminance *
                               SampleGroundIrradiance(Inspect(renderer).ReadGroundIrradiance(),
                                                      lights.sun_direction.z);
        const glm::dvec3 harmonics = ShIrradiance(sh, {0, 0, 1});
        std::printf(
            "sun %.0f deg up: E_sh %.0f lux, cube's own sum %.0f, ground-irradiance LUT "
            "%.0f lux (%+.2f %%, %+.2f %%)\n",
            std::asin(lights.sun_direction.z) * 180.0 / kPi, Mean(harmonics), Mean(exact),
            Mean(lut), 100.0 * (Mean(harmonics) / Mean(lut) - 1.0),
            100.0 * (Mean(exact) / Mean(lut) - 1.0));
        for (int c = 0; c < 3; ++c) {
            // Measured: +0.6 % in luminance with the Sun 58 deg up, +1.3 % (red +3.8 %) 8 deg up,
            // where the LUT's 8 x 8 directions and the Sky-View LUT's texels meet the aureole.
            EXPECT_NEAR(exact[c] / lut[c], 1.0, 0.05) << "channel " << c;
            // L2's truncation of a sky with a bright horizon and aureole (measured: +4 % to +6 %
            // in luminance, +11 % in red with the Sun 8 deg up): the cosine's l = 4 part.
            EXPECT_NEAR(harmonics[c] / exact[c], 1.0, 0.12) << "channel " << c;
        }
        EXPECT_NEAR(Mean(harmonics) / Mean(exact), 1.0, 0.07);
        EXPECT_NEAR(Mean(exact) / Mean(lut), 1.0, 0.02);
        // Walls and the ground's light from below (brighter than the sky's at a high Sun).
        const glm::dvec3 toward =
            glm::normalize(glm::dvec3(lights.sun_direction.x, lights.sun_direction.y, 0.0));
        for (const glm::dvec3& n : {toward, -toward, glm::dvec3(0, 0, -1)}) {
            const double e = Mean(AtlasIrradiance(atlas, n));
            std::printf(
                "  normal (%.2f, %.2f, %.2f): E_sh %.0f lux, the cube's own %.0f "
                "(%+.2f %%)\n",
                n.x, n.y, n.z, Mean(ShIrradiance(sh, n)), e,
                100.0 * (Mean(ShIrradiance(sh, n)) / e - 1.0));
            EXPECT_NEAR(Mean(ShIrradiance(sh, n)) / e, 1.0, 0.07);
        }
    }
}

// Under an overcast deck the harmonics carry the clouds' light: the irradiance on a horizontal
// surface is the cube's own (the clouds traced along each texel) and far above the clear sky's,
// and the cube sees the clouds the sky shade sees (sky_shade.comp: its own directions from the
// ground below the camera): its mean luminance over the upper hemisphere is the shade's
// CloudShade::luminance (the deck is dark enough that its transmittance of the clear sky, 0.6 %,
// does not count).
TEST_F(EnvironmentGlTest, OvercastIrradianceCarriesTheClouds) {
    const Atmosphere earth;
    AtmosphereRenderer renderer(earth);
    CloudSettings settings;
    settings.noise_cache_directory = std::filesystem::path(ZENITH_BINARY_DIR) / "cloud-noise-cache";
    settings.shadow_map_size = 64;
    renderer.SetWeather(clouds::LoadWeather("overcast_stratus"), settings);
    constexpr int kSize = 32;
    renderer.SetEnvironment(Environment(kSize));
    const Lights lights = HighSun();
    SkyScene scene = test::LightsOnly(lights, false);
    scene.clouds.reset_history = true;
    const SphericalHarmonics9 sh = RoundSh(renderer, scene, Looking({0, 1, 0}, 100.0));
    const std::optional<CloudShade> shade = renderer.LatestCloudShade();
    ASSERT_TRUE(shade.has_value());
    const LutImage atlas = Inspect(renderer).ReadEnvironmentAtlas();
    // The upper hemisphere's mean: its texels (the horizon runs along texel edges) cover 2 pi.
    const glm::dvec3 upper =
        AtlasIntegral(atlas, [](const glm::dvec3& d) { return d.z > 0.0 ? 1.0 : 0.0; }) /
        (2.0 * kPi);
    const glm::dvec3 clear =
        lights.sun_illuminance *
        SampleGroundIrradiance(Inspect(renderer).ReadGroundIrradiance(), lights.sun_direction.z);
    const glm::dvec3 harmonics = ShIrradiance(sh, {0, 0, 1});
    const glm::dvec3 exact = AtlasIrradiance(atlas, {0, 0, 1});
    std::printf(
        "overcast: E_sh %.0f lux, the cube's own %.0f (%+.2f %%), clear sky %.0f lux; "
        "mean luminance overhead: cube %.0f cd/m^2, sky shade %.0f (%+.2f %%), "
        "transmittance %.4f\n",
        Mean(harmonics), Mean(exact), 100.0 * (Mean(harmonics) / Mean(exact) - 1.0), Mean(clear),
        Mean(upper), Mean(shade->luminance), 100.0 * (Mean(upper) / Mean(shade->luminance) - 1.0),
        shade->sky_transmittance);
    EXPECT_NEAR(Mean(harmonics) / Mean(exact), 1.0, 0.01);
    EXPECT_GT(Mean(harmonics), 3.0 * Mean(clear));
    EXPECT_LT(shade->sky_transmittance, 0.02);
    EXPECT_NEAR(Mean(upper) / Mean(shade->luminance), 1.0, 0.03);
}

}  // namespace
}  // namespace zenith::sky
