// The clouds' sky shade, one invocation per direction (TraceSkyShadeDirection), into the image
// sky_shade.comp then reads.
layout(local_size_x = kCloudPassGroupSize, local_size_y = kCloudPassGroupSize) in;
layout(binding = kCloudPassImageUnit, rgba32f) uniform writeonly image2D shade_image;

void main() {
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(texel, ivec2(sky_shade_size)))) return;
    imageStore(shade_image, texel, TraceSkyShadeDirection(texel));
}
