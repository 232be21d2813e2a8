// The clouds' shadow on the ground (F16 §5.9): for each texel of a square of shadow_map_extent
// around the camera's ground point, the transmittance toward the main light (the Sun; the Moon
// at night, MakeCloudLightSet) through every layer, marched with shadow_map_steps steps per layer
// (density only).
layout(local_size_x = kShadowMapGroupSize, local_size_y = kShadowMapGroupSize) in;
layout(binding = kOutputImageUnit, rgba32f) uniform writeonly image2D shadow_map;

void main() {
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(texel, ivec2(shadow_map_size)))) return;
    if (cloud_light_count == 0) {  // no light reaches the clouds: nothing to shadow
        imageStore(shadow_map, texel, vec4(1.0));
        return;
    }
    vec3 ground = CloudShadowMapGroundPoint(camera_km, atmosphere.bottom_radius,
                                            shadow_map_extent_km,
                                            (vec2(texel) + 0.5) / float(shadow_map_size));
    vec3 origin = WeatherFromFrame() * ground;
    float optical_depth = 0.0;
    for (int k = 0; k < cloud_layer_count; ++k) {
        int i = cloud_layer_order[k];
        optical_depth += CloudLayerShadowDepth(cloud_layers[i], CloudWeatherMap(i), shape_noise,
                                               detail_noise, cloud_march, origin, 0.0,
                                               cloud_lights.light[0].direction,
                                               shadow_map_steps);
    }
    imageStore(shadow_map, texel, vec4(vec3(exp(-optical_depth)), 1.0));
}
