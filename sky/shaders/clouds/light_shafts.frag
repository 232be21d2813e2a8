// The light shafts (CloudAirShadow), one value per cell of 2 x 2 trace cells at its centre,
// which the composite interpolates (CloudLightShafts): they vary over the shadow map's texels,
// hundreds of metres, and cost llvmpipe 41 ms at 720p worked out per trace cell. The samples keep
// their place from frame to frame (nothing here averages a moving jitter away).
layout(location = 0) out vec4 out_air;

void main() {
    int cell = kCloudLightShaftCell * block;
    vec2 pixel = (gl_FragCoord.xy - 0.5) * float(cell) + 0.5 * float(cell - 1);
    vec3 view = CameraDirection(pixel, vec2(output_size));
    out_air = vec4(CloudAirShadow(view, CloudJitter(ivec2(gl_FragCoord.xy), 0.0)), 0.0);
}
