// The night sky in rendered frames: a moonless dark-site zenith in mag/arcsec^2, the composite
// against its CPU twin (NightSkyLuminance over the renderer's own transmittance LUT), stars
// across the visibility threshold, and a daytime frame the night sky does not change.
#include <gtest/gtest.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <string>

#include "gl_test_support.h"
#include "luminance.h"
#include "night_sky_map.h"
#include "reference/atmosphere_functions.h"
#include "reference/lut_texture.h"
#include "shader_parameters.h"
#include "zenith/geo/ephemeris.h"
#include "zenith/sky/atmosphere_renderer.h"
#include "zenith/sky/inspection.h"
#include "zenith/sky/night_sky.h"
#include "zenith/sky/sky_state.h"

namespace zenith::sky {
namespace {

using zenith::test::Luminance;

class NightSkyGlTest : public gl::test::HeadlessGlTest {};

// Roque de los Muchachos, La Palma (2396 m), 2024-04-08 01:00 UTC (or `utc`): new Moon (below
// the horizon), the Sun 56 deg down, the zenith 2 deg from the north galactic pole.
SkyState DarkSite(double pitch_deg, const Atmosphere& atmosphere, glm::ivec2 size,
                  const char* utc = "2024-04-08T01:00:00Z") {
    const geo::Observer observer(28.7606, -17.8816, 2396.0);
    const geo::SkyEphemeris e = geo::Ephemeris().Compute(geo::TimeFromIso8601(utc), observer);
    EXPECT_LT(e.sun.topocentric.horizontal.elevation, -18.0 * M_PI / 180.0);
    EXPECT_LT(e.moon.topocentric.horizontal.elevation, 0.0);
    const geo::Attitude attitude{0.0, pitch_deg * M_PI / 180.0, 0.0};
    return MakeSkyState(e, observer, atmosphere, attitude, 2.0 * M_PI / 180.0,
                        static_cast<double>(size.x) / size.y);
}

struct Frames {
    LutImage with, without;
};

LutImage Draw(AtmosphereRenderer& renderer, const SkyScene& scene, const SkyView& view,
              glm::ivec2 size) {
    renderer.Update(scene, view);
    renderer.Render(RenderTarget::Offscreen(size));
    return Inspect(renderer).ReadFrame();
}

// The frame with `scene`'s night sky and without it.
Frames Render(AtmosphereRenderer& renderer, SkyScene scene, const SkyView& view, glm::ivec2 size) {
    Frames f;
    f.with = Draw(renderer, scene, view, size);
    scene.night_sky.enabled = false;
    f.without = Draw(renderer, scene, view, size);
    return f;
}

TEST_F(NightSkyGlTest, DarkSiteZenithIsTwentyTwoMagnitudes) {
    const Atmosphere atmosphere;
    AtmosphereRenderer renderer(atmosphere);
    const glm::ivec2 size(16, 16);
    const SkyState state = DarkSite(90.0, atmosphere, size);
    SkyScene scene = state.scene;
    scene.night_sky.starlight = std::make_shared<const StarlightMap>(StarlightMap::ModelOnly());
    const Frames f = Render(renderer, scene, state.view, size);
    const glm::vec4 centre = f.with.at(size.x / 2, size.y / 2);
    const double mag = SurfaceBrightnessFromLuminance(Luminance(centre));
    // The CPU twin at the same direction, over the renderer's transmittance LUT.
    const glm::dvec3 direction = state.view.camera.Direction(1.0 / size.x, 1.0 / size.y);
    const glm::dvec3 camera_km = state.view.camera.position / 1000.0;
    const glm::dvec3 twin = NightSkyLuminance(
        scene.night_sky, atmosphere, ref::FromImage(Inspect(renderer).ReadTransmittance()),
        camera_km, glm::length(camera_km) - atmosphere.bottom_radius / 1000.0, direction);
    const double scattered = Luminance(f.without.at(size.x / 2, size.y / 2));
    const NightSkyComponents c = NightSkySources(scene.night_sky, atmosphere.bottom_radius,
                                                 state.view.camera.position, direction);
    std::printf(
        "dark-site zenith: %.3f V mag/arcsec^2 (%.3g cd/m^2; airglow %.2f, zodiacal %.2f, "
        "starlight %.2f mag/arcsec^2 above the air); CPU twin %.3g, sky without it %.3g\n",
        mag, Luminance(centre), SurfaceBrightnessFromLuminance(Luminance(c.airglow)),
        SurfaceBrightnessFromLuminance(Luminance(c.zodiacal)),
        SurfaceBrightnessFromLuminance(Luminance(c.starlight)), Luminance(twin), scattered);
    EXPECT_GT(mag, 21.5);
    EXPECT_LT(mag, 22.0);
    EXPECT_NEAR((Luminance(centre) - scattered) / Luminance(twin), 1.0, 0.01);
    EXPECT_LT(scattered, 1e-3 * Luminance(centre));  // the Sun's and the Moon's light is gone
}

TEST_F(NightSkyGlTest, HorizonAgainstCpuTwin) {
    // 5 deg above the horizon: van Rhijn's brightening through the air's extinction, and light
    // pollution's glow, against the CPU twin (the map's interpolation is the difference).
    const Atmosphere atmosphere;
    AtmosphereRenderer renderer(atmosphere);
    const glm::ivec2 size(16, 16);
    const SkyState state = DarkSite(5.0, atmosphere, size);
    const ref::TransmittanceTexture transmittance =
        ref::FromImage(Inspect(renderer).ReadTransmittance());
    const glm::dvec3 camera_km = state.view.camera.position / 1000.0;
    const double altitude = glm::length(camera_km) - atmosphere.bottom_radius / 1000.0;
    const glm::dvec3 direction = state.view.camera.Direction(1.0 / size.x, 1.0 / size.y);
    const glm::dvec3 zenith = glm::normalize(state.view.camera.position);
    for (bool polluted : {false, true}) {
        SkyScene scene = state.scene;
        if (polluted) scene.night_sky.settings.artificial_zenith_brightness = 20.0;
        const Frames f = Render(renderer, scene, state.view, size);
        const double rendered = Luminance(f.with.at(size.x / 2, size.y / 2)) -
                                Luminance(f.without.at(size.x / 2, size.y / 2));
        const double twin = Luminance(NightSkyLuminance(scene.night_sky, atmosphere, transmittance,
                                                        camera_km, altitude, direction));
        const double at_zenith = Luminance(NightSkyLuminance(
            scene.night_sky, atmosphere, transmittance, camera_km, altitude, zenith));
        std::printf("%s: 5 deg elevation %.3f mag/arcsec^2 (CPU twin %.3f), %.2fx the zenith\n",
                    polluted ? "light pollution 20 mag/arcsec^2" : "dark site",
                    SurfaceBrightnessFromLuminance(rendered), SurfaceBrightnessFromLuminance(twin),
                    twin / at_zenith);
        EXPECT_NEAR(rendered / twin, 1.0, 0.02);
        EXPECT_GT(twin / at_zenith, 1.3);  // brighter toward the horizon
    }
}

// The ground under a moonless sky is lit by it: looking 20 deg down from the dark site, the
// ground's light (the frame with the night sky less the frame without) is albedo E / pi of the
// night sky's illuminance the renderer reports (NightGroundIrradiance), dimmed by the ~7 km of
// air to it; before, the ground was black.
TEST_F(NightSkyGlTest, TheGroundIsLitByTheNightSky) {
    const Atmosphere atmosphere;
    AtmosphereRenderer renderer(atmosphere);
    const glm::ivec2 size(16, 16);
    const SkyState state = DarkSite(-20.0, atmosphere, size);
    SkyScene scene = state.scene;
    scene.night_sky.starlight = std::make_shared<const StarlightMap>(StarlightMap::ModelOnly());
    const Frames f = Render(renderer, scene, state.view, size);
    renderer.Update(scene, state.view);
    const glm::dvec3 e = renderer.NightGroundIrradiance();
    const double lit = Luminance(f.with.at(size.x / 2, size.y / 2)) -
                       Luminance(f.without.at(size.x / 2, size.y / 2));
    const double lambert = Luminance(atmosphere.ground_albedo * e) / M_PI;
    std::printf("moonless ground: %.3g cd/m^2 (albedo E / pi = %.3g, E = %.3g lux)\n", lit, lambert,
                Luminance(e));
    EXPECT_GT(Luminance(e), 2.5e-4);
    EXPECT_GT(lit / lambert, 0.7);
    EXPECT_LT(lit / lambert, 1.0);
}

// The night sky's map is filled on the CPU only when the sky, the Sun or the camera has turned
// or moved enough to show: half a second later (the sky turned 0.002 deg) the kept map draws
// what a new one would to 1e-4; two minutes later (0.5 deg) it has been filled again, and the
// frame is a new renderer's.
TEST_F(NightSkyGlTest, TheMapIsKeptWhileTheSkyHardlyTurns) {
    const Atmosphere atmosphere;
    const glm::ivec2 size(32, 16);
    const auto starlight = std::make_shared<const StarlightMap>(StarlightMap::ModelOnly());
    AtmosphereRenderer kept(atmosphere);
    SkyState first = DarkSite(20.0, atmosphere, size);
    first.scene.night_sky.starlight = starlight;
    Draw(kept, first.scene, first.view, size);
    for (const double seconds : {0.5, 120.0}) {
        const std::string utc = seconds < 1.0 ? "2024-04-08T01:00:00.5Z" : "2024-04-08T01:02:00Z";
        SkyState later = DarkSite(20.0, atmosphere, size, utc.c_str());
        later.scene.night_sky.starlight = starlight;  // the same map
        const LutImage reused = Draw(kept, later.scene, later.view, size);
        AtmosphereRenderer fresh(atmosphere);
        const LutImage filled = Draw(fresh, later.scene, later.view, size);
        double largest = 0.0;
        for (std::size_t i = 0; i < filled.texels.size(); ++i) {
            const double y = Luminance(filled.texels[i]);
            largest = std::max(largest, std::abs(Luminance(reused.texels[i]) - y) / y);
        }
        std::printf("%.1f s later: the kept map's frame within %.2g of a new renderer's\n", seconds,
                    largest);
        if (seconds < 1.0) {
            EXPECT_LT(largest, 1e-4);
        } else {
            EXPECT_EQ(largest, 0.0);
        }
    }
}

TEST_F(NightSkyGlTest, StarsAppearAcrossTheThreshold) {
    const Atmosphere atmosphere;
    AtmosphereRenderer renderer(atmosphere);
    const glm::ivec2 size(32, 32);
    const SkyState state = DarkSite(90.0, atmosphere, size);
    SkyScene scene = state.scene;
    scene.stars.clear();
    const LutImage sky = Draw(renderer, scene, state.view, size);
    // Three stars at pixel centres: 0.9x, 1.58x (half a magnitude) and 3x the threshold of the
    // sky behind them, with the atmosphere's extinction undone so the pixel gets that much.
    const glm::ivec2 pixels[3] = {{8, 16}, {16, 16}, {24, 16}};
    const double factors[3] = {0.9, std::pow(10.0, 0.2), 3.0};
    const ref::TransmittanceTexture transmittance =
        ref::FromImage(Inspect(renderer).ReadTransmittance());
    const glm::dvec3 camera_km = state.view.camera.position / 1000.0;
    const double altitude = glm::length(camera_km) - atmosphere.bottom_radius / 1000.0;
    const double tan_y = std::tan(0.5 * state.view.camera.vertical_fov);
    const double tan_x = tan_y * state.view.camera.aspect;
    double expected_share[3] = {0.0, 0.5, 1.0};
    double star_lux[3] = {};
    for (int i = 0; i < 3; ++i) {
        const glm::dvec2 ndc = 2.0 * (glm::dvec2(pixels[i]) + 0.5) / glm::dvec2(size) - 1.0;
        const glm::dvec3 direction = state.view.camera.Direction(ndc.x, ndc.y);
        const double t = Luminance(
            ref::TransmittanceToSpace(MakeShaderParameters<ref::AtmosphereParameters>(atmosphere),
                                      transmittance, camera_km, altitude, direction));
        const double background = Luminance(sky.at(pixels[i].x, pixels[i].y));
        star_lux[i] = factors[i] * StarThresholdIlluminance(background);
        scene.stars.push_back({direction, glm::dvec3(star_lux[i] / t)});
    }
    const LutImage frame = Draw(renderer, scene, state.view, size);
    const double dx = 2.0 * tan_x / size.x, dy = 2.0 * tan_y / size.y;
    for (int i = 0; i < 3; ++i) {
        const glm::dvec2 t((pixels[i].x + 0.5) / size.x * 2.0 - 1.0,
                           (pixels[i].y + 0.5) / size.y * 2.0 - 1.0);
        const double solid_angle =
            dx * dy / std::pow(1.0 + std::pow(t.x * tan_x, 2) + std::pow(t.y * tan_y, 2), 1.5);
        const double seen = (Luminance(frame.at(pixels[i].x, pixels[i].y)) -
                             Luminance(sky.at(pixels[i].x, pixels[i].y))) *
                            solid_angle / star_lux[i];
        std::printf("star at %.2fx the threshold: %.3f of it seen\n", factors[i], seen);
        EXPECT_NEAR(seen, expected_share[i], 0.01);
    }
}

TEST_F(NightSkyGlTest, DaytimeFrameIsUnchanged) {
    // Noon over La Palma: the night sky's 2e-4 cd/m^2 against a 3000+ cd/m^2 sky.
    const Atmosphere atmosphere;
    AtmosphereRenderer renderer(atmosphere);
    const glm::ivec2 size(64, 36);
    const geo::Observer observer(28.7606, -17.8816, 2396.0);
    const geo::SkyEphemeris e =
        geo::Ephemeris().Compute(geo::TimeFromIso8601("2024-04-08T13:00:00Z"), observer);
    const SkyState state = MakeSkyState(e, observer, atmosphere, {0.0, 0.3, 0.0}, 1.0, 16.0 / 9.0);
    SkyScene scene = state.scene;
    scene.night_sky.starlight = std::make_shared<const StarlightMap>(StarlightMap::ModelOnly());
    const Frames f = Render(renderer, scene, state.view, size);
    double worst = 0.0;
    for (std::size_t i = 0; i < f.with.texels.size(); ++i) {
        const double a = Luminance(f.with.texels[i]), b = Luminance(f.without.texels[i]);
        worst = std::max(worst, std::abs(a - b) / b);
    }
    std::printf("daytime frame with / without the night sky: largest relative change %.2g\n",
                worst);
    // Not bit-identical: adding it rounds some channels of some pixels by an ulp or two.
    EXPECT_LT(worst, 4.0 * FLT_EPSILON);
}

}  // namespace
}  // namespace zenith::sky
