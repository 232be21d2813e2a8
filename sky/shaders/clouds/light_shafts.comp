// The light shafts, one invocation per shaft cell (LightShaftCell), into the four parts'
// images that light_shafts.frag draws.
layout(local_size_x = kCloudPassGroupSize, local_size_y = kCloudPassGroupSize) in;
layout(binding = kCloudPassImageUnit, rgba32f) uniform writeonly image2D air_shadow_images[4];

void main() {
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(texel, imageSize(air_shadow_images[0])))) return;
    CloudShaftProfile profile = LightShaftCell(texel);
    for (int k = 0; k < 4; ++k) imageStore(air_shadow_images[k], texel, profile.part[k]);
}
