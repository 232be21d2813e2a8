// One order of the multiple-scattering LUT (ComputeScatteringOrderTexel), dispatched for orders
// 2 .. K in turn (AtmospherePasses::BuildMultipleScattering): reads order k - 1 from
// multiple_scattering_texture, writes order k to order_image and adds it to the LUT, output_image,
// which after order K holds Psi_ms and its moments (order K adds column_image's correction). Both
// are kMultipleScatteringTiles tiles wide (MultipleScatteringTexel), column_image one. One work
// group per texel: each invocation integrates every kDirectionsGroupSize-th direction, and the
// group sums them in shared memory.
layout(local_size_x = kDirectionsGroupSize) in;
layout(binding = kOutputImageUnit, rgba32f) uniform image2D output_image;
layout(binding = kScatteringOrderImageUnit, rgba32f) uniform writeonly image2D order_image;
// The column's correction of the orders past K (ScatteringOrdersSum), one tile's size.
layout(binding = kColumnCorrectionImageUnit, rgba32f) uniform readonly image2D column_image;
layout(location = 0) uniform int scattering_order;       // k
layout(location = 1) uniform int last_scattering_order;  // K

shared vec3 partial_psi[kDirectionsGroupSize];
shared vec3 partial_q_xx[kDirectionsGroupSize];
shared vec3 partial_q_zz[kDirectionsGroupSize];
shared vec3 partial_q_xz[kDirectionsGroupSize];
shared vec3 partial_transfer[kDirectionsGroupSize];

void main() {
    ivec2 texel = ivec2(gl_WorkGroupID.xy);
    int lane = int(gl_LocalInvocationID.x);
    vec2 uv = (vec2(texel) + 0.5) / vec2(multiple_scattering_size);
    ScatteringOrder o = ComputeScatteringOrderTexel(
        atmosphere, transmittance_texture, multiple_scattering_texture, scattering_order, uv,
        multiple_scattering_size, multiple_scattering_directions_sqrt, multiple_scattering_steps,
        lane, kDirectionsGroupSize);
    partial_psi[lane] = o.light.psi;
    partial_q_xx[lane] = o.light.q_xx;
    partial_q_zz[lane] = o.light.q_zz;
    partial_q_xz[lane] = o.light.q_xz;
    partial_transfer[lane] = o.transfer;
    for (int half_size = kDirectionsGroupSize / 2; half_size > 0; half_size /= 2) {
        memoryBarrierShared();
        barrier();
        if (lane < half_size) {
            partial_psi[lane] += partial_psi[lane + half_size];
            partial_q_xx[lane] += partial_q_xx[lane + half_size];
            partial_q_zz[lane] += partial_q_zz[lane + half_size];
            partial_q_xz[lane] += partial_q_xz[lane + half_size];
            partial_transfer[lane] += partial_transfer[lane + half_size];
        }
    }
    if (lane != 0) return;
    o.light.psi = partial_psi[0];
    o.light.q_xx = partial_q_xx[0];
    o.light.q_zz = partial_q_zz[0];
    o.light.q_xz = partial_q_xz[0];
    o.transfer = partial_transfer[0];
    ivec2 tile = ivec2(multiple_scattering_size.x, 0);
    MultipleScatteringSample sum = AccumulateScatteringOrder(
        MultipleScatteringFromTexels(imageLoad(output_image, texel),
                                     imageLoad(output_image, texel + tile),
                                     imageLoad(output_image, texel + 2 * tile)),
        o, scattering_order, last_scattering_order, imageLoad(column_image, texel).rgb);
    for (int t = 0; t < kMultipleScatteringTiles; ++t) {
        imageStore(order_image, texel + t * tile, MultipleScatteringTexel(o.light, t));
        imageStore(output_image, texel + t * tile, MultipleScatteringTexel(sum, t));
    }
}
