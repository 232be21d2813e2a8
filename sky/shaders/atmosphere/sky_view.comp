layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0, rgba32f) uniform writeonly image2D output_image;

void main() {
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(texel, sky_view_size))) return;
    vec2 uv = (vec2(texel) + 0.5) / vec2(sky_view_size);
    vec3 l = ComputeSkyViewTexel(atmosphere, transmittance_texture, transmittance_size,
                                 multiple_scattering_texture, multiple_scattering_size,
                                 irradiance_texture, irradiance_size, lights, camera_km,
                                 camera_altitude_km, uv, sky_view_size, sky_view_steps);
    imageStore(output_image, texel, vec4(l, 1.0));
}
