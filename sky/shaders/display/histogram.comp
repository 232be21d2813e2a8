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
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (all(lessThan(pixel, display_size))) {
        vec3 rgb = texelFetch(display_input, pixel, 0).rgb;
        int bin = DisplayHistogramBin(float(DisplayLuminance(rgb)));
        if (bin >= 0) atomicAdd(group_histogram[bin], 1u);
    }
    barrier();
    for (uint b = local; b < uint(kDisplayHistogramBins); b += kGroupInvocations) {
        uint count = group_histogram[b];
        if (count != 0u) atomicAdd(display_histogram[b], count);
    }
}
