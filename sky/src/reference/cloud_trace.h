// The clouds on the CPU: the GL trace pass (clouds/interface.glsl TraceClouds) in double
// precision over the same shared functions, for GPU-vs-CPU parity tests and for host queries
// such as the sunlight reaching the aircraft through the clouds.
#pragma once

#include <algorithm>
#include <vector>

#include "clouds/cloud_parameters.h"
#include "reference/cloud_march.h"
#include "reference/lut_texture.h"
#include "shader_parameters.h"

namespace zenith::sky::ref {
namespace {

// Everything the trace reads, in the shaders' units (km) and the renderer's frame.
struct CloudScene {
    AtmosphereParameters atmosphere{};
    Texture2D transmittance, multiple_scattering, irradiance;
    std::vector<CloudLayerParameters> layers;
    std::vector<RepeatTexture2D> weather_maps;
    Texture3D shape, detail;
    Texture3D sun_depth{1, 1, 1};  // the far sun-depth volume (CloudSunDepthVolume)
    CloudScatteringParameters scattering{};
    CloudMarchParameters march{};
    LightSet lights{};        // the atmosphere's, for the aerial perspective
    LightSet cloud_lights{};  // MakeCloudLightSet's, in the weather frame
    mat3 weather_from_frame{1.0};
    std::vector<int> order;         // the layers as a ray from the camera meets them
    std::vector<int> ground_order;  // ...and from the ground
    int aerial_perspective_steps = 8;
};

// MarchCloudLayers of clouds/interface.glsl: the clouds alone along `direction` from `origin`
// (cloud frame, km; `altitude` km above the ground, exact), layers in `order`.
CloudMarchState MarchCloudLayers(const CloudScene& scene, vec3 origin, Number altitude,
                                 vec3 direction, Number jitter, const std::vector<int>& order) {
    const Number r = length(origin);
    const Number mu = dot(origin, direction) / r;
    CloudMarchState state = CloudMarchStart();
    for (int i : order) {
        const auto layer = static_cast<std::size_t>(i);
        const vec2 interval =
            CloudLayerInterval(scene.layers[layer], r, mu, altitude, scene.march.max_distance);
        MarchCloudLayer(scene.atmosphere, scene.transmittance, scene.irradiance,
                        scene.layers[layer],
                        scene.layers[std::min(layer + 1, scene.layers.size() - 1)],
                        scene.weather_maps[layer], scene.shape, scene.detail, scene.sun_depth,
                        scene.scattering, scene.march, scene.cloud_lights, scene.cloud_lights.count,
                        origin, direction, interval, jitter, state);
    }
    return state;
}

// TraceClouds of clouds/interface.glsl: (L, T) of the clouds along `view` from `camera` (km,
// the renderer's frame; `altitude` km above the ground, exact), aerial perspective applied;
// *depth gets the mean depth (km, -1 for none).
vec4 TraceClouds(const CloudScene& scene, vec3 camera, Number altitude, vec3 view, Number jitter,
                 Number* depth = nullptr) {
    const CloudMarchState state =
        MarchCloudLayers(scene, scene.weather_from_frame * camera, altitude,
                         scene.weather_from_frame * view, jitter, scene.order);
    if (depth != nullptr) *depth = CloudMeanDepth(state);
    return CloudApplyAerialPerspective(
        scene.atmosphere, scene.transmittance, scene.multiple_scattering, scene.irradiance,
        scene.lights, camera, altitude, view, state, scene.aerial_perspective_steps);
}

// clouds/sun_depth.comp: the far sun-depth volume for scene.march's frame (SetCloudSunDepthFrame),
// its levels from the top down; one texel that no sample reads where there is none.
Texture3D CloudSunDepthVolume(const CloudScene& scene, const CloudSettings& settings) {
    const ivec3 size = CloudSunDepthSize(settings);
    Texture3D volume(size.x, size.y, size.z);
    if (!(scene.march.sun_depth_extent > 0.0)) return volume;  // no volume, or no clouds: 0
    if (scene.cloud_lights.count == 0) return volume;          // no light reaches the clouds: 0
    const vec3 light = scene.cloud_lights.light[0].direction;
    for (int z = size.z - 1; z >= 0; --z) {
        for (int y = 0; y < size.y; ++y) {
            for (int x = 0; x < size.x; ++x) {
                const CloudSunDepthWay way = CloudSunDepthTexelWay(scene.march, scene.layers[0],
                                                                   ivec3(x, y, z), size, light);
                Number optical_depth = way.above ? volume.Sample(way.end_uvw).r : 0.0;
                for (std::size_t i = 0; i < scene.layers.size(); ++i) {
                    if (scene.layers[i].precipitation_shaft > 0.5) continue;
                    optical_depth += CloudRayDepth(
                        scene.layers[i], scene.weather_maps[i], scene.shape, scene.detail,
                        scene.march, way.origin, light, vec2(0.0, way.length_km), way.steps);
                }
                volume.at(x, y, z) = vec4(optical_depth);
            }
        }
    }
    return volume;
}

// A texel of clouds/shadow_map.comp: the transmittance toward the main cloud light from the
// ground at shadow-map coordinate uv around `camera` (km, the renderer's frame).
Number CloudShadowMapTexel(const CloudScene& scene, const CloudSettings& settings, vec3 camera,
                           vec2 uv) {
    if (scene.cloud_lights.count == 0) return 1.0;
    const vec3 origin = scene.weather_from_frame *
                        CloudShadowMapGroundPoint(camera, scene.atmosphere.bottom_radius,
                                                  settings.shadow_map_extent / 1000.0, uv);
    Number optical_depth = 0.0;
    for (std::size_t i = 0; i < scene.layers.size(); ++i) {
        optical_depth += CloudLayerShadowDepth(
            scene.layers[i], scene.weather_maps[i], scene.shape, scene.detail, scene.march, origin,
            0.0, scene.cloud_lights.light[0].direction, settings.shadow_map_steps);
    }
    return exp(-optical_depth);
}

// clouds/sky_shade.comp: the LightSet members that say what the clouds do to the light beneath
// them, for `camera` (km): the shadow map's mean and the clouds' mean transmittance and
// luminance over the upper hemisphere from the ground below the camera, and both weighted by the
// cosine for the ground.
void ShadeLightsUnderClouds(const CloudScene& scene, const CloudSettings& settings, vec3 camera,
                            LightSet& lights) {
    if (scene.layers.empty()) return;  // a clear sky: nothing to shade
    constexpr int kShadeSqrt = kCloudSkyShadeSize;
    const vec3 up = normalize(camera);
    vec4 sum(0.0), ground_sum(0.0);
    for (int i = 0; i < kShadeSqrt * kShadeSqrt; ++i) {
        const CloudMarchState state = MarchCloudLayers(
            scene, scene.weather_from_frame * (up * scene.atmosphere.bottom_radius), 0.0,
            scene.weather_from_frame * CloudSkyShadeDirection(i, kShadeSqrt, up), 0.5,
            scene.ground_order);
        sum += vec4(state.luminance, state.transmittance);
        ground_sum +=
            vec4(state.luminance, state.transmittance) * CloudSkyShadeCosine(i, kShadeSqrt);
    }
    const int n = settings.shadow_map_size;
    Number shadow = 0.0;
    for (int y = 0; y < n; ++y) {
        for (int x = 0; x < n; ++x) {
            shadow +=
                CloudShadowMapTexel(scene, settings, camera, (vec2(x, y) + vec2(0.5)) / Number(n));
        }
    }
    // The lowest cloud's base: rain and snow shafts reach the ground but are not clouds.
    Number base = 1e9;
    for (const CloudLayerParameters& layer : scene.layers) {
        if (layer.precipitation_shaft < 0.5) base = min(base, layer.base_altitude);
    }
    const vec4 mean = sum / Number(kShadeSqrt * kShadeSqrt);
    const vec4 ground_mean = ground_sum * (2.0 / Number(kShadeSqrt * kShadeSqrt));
    lights.cloud_base = base;
    lights.cloud_direct = shadow / Number(n * n);
    lights.cloud_sky = mean.w;
    lights.cloud_luminance = vec3(mean);
    lights.cloud_ground_sky = ground_mean.w;
    lights.cloud_ground_luminance = vec3(ground_mean);
    lights.cloud_shaded = 1.0;
}

// CloudPasses::CopyShade: the shade's members of `from` into `to`.
void CopyCloudShade(const LightSet& from, LightSet& to) {
    to.cloud_base = from.cloud_base;
    to.cloud_direct = from.cloud_direct;
    to.cloud_sky = from.cloud_sky;
    to.cloud_luminance = from.cloud_luminance;
    to.cloud_ground_sky = from.cloud_ground_sky;
    to.cloud_ground_luminance = from.cloud_ground_luminance;
    to.cloud_shaded = from.cloud_shaded;
}

// The scene the renderer draws for this camera: LUTs as read back from the GPU (so the CPU
// samples what the GPU samples), the noise and weather maps as uploaded, and the atmosphere's
// lights shaded by the clouds as AtmosphereRenderer::Update shades them.
CloudScene MakeCloudScene(const Atmosphere& atmosphere, const LutImage& transmittance,
                          const LutImage& multiple_scattering, const LutImage& irradiance,
                          const clouds::Weather& weather, const CloudSettings& settings,
                          const clouds::CloudNoise& noise, const Camera& camera,
                          const Lights& lights, const CloudView& view) {
    CloudScene scene;
    scene.atmosphere = MakeShaderParameters<AtmosphereParameters>(atmosphere);
    scene.transmittance = FromImage(transmittance);
    scene.multiple_scattering = FromImage(multiple_scattering);
    scene.irradiance = FromImage(irradiance);
    for (const clouds::CloudLayer& layer : weather.layers) {
        const clouds::WeatherMap map = clouds::BuildWeatherMap(layer);
        scene.layers.push_back(MakeCloudLayerParameters<CloudLayerParameters>(
            layer, clouds::LayerTopFraction(layer, map), settings, atmosphere.bottom_radius,
            view.time));
        scene.weather_maps.push_back(ToTexture(map));
    }
    scene.shape = ToTexture(noise.shape);
    scene.detail = ToTexture(noise.detail);
    scene.scattering = MakeCloudScatteringParameters<CloudScatteringParameters>(
        settings, atmosphere.ground_albedo);
    scene.march = MakeCloudMarchParameters<CloudMarchParameters>(settings);
    SetCloudSunDepthFrame(scene.march, settings, scene.layers,
                          scene.weather_from_frame * (camera.position / 1000.0));
    scene.lights = MakeLightSet<LightSet>(lights, camera.position);
    scene.cloud_lights =
        MakeCloudLightSet<LightSet>(lights, camera.position, view.weather_from_world);
    scene.weather_from_frame = view.weather_from_world;
    scene.order = CloudLayerOrder(weather, glm::length(camera.position) - atmosphere.bottom_radius);
    scene.ground_order = CloudLayerOrder(weather, 0.0);
    scene.aerial_perspective_steps = settings.aerial_perspective_steps;
    scene.sun_depth = CloudSunDepthVolume(scene, settings);
    // The shade's own trace reads the cloud lights unshaded; the clouds' trace, shaded.
    ShadeLightsUnderClouds(scene, settings, camera.position / 1000.0, scene.lights);
    CopyCloudShade(scene.lights, scene.cloud_lights);
    return scene;
}

}  // namespace
}  // namespace zenith::sky::ref
