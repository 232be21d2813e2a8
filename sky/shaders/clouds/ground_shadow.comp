// The clouds' shadow on our own ground, one invocation per trace cell (GroundShadowCell).
layout(local_size_x = kCloudPassGroupSize, local_size_y = kCloudPassGroupSize) in;
layout(binding = kCloudPassImageUnit, rgba32f) uniform writeonly image2D ground_shadow_image;

void main() {
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(texel, trace_size))) return;
    imageStore(ground_shadow_image, texel, vec4(GroundShadowCell(texel), 0.0));
}
