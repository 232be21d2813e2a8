// The clouds on the CPU: the GL trace pass (clouds/interface.glsl TraceClouds) in double
// precision over the same shared functions, for GPU-vs-CPU parity tests and for host queries
// such as the sunlight reaching the aircraft through the clouds.
#pragma once

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
    CloudScatteringParameters scattering{};
    CloudMarchParameters march{};
    LightSet lights{};        // the atmosphere's, for the aerial perspective
    LightSet cloud_lights{};  // MakeCloudLightSet's, in the weather frame
    mat3 weather_from_frame{1.0};
    std::vector<int> order;
    int aerial_perspective_steps = 8;
};

// The scene the renderer draws for this camera: LUTs as read back from the GPU (so the CPU
// samples what the GPU samples), the noise and weather maps as uploaded.
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
        scene.layers.push_back(MakeCloudLayerParameters<CloudLayerParameters>(
            layer, settings, atmosphere.bottom_radius, view.time));
        scene.weather_maps.push_back(ToTexture(clouds::BuildWeatherMap(layer)));
    }
    scene.shape = ToTexture(noise.shape);
    scene.detail = ToTexture(noise.detail);
    scene.scattering = MakeCloudScatteringParameters<CloudScatteringParameters>(settings);
    scene.march = MakeCloudMarchParameters<CloudMarchParameters>(settings);
    scene.lights = MakeLightSet<LightSet>(lights, camera.position);
    scene.cloud_lights =
        MakeCloudLightSet<LightSet>(lights, camera.position, view.weather_from_world);
    scene.weather_from_frame = view.weather_from_world;
    scene.order = CloudLayerOrder(weather, glm::length(camera.position) - atmosphere.bottom_radius);
    scene.aerial_perspective_steps = settings.aerial_perspective_steps;
    return scene;
}

// TraceClouds of clouds/interface.glsl: (L, T) of the clouds along `view` from `camera` (km,
// the renderer's frame; `altitude` km above the ground, exact), aerial perspective applied;
// *depth gets the mean depth (km, -1 for none).
vec4 TraceClouds(const CloudScene& scene, vec3 camera, Number altitude, vec3 view, Number jitter,
                 Number* depth = nullptr) {
    const vec3 origin = scene.weather_from_frame * camera;
    const vec3 direction = scene.weather_from_frame * view;
    const Number r = length(origin);
    const Number mu = dot(origin, direction) / r;
    CloudMarchState state = CloudMarchStart();
    const ivec2 transmittance_size(scene.transmittance.width(), scene.transmittance.height());
    const ivec2 irradiance_size(scene.irradiance.width(), scene.irradiance.height());
    for (int i : scene.order) {
        const auto layer = static_cast<std::size_t>(i);
        const vec2 interval = CloudLayerInterval(scene.layers[layer], r, mu, altitude,
                                                 scene.march.max_distance);
        MarchCloudLayer(scene.atmosphere, scene.transmittance, transmittance_size,
                        scene.irradiance, irradiance_size, scene.layers[layer],
                        scene.weather_maps[layer], scene.shape, scene.detail, scene.scattering,
                        scene.march, scene.cloud_lights, scene.cloud_lights.count, origin,
                        direction, interval, jitter, state);
    }
    if (depth != nullptr) *depth = CloudMeanDepth(state);
    return CloudApplyAerialPerspective(
        scene.atmosphere, scene.transmittance, transmittance_size, scene.multiple_scattering,
        ivec2(scene.multiple_scattering.width(), scene.multiple_scattering.height()),
        scene.irradiance, irradiance_size, scene.lights, camera, altitude, view, state,
        scene.aerial_perspective_steps);
}

}  // namespace
}  // namespace zenith::sky::ref
