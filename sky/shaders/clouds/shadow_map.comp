// The clouds' shadow on the ground (F16 §5.9): for each texel of a square of shadow_map_extent
// around the camera's ground point, the transmittance toward the main light (the Sun; the Moon
// at night, MakeCloudLightSet) through every layer,
// marched with shadow_map_steps steps per layer (density only).
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0, rgba32f) uniform writeonly image2D shadow_map;

void main() {
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(texel, ivec2(shadow_map_size)))) return;
    if (cloud_light_count == 0) {  // no light reaches the clouds: nothing to shadow
        imageStore(shadow_map, texel, vec4(1.0));
        return;
    }
    // East/north offset (km) in the camera's tangent plane, mapped onto the sphere as arc
    // length from the camera's ground point (the renderer's +z axis).
    vec2 offset = ((vec2(texel) + 0.5) / float(shadow_map_size) - 0.5) * shadow_map_extent_km;
    vec3 up = normalize(camera_km);
    vec3 east = normalize(cross(vec3(0.0, 0.0, 1.0), up));
    if (!(length(cross(vec3(0.0, 0.0, 1.0), up)) > 1e-6)) east = vec3(1.0, 0.0, 0.0);
    vec3 north = cross(up, east);
    float arc = length(offset);
    float theta = arc / atmosphere.bottom_radius;
    vec3 along = arc > 0.0 ? (east * offset.x + north * offset.y) / arc : east;
    vec3 ground = atmosphere.bottom_radius * (up * cos(theta) + along * sin(theta));

    mat3 to_weather = WeatherFromFrame();
    vec3 origin = to_weather * ground;
    vec3 sun = cloud_lights.light[0].direction;
    float r = length(origin);
    float mu = dot(origin, sun) / r;
    float optical_depth = 0.0;
    for (int k = 0; k < cloud_layer_count; ++k) {
        int i = cloud_layer_order[k];
        vec2 interval = CloudLayerInterval(cloud_layers[i], r, mu, 0.0, cloud_march.max_distance);
        float length_km = interval.y - interval.x;
        if (!(length_km > 0.0)) continue;
        float dt = length_km / float(shadow_map_steps);
        for (int j = 0; j < shadow_map_steps; ++j) {
            vec3 p = origin + sun * (interval.x + (float(j) + 0.5) * dt);
            optical_depth += SampleCloudDensity(cloud_layers[i], weather_maps[i], shape_noise,
                                                detail_noise, p).density *
                             cloud_march.extinction * dt;
        }
    }
    imageStore(shadow_map, texel, vec4(vec3(exp(-optical_depth)), 1.0));
}
