layout(local_size_x = kIrradianceGroupSize, local_size_y = 1) in;
layout(binding = kOutputImageUnit, rgba32f) uniform writeonly image2D output_image;

void main() {
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(texel, irradiance_size))) return;
    float u = (float(texel.x) + 0.5) / float(irradiance_size.x);
    // The irradiance sampler is bound but unused while this LUT is built (sky rays only).
    vec3 e = ComputeGroundIrradianceTexel(atmosphere, transmittance_texture,
                                          multiple_scattering_texture, irradiance_texture,
                                          irradiance_size, u,
                                          irradiance_directions_sqrt, irradiance_steps);
    imageStore(output_image, texel, vec4(e, 1.0));
}
