// The ground-irradiance LUT (ComputeGroundIrradianceTexel): one work group per texel, each
// invocation integrating every kDirectionsGroupSize-th direction, summed in shared memory.
layout(local_size_x = kDirectionsGroupSize) in;
layout(binding = kOutputImageUnit, rgba32f) uniform writeonly image2D output_image;

shared vec3 partial_irradiance[kDirectionsGroupSize];

void main() {
    ivec2 texel = ivec2(gl_WorkGroupID.xy);
    int lane = int(gl_LocalInvocationID.x);
    float u = (float(texel.x) + 0.5) / float(irradiance_size.x);
    // The irradiance sampler is bound but unused while this LUT is built (sky rays only).
    partial_irradiance[lane] = ComputeGroundIrradianceTexel(
        atmosphere, transmittance_texture, multiple_scattering_texture, irradiance_texture,
        irradiance_size, u, irradiance_directions_sqrt, irradiance_steps, lane,
        kDirectionsGroupSize);
    for (int half_size = kDirectionsGroupSize / 2; half_size > 0; half_size /= 2) {
        memoryBarrierShared();
        barrier();
        if (lane < half_size) partial_irradiance[lane] += partial_irradiance[lane + half_size];
    }
    if (lane == 0) imageStore(output_image, texel, vec4(partial_irradiance[0], 1.0));
}
