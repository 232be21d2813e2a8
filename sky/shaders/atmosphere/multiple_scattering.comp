// One order of the multiple-scattering LUT (ComputeScatteringOrderTexel), dispatched for orders
// 2 .. K in turn (AtmospherePasses::BuildMultipleScattering): reads order k - 1 from
// multiple_scattering_texture, writes order k to order_image and adds it to the LUT, output_image,
// which after order K holds Psi_ms and its moments. Both images are kMultipleScatteringTiles
// tiles wide (MultipleScatteringTexel).
layout(local_size_x = kLutGroupSize, local_size_y = kLutGroupSize) in;
layout(binding = kOutputImageUnit, rgba32f) uniform image2D output_image;
layout(binding = kScatteringOrderImageUnit, rgba32f) uniform writeonly image2D order_image;
layout(location = 0) uniform int scattering_order;       // k
layout(location = 1) uniform int last_scattering_order;  // K

void main() {
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(texel, multiple_scattering_size))) return;
    vec2 uv = (vec2(texel) + 0.5) / vec2(multiple_scattering_size);
    ScatteringOrder o = ComputeScatteringOrderTexel(
        atmosphere, transmittance_texture, multiple_scattering_texture, scattering_order, uv,
        multiple_scattering_size, multiple_scattering_directions_sqrt, multiple_scattering_steps);
    ivec2 tile = ivec2(multiple_scattering_size.x, 0);
    MultipleScatteringSample sum = AccumulateScatteringOrder(
        MultipleScatteringFromTexels(imageLoad(output_image, texel),
                                     imageLoad(output_image, texel + tile),
                                     imageLoad(output_image, texel + 2 * tile)),
        o, scattering_order, last_scattering_order);
    for (int t = 0; t < kMultipleScatteringTiles; ++t) {
        imageStore(order_image, texel + t * tile, MultipleScatteringTexel(o.light, t));
        imageStore(output_image, texel + t * tile, MultipleScatteringTexel(sum, t));
    }
}
