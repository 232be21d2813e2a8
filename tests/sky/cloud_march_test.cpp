// The cloud march on the CPU (clouds/march.glsl compiled as C++): the layer's entry and exit
// against closed forms from below, inside, above and from orbit; the march's convergence in its
// step count and its exact energy balance; the layer order, the settings' checks and the lights.
#include "reference/cloud_march.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "clouds/cloud_parameters.h"
#include "zenith/base/error.h"

namespace zenith::sky::ref {
namespace {

constexpr double kR = 6360.0;

CloudLayerParameters Layer(double base = 1.5, double top = 4.0) {
    CloudLayerParameters p{};
    p.bottom_radius = kR;
    p.base_altitude = base;
    p.top_altitude = top;
    p.weather_period = 40.0;
    p.shape_period = 14.0;
    p.shape_period_y = 3.5;
    p.detail_period = 1.8;
    p.erosion_strength = 0.45;
    p.cloud_top_altitude = top;
    p.extinction_scale = 1.0;
    return p;
}

// Distance along a ray from radius r at elevation angle e to the sphere of radius s (the far
// root when inside it, the near one outside), by the law of cosines.
double Chord(double r, double elevation, double s, bool near_root) {
    const double b = r * std::sin(elevation);
    const double d = std::sqrt(b * b - (r * r - s * s));
    return near_root ? -b - d : -b + d;
}

TEST(CloudLayerInterval, MatchesClosedFormsFromBelowInsideAboveAndOrbit) {
    const CloudLayerParameters layer = Layer();
    const double base = kR + 1.5, top = kR + 4.0;
    // Straight up and down: the shell's thickness, or what is left of it.
    EXPECT_NEAR(CloudLayerInterval(layer, kR, 1.0, 0.0, 1e9).x, 1.5, 1e-9);
    EXPECT_NEAR(CloudLayerInterval(layer, kR, 1.0, 0.0, 1e9).y, 4.0, 1e-9);
    EXPECT_NEAR(CloudLayerInterval(layer, kR + 2.0, 1.0, 2.0, 1e9).x, 0.0, 1e-12);
    EXPECT_NEAR(CloudLayerInterval(layer, kR + 2.0, 1.0, 2.0, 1e9).y, 2.0, 1e-9);
    EXPECT_NEAR(CloudLayerInterval(layer, kR + 2.0, -1.0, 2.0, 1e9).y, 0.5, 1e-9);
    EXPECT_NEAR(CloudLayerInterval(layer, kR + 12.0, -1.0, 12.0, 1e9).x, 8.0, 1e-9);
    EXPECT_NEAR(CloudLayerInterval(layer, kR + 12.0, -1.0, 12.0, 1e9).y, 10.5, 1e-9);
    // Oblique: from the ground at 5 deg the ray crosses the whole shell far away.
    const double e = 5.0 * kPi / 180.0;
    const vec2 low = CloudLayerInterval(layer, kR, std::sin(e), 0.0, 1e9);
    EXPECT_NEAR(low.x, Chord(kR, e, base, false), 1e-6);
    EXPECT_NEAR(low.y, Chord(kR, e, top, false), 1e-6);
    // From 400 km looking 30 deg below the horizontal: in at the top, out at the base.
    const double r = kR + 400.0, down = -30.0 * kPi / 180.0;
    const vec2 orbit = CloudLayerInterval(layer, r, std::sin(down), 400.0, 1e9);
    EXPECT_NEAR(orbit.x, Chord(r, down, top, true), 1e-6);
    EXPECT_NEAR(orbit.y, Chord(r, down, base, true), 1e-6);
    // Above the layer, grazing it: the lowest point of the ray (radius r cos e) lies between
    // the base and the top, so it leaves through the top again.
    const double high = kR + 10.0, skim_e = -std::acos((kR + 2.5) / high);
    const vec2 skim = CloudLayerInterval(layer, high, std::sin(skim_e), 10.0, 1e9);
    EXPECT_NEAR(skim.x, Chord(high, skim_e, top, true), 1e-5);
    EXPECT_NEAR(skim.y, Chord(high, skim_e, top, false), 1e-5);
    // Looking down from below the layer meets the ground first: nothing.
    const vec2 ground = CloudLayerInterval(layer, kR + 1.0, -0.2, 1.0, 1e9);
    EXPECT_LT(ground.y, ground.x);
    // Looking up from above the layer: nothing.
    const vec2 away = CloudLayerInterval(layer, kR + 6.0, 0.3, 6.0, 1e9);
    EXPECT_LT(away.y, away.x);
    // max_distance counts from the entry.
    const vec2 cut = CloudLayerInterval(layer, kR, std::sin(e), 0.0, 10.0);
    EXPECT_NEAR(cut.y - cut.x, 10.0, 1e-9);

    // Clouds that reach only 3 km: the march ends there, and a camera at 3.5 km is above them.
    CloudLayerParameters low_clouds = layer;
    low_clouds.cloud_top_altitude = 3.0;
    EXPECT_NEAR(CloudLayerInterval(low_clouds, kR, 1.0, 0.0, 1e9).y, 3.0, 1e-9);
    EXPECT_NEAR(CloudLayerInterval(low_clouds, kR, std::sin(e), 0.0, 1e9).y,
                Chord(kR, e, kR + 3.0, false), 1e-6);
    const vec2 above = CloudLayerInterval(low_clouds, kR + 3.5, -1.0, 3.5, 1e9);
    EXPECT_NEAR(above.x, 0.5, 1e-9);
    EXPECT_NEAR(above.y, 2.0, 1e-9);
    const vec2 level = CloudLayerInterval(low_clouds, kR + 3.5, 0.0, 3.5, 1e9);
    EXPECT_LT(level.y, level.x);
}

// A smooth cloud (constant noise, uniform full coverage: density is the height signal's
// parabola) lit by an overhead sun through a clear atmosphere (transmittance 1, no sky light):
// the march with 20 steps lands within 2 % of 1000 steps, and the light it returns never exceeds
// what a fully lit, non-absorbing slab can scatter.
TEST(MarchCloudLayer, ConvergesInItsStepCountAndConservesEnergy) {
    CloudLayerParameters layer = Layer();
    RepeatTexture2D weather(1, 1);
    weather.at(0, 0) = vec4(1.0, 0.0, 1.0, 1.0);  // coverage 1, no rain, cumulonimbus, full height
    Texture3D shape(1, 1, 1, true), detail(1, 1, 1, true);
    shape.at(0, 0, 0) = vec4(1.0, 1.0, 1.0, 1.0);
    detail.at(0, 0, 0) = vec4(0.0, 0.0, 0.0, 1.0);
    layer.erosion_strength = 0.0;
    AtmosphereParameters atmosphere{};
    atmosphere.bottom_radius = kR;
    atmosphere.top_radius = kR + 100.0;
    atmosphere.sun_angular_radius = 0.00465;
    Texture2D transmittance(1, 1), irradiance(1, 1);
    transmittance.at(0, 0) = vec4(1.0);
    irradiance.at(0, 0) = vec4(0.0);
    CloudScatteringParameters scattering{};
    scattering.forward_g = 0.0;
    scattering.backward_g = 0.0;
    scattering.albedo = 1.0;
    scattering.multiple_scattering = 0.0;  // single scattering: the closed form below
    CloudMarchParameters march{};
    march.extinction = 1.0;  // 1/km: an optical depth of 1.7 through the layer's top 3.5 km
    march.min_step = 1e-4;
    march.shadow_steps = 0;  // no self-shadowing: every sample sees the whole sun
    march.shadow_first_step = 0.1;
    march.shadow_growth = 2.0;
    march.min_transmittance = 0.0;
    march.max_distance = 1e9;
    LightSet lights{};
    lights.light[0].direction = vec3(0.0, 0.0, 1.0);
    lights.light[0].illuminance = vec3(1.0);
    lights.count = 1;
    const vec3 camera(0.0, 0.0, kR + 0.5);
    const vec3 view(0.0, 0.0, 1.0);
    const vec2 interval = CloudLayerInterval(layer, kR + 0.5, 1.0, 0.5, 1e9);
    const auto luminance = [&](int steps) {
        CloudMarchParameters m = march;
        m.max_steps = steps;
        CloudMarchState state = CloudMarchStart();
        MarchCloudLayer(atmosphere, transmittance, irradiance, layer, layer, weather, shape, detail,
                        Texture3D(1, 1, 1), scattering, m, lights, 1, camera, view, interval, 0.5,
                        state);
        return state.luminance.x;
    };
    const double reference = luminance(1000);
    const double twenty = luminance(20);
    std::printf(
        "overhead sun through a smooth cumulonimbus: 20 steps %.5g, 1000 steps %.5g "
        "(%.2f %%)\n",
        twenty, reference, 100.0 * (twenty / reference - 1.0));
    EXPECT_NEAR(twenty / reference, 1.0, 0.02);
    // Unshadowed isotropic scattering adds (1 - T) E / (4 pi): exactly, whatever the steps.
    CloudMarchState state = CloudMarchStart();
    CloudMarchParameters m = march;
    m.max_steps = 7;
    MarchCloudLayer(atmosphere, transmittance, irradiance, layer, layer, weather, shape, detail,
                    Texture3D(1, 1, 1), scattering, m, lights, 1, camera, view, interval, 0.5,
                    state);
    EXPECT_NEAR(state.luminance.x, (1.0 - state.transmittance) / (4.0 * kPi), 1e-12);
    EXPECT_GT(state.transmittance, 0.05);
    EXPECT_LT(state.transmittance, 0.5);
}

// The transmittance profile the march records for a host's geometry inside the clouds, against
// closed forms: a homogeneous medium from the camera (fog), sigma = 3 /km, recorded step by step
// as the march records it, gives 1 - exp(-sigma d) exactly in front of d, before its last
// crossing and past it; a cloud 5-6 km away leaves nothing in front of geometry at 4 km and all of
// its opacity in front of geometry at 8 km.
// A precipitation shaft is lit through the cloud it falls from: from a point in a homogeneous
// shaft (0-1 km, 0.4 /km) under a fog-like cloud layer (1-2 km, 2 /km, flat to 80 % of it, then
// thinning linearly to its top), the optical depth toward the light is the shaft's own part to
// its top plus the cloud's whole crossing, however low the light: against the densities
// integrated along the light's way in 20,000 steps on the sphere (at 5 deg that way is 19 km
// long; the growing shadow steps, 80 m doubling four times, reach 1.2 km).
TEST(CloudShadowOpticalDepth, AShaftSeesTheWholeCloudItFallsFrom) {
    CloudLayerParameters shaft = Layer(0.0, 1.0);
    shaft.precipitation_shaft = 1.0;
    shaft.extinction_scale = 0.4;
    CloudLayerParameters cloud = Layer(1.0, 2.0);
    cloud.ground_fog = 1.0;
    cloud.extinction_scale = 2.0;
    RepeatTexture2D weather(1, 1);
    weather.at(0, 0) = vec4(1.0, 0.9, 0.0, 1.0);  // coverage 1, heavy precipitation (share 1)
    Texture3D shape(1, 1, 1, true), detail(1, 1, 1, true);
    CloudMarchParameters march{};
    march.extinction = 1.0;
    march.shadow_steps = 4;
    march.shadow_first_step = 0.08;
    march.shadow_growth = 2.0;
    march.column_steps = 1.0;
    march.max_distance = 1e9;
    const auto density = [&](double altitude) {
        if (altitude > 0.0 && altitude < 1.0) return 0.4;
        const double x = altitude - 1.0;  // into the cloud, of its 1 km
        if (x > 0.0 && x < 1.0) return 2.0 * std::min((1.0 - x) / 0.2, 1.0);
        return 0.0;
    };
    const vec3 p(0.0, 0.0, kR + 0.3);
    const CloudSample origin = SampleCloudDensity(shaft, weather, shape, detail, p);
    ASSERT_NEAR(origin.density, 0.4, 1e-12);
    for (const double elevation_deg : {90.0, 45.0, 17.0, 5.0}) {
        const double e = elevation_deg * kPi / 180.0;
        const vec3 light(0.0, std::cos(e), std::sin(e));
        // Past the cloud's top sphere the densities are 0.
        const double length = Chord(kR + 0.3, e, kR + 2.0, false);
        constexpr int kSteps = 20000;
        double reference = 0.0;
        for (int i = 0; i < kSteps; ++i) {
            const vec3 q = p + light * ((i + 0.5) * length / kSteps);
            reference += density(std::sqrt(dot(q, q)) - kR) * length / kSteps;
        }
        double reach = 0.0;
        const double shadow = CloudShadowOpticalDepth(shaft, cloud, weather, shape, detail, march,
                                                      origin, p, light, 0, reach);
        EXPECT_EQ(reach, -1.0) << "a shaft's crossing has nothing beyond it";
        std::printf("light %.0f deg up: shaft and cloud %.4f, integrated %.4f\n", elevation_deg,
                    shadow, reference);
        EXPECT_NEAR(shadow / reference, 1.0, 0.02) << elevation_deg << " deg";
    }
}

TEST(CloudOpacityShareInFront, ClosedFormsForFogAndACloudAhead) {
    const double sigma = 3.0, dt = 0.01;
    CloudMarchState fog = CloudMarchStart();
    for (int i = 0; i < 400 && fog.transmittance >= 0.01; ++i) {
        const double before = fog.transmittance;
        fog.transmittance *= std::exp(-sigma * dt);
        CloudRecordCrossings(fog, i * dt, dt, before);
    }
    EXPECT_EQ(fog.entry, 0.0);
    for (int k = 0; k < 4; ++k) {
        EXPECT_NEAR(fog.crossing[k], -std::log(CloudProfileThreshold(k)) / sigma, 1e-9) << k;
    }
    const double transmittance = 0.0;  // the march counts the rest as opaque
    for (double d : {0.05, 0.2, 0.5, 0.9}) {
        EXPECT_NEAR(
            CloudOpacityShareInFront(fog.entry, 1.0 / sigma, fog.crossing, transmittance, d),
            1.0 - std::exp(-sigma * d), 1e-9)
            << d;
    }
    // Past the last crossing (T = 0.05) with the last segment's slope.
    EXPECT_NEAR(CloudOpacityShareInFront(fog.entry, 1.0 / sigma, fog.crossing, transmittance, 2.0),
                1.0 - std::exp(-sigma * 2.0), 1e-9);

    // A thin cloud (T = 0.9, no crossing below 0.8) from 5 to 6 km: mean depth 5.5 km.
    const vec4 none(-1.0);
    EXPECT_EQ(CloudOpacityShareInFront(5.0, 5.5, none, 0.9, 4.0), 0.0);
    EXPECT_NEAR(CloudOpacityShareInFront(5.0, 5.5, none, 0.9, 8.0), 1.0, 1e-12);
    const double half = CloudOpacityShareInFront(5.0, 5.5, none, 0.9, 5.5);
    EXPECT_GT(half, 0.4);
    EXPECT_LT(half, 0.6);
    // No cloud met: nothing in front of anything.
    EXPECT_EQ(CloudOpacityShareInFront(-1.0, -1.0, none, 1.0, 3.0), 0.0);
}

TEST(CloudLayerOrder, CameraLayerAndBelowDownwardThenAboveUpward) {
    clouds::Weather w;
    for (double base : {1000.0, 4000.0, 8000.0}) {
        clouds::CloudLayer layer;
        layer.base_altitude = base;
        layer.top_altitude = base + 1000.0;
        w.layers.push_back(layer);
    }
    EXPECT_EQ(CloudLayerOrder(w, 0.0), (std::vector<int>{0, 1, 2}));
    EXPECT_EQ(CloudLayerOrder(w, 4500.0), (std::vector<int>{1, 0, 2}));
    EXPECT_EQ(CloudLayerOrder(w, 6000.0), (std::vector<int>{1, 0, 2}));
    EXPECT_EQ(CloudLayerOrder(w, 12000.0), (std::vector<int>{2, 1, 0}));
}

TEST(CloudSettings, RejectsOutOfRangeValuesByName) {
    CloudSettings s;
    EXPECT_NO_THROW(s.Validate());
    s.multiple_scattering = 1.5;
    try {
        s.Validate();
        FAIL();
    } catch (const zenith::ArgumentError& e) {
        EXPECT_STREQ(e.what(), "CloudSettings::multiple_scattering = 1.5 (expected [0, 1])");
    }
    s = CloudSettings{};
    s.multiple_scattering = std::nan("");
    EXPECT_THROW(s.Validate(), zenith::ArgumentError);
    s = CloudSettings{};
    s.max_steps = 0;
    EXPECT_THROW(s.Validate(), zenith::ArgumentError);
    s = CloudSettings{};
    s.extinction = std::nan("");
    EXPECT_THROW(s.Validate(), zenith::ArgumentError);
    s = CloudSettings{};
    s.pass_stage = static_cast<CloudPassStage>(7);
    try {
        s.Validate();
        FAIL();
    } catch (const zenith::ArgumentError& e) {
        EXPECT_STREQ(e.what(),
                     "CloudSettings::pass_stage = 7 (expected 0 kAuto, 1 kFragment or 2 kCompute)");
    }
    // The far sun-depth volume: none (0) or a bounded size, so no input sizes its memory.
    s = CloudSettings{};
    s.sun_depth_size = 0;
    EXPECT_NO_THROW(s.Validate());
    s.sun_depth_size = 4096;
    try {
        s.Validate();
        FAIL();
    } catch (const zenith::ArgumentError& e) {
        EXPECT_STREQ(e.what(),
                     "CloudSettings::sun_depth_size = 4096 (expected 0 (none) or 8..512)");
    }
    s = CloudSettings{};
    s.sun_depth_levels = 1;
    EXPECT_THROW(s.Validate(), zenith::ArgumentError);
    s = CloudSettings{};
    s.sun_depth_extent = std::nan("");
    EXPECT_THROW(s.Validate(), zenith::ArgumentError);
}

TEST(CloudLightSet, DropsTheSunAtNightAndAFaintMoonByDay) {
    Lights day;
    day.sun_direction = {0.0, 0.6, 0.8};
    day.moon_enabled = true;
    day.moon_direction = {0.0, -0.6, 0.8};
    day.moon_illuminance = glm::dvec3(0.2);
    const glm::dvec3 up(0.0, 0.0, 1.0);
    EXPECT_EQ(MakeCloudLightSet<LightSet>(day, up, mat3(1.0)).count, 1);
    Lights night = day;
    night.sun_direction = {0.0, 0.9, -0.3};
    const LightSet lights = MakeCloudLightSet<LightSet>(night, up, mat3(1.0));
    ASSERT_EQ(lights.count, 1);
    EXPECT_NEAR(lights.light[0].illuminance.x, 0.2, 1e-12);  // the Moon
    // Directions are rotated into the weather frame.
    const mat3 quarter(vec3(0, 1, 0), vec3(-1, 0, 0), vec3(0, 0, 1));
    const LightSet rotated = MakeCloudLightSet<LightSet>(day, up, quarter);
    EXPECT_NEAR(glm::length(rotated.light[0].direction - quarter * day.sun_direction), 0.0, 1e-12);
}

}  // namespace
}  // namespace zenith::sky::ref
