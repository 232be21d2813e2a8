// The far sun-depth volume (clouds/march.glsl, CloudFarSunDepth): level sun_depth_level of it, each
// texel the optical depth toward the main light through every cloud layer from its point to the
// next level up, plus that level's value where the light's ray reaches it. The host dispatches the
// levels from the top down, with a barrier between them; the top level's way is empty (0).
layout(local_size_x = kShadowMapGroupSize, local_size_y = kShadowMapGroupSize) in;
layout(binding = kOutputImageUnit, r32f) uniform writeonly image3D sun_depth_volume;
layout(location = 0) uniform int sun_depth_level;

void main() {
    ivec3 size = textureSize(cloud_sun_depth, 0);
    ivec3 texel = ivec3(gl_GlobalInvocationID.xy, sun_depth_level);
    if (any(greaterThanEqual(texel.xy, size.xy))) return;
    if (cloud_light_count == 0) {  // no light reaches the clouds: nothing to shadow
        imageStore(sun_depth_volume, texel, vec4(0.0));
        return;
    }
    vec3 light = cloud_lights.light[0].direction;
    CloudSunDepthWay way = CloudSunDepthTexelWay(cloud_march, cloud_layers[0], texel, size, light);
    float optical_depth = way.above ? SampleTexture3D(cloud_sun_depth, way.end_uvw).r : 0.0;
    for (int i = 0; i < cloud_layer_count; ++i) {
        if (cloud_layers[i].precipitation_shaft > 0.5) continue;  // below the levels' clouds
        optical_depth += CloudRayDepth(cloud_layers[i], CloudWeatherMap(i), shape_noise,
                                       detail_noise, cloud_march, way.origin, light,
                                       vec2(0.0, way.length_km), way.steps);
    }
    imageStore(sun_depth_volume, texel, vec4(optical_depth));
}
