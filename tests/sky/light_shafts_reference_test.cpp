// Light shafts against the cloud path tracer (issue 15 §4): the air below an isolated cumulus,
// looked at through the cumulus' shadow and beside it. The path tracer, limited to single
// scattering over a black ground, gives the light the air scatters once with the clouds' shadow
// worked out by its own ratio tracking toward the Sun through the cloud field; the renderer gives
// that light as the air lit by the shadow map's mean (what its LUTs assume below the clouds) plus
// CloudAirShadowCorrection over its CPU shadow map. Only the medium is shared.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "cloud_test_support.h"
// Internal linkage, like shaders: this test uses some of what these define.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#include "cloud_march_support.h"
#include "reference/cloud_trace.h"
#pragma GCC diagnostic pop
#include "zenith/sky/reference/atmosphere_reference.h"
#include "zenith/sky/reference/cloud_path_tracer.h"

namespace zenith::sky::ref {
namespace {

double Y(vec3 c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; }

TEST(LightShaftsReference, TheShadowedAirMatchesThePathTracer) {
    const Atmosphere earth;
    const CloudSettings settings;
    const clouds::CloudNoise& noise = clouds::test::CachedNoise();
    const std::filesystem::path scratch =
        std::filesystem::path(ZENITH_BINARY_DIR) / "light-shafts-reference";
    const clouds::Weather weather = IsolatedCumulusWeather(scratch);

    // The Sun 30 deg up in the east: the cumulus (base 1.5 km, top 4 km, over ground 0, 0)
    // shades the air west of it down to the ground 1-8.5 km west. The camera 1.2 km up, 4 km
    // west and 6 km south of it, looks 10 deg down: north through the shaded air, north-west
    // and south beside it; each ray ends on the ground below the base.
    const double elevation = 30.0 * kPi / 180.0;
    Lights lights;
    lights.sun_direction = glm::dvec3(std::cos(elevation), 0.0, std::sin(elevation));
    lights.sun_illuminance = earth.solar_illuminance;
    Camera camera;
    camera.position = glm::dvec3(-4000.0, -6000.0, earth.bottom_radius + 1200.0);
    const double altitude_km = glm::length(camera.position) / 1000.0 - kR;

    const reference::CloudField field(weather, settings, noise, earth.bottom_radius);
    const reference::AtmosphereReference air(earth);
    const CloudScene scene =
        MakeCloudScene(earth, air.transmittance(), air.multiple_scattering(),
                       air.ground_irradiance(), weather, settings, noise, camera, lights, {});
    std::filesystem::remove_all(scratch);
    const vec3 camera_km = camera.position / 1000.0;
    const int n = settings.shadow_map_size;
    Texture2D shadow_map(n, n);
    for (int y = 0; y < n; ++y) {
        for (int x = 0; x < n; ++x) {
            shadow_map.at(x, y) = vec4(
                CloudShadowMapTexel(scene, settings, camera_km, (vec2(x, y) + 0.5) / double(n)));
        }
    }
    const LightSet& set = scene.lights;
    const AtmosphereParameters& a = scene.atmosphere;
    const double extent_km = settings.shadow_map_extent / 1000.0;

    reference::CloudScene traced;
    traced.atmosphere = earth;
    traced.clouds = &field;
    traced.sun_direction = lights.sun_direction;
    traced.ground = false;
    reference::CloudPathTraceOptions options;
    options.samples = 200000;
    options.max_bounces = 1;
    options.threads = 2;

    struct View {
        const char* name;
        double azimuth;  // from north toward east
    };
    const View views[] = {{"north, through the shade", 0.0},
                          {"north-west, beside it", -50.0},
                          {"south, away from it", 180.0}};
    double shaded_mean = 0.0, shaded_shafts = 0.0, shaded_reference = 0.0;
    for (const View& v : views) {
        const double az = v.azimuth * kPi / 180.0, down = -10.0 * kPi / 180.0;
        const vec3 view = normalize(
            vec3(std::sin(az) * std::cos(down), std::cos(az) * std::cos(down), std::sin(down)));
        // The air's single scattering under the map's mean, by a fine midpoint quadrature (the
        // renderer's LUTs draw this with their multiple scattering added).
        const double r = length(camera_km);
        const double t_ground =
            RaySphereDistance(r, dot(camera_km, view) / r, altitude_km, a.bottom_radius);
        ASSERT_GT(t_ground, 0.0);
        const vec3 light = set.light[0].direction;
        const double nu = dot(view, light);
        vec3 depth(0.0), mean(0.0);
        const int steps = 4000;
        const double dt = t_ground / steps;
        for (int i = 0; i < steps; ++i) {
            const vec3 p = camera_km + view * ((i + 0.5) * dt);
            const double r_p = length(p);
            const MediumSample s = SampleMedium(a, r_p - a.bottom_radius);
            depth += s.extinction * (0.5 * dt);
            const vec3 phase = s.rayleigh_scattering * RayleighPhase(nu) +
                               s.mie_scattering * CornetteShanksPhase(a.mie_g, nu);
            mean += exp(-depth) * phase * set.light[0].illuminance *
                    GetTransmittanceToSun(a, scene.transmittance, r_p, dot(p, light) / r_p) *
                    set.cloud_direct * dt;
            depth += s.extinction * (0.5 * dt);
        }
        const vec3 shafts =
            vec3(CloudAirShadowCorrection(a, scene.transmittance, shadow_map, set, light,
                                          set.cloud_base, extent_km, camera_km, altitude_km, view,
                                          1e9, settings.light_shaft_steps, 0.5)
                     .part[3]);
        const reference::CloudPathTraceResult pt =
            reference::CloudPathTrace(traced, camera.position, view, options);
        const double with = Y(mean + shafts), without = Y(mean);
        std::printf(
            "%-26s path tracer %.2f +- %.2f cd/m^2; renderer with shafts %.2f (%+.1f %%), "
            "with the mean shadow only %.2f (%+.1f %%)\n",
            v.name, pt.luminance, pt.luminance_error, with, 100.0 * (with / pt.luminance - 1.0),
            without, 100.0 * (without / pt.luminance - 1.0));
        // Within 4 % and three standard errors of the path tracer.
        EXPECT_LT(std::abs(with - pt.luminance), 0.04 * pt.luminance + 3.0 * pt.luminance_error)
            << v.name;
        if (v.azimuth == 0.0) {
            shaded_mean = without;
            shaded_shafts = with;
            shaded_reference = pt.luminance;
        }
    }
    // Through the shade the mean alone is far too bright; the shafts take most of that away.
    EXPECT_GT(std::abs(shaded_mean - shaded_reference),
              3.0 * std::abs(shaded_shafts - shaded_reference));
}

}  // namespace
}  // namespace zenith::sky::ref
