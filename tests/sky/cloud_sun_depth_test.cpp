// The far sun-depth volume on the CPU (clouds/march.glsl's CloudSunDepthTexelWay and
// CloudFarSunDepth, cloud_trace.h's CloudSunDepthVolume): each texel is built from its way to
// the next level and that level's value, so what is checked is that the chain adds up to the
// whole way to the clouds' top, against a fine integration (2 m steps) of the same density
// along the light's ray: in a horizontally uniform cloud (where only the levels' geometry matters),
// and in a field that varies across the square (where the end of each way is read between
// texels). And where the volume must add nothing.
//
// cloud_trace.h's scene and trace are not used here; GCC reports internal-linkage functions at
// the end of the translation unit, so the whole file is covered.
#pragma GCC diagnostic ignored "-Wunused-function"
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "reference/cloud_trace.h"

namespace zenith::sky::ref {
namespace {

constexpr double kR = 6360.0;

// A thunderstorm-sized layer, 1 to 12 km, with flat noise and clouds of type 0.75 (the tallest
// without an anvil: a smooth parabola from 1 to 9.8 km): their density is the height profile
// times the weather map's coverage. (An anvil's 4 % edges are sharper than the volume's steps
// across them when the light is high: 6.5 % off at 60 deg, where the far field seldom reaches.)
CloudScene SmoothScene(const RepeatTexture2D& weather, double weather_period,
                       double elevation_deg) {
    CloudLayerParameters p{};
    p.bottom_radius = kR;
    p.base_altitude = 1.0;
    p.top_altitude = 12.0;
    p.cloud_top_altitude = 9.8;
    p.weather_period = weather_period;
    p.shape_period = 14.0;
    p.shape_period_y = 3.5;
    p.detail_period = 1.8;
    p.erosion_strength = 0.0;
    p.extinction_scale = 1.0;
    CloudScene scene;
    scene.layers = {p};
    scene.weather_maps = {weather};
    scene.shape = Texture3D(1, 1, 1, true);
    scene.shape.at(0, 0, 0) = vec4(1.0);
    scene.detail = Texture3D(1, 1, 1, true);
    scene.detail.at(0, 0, 0) = vec4(0.0, 0.0, 0.0, 1.0);
    scene.march.extinction = 2.0;  // 1/km at density 1
    scene.march.max_distance = 1e4;
    const double e = elevation_deg * kPi / 180.0;
    scene.cloud_lights.count = 1;
    scene.cloud_lights.light[0].direction =
        normalize(vec3(std::cos(e), 0.3 * std::cos(e), 0.0) + vec3(0.0, 0.0, std::sin(e)));
    return scene;
}

CloudSettings VolumeSettings(int size, int levels, double extent_m) {
    CloudSettings settings;
    settings.sun_depth_size = size;
    settings.sun_depth_levels = levels;
    settings.sun_depth_extent = extent_m;
    return settings;
}

// The optical depth from p toward the light to the clouds' top, by the midpoint rule over 2 m
// steps: the reference the volume's chain is checked against.
double FineDepthToTheTop(const CloudScene& scene, vec3 p) {
    const CloudLayerParameters& layer = scene.layers[0];
    const vec3 light = scene.cloud_lights.light[0].direction;
    const double r = length(p);
    const double top = layer.bottom_radius + layer.cloud_top_altitude;
    const double length_km =
        RaySphereDistance(r, dot(p, light) / r, r - top, top);  // inside: the exit
    const int steps = static_cast<int>(std::ceil(length_km / 0.002));
    return CloudRayDepth(layer, scene.weather_maps[0], scene.shape, scene.detail, scene.march, p,
                         light, vec2(0.0, length_km), steps);
}

TEST(CloudSunDepth, EachLevelHoldsTheWholeWayToTheTopOfAUniformCloud) {
    RepeatTexture2D weather(1, 1);
    weather.at(0, 0) = vec4(1.0, 0.0, 0.75, 1.0);  // coverage 1, no rain, type 0.75, full height
    for (const double elevation : {8.0, 20.0, 60.0}) {
        CloudScene scene = SmoothScene(weather, 40.0, elevation);
        const CloudSettings settings = VolumeSettings(8, 12, 100000.0);
        SetCloudSunDepthFrame(scene.march, settings, scene.layers, vec3(3.0, -2.0, kR));
        const Texture3D volume = CloudSunDepthVolume(scene, settings);
        ASSERT_EQ(volume.size(), ivec3(8, 8, 12));
        double worst = 0.0;
        for (int z = 0; z < 12; ++z) {
            const ivec3 texel(3, 4, z);
            const CloudSunDepthWay way =
                CloudSunDepthTexelWay(scene.march, scene.layers[0], texel, volume.size(),
                                      scene.cloud_lights.light[0].direction);
            const double reference = FineDepthToTheTop(scene, way.origin);
            const double value = volume.at(texel.x, texel.y, texel.z).r;
            if (z == 11) {
                EXPECT_EQ(value, 0.0);  // the top level: nothing above it
                continue;
            }
            ASSERT_GT(reference, 0.1);
            worst = std::max(worst, std::abs(value / reference - 1.0));
        }
        std::printf("uniform cloud, light %.0f deg up: worst level %.3f %% off the fine march\n",
                    elevation, 100.0 * worst);
        // Steps of at most 500 m (the midpoint rule on a parabola), and the levels' joins exact.
        EXPECT_LT(worst, 0.01) << elevation << " deg";
    }
}

TEST(CloudSunDepth, TheFarDepthBeyondAnyPointMatchesAFineMarchInAVaryingField) {
    // Coverage varying across the square on scales of tens of kilometres (a 4 x 4 map over
    // 160 km, linearly filtered), much larger than the 1.6 km texels. The points lie where the
    // light's way from them to the top (up to 52 km long across the ground) stays inside the
    // 200 km square: beyond it the chain reads the square's edge.
    RepeatTexture2D weather(4, 4);
    std::mt19937 random(7);
    std::uniform_real_distribution<double> coverage(0.2, 1.0);
    for (int y = 0; y < 4; ++y) {
        for (int x = 0; x < 4; ++x) weather.at(x, y) = vec4(coverage(random), 0.0, 0.75, 1.0);
    }
    CloudScene scene = SmoothScene(weather, 160.0, 12.0);
    // The shipped levels, and texels as wide as the shipped ones (64 over 100 km).
    const CloudSettings settings = VolumeSettings(128, CloudSettings{}.sun_depth_levels, 200000.0);
    const vec3 camera(0.0, 0.0, kR + 0.3);
    SetCloudSunDepthFrame(scene.march, settings, scene.layers, camera);
    scene.sun_depth = CloudSunDepthVolume(scene, settings);
    std::uniform_real_distribution<double> along(-45.0, 0.0), across(-30.0, 30.0), height(1.0, 9.5);
    double sum = 0.0, sum_reference = 0.0, worst = 0.0;
    for (int i = 0; i < 200; ++i) {
        const vec3 q = CloudDomePoint(kR, vec2(along(random), across(random)), height(random));
        const double far = CloudFarSunDepth(scene.march, scene.layers[0], scene.sun_depth, q);
        const double reference = FineDepthToTheTop(scene, q);
        sum += far;
        sum_reference += reference;
        worst = std::max(worst, std::abs(far - reference) / std::max(reference, 1.0));
    }
    std::printf("varying field, 200 points: mean far depth %.3f against %.3f, worst %.2f %%\n",
                sum / 200.0, sum_reference / 200.0, 100.0 * worst);
    // The depth between levels is interpolated linearly, and where coverage thins the clouds
    // their tops are a kink in it: 0.38 km levels (24) are 5.3 % off at worst (in optical depth,
    // or of it where it exceeds 1), 0.8 km ones (12 levels) were 22 %.
    EXPECT_NEAR(sum / sum_reference, 1.0, 0.01);
    EXPECT_LT(worst, 0.07);
}

TEST(CloudSunDepth, AddsNothingWithoutAVolumeAboveItsTopOrOutsideItsSquare) {
    RepeatTexture2D weather(1, 1);
    weather.at(0, 0) = vec4(1.0, 0.0, 0.75, 1.0);
    CloudScene scene = SmoothScene(weather, 40.0, 20.0);
    const vec3 inside = CloudDomePoint(kR, vec2(1.0, 2.0), 5.0);
    // sun_depth_size 0: no volume, whatever the texture holds.
    CloudSettings settings = VolumeSettings(0, 12, 100000.0);
    SetCloudSunDepthFrame(scene.march, settings, scene.layers, vec3(0.0, 0.0, kR));
    EXPECT_EQ(scene.march.sun_depth_extent, 0.0);
    EXPECT_EQ(CloudSunDepthVolume(scene, settings).size(), ivec3(1));
    EXPECT_EQ(CloudFarSunDepth(scene.march, scene.layers[0], scene.sun_depth, inside), 0.0);

    settings = VolumeSettings(16, 8, 50000.0);
    SetCloudSunDepthFrame(scene.march, settings, scene.layers, vec3(0.0, 0.0, kR));
    EXPECT_DOUBLE_EQ(scene.march.sun_depth_base, 1.0);
    EXPECT_DOUBLE_EQ(scene.march.sun_depth_top, 9.8);
    scene.sun_depth = CloudSunDepthVolume(scene, settings);
    EXPECT_GT(CloudFarSunDepth(scene.march, scene.layers[0], scene.sun_depth, inside), 1.0);
    // At or above the top level, and beyond the square (50 km wide around the origin).
    EXPECT_EQ(CloudFarSunDepth(scene.march, scene.layers[0], scene.sun_depth,
                               CloudDomePoint(kR, vec2(1.0, 2.0), 9.8)),
              0.0);
    EXPECT_EQ(CloudFarSunDepth(scene.march, scene.layers[0], scene.sun_depth,
                               CloudDomePoint(kR, vec2(26.0, 0.0), 5.0)),
              0.0);
    // No light reaches the clouds: a volume of zeros.
    scene.cloud_lights.count = 0;
    const Texture3D dark = CloudSunDepthVolume(scene, settings);
    EXPECT_EQ(dark.at(3, 3, 0).r, 0.0);
}

TEST(CloudSunDepth, DomePointIsTheInverseOfTheGroundCoordinates) {
    CloudLayerParameters layer{};
    layer.bottom_radius = kR;
    layer.cloud_top_altitude = 1.0;
    // SetCloudSunDepthFrame works out the square's centre on the host (float uniforms too) with
    // its own copy of the dome projection: it must be CloudGroundCoordinates', which the lookups
    // use, or the volume would be read shifted.
    CloudMarchParameters march{};
    const vec3 camera = CloudDomePoint(kR, vec2(-83.0, 41.5), 0.3);
    SetCloudSunDepthFrame(march, CloudSettings{}, std::vector<CloudLayerParameters>{layer}, camera);
    EXPECT_NEAR(march.sun_depth_center_x, CloudGroundCoordinates(layer, camera).x, 1e-9);
    EXPECT_NEAR(march.sun_depth_center_y, CloudGroundCoordinates(layer, camera).y, 1e-9);
    for (const vec2 ground : {vec2(0.0, 0.0), vec2(12.5, -40.0), vec2(-300.0, 800.0)}) {
        const vec3 p = CloudDomePoint(kR, ground, 7.0);
        const vec2 back = CloudGroundCoordinates(layer, p);
        EXPECT_NEAR(back.x, ground.x, 1e-9);
        EXPECT_NEAR(back.y, ground.y, 1e-9);
        EXPECT_NEAR(CloudAltitude(layer, p), 7.0, 1e-9);
    }
}

}  // namespace
}  // namespace zenith::sky::ref
