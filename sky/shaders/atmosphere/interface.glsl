// Uniform blocks and samplers of the atmosphere passes. Each block has one C++ mirror in
// sky/src/gl/atmosphere_uniforms.h, checked with static_assert against std140 and by
// tests/sky/gl_bindings_gl_test.cpp against the linked programs.
layout(std140, binding = kAtmosphereBlockBinding) uniform AtmosphereBlock {
    AtmosphereParameters atmosphere;
};

layout(std140, binding = kLightBlockBinding) uniform LightBlock {
    LightSet lights;
};

layout(std140, binding = kSettingsBlockBinding) uniform SettingsBlock {
    ivec2 transmittance_size;
    ivec2 multiple_scattering_size;
    ivec2 irradiance_size;
    ivec2 sky_view_size;
    ivec4 aerial_perspective_size;  // xyz; w unused
    int transmittance_steps;
    int multiple_scattering_directions_sqrt;
    int multiple_scattering_steps;
    int irradiance_directions_sqrt;
    int irradiance_steps;
    int sky_view_steps;
    int aerial_perspective_steps;
    float aerial_perspective_range_km;
};

layout(std140, binding = kFrameBlockBinding) uniform FrameBlock {
    vec3 camera_km;  // planet-centred
    float tan_half_fov;
    vec4 world_from_view[3];  // columns right, up, backward (xyz)
    ivec2 output_size;
    float aspect;
    int ray_march_steps;
    int viewport_x;  // origin of the viewport drawn into (a host's framebuffer may offset it)
    int draw_sun_disk;
    float camera_altitude_km;  // above the ground, computed in double on the CPU
    int moon_enabled;
    vec3 moon_direction;
    float moon_angular_radius;
    float moon_albedo;
    int stars_enabled;
    float horizon_zenith;   // per-frame constants of the composite, computed on the CPU with the
    float cos_sun_radius;   // same functions: the Sky-View frame, the horizon's zenith angle and
    vec3 sky_view_up;       // the cosines of the disks' radii
    float cos_moon_radius;
    vec3 sky_view_x;
    int viewport_y;
    // The host's depth d to eye depth: scene_near_m / (scene_depth_offset + scene_depth_slope d)
    // (SceneDepth: standard or reversed, finite or infinite far plane); sky where d is at the
    // far plane (1, or 0 when scene_depth_reversed).
    float scene_near_m;
    float scene_depth_offset;
    float scene_depth_slope;
    int scene_depth_reversed;
    vec3 moon_sunlight;  // MoonDisk::sunlight: the Sun's light reaching the Moon (lunar eclipse)
    // The night sky's light (zenith/sky/night_sky.h): a map in the Sky-View LUT's
    // parameterisation and frame, added to the sky when night_sky_enabled; star_visibility
    // draws each pixel's stars in the share the eye sees against that sky (StarVisibility).
    int night_sky_enabled;
    int star_visibility;
    int environment_size;  // texels per side of the environment's cube faces (environment.h)
    // Where refraction shows the disks (ApparentPlace): the apparent centres and vertical
    // scales; the geometric ones are lights.light[0].direction and moon_direction.
    float sun_disk_scale;
    float moon_disk_scale;
    vec3 sun_disk_direction;
    int frame_padding1;
    vec3 moon_disk_direction;
    int frame_padding2;
    // In a lunar eclipse (moon_shadow_enabled), the sunlight reaching the Moon at
    // kMoonShadowSamples distances from the Earth's shadow's axis (MoonDisk::Shadow), from
    // moon_shadow_axis_min_km to moon_shadow_axis_max_km; moon_distance_km places the disk.
    vec4 moon_shadow[kMoonShadowSamples];
    float moon_shadow_axis_min_km;
    float moon_shadow_axis_max_km;
    float moon_distance_km;
    int moon_shadow_enabled;
};

// Units and bindings: bindings.glsl.
layout(binding = kTransmittanceUnit) uniform sampler2D transmittance_texture;
layout(binding = kMultipleScatteringUnit) uniform sampler2D multiple_scattering_texture;
layout(binding = kIrradianceUnit) uniform sampler2D irradiance_texture;
layout(binding = kSkyViewUnit) uniform sampler2D sky_view_texture;
layout(binding = kStarUnit) uniform sampler2D star_texture;  // point sources, frame-sized
layout(binding = kSceneDepthUnit) uniform sampler2D scene_depth_texture;  // the host's (0..1)
layout(binding = kAerialPerspectiveUnit) uniform sampler3D aerial_perspective_texture;
layout(binding = kNightSkyUnit) uniform sampler2D night_sky_texture;

// World direction through the centre of pixel/cell `cell` of a grid of `grid` cells covering the
// view (NDC y up, so row 0 is the bottom row, as in GL textures).
vec3 CameraDirection(vec2 cell, vec2 grid) {
    vec2 ndc = 2.0 * (cell + 0.5) / grid - 1.0;
    vec3 view = vec3(ndc.x * tan_half_fov * aspect, ndc.y * tan_half_fov, -1.0);
    return normalize(world_from_view[0].xyz * view.x + world_from_view[1].xyz * view.y +
                     world_from_view[2].xyz * view.z);
}

// The distance (km) along pixel `pixel`'s ray to the host's geometry, from its depth (SceneDepth:
// scene_depth_* above), or -1 where the depth is at the far plane (sky).
float SceneDistanceKm(ivec2 pixel) {
    float depth = texelFetch(scene_depth_texture, pixel, 0).r;
    bool geometry = scene_depth_reversed != 0 ? depth > 0.0 : depth < 1.0;
    if (!geometry) return -1.0;
    float eye_depth = scene_near_m / (scene_depth_offset + scene_depth_slope * depth);
    vec2 ndc = 2.0 * (vec2(pixel) + 0.5) / vec2(output_size) - 1.0;
    return eye_depth * length(vec3(ndc.x * tan_half_fov * aspect, ndc.y * tan_half_fov, 1.0)) /
           1000.0;
}

// The sky's luminance along `direction` from the camera, as the composite and the environment
// draw it: the Sky-View LUT inside the atmosphere, or (`ray_march`, a constant of the program:
// above it, or asked for) a ray march, plus the night sky's diffuse light through the atmosphere
// (computed on the CPU per frame).
vec3 SkyLuminance(vec3 direction, bool ray_march) {
    vec3 luminance = ray_march
                         ? IntegrateScatteredLuminance(
                               atmosphere, transmittance_texture, multiple_scattering_texture,
                               irradiance_texture, lights, camera_km, camera_altitude_km,
                               direction, 0.0, 1e9, ray_march_steps, true).luminance
                         : SampleSkyViewInFrame(sky_view_texture, sky_view_up, sky_view_x,
                                                horizon_zenith, direction);
    if (night_sky_enabled != 0) {
        luminance += SampleSkyViewInFrame(night_sky_texture, sky_view_up, sky_view_x,
                                          horizon_zenith, direction);
    }
    return luminance;
}

// The direction through the centre of texel `texel` of the environment's atlas (environment.frag):
// face texel.y / environment_size, OpenGL's cube map orientation (CubeFaceDirection on the CPU).
vec3 EnvironmentDirection(ivec2 texel) {
    int face = texel.y / environment_size;
    vec2 uv = 2.0 * (vec2(texel.x, texel.y - face * environment_size) + 0.5) /
                  float(environment_size) - 1.0;
    vec3 d;
    if (face == 0) {
        d = vec3(1.0, -uv.y, -uv.x);
    } else if (face == 1) {
        d = vec3(-1.0, -uv.y, uv.x);
    } else if (face == 2) {
        d = vec3(uv.x, 1.0, uv.y);
    } else if (face == 3) {
        d = vec3(uv.x, -1.0, -uv.y);
    } else if (face == 4) {
        d = vec3(uv.x, -uv.y, 1.0);
    } else {
        d = vec3(-uv.x, -uv.y, -1.0);
    }
    return normalize(d);
}
