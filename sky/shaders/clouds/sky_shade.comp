// What the clouds do to the light beneath them (F16 §5.9.2, LightSet's cloud_* members): the
// mean of sky_shade_trace.frag's directions (equal solid angles of the upper hemisphere seen
// from the ground below the camera), the same weighted by the cosine for the ground, and the
// mean of the shadow map, written into the cloud
// members of a LightSet, which CloudPasses copies into the atmosphere's light block each frame
// for the later passes: the Sky-View and aerial-perspective LUTs, the composite's ray march and
// the clouds' own aerial perspective. One invocation: some 16,000 texel reads.
layout(local_size_x = 1) in;
layout(std140, binding = kLightStorageBinding) buffer LightStorage {
    LightSet shaded_lights;
};
layout(binding = kShadeDirectionsImageUnit, rgba32f) uniform readonly image2D shade_directions;
layout(binding = kShadowMapImageUnit, rgba32f) uniform readonly image2D shadow_map_image;

void main() {
    vec4 shade = vec4(0.0);
    vec4 ground_shade = vec4(0.0);  // weighted by the cosine, for the ground
    for (int y = 0; y < sky_shade_size; ++y) {
        for (int x = 0; x < sky_shade_size; ++x) {
            vec4 direction = imageLoad(shade_directions, ivec2(x, y));
            shade += direction;
            ground_shade += direction * CloudSkyShadeCosine(y * sky_shade_size + x, sky_shade_size);
        }
    }
    shade /= float(sky_shade_size * sky_shade_size);
    ground_shade *= 2.0 / float(sky_shade_size * sky_shade_size);
    float shadow = 0.0;
    for (int y = 0; y < shadow_map_size; ++y) {
        for (int x = 0; x < shadow_map_size; ++x) {
            shadow += imageLoad(shadow_map_image, ivec2(x, y)).r;
        }
    }
    // The lowest cloud's base: rain and snow shafts reach the ground but are not clouds.
    float base = 1e9;
    for (int k = 0; k < cloud_layer_count; ++k) {
        if (cloud_layers[k].precipitation_shaft < 0.5) base = min(base, cloud_layers[k].base_altitude);
    }
    shaded_lights.cloud_base = base;
    shaded_lights.cloud_direct = shadow / float(shadow_map_size * shadow_map_size);
    shaded_lights.cloud_sky = shade.a;
    shaded_lights.cloud_luminance = shade.rgb;
    shaded_lights.cloud_ground_sky = ground_shade.a;
    shaded_lights.cloud_ground_luminance = ground_shade.rgb;
    shaded_lights.cloud_shaded = 1.0;
}
