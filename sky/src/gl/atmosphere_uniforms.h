// C++ mirrors of the uniform blocks in sky/shaders/atmosphere/interface.glsl (std140). Offsets
// are checked here at compile time, and every member's against the linked programs by
// tests/sky/gl_bindings_gl_test.cpp, so a change on one side without the other fails.
#pragma once

#include <cstddef>
#include <glm/glm.hpp>

#include "bindings.h"
#include "zenith/sky/lut.h"

namespace zenith::sky::gl {

struct AtmosphereUniforms {  // functions.glsl: struct AtmosphereParameters
    glm::vec3 rayleigh_scattering;
    float rayleigh_scale_height;
    glm::vec3 mie_scattering;
    float mie_scale_height;
    glm::vec3 mie_extinction;
    float mie_g;
    glm::vec3 absorption_extinction;
    float absorption_center;
    glm::vec3 ground_albedo;
    float absorption_half_width;
    glm::vec3 solar_illuminance;
    float sun_angular_radius;
    float bottom_radius;
    float top_radius;
    float padding0;
    float padding1;
};
static_assert(sizeof(AtmosphereUniforms) == 112);
static_assert(offsetof(AtmosphereUniforms, mie_scattering) == 16);
static_assert(offsetof(AtmosphereUniforms, mie_g) == 44);
static_assert(offsetof(AtmosphereUniforms, solar_illuminance) == 80);
static_assert(offsetof(AtmosphereUniforms, bottom_radius) == 96);

struct LightUniforms {  // functions.glsl: struct LightSet (array elements 16-byte aligned)
    struct Light {
        glm::vec3 direction;
        float padding0;
        glm::vec3 illuminance;
        float padding1;
    } light[kMaxLights];
    int count;
    float cloud_base;
    float cloud_direct;
    float cloud_sky;
    glm::vec3 cloud_luminance;
    float cloud_ground_sky;
    glm::vec3 cloud_ground_luminance;
    float cloud_shaded;
    glm::vec3 eclipse_sun_illuminance;
    int eclipse;
    glm::vec3 eclipse_axis_point;
    float eclipse_axis_distance;
    float eclipse_sun_radius;
    float eclipse_moon_radius;
    float padding1;
    float padding2;
    glm::vec3 eclipse_around_illuminance;
    float padding3;
    glm::vec4 eclipse_limb[kEclipseLimbSamples];
    glm::vec3 night_ground_irradiance;
    float padding4;
};
static_assert(sizeof(LightUniforms::Light) == 32);
static_assert(sizeof(LightUniforms) == 320);
static_assert(offsetof(LightUniforms, night_ground_irradiance) == 304);
static_assert(offsetof(LightUniforms, eclipse_around_illuminance) == 160);
static_assert(offsetof(LightUniforms, eclipse_limb) == 176);
static_assert(offsetof(LightUniforms, eclipse_sun_illuminance) == 112);
static_assert(offsetof(LightUniforms, eclipse) == 124);
static_assert(offsetof(LightUniforms, eclipse_axis_point) == 128);
static_assert(offsetof(LightUniforms, eclipse_sun_radius) == 144);
static_assert(offsetof(LightUniforms, cloud_ground_luminance) == 96);
static_assert(offsetof(LightUniforms, count) == 64);
static_assert(offsetof(LightUniforms, cloud_base) == 68);
static_assert(offsetof(LightUniforms, cloud_luminance) == 80);

struct SettingsUniforms {  // interface.glsl: SettingsBlock
    glm::ivec2 transmittance_size;
    glm::ivec2 multiple_scattering_size;
    glm::ivec2 irradiance_size;
    glm::ivec2 sky_view_size;
    glm::ivec4 aerial_perspective_size;
    int transmittance_steps;
    int multiple_scattering_directions_sqrt;
    int multiple_scattering_steps;
    int irradiance_directions_sqrt;
    int irradiance_steps;
    int sky_view_steps;
    int aerial_perspective_steps;
    float aerial_perspective_range_km;
};
static_assert(sizeof(SettingsUniforms) == 80);
static_assert(offsetof(SettingsUniforms, aerial_perspective_size) == 32);
static_assert(offsetof(SettingsUniforms, transmittance_steps) == 48);

struct FrameUniforms {  // interface.glsl: FrameBlock
    glm::vec3 camera_km;
    float tan_half_fov;
    glm::vec4 world_from_view[3];
    glm::ivec2 output_size;
    float aspect;
    int ray_march_steps;
    int viewport_x;
    int draw_sun_disk;
    float camera_altitude_km;
    int moon_enabled;
    glm::vec3 moon_direction;
    float moon_angular_radius;
    float moon_albedo;
    int stars_enabled;
    float horizon_zenith;
    float cos_sun_radius;
    glm::vec3 sky_view_up;
    float cos_moon_radius;
    glm::vec3 sky_view_x;
    int viewport_y;
    float scene_near_m;
    float scene_depth_offset;
    float scene_depth_slope;
    int scene_depth_reversed;
    glm::vec3 moon_sunlight;
    int night_sky_enabled;
    int star_visibility;
    int environment_size;
    float sun_disk_scale;
    float moon_disk_scale;
    glm::vec3 sun_disk_direction;
    int frame_padding1;
    glm::vec3 moon_disk_direction;
    int frame_padding2;
    glm::vec4 moon_shadow[kMoonShadowSamples];
    float moon_shadow_axis_min_km;
    float moon_shadow_axis_max_km;
    float moon_distance_km;
    int moon_shadow_enabled;
};
static_assert(MoonDisk::kShadowSamples == kMoonShadowSamples);
static_assert(sizeof(FrameUniforms) == 1280);
static_assert(offsetof(FrameUniforms, moon_shadow) == 240);
static_assert(offsetof(FrameUniforms, sun_disk_direction) == 208);
static_assert(offsetof(FrameUniforms, moon_disk_direction) == 224);
static_assert(offsetof(FrameUniforms, moon_sunlight) == 176);
static_assert(offsetof(FrameUniforms, night_sky_enabled) == 188);
static_assert(offsetof(FrameUniforms, scene_near_m) == 160);
static_assert(offsetof(FrameUniforms, moon_direction) == 96);
static_assert(offsetof(FrameUniforms, stars_enabled) == 116);
static_assert(offsetof(FrameUniforms, sky_view_up) == 128);
static_assert(offsetof(FrameUniforms, sky_view_x) == 144);
static_assert(offsetof(FrameUniforms, world_from_view) == 16);
static_assert(offsetof(FrameUniforms, output_size) == 64);
static_assert(offsetof(FrameUniforms, viewport_x) == 80);
static_assert(offsetof(FrameUniforms, viewport_y) == 156);

struct PrecipitationUniforms {  // atmosphere/precipitation_block.glsl: PrecipitationBlock
    glm::vec4 world_from_box[3];
    glm::vec3 phase;
    float box_size;
    glm::vec3 box_velocity;
    float exposure_s;
    float diameter_m;
    float coverage_scale;
    int snow;
    int has_scene_depth;
};
static_assert(sizeof(PrecipitationUniforms) == 96);
static_assert(offsetof(PrecipitationUniforms, phase) == 48);
static_assert(offsetof(PrecipitationUniforms, box_velocity) == 64);
static_assert(offsetof(PrecipitationUniforms, diameter_m) == 80);

// atmosphere/environment_sh.comp: EnvironmentShStorage (std430), the environment's spherical
// harmonics, coefficient i in environment_sh[i].rgb (zenith/sky/environment.h's order).
struct EnvironmentShStorage {
    glm::vec4 environment_sh[9];
};
static_assert(sizeof(EnvironmentShStorage) == 144);

// Uniform locations of atmosphere/multiple_scattering.comp (layout(location = N)).
constexpr int kScatteringOrderLocation = 0;      // int scattering_order: k
constexpr int kLastScatteringOrderLocation = 1;  // int last_scattering_order: K

}  // namespace zenith::sky::gl
