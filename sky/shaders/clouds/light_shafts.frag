// The light shafts (CloudAirShadow), one profile per cell of 2 x 2 trace cells at its centre,
// which the composite interpolates (CloudLightShafts, CloudLightShaftsTo): they vary over the
// shadow map's texels, hundreds of metres, and cost llvmpipe 44 ms at 720p worked out per trace
// cell. The samples keep their place from frame to frame (nothing here averages a moving jitter
// away).
layout(location = 0) out vec4 out_quarter;
layout(location = 1) out vec4 out_half;
layout(location = 2) out vec4 out_three_quarters;
layout(location = 3) out vec4 out_whole;

void main() {
    int cell = kCloudLightShaftCell * block;
    vec2 pixel = (gl_FragCoord.xy - 0.5) * float(cell) + 0.5 * float(cell - 1);
    vec3 view = CameraDirection(pixel, vec2(output_size));
    CloudShaftProfile profile = CloudAirShadow(view, CloudJitter(ivec2(gl_FragCoord.xy), 0.0));
    out_quarter = profile.part[0];
    out_half = profile.part[1];
    out_three_quarters = profile.part[2];
    out_whole = profile.part[3];
}
