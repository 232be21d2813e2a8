// The cloud trace (H16 §6.1): one cell per block x block pixels, each marching the ray through
// the pixel of its block chosen for this frame (trace_offset). With block 1 every pixel is
// traced. Writes (L, T) of the clouds with aerial perspective applied, their mean depth and
// where the ray enters cloud, and the transmittance's profile (CloudMarchState.crossing).
layout(location = 0) out vec4 out_cloud;
layout(location = 1) out vec4 out_depth;
layout(location = 2) out vec4 out_profile;

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy) * block + trace_offset;
    vec3 view = CameraDirection(vec2(pixel), vec2(output_size));
    CloudMarchState state;
    out_cloud = TraceClouds(view, 1e9, CloudJitter(pixel, frame_jitter), cloud_march, state);
    out_depth = vec4(CloudMeanDepth(state), state.entry, 0.0, 0.0);
    out_profile = state.crossing;
}
