// The cloud passes' uniform block and textures, after atmosphere/interface.glsl. One C++ mirror
// in sky/src/gl/cloud_uniforms.h, checked with static_assert against std140.
const int kCloudMaxLayers = 4;

layout(std140, binding = 4) uniform CloudBlock {
    CloudLayerParameters cloud_layers[kCloudMaxLayers];
    CloudScatteringParameters cloud_scattering;
    CloudMarchParameters cloud_march;
    LightSet cloud_lights;               // the lights with directions in the weather frame
    vec4 weather_from_frame[3];          // rotation, columns (xyz)
    vec4 previous_view_from_frame[3];    // rotation: this frame -> the previous camera's view
    vec3 previous_camera_km;             // the previous camera in this frame
    float previous_tan_half_fov;
    ivec2 trace_size;                    // cells of the trace, each block x block pixels
    ivec2 trace_offset;                  // the pixel of each block traced this frame
    int block;
    int cloud_layer_count;
    int cloud_light_count;
    int history_valid;
    float frame_jitter;                  // this frame's shift of the samples along the rays
    float history_weight;
    float previous_aspect;
    int cloud_aerial_perspective_steps;
    float shadow_map_extent_km;
    int shadow_map_size;
    int shadow_map_steps;
    int cloud_padding0;
    // The layers in the order a ray from the camera meets them (CloudLayerOrder on the CPU: the
    // camera's layer and those below it downward, then those above upward). The same for every
    // pixel, so the weather maps are indexed by a dynamically uniform index, as GLSL requires.
    ivec4 cloud_layer_order;
};

layout(binding = 7) uniform sampler3D shape_noise;
layout(binding = 8) uniform sampler3D detail_noise;
layout(binding = 9) uniform sampler2D weather_maps[kCloudMaxLayers];  // units 9-12
layout(binding = 13) uniform sampler2D cloud_trace;        // rgb luminance, a transmittance
layout(binding = 14) uniform sampler2D cloud_trace_depth;  // r: mean depth (km), -1 for none
layout(binding = 15) uniform sampler2D cloud_history;
layout(binding = 16) uniform sampler2D cloud_history_depth;

mat3 WeatherFromFrame() {
    return mat3(weather_from_frame[0].xyz, weather_from_frame[1].xyz, weather_from_frame[2].xyz);
}

// Marches every layer along `view` (this frame's world direction) from the camera, front to
// back, and applies the aerial perspective at the clouds' mean depth. Returns (L, T) and the
// mean depth in km (-1 where no cloud was met).
vec4 TraceClouds(vec3 view, float jitter, out float depth) {
    mat3 to_weather = WeatherFromFrame();
    vec3 origin = to_weather * camera_km;
    vec3 direction = to_weather * view;
    float r = length(origin);
    float mu = dot(origin, direction) / r;
    CloudMarchState state = CloudMarchStart();
    for (int k = 0; k < cloud_layer_count; ++k) {
        int i = cloud_layer_order[k];
        vec2 interval = CloudLayerInterval(cloud_layers[i], r, mu, camera_altitude_km,
                                           cloud_march.max_distance);
        MarchCloudLayer(atmosphere, transmittance_texture, transmittance_size, irradiance_texture,
                        irradiance_size, cloud_layers[i], weather_maps[i], shape_noise,
                        detail_noise, cloud_scattering, cloud_march, cloud_lights,
                        cloud_light_count, origin, direction, interval, jitter, state);
    }
    depth = CloudMeanDepth(state);
    return CloudApplyAerialPerspective(atmosphere, transmittance_texture, transmittance_size,
                                       multiple_scattering_texture, multiple_scattering_size,
                                       irradiance_texture, irradiance_size, lights, camera_km,
                                       camera_altitude_km, view, state,
                                       cloud_aerial_perspective_steps);
}
