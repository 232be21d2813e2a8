// SI weather and CloudSettings -> the shaders' kilometre structs (clouds/functions.glsl and
// clouds/march.glsl), for either side of the shared code: the double CPU mirror or the float
// std140 GL mirror, like shader_parameters.h for the atmosphere.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <glm/glm.hpp>
#include <type_traits>
#include <vector>

#include "zenith/sky/atmosphere_renderer.h"
#include "zenith/sky/clouds/weather.h"

namespace zenith::sky {

// Directions per side of the clouds' sky shade (clouds/sky_shade_trace.comp): 16^2 over the
// upper hemisphere, equal solid angles.
inline constexpr int kCloudSkyShadeSize = 16;

// Layer `layer` after `time` seconds of wind, on a planet of bottom_radius metres; its clouds
// reach top_fraction of its thickness (clouds::CloudTopFraction of its map).
template <typename Parameters>
Parameters MakeCloudLayerParameters(const clouds::CloudLayer& layer, double top_fraction,
                                    const CloudSettings& s, double bottom_radius, double time) {
    using Scalar = decltype(Parameters{}.bottom_radius);
    constexpr double kKm = 1000.0;
    // The map is sampled at ground + offset: to carry the clouds downwind by d, offset = -d.
    const glm::dvec2 drift = clouds::WindDisplacement(layer, time);
    Parameters p{};
    p.bottom_radius = Scalar(bottom_radius / kKm);
    p.base_altitude = Scalar(layer.base_altitude / kKm);
    p.top_altitude = Scalar(layer.top_altitude / kKm);
    p.weather_period = Scalar(layer.map_period / kKm);
    p.shape_period = Scalar(s.shape_period / kKm);
    p.shape_period_y = Scalar(s.shape_period / kKm * s.noise.shape_size.y / s.noise.shape_size.x);
    p.detail_period = Scalar(s.detail_period / kKm);
    p.erosion_strength = Scalar(s.erosion);
    p.wind_offset_x = Scalar(-drift.x / kKm);
    p.wind_offset_y = Scalar(-drift.y / kKm);
    p.cloud_top_altitude = Scalar(
        (layer.base_altitude + (layer.top_altitude - layer.base_altitude) * top_fraction) / kKm);
    // A precipitation shaft's density scales heavy rain's or snow's extinction instead.
    p.extinction_scale = Scalar(
        layer.precipitation_shaft ? clouds::HeavyPrecipitationExtinction(layer.snow) / s.extinction
                                  : layer.extinction_scale);
    p.ground_fog = Scalar(layer.ground_fog ? 1.0 : 0.0);
    p.precipitation_shaft = Scalar(layer.precipitation_shaft ? 1.0 : 0.0);
    // Downwind, whatever the wind's speed.
    p.shear_x = Scalar(-layer.shear * std::sin(layer.wind_from) / kKm);
    p.shear_y = Scalar(-layer.shear * std::cos(layer.wind_from) / kKm);
    return p;
}

// Nodes per side of the slab's tables (clouds/functions.glsl: kCloudSlabTableSize, checked in
// cloud_parameters.cpp).
inline constexpr int kCloudSlabTableSize = 8;

// The slab's tables (clouds/functions.glsl, CloudSlabTables) for the phase function of `s`, node
// (depth i, cosine j) of table t at number (t kCloudSlabTableSize + j) kCloudSlabTableSize + i:
// - t = 0, the lit face's source scale c: the loss of the renderer's source through a
//   homogeneous non-absorbing slab over a black ground (1 - the light it sends out, by a
//   deterministic quadrature of its formal solution; < 0 where it sends out more) over what the
//   unit lit-face source sends out of the same slab. Zeros when s.lit_face_source is false.
// - t = 1, the beam's cosine in the diffuse field's source less mu0 (CloudBeamCosine): the one
//   with which the field's closed form transmits what the exact slab does
//   (ConservativeSlabTransfer).
// Computed once per phase function (tens of ms; the last eight are kept), then looked up.
using CloudSlabTableNodes = std::array<double, 2 * kCloudSlabTableSize * kCloudSlabTableSize>;
CloudSlabTableNodes CloudSlabTables(const CloudSettings& s);

// ground_albedo: the atmosphere's (per channel), which the clouds' diffuse light sees as its
// luminance, Rec. 709 weights.
template <typename Parameters>
Parameters MakeCloudScatteringParameters(const CloudSettings& s, const glm::dvec3& ground_albedo) {
    using Scalar = decltype(Parameters{}.albedo);
    Parameters p{};
    static_assert(std::extent_v<decltype(Parameters::slab_tables)> * 4 ==
                  std::tuple_size_v<CloudSlabTableNodes>);
    const CloudSlabTableNodes tables = CloudSlabTables(s);
    for (std::size_t k = 0; k < tables.size(); ++k) {
        p.slab_tables[k / 4][static_cast<int>(k % 4)] = Scalar(tables[k]);
    }
    p.forward_g = Scalar(s.forward_g);
    p.backward_g = Scalar(s.backward_g);
    p.lobe_weight = Scalar(s.lobe_weight);
    p.albedo = Scalar(s.albedo);
    p.multiple_scattering = Scalar(s.multiple_scattering);
    p.ground_albedo = Scalar(glm::dot(ground_albedo, glm::dvec3(0.2126, 0.7152, 0.0722)));
    return p;
}

template <typename Parameters>
Parameters MakeCloudMarchParameters(const CloudSettings& s) {
    using Scalar = decltype(Parameters{}.extinction);
    constexpr double kKm = 1000.0;
    Parameters p{};
    p.extinction = Scalar(s.extinction * kKm);
    p.min_step = Scalar(s.min_step / kKm);
    p.max_steps = Scalar(s.max_steps);
    p.shadow_steps = Scalar(s.shadow_steps);
    p.shadow_first_step = Scalar(s.shadow_first_step / kKm);
    p.shadow_growth = Scalar(s.shadow_growth);
    p.ambient_scale = Scalar(s.ambient_scale);
    p.thick_step_refinement = Scalar(s.thick_step_refinement);
    p.oriented_slabs = Scalar(s.oriented_slabs ? 1.0 : 0.0);
    p.column_steps = Scalar(s.column_steps ? 1.0 : 0.0);
    p.min_transmittance = Scalar(s.min_transmittance);
    p.max_distance = Scalar(s.max_distance / kKm);
    p.light_shaft_steps = Scalar(s.light_shaft_steps);
    return p;
}

// The far sun-depth volume's texels: sun_depth_size^2 by sun_depth_levels, or one that no sample
// reads where there is none (sun_depth_size 0), so the sampler stays complete.
inline glm::ivec3 CloudSunDepthSize(const CloudSettings& settings) {
    return settings.sun_depth_size > 0
               ? glm::ivec3(settings.sun_depth_size, settings.sun_depth_size,
                            settings.sun_depth_levels)
               : glm::ivec3(1);
}

// The far sun-depth volume's frame in `march` (clouds/march.glsl, CloudFarSunDepth): its square
// centred below `camera` (cloud frame, km) in the dome's ground coordinates, its side, and its
// levels from the lowest of the `layers`' bases to the highest of their clouds' tops, leaving
// out precipitation shafts (below their clouds, which the light's way up from a cloud never
// meets; a shaft's own light crosses its cloud whole). No volume (extent 0) where
// settings.sun_depth_size is 0 or there are no clouds.
template <typename Parameters, typename LayerParameters>
void SetCloudSunDepthFrame(Parameters& march, const CloudSettings& settings,
                           const std::vector<LayerParameters>& layers, glm::dvec3 camera) {
    using Scalar = decltype(Parameters{}.extinction);
    march.sun_depth_extent = Scalar(0.0);
    double base = 1e9, top = -1e9;
    for (const LayerParameters& layer : layers) {
        if (layer.precipitation_shaft > 0.5) continue;
        base = std::min(base, double(layer.base_altitude));
        top = std::max(top, double(layer.cloud_top_altitude));
    }
    if (settings.sun_depth_size == 0 || !(top >= base)) return;
    const double s = glm::length(glm::dvec2(camera));
    const double radius = double(layers[0].bottom_radius);
    const glm::dvec2 ground =
        s > 0.0 ? glm::dvec2(camera) * (radius * std::atan2(s, camera.z) / s) : glm::dvec2(0.0);
    march.sun_depth_center_x = Scalar(ground.x);
    march.sun_depth_center_y = Scalar(ground.y);
    march.sun_depth_extent = Scalar(settings.sun_depth_extent / 1000.0);
    march.sun_depth_base = Scalar(base);
    march.sun_depth_top = Scalar(std::max(top, base + 0.001));
}

// The order in which a ray from a camera at `camera_altitude` (m) meets the layers (indices
// into weather.layers, bottom to top and not overlapping): the camera's layer and those below it,
// downward, then those above, upward. A ray going down meets the first kind in that order and
// can only rise into the second after its lowest point; a ray going up meets only the second.
std::vector<int> CloudLayerOrder(const clouds::Weather& weather, double camera_altitude);

// Which lights light the clouds (each costs a shadow march per sample): the Sun unless it is
// more than 10 deg below the camera's horizon (the highest clouds see it to about -5 deg, and its
// twilight then is far below moonlight); the Moon when it is up in the Lights and either the Sun
// is dropped or the Moon gives at least 1e-3 of the Sun's illuminance. Returns 0-2 lights in a
// LightSet (count = how many), directions rotated into the weather frame.
template <typename LightSet>
LightSet MakeCloudLightSet(const Lights& lights, const glm::dvec3& up,
                           const glm::dmat3& weather_from_world) {
    using Vec3 = decltype(LightSet{}.light[0].direction);
    const glm::dvec3 sun = glm::normalize(lights.sun_direction);
    const bool sun_counts = glm::dot(sun, glm::normalize(up)) > -0.17364817766693033;  // sin 10 deg
    const bool moon_counts =
        lights.moon_enabled && (!sun_counts || glm::length(lights.moon_illuminance) >=
                                                   1e-3 * glm::length(lights.sun_illuminance));
    LightSet l{};
    int count = 0;
    const auto add = [&](const glm::dvec3& direction, const glm::dvec3& illuminance) {
        l.light[count].direction = Vec3(weather_from_world * glm::normalize(direction));
        l.light[count].illuminance = Vec3(illuminance);
        ++count;
    };
    if (sun_counts) add(sun, lights.sun_illuminance);
    if (moon_counts) add(lights.moon_direction, lights.moon_illuminance);
    l.count = count;
    return l;
}

}  // namespace zenith::sky
