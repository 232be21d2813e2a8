layout(local_size_x = kLutGroupSize, local_size_y = kLutGroupSize) in;
layout(binding = kOutputImageUnit, rgba32f) uniform writeonly image2D output_image;

void main() {
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(texel, multiple_scattering_size))) return;
    vec2 uv = (vec2(texel) + 0.5) / vec2(multiple_scattering_size);
    vec3 psi = ComputeMultipleScatteringTexel(atmosphere, transmittance_texture, uv,
                                              multiple_scattering_size,
                                              multiple_scattering_directions_sqrt,
                                              multiple_scattering_steps);
    imageStore(output_image, texel, vec4(psi, 1.0));
}
