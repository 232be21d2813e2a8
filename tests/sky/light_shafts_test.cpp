// Light shafts (issue 15 §4): CloudAirShadowCorrection, clouds/march.glsl compiled as C++, against
// the single-scattering integral worked out here by a fine quadrature along the same ray. With a
// uniform shadow map the shafts are the air's single scattering times (map - mean); with the map's
// shadow edge, each point of the ray takes the map where the light through it comes from; where
// the samples are farther apart than the map's texels, the map fades into its mean.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <vector>

#include "reference/cloud_march.h"
#include "shader_parameters.h"
#include "zenith/sky/atmosphere.h"

namespace zenith::sky::ref {
namespace {

constexpr double kExtent = 60.0;  // km, the shadow map's side

struct Scene {
    AtmosphereParameters atmosphere = MakeShaderParameters<AtmosphereParameters>(Atmosphere{});
    Texture2D transmittance{1, 1};  // the light arrives whole: only the shafts' own terms count
    Texture2D map;
    LightSet lights{};
    double R = atmosphere.bottom_radius;

    // `texels` per side: 600 are 100 m, 128 (the renderer's default) 470 m.
    Scene(vec3 sun, double base, double mean, const std::function<double(double)>& map_at_east,
          int texels = 600)
        : map(texels, texels) {
        transmittance.at(0, 0) = vec4(1.0);
        for (int y = 0; y < texels; ++y) {
            for (int x = 0; x < texels; ++x) {
                const double east = ((x + 0.5) / texels - 0.5) * kExtent;
                map.at(x, y) = vec4(map_at_east(east));
            }
        }
        lights.light[0].direction = normalize(sun);
        lights.light[0].illuminance = vec3(1.0);
        lights.count = 1;
        lights.cloud_base = base;
        lights.cloud_direct = mean;
    }

    // The camera `altitude` km above the map's centre (its east is +x, its north +y).
    vec3 Camera(double altitude) const { return vec3(0.0, 0.0, R + altitude); }

    vec3 Shafts(double altitude, vec3 view, int steps, double jitter = 0.5,
                double t_limit = 1e9) const {
        return vec3(CloudAirShadowCorrection(atmosphere, transmittance, map, lights,
                                             lights.light[0].direction, lights.cloud_base, kExtent,
                                             Camera(altitude), altitude, normalize(view), t_limit,
                                             steps, jitter)
                        .part[3]);
    }

    // The reference: sum over [t0, t1] of T(camera, x) sigma_s p(nu) E (S(x) - mean) dt by the
    // midpoint rule in n steps, S from `shadow` at the point's altitude and east offset.
    vec3 Integral(double altitude, vec3 view, double t0, double t1,
                  const std::function<double(double, double)>& shadow, int n = 20000) const {
        view = normalize(view);
        const vec3 camera = Camera(altitude);
        const vec3 light = lights.light[0].direction;
        const double nu = dot(view, light);
        vec3 depth(0.0), sum(0.0);
        const double dt = t1 / n;  // march from the camera so the transmittance is exact
        for (int i = 0; i < n; ++i) {
            const double t = (i + 0.5) * dt;
            const vec3 p = camera + view * t;
            const double h = length(p) - R;
            const MediumSample s = SampleMedium(atmosphere, h);
            depth += s.extinction * (0.5 * dt);
            if (t >= t0) {
                const vec3 phase = s.rayleigh_scattering * RayleighPhase(nu) +
                                   s.mie_scattering * CornetteShanksPhase(atmosphere.mie_g, nu);
                sum += exp(-depth) * phase * (shadow(h, p.x) - lights.cloud_direct) * dt;
            }
            depth += s.extinction * (0.5 * dt);
        }
        return sum;
    }
};

double Relative(vec3 a, vec3 b) { return std::abs(a.y / b.y - 1.0); }

TEST(LightShafts, UniformMapGivesTheAirsSingleScatteringTimesMapMinusMean) {
    const Scene lit(vec3(0.5, 0.0, 0.866), 2.0, 0.4, [](double) { return 1.0; });
    const Scene shade(vec3(0.5, 0.0, 0.866), 2.0, 0.4, [](double) { return 0.0; });
    // Straight up from 1 m: the air from the camera to the base, 2 km.
    const vec3 up(0.0, 0.0, 1.0);
    const auto one = [](double, double) { return 1.0; };
    const auto zero = [](double, double) { return 0.0; };
    const vec3 want_lit = lit.Integral(0.001, up, 0.0, 1.999, one);
    const vec3 want_shade = shade.Integral(0.001, up, 0.0, 1.999, zero);
    const vec3 got_lit = lit.Shafts(0.001, up, 256);
    const vec3 got_shade = shade.Shafts(0.001, up, 256);
    // 24 samples over 2 km are 170 m apart at most: within one of the default map's texels.
    const Scene lit_470m(
        vec3(0.5, 0.0, 0.866), 2.0, 0.4, [](double) { return 1.0; }, 128);
    const vec3 got_24 = lit_470m.Shafts(0.001, up, 24);
    std::printf("up to the base: lit %.6g (reference %.6g), shaded %.6g (%.6g), 24 steps %.6g\n",
                got_lit.y, want_lit.y, got_shade.y, want_shade.y, got_24.y);
    EXPECT_GT(want_lit.y, 0.0);
    EXPECT_LT(want_shade.y, 0.0);
    EXPECT_NEAR(want_shade.y / want_lit.y, -0.4 / 0.6, 1e-9);
    EXPECT_LT(Relative(got_lit, want_lit), 0.005);
    EXPECT_LT(Relative(got_shade, want_shade), 0.005);
    EXPECT_LT(Relative(got_24, want_lit), 0.02);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(got_lit[c] / want_lit[c], 1.0, 0.005) << c;

    // Above the base looking 30 deg down: the shafts begin at the base (the air above it is in
    // front of them, and dims them) and end on the ground.
    const vec3 down(std::cos(0.5236), 0.0, -std::sin(0.5236));
    const double t_base = 1.0 / std::sin(0.5236), t_ground = 3.0 / std::sin(0.5236);
    const vec3 want_down = lit.Integral(3.0, down, t_base, t_ground, one);
    const vec3 got_down = lit.Shafts(3.0, down, 256);
    std::printf("from 3 km, 30 deg down: %.6g (reference %.6g)\n", got_down.y, want_down.y);
    EXPECT_LT(Relative(got_down, want_down), 0.01);

    // A ray that stays above the base has none; nor does a layer with no clouds (base 0).
    EXPECT_EQ(lit.Shafts(3.0, up, 64).y, 0.0);
    Scene none = lit;
    none.lights.cloud_base = 0.0;
    EXPECT_EQ(none.Shafts(0.001, up, 64).y, 0.0);
}

TEST(LightShafts, EachPointTakesTheMapWhereItsLightComesFrom) {
    // Lit east of 0.5 km west of the camera, shaded west of it; the Sun 45 deg up in the east.
    // Straight up, a point h km up is lit through the ground point h km west of the camera's:
    // lit up to 0.5 km, shaded above, whatever the map says right below it.
    const double edge = -0.5;
    const Scene scene(vec3(1.0, 0.0, 1.0), 2.0, 0.5,
                      [&](double east) { return east > edge ? 1.0 : 0.0; });
    const vec3 up(0.0, 0.0, 1.0);
    const auto by_light = [&](double h, double) { return h < -edge ? 1.0 : 0.0; };
    const vec3 want = scene.Integral(0.001, up, 0.0, 1.999, by_light);
    const vec3 got = scene.Shafts(0.001, up, 256);
    // Had it taken the map below each point (all lit), the sign would be the other way.
    const vec3 below = scene.Integral(0.001, up, 0.0, 1.999, [](double, double) { return 1.0; });
    std::printf("shadow edge: %.6g (reference %.6g; with the map below each point %.6g)\n", got.y,
                want.y, below.y);
    EXPECT_LT(want.y, 0.0);
    EXPECT_GT(below.y, 0.0);
    EXPECT_LT(Relative(got, want), 0.02);
}

TEST(LightShafts, ResolvedNearTheCameraAndFreeOfAliasingNoiseBeyond) {
    // 1 km stripes of light and shade on the default map (470 m texels); the Sun 11 deg up in the
    // east; looking east 3 deg up, under a base at 1.5 km: 29 km of air below the clouds, whose
    // points are lit from map points 0.75 km apart per km of ray.
    const Scene scene(
        vec3(1.0, 0.0, 0.2), 1.5, 0.5,
        [](double east) { return std::fmod(std::abs(east), 2.0) < 1.0 ? 1.0 : 0.0; }, 128);
    const vec3 toward(1.0, 0.0, 0.05);
    const int n = 64;
    // The first 3.5 km, where 24 samples are lit from points within half a texel of each other:
    // any jitter estimates the same integral as 4,096 samples.
    vec3 near(0.0);
    for (int i = 0; i < n; ++i) {
        near += scene.Shafts(0.001, toward, 24, (i + 0.5) / n, 3.5) / double(n);
    }
    const vec3 near_fine = scene.Shafts(0.001, toward, 4096, 0.5, 3.5);
    // The whole ray: how much the estimate changes with the jitter (a cell's noise), against
    // the light the air along it scatters under the mean shadow (what the pixel shows of it).
    std::vector<double> whole;
    double mean = 0.0;
    for (int i = 0; i < n; ++i) {
        whole.push_back(scene.Shafts(0.001, toward, 24, (i + 0.5) / n).y);
        mean += whole.back() / n;
    }
    double variance = 0.0;
    for (double v : whole) variance += (v - mean) * (v - mean) / n;
    const double t_base = 1.5 / 0.05;  // roughly; the integral stops where the ray leaves the air
    const vec3 air = scene.Integral(0.001, toward, 0.0, t_base, [](double, double) { return 1.0; });
    const double noise = std::sqrt(variance) / air.y;  // air = (1 - mean) x single scattering
    std::printf(
        "stripes toward a low Sun: first 3.5 km %.6g (4096 samples %.6g); whole ray %.6g, "
        "spread over jitters %.2f %% of the air's light\n",
        near.y, near_fine.y, mean, 100.0 * noise);
    EXPECT_NE(near_fine.y, 0.0);
    EXPECT_LT(Relative(near, near_fine), 0.02);
    EXPECT_LT(noise, 0.015);  // 0.6 % measured; 4.7 % with every sample kept
}

}  // namespace
}  // namespace zenith::sky::ref
