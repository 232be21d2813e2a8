// The cloud trace as a compute pass: one invocation per trace cell (TraceCloudCell), into the
// targets trace.frag draws (CloudPasses' trace_color_, trace_depth_, trace_profile_).
layout(local_size_x = kCloudPassGroupSize, local_size_y = kCloudPassGroupSize) in;
layout(binding = kCloudPassImageUnit, rgba32f) uniform writeonly image2D trace_cloud_image;
layout(binding = kCloudPassImageUnit + 1, rg32f) uniform writeonly image2D trace_depth_image;
layout(binding = kCloudPassImageUnit + 2, rgba32f) uniform writeonly image2D trace_profile_image;

void main() {
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(texel, trace_size))) return;
    CloudTraceCell cell = TraceCloudCell(texel);
    imageStore(trace_cloud_image, texel, cell.cloud);
    imageStore(trace_depth_image, texel, cell.depth);
    imageStore(trace_profile_image, texel, cell.profile);
}
