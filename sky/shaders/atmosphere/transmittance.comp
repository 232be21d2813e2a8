layout(local_size_x = kLutGroupSize, local_size_y = kLutGroupSize) in;
layout(binding = kOutputImageUnit, rgba32f) uniform writeonly image2D output_image;

void main() {
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(texel, transmittance_size))) return;
    vec2 uv = (vec2(texel) + 0.5) / vec2(transmittance_size);
    vec3 t = ComputeTransmittanceTexel(atmosphere, uv, transmittance_size, transmittance_steps);
    imageStore(output_image, texel, vec4(t, 1.0));
}
