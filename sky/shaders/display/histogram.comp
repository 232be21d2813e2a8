// The meter, first pass: a histogram of log2 Rec.709 luminance over the frame (one bin count
// per pixel; non-finite pixels skipped), as image_io's AutoExposureEV100 sorts its pixels.
layout(local_size_x = kDisplayGroupSize, local_size_y = kDisplayGroupSize) in;
layout(binding = kDisplayInputUnit) uniform sampler2D display_input;
layout(location = 0) uniform ivec2 display_size;

shared uint group_histogram[kDisplayHistogramBins];

void main() {
    uint local = gl_LocalInvocationIndex;
    const uint kGroupInvocations = uint(kDisplayGroupSize * kDisplayGroupSize);
    for (uint b = local; b < uint(kDisplayHistogramBins); b += kGroupInvocations) {
        group_histogram[b] = 0u;
    }
    barrier();
    // Each invocation counts a kDisplayPixelsPerInvocation^2 block, so that clearing and adding
    // the group's bins (2 x 1024 operations) is spread over 64 x 64 pixels, not 16 x 16.
    ivec2 base = ivec2(gl_GlobalInvocationID.xy) * kDisplayPixelsPerInvocation;
    for (int j = 0; j < kDisplayPixelsPerInvocation; ++j) {
        for (int i = 0; i < kDisplayPixelsPerInvocation; ++i) {
            ivec2 pixel = base + ivec2(i, j);
            if (any(greaterThanEqual(pixel, display_size))) continue;
            vec3 rgb = texelFetch(display_input, pixel, 0).rgb;
            int bin = DisplayHistogramBin(float(DisplayLuminance(rgb)));
            if (bin >= 0) atomicAdd(group_histogram[bin], 1u);
        }
    }
    barrier();
    for (uint b = local; b < uint(kDisplayHistogramBins); b += kGroupInvocations) {
        uint count = group_histogram[b];
        if (count != 0u) atomicAdd(display_histogram[b], count);
    }
}
