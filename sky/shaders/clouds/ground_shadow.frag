// The clouds' shadow on our own ground (GroundShadowCorrection), one value per trace cell at its
// centre: the shadow map's texels are hundreds of metres wide, so the composite interpolates
// these instead of working it out for every pixel (which cost llvmpipe 19 ms at 720p).
layout(location = 0) out vec4 out_shadow;

void main() {
    vec2 pixel = (gl_FragCoord.xy - 0.5) * float(block) + 0.5 * float(block - 1);
    out_shadow = vec4(GroundShadowCorrection(CameraDirection(pixel, vec2(output_size))), 0.0);
}
