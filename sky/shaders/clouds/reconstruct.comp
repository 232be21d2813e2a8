// The clouds' reconstruction, one invocation per pixel (ReconstructCloudPixel), into the history
// reconstruct.frag draws.
layout(local_size_x = kCloudPassGroupSize, local_size_y = kCloudPassGroupSize) in;
layout(binding = kCloudPassImageUnit, rgba32f) uniform writeonly image2D history_image;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, output_size))) return;
    imageStore(history_image, pixel, ReconstructCloudPixel(pixel));
}
