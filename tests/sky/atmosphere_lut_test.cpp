// The renderer's atmosphere functions (functions.glsl compiled as C++) against closed forms and
// against themselves at higher resolution: what the LUTs must get right before any GPU is involved.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "luminance.h"
#include "reference/atmosphere_functions.h"
#include "reference/lut_texture.h"
#include "shader_parameters.h"
#include "zenith/sky/lighting.h"
#include "zenith/sky/reference/atmosphere_reference.h"
#include "zenith/sky/sky_state.h"

namespace zenith::sky {
namespace {

using zenith::test::Luminance;

using reference::AtmosphereReference;

ref::AtmosphereParameters EarthKm() {
    return MakeShaderParameters<ref::AtmosphereParameters>(Atmosphere{});
}

TEST(AtmosphereFunctions, PhaseFunctionsIntegrateToOne) {
    // Integral over the sphere = 2 pi * integral over nu in [-1, 1]; Simpson with 20000 intervals.
    auto integrate = [](auto phase) {
        const int n = 20000;
        double sum = 0.0;
        for (int i = 0; i <= n; ++i) {
            const double nu = -1.0 + 2.0 * i / n;
            const double w = (i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0);
            sum += w * phase(nu);
        }
        return 2.0 * ref::kPi * sum * (2.0 / n) / 3.0;
    };
    EXPECT_NEAR(integrate([](double nu) { return ref::RayleighPhase(nu); }), 1.0, 1e-9);
    EXPECT_NEAR(integrate([](double) { return ref::IsotropicPhase(); }), 1.0, 1e-12);
    for (double g : {-0.5, 0.0, 0.3, 0.76, 0.8}) {
        EXPECT_NEAR(integrate([g](double nu) { return ref::CornetteShanksPhase(g, nu); }), 1.0,
                    1e-6)
            << "g = " << g;
    }
}

TEST(AtmosphereFunctions, VerticalTransmittanceEqualsClosedForm) {
    // Optical depth of a vertical column from altitude h0 to the top (Hillaire 2020 §4 profiles):
    // sigma * H * (exp(-h0/H) - exp(-h_top/H)) for each exponential layer, plus sigma times the
    // part of the tent's area above h0.
    const ref::AtmosphereParameters a = EarthKm();
    const double h_top = a.top_radius - a.bottom_radius;
    auto tent_area_above = [&](double h0) {
        const double c = a.absorption_center, w = a.absorption_half_width;
        auto cumulative = [&](double h) {  // area of the tent below h
            if (h <= c - w) return 0.0;
            if (h >= c + w) return w;
            if (h <= c) return 0.5 * (h - (c - w)) * (h - (c - w)) / w;
            return w - 0.5 * (c + w - h) * (c + w - h) / w;
        };
        return cumulative(h_top) - cumulative(h0);
    };
    // h0 = 0, 25, 40, 60: the tent's kinks (10 and 40 km) fall on segment ends or outside the
    // column, so the 40-segment result is exact; for h0 = 1 and 10 a kink falls inside a segment
    // and the trapezoid's error on the tent is below 1e-5 of the ozone depth there.
    for (double h0 : {0.0, 1.0, 10.0, 25.0, 40.0, 60.0}) {
        const bool kinks_aligned = h0 == 0.0 || h0 == 25.0 || h0 == 40.0 || h0 == 60.0;
        const ref::vec3 depth =
            a.rayleigh_scattering * a.rayleigh_scale_height *
                (std::exp(-h0 / a.rayleigh_scale_height) -
                 std::exp(-h_top / a.rayleigh_scale_height)) +
            a.mie_extinction * a.mie_scale_height *
                (std::exp(-h0 / a.mie_scale_height) - std::exp(-h_top / a.mie_scale_height)) +
            a.absorption_extinction * tent_area_above(h0);
        const ref::vec3 expected = ref::exp(-depth);
        const ref::vec3 computed =
            ref::ComputeTransmittanceToTopAtmosphereBoundary(a, a.bottom_radius + h0, 1.0, 40);
        const double tolerance = kinks_aligned ? 1e-9 : 1e-4;
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(computed[c], expected[c], tolerance * expected[c])
                << "h0 " << h0 << " ch " << c;
        }
    }
}

TEST(AtmosphereFunctions, TransmittanceUvRoundTrips) {
    const ref::AtmosphereParameters a = EarthKm();
    const ref::ivec2 size(256, 64);
    for (double h : {0.0, 0.5, 3.0, 20.0, 99.9}) {
        for (double mu : {-1.0, -0.3, -0.05, 0.0, 0.01, 0.2, 0.9, 1.0}) {
            const double r = a.bottom_radius + h;
            if (ref::RayIntersectsGround(a, r, mu)) continue;  // not in the LUT's domain
            const ref::vec2 uv = ref::GetTransmittanceTextureUvFromRMu(a, r, mu, size);
            double r2, mu2;
            ref::GetRMuFromTransmittanceTextureUv(a, uv, size, r2, mu2);
            EXPECT_NEAR(r2, r, 1e-9) << h << " " << mu;
            EXPECT_NEAR(mu2, mu, 1e-9) << h << " " << mu;
        }
    }
}

TEST(AtmosphereFunctions, SkyViewUvRoundTripsWithTheHorizonInTheMiddle) {
    const ref::AtmosphereParameters a = EarthKm();
    const ref::ivec2 size(200, 100);
    for (double h : {0.001, 1.0, 10.0, 80.0}) {
        const double horizon = ref::HorizonZenithAngle(a, h);
        // The dip of the horizon, acos(R / (R + h)).
        EXPECT_NEAR(horizon - 0.5 * ref::kPi, std::acos(a.bottom_radius / (a.bottom_radius + h)),
                    1e-9);
        EXPECT_NEAR(ref::GetSkyViewTextureUv(a, h, horizon, 0.0, size).y, 0.5, 1e-12);
        EXPECT_GT(ref::GetSkyViewTextureUv(a, h, 0.0, 0.0, size).y, 0.99);  // zenith at the top
        for (double zenith : {0.01, 0.5, 1.5, horizon - 1e-3, horizon + 1e-3, 2.5, 3.1}) {
            for (double azimuth : {0.1, 1.0, 3.0, 6.0}) {
                const ref::vec2 uv = ref::GetSkyViewTextureUv(a, h, zenith, azimuth, size);
                double z2, az2;
                ref::GetViewFromSkyViewTextureUv(a, h, uv, size, z2, az2);
                EXPECT_NEAR(z2, zenith, 1e-9);
                EXPECT_NEAR(az2, azimuth, 1e-9);
            }
        }
    }
}

TEST(AtmosphereLuts, TransmittanceLutMatchesDirectIntegration) {
    const AtmosphereReference reference(Atmosphere{});
    const double bottom = 6360e3;
    double worst = 0.0;
    for (double h : {0.0, 200.0, 1500.0, 8000.0, 30000.0, 90000.0}) {
        for (double mu = -0.2; mu <= 1.0; mu += 0.01) {
            const double r = bottom + h;
            if (mu < 0.0 && r * r * (mu * mu - 1.0) + bottom * bottom >= 0.0) continue;
            const glm::dvec3 lut = reference.TransmittanceFromLut(r, mu);
            const glm::dvec3 exact = reference.TransmittanceIntegrated(r, mu, 2000);
            for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(lut[c] - exact[c]));
        }
    }
    std::printf("transmittance LUT 256x64 vs 2000-step integration: max |dT| = %.2e\n", worst);
    EXPECT_LT(worst, 5e-3);
}

TEST(AtmosphereLuts, MultipleScatteringConvergesInDirections) {
    // Psi_ms from 64 directions and 20 steps (the paper's counts) vs 256 directions and 60 steps:
    // the LUT's own discretisation error, relative to the LUT's peak in each channel (in the
    // Earth's shadow Psi_ms falls to ~0 and relative errors there mean nothing). On the paper's
    // 32 x 32 texels and its two orders, to keep the test short: the directions' sampling is the
    // same at every order and resolution.
    LutSettings coarse;
    coarse.multiple_scattering_size = {32, 32};
    coarse.multiple_scattering_directions_sqrt = 8;
    coarse.multiple_scattering_orders = 2;
    LutSettings fine = coarse;
    fine.multiple_scattering_directions_sqrt = 16;
    fine.multiple_scattering_steps = 60;
    const AtmosphereReference a(Atmosphere{}, coarse), b(Atmosphere{}, fine);
    glm::dvec3 peak(0.0);
    for (const glm::vec4& q : b.multiple_scattering().texels) peak = glm::max(peak, glm::dvec3(q));
    double worst = 0.0;
    for (std::size_t i = 0; i < a.multiple_scattering().texels.size(); ++i) {
        const glm::vec4 p = a.multiple_scattering().texels[i];
        const glm::vec4 q = b.multiple_scattering().texels[i];
        for (int c = 0; c < 3; ++c)
            worst = std::max(worst, std::abs(double(p[c] - q[c])) / peak[c]);
    }
    std::printf("multiple scattering 64 dirs/20 steps vs 256/60: max error %.4f of the peak\n",
                worst);
    EXPECT_LT(worst, 0.02);
}

TEST(AtmosphereLuts, GroundIrradianceBetweenTexelsFollowsTwilight) {
    // Through twilight the sky's illuminance on the ground falls by a factor ~3 per degree of sun
    // depression (Brown 1952: 192 lux at -2 deg, 3.5 at -6 deg), so between two LUT texels linear
    // interpolation can overshoot. The LUT as sampled (SampleGroundIrradiance, the shaders'
    // GetGroundSkyIrradiance) against the same integral evaluated exactly at each sun elevation,
    // every 0.1 deg from +10 to -8 deg. With 64 texels linear in mu_s it was 48 % high at -6 deg;
    // 256 texels in sqrt(mu_s) (the multiple-scattering LUT's u) leave 3.9 % at -7.2 deg (512:
    // 1.2 %, at 1.3x the static-LUT rebuild's time on llvmpipe; 256: 1.04x).
    const Atmosphere earth;
    const LutSettings settings;
    const AtmosphereReference reference(earth, settings);
    const auto a = MakeShaderParameters<ref::AtmosphereParameters>(earth);
    const ref::Texture2D transmittance = ref::FromImage(reference.transmittance());
    const ref::Texture2D multiple_scattering = ref::FromImage(reference.multiple_scattering());
    const ref::Texture2D unused(1, 1);
    double worst = 0.0, worst_elevation = 0.0;
    for (int i = 0; i <= 180; ++i) {
        const double elevation = 10.0 - 0.1 * i;
        const double mu = std::sin(elevation * ref::kPi / 180.0);
        const double u = ref::GetTextureCoordFromUnitRange(ref::UnitRangeFromSunCosine(mu),
                                                           settings.irradiance_size.x);
        const double exact = Luminance(glm::dvec3(ref::ComputeGroundIrradianceTexel(
            a, transmittance, multiple_scattering, unused, settings.irradiance_size, u,
            settings.irradiance_directions_sqrt, settings.irradiance_steps, 0, 1)));
        const double sampled = Luminance(SampleGroundIrradiance(reference.ground_irradiance(), mu));
        const double error = std::abs(sampled / exact - 1.0);
        if (error > worst) worst = error, worst_elevation = elevation;
    }
    std::printf(
        "ground irradiance LUT %d texels vs exact, +10..-8 deg: max |error| %.2f %% at %.1f "
        "deg\n",
        settings.irradiance_size.x, 100.0 * worst, worst_elevation);
    EXPECT_LT(worst, 0.05);
}

TEST(AtmosphereLuts, AerialPerspectiveColumnsMatchDirectMarching) {
    // Each froxel (one step per 1 km slice, marched front to back) against a 500-step march from
    // the camera to the same depth.
    const AtmosphereReference reference(Atmosphere{});
    Lights lights;
    lights.sun_direction = glm::normalize(glm::dvec3(0.6, 0.2, 0.3));
    Camera camera;
    camera.position = glm::dvec3(0.0, 0.0, 6360e3 + 1500.0);
    camera.world_from_view =
        glm::dmat3(glm::dvec3(0, 1, 0), glm::dvec3(0, 0, 1), glm::dvec3(-1, 0, 0));
    const LutImage ap = reference.AerialPerspective(camera, lights);
    double worst = 0.0;
    for (int z : {0, 3, 15, 31}) {
        for (int y : {2, 16, 29}) {
            for (int x : {0, 16, 31}) {
                const glm::dvec3 direction =
                    camera.Direction(2.0 * (x + 0.5) / 32 - 1.0, 2.0 * (y + 0.5) / 32 - 1.0);
                const glm::dvec4 direct = reference.InScattering(camera.position, direction, lights,
                                                                 (z + 0.5) / 32.0 * 32000.0, 500);
                const glm::vec4 froxel = ap.at(x, y, z);
                for (int c = 0; c < 3; ++c) {
                    worst = std::max(worst,
                                     std::abs(froxel[c] - direct[c]) / std::max(direct[c], 1e-3));
                }
                worst = std::max(worst, std::abs(froxel.w - direct.w));
            }
        }
    }
    std::printf("aerial perspective columns vs 500-step marches: max relative %.4f\n", worst);
    EXPECT_LT(worst, 0.01);
}

TEST(AtmosphereLuts, SkyViewMatchesPerPixelRayMarching) {
    const AtmosphereReference reference(Atmosphere{});
    Lights lights;
    lights.sun_direction = glm::normalize(glm::dvec3(0.6, 0.0, 0.8));
    for (double h : {10.0, 1000.0, 12000.0}) {
        const glm::dvec3 camera(0.0, 0.0, 6360e3 + h);
        const LutImage sky_view = reference.SkyView(camera, lights);
        double sum_sq = 0.0, sum_ref = 0.0;
        int n = 0;
        for (double el = -0.5; el <= 1.5; el += 0.05) {
            for (double az = 0.0; az < 6.28; az += 0.2) {
                const glm::dvec3 d(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az),
                                   std::sin(el));
                const glm::dvec3 lut =
                    reference.SampleSkyView(sky_view, camera, lights.sun_direction, d);
                const glm::dvec3 marched = reference.RayMarch(camera, d, lights, 200);
                const double y_lut = Luminance(lut);
                const double y_ref = Luminance(marched);
                sum_sq += (y_lut - y_ref) * (y_lut - y_ref);
                sum_ref += y_ref;
                ++n;
            }
        }
        const double relative_rmse = std::sqrt(sum_sq / n) / (sum_ref / n);
        std::printf("Sky-View LUT vs 200-step ray march at %.0f m: relative RMSE %.4f\n", h,
                    relative_rmse);
        EXPECT_LT(relative_rmse, 0.03) << h;
    }
}

TEST(AtmosphereLuts, MoonIsDroppedOnlyWhereItsSkyIsNegligible) {
    // MakeLightSet leaves the Moon out while the Sun is up (so the Sky-View LUT is symmetric and
    // half of it is marched). The full Moon's sky against the Sun's, texel by texel, with the
    // Sun just above the horizon (its sky at its darkest) and the Moon where it scatters most
    // into the Sun's darkest sky: opposite it, low, and high.
    const AtmosphereReference reference(Atmosphere{});
    const glm::dvec3 camera(0.0, 0.0, 6360e3 + 1500.0);
    const double moon_radius = 0.5 * 0.5181 * ref::kPi / 180.0;
    const double full_moon = LambertSphereIlluminanceFactor(0.12, 0.0, moon_radius);
    double worst = 0.0;
    for (double sun_elevation_deg : {0.25, 5.0}) {
        const double e = sun_elevation_deg * ref::kPi / 180.0;
        Lights sun;
        sun.sun_direction = glm::dvec3(std::cos(e), 0.0, std::sin(e));
        const LutImage sun_sky = reference.SkyView(camera, sun);
        for (const glm::dvec3& moon_direction :
             {glm::dvec3(-0.996, 0.0, 0.087), glm::dvec3(-0.5, 0.5, 0.707),
              glm::dvec3(0.0, -0.94, 0.34)}) {
            Lights both = sun;
            both.moon_enabled = true;
            both.moon_direction = glm::normalize(moon_direction);
            both.moon_illuminance = sun.sun_illuminance * full_moon;
            EXPECT_FALSE(MoonIsLight(both, camera));
            Lights moon = both;
            moon.sun_illuminance = glm::dvec3(0.0);  // the Moon's sky alone (the Moon is a light)
            ASSERT_TRUE(MoonIsLight(moon, camera));
            const LutImage moon_sky = reference.SkyView(camera, moon);
            for (int y = 0; y < sun_sky.size.y; ++y) {
                for (int x = 0; x < sun_sky.size.x; ++x) {
                    worst =
                        std::max(worst, Luminance(moon_sky.at(x, y)) / Luminance(sun_sky.at(x, y)));
                }
            }
        }
    }
    std::printf("the full Moon's sky over the Sun's with the Sun up: at most %.2e per texel\n",
                worst);
    EXPECT_LT(worst, 2e-4);  // 1.1e-4 at the Sun's darkest (Sun 0.25 deg up, Moon opposite)
    // Once the Sun has set, the Moon lights the sky.
    Lights dusk;
    dusk.sun_direction = glm::normalize(glm::dvec3(1.0, 0.0, -0.01));
    dusk.moon_enabled = true;
    dusk.moon_illuminance = dusk.sun_illuminance * full_moon;
    EXPECT_TRUE(MoonIsLight(dusk, camera));
}

TEST(AtmosphereFunctions, UnderCloudsTheAirScattersTheCloudsLight) {
    // Frostbite 2016 Eq. 22 as IntegrateScatteredLuminance applies it: below cloud_base the air
    // scatters the clouds' mean luminance L isotropically (half of it: they fill the upper
    // hemisphere), the ground is lit by them with irradiance pi L_g (L_g their mean weighted by
    // the cosine), and the lights are dimmed. With the lights fully blocked and no absorption,
    // energy conservation gives closed forms: L (1 - T) / 2 toward the sky, plus T albedo L_g
    // where the ray ends on the ground.
    ref::AtmosphereParameters a = EarthKm();
    a.mie_extinction = a.mie_scattering;
    a.absorption_extinction = ref::vec3(0.0);
    const ref::Texture2D zero(8, 8);  // LUTs: every lookup is multiplied by a zero light
    ref::LightSet lights{};
    lights.count = 1;
    lights.light[0].direction = ref::vec3(0.0, 0.0, 1.0);
    lights.light[0].illuminance = ref::vec3(127000.0);
    lights.cloud_base = 200.0;  // the whole atmosphere is beneath
    lights.cloud_direct = 0.0;
    lights.cloud_sky = 0.0;
    lights.cloud_luminance = ref::vec3(1000.0, 2000.0, 3000.0);
    // The ground's: the same weighted by the cosine (brighter overhead, as under a deck).
    lights.cloud_ground_sky = 0.0;
    lights.cloud_ground_luminance = ref::vec3(1100.0, 2300.0, 3500.0);
    const ref::vec3 origin(0.0, 0.0, a.bottom_radius + 1.0);
    for (double mu : {0.3, -0.01, -0.02, -0.6}) {  // up; above, beyond and below the horizon
        const ref::vec3 direction(std::sqrt(1.0 - mu * mu), 0.0, mu);
        const ref::ScatteringResult r = ref::IntegrateScatteredLuminance(
            a, zero, zero, zero, lights, origin, 1.0, direction, 0.0, 1e9, 40, true);
        const double r0 = a.bottom_radius + 1.0;
        const bool ground = mu < -std::sqrt(1.0 - a.bottom_radius * a.bottom_radius / (r0 * r0));
        for (int c = 0; c < 3; ++c) {
            const double l = lights.cloud_luminance[c];
            const double l_ground = lights.cloud_ground_luminance[c];
            const double t = r.transmittance[c];
            const double expected =
                0.5 * l * (1.0 - t) + (ground ? t * a.ground_albedo[c] * l_ground : 0.0);
            EXPECT_NEAR(r.luminance[c] / expected, 1.0, 1e-9) << "mu " << mu << " channel " << c;
        }
    }
    // Without clouds (cloud_base 0) nothing changes: the same march, the lights at full.
    lights.cloud_base = 0.0;
    const ref::ScatteringResult clear = ref::IntegrateScatteredLuminance(
        a, zero, zero, zero, lights, origin, 1.0, ref::vec3(0.0, 0.6, 0.8), 0.0, 1e9, 40, true);
    EXPECT_EQ(clear.luminance, ref::vec3(0.0));  // zero LUTs: no light but the clouds'
}

}  // namespace
}  // namespace zenith::sky
