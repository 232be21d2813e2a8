// The display pass: the linear frame (cd/m^2) through DisplayTransform (common/display.glsl:
// night adaptation, exposure, ACES fitted, sRGB encoding) into the host's draw buffer 0. The
// values are sRGB-encoded here and GL_FRAMEBUFFER_SRGB is off, so an RGBA8 and an
// SRGB8_ALPHA8 target receive the same bytes.
layout(binding = kDisplayInputUnit) uniform sampler2D display_input;
layout(binding = kSceneDepthUnit) uniform sampler2D display_scene_depth;
layout(location = 0) uniform ivec2 display_origin;  // the viewport's lower-left pixel
layout(location = 1) uniform int display_night;
layout(location = 2) uniform int display_depth_mode;  // 0: none, 1: standard, 2: reversed-Z

layout(location = 0) out vec4 display_output;

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy) - display_origin;
    if (display_depth_mode != 0) {
        // The host's geometry (nearer than the far plane) keeps the host's colour.
        float depth = texelFetch(display_scene_depth, pixel, 0).r;
        if (display_depth_mode == 2 ? depth > 0.0 : depth < 1.0) discard;
    }
    vec3 rgb = texelFetch(display_input, pixel, 0).rgb;
    float scale = float(DisplayExposureScale(display_ev100));
    display_output = vec4(vec3(DisplayTransform(rgb, scale, display_night != 0)), 1.0);
}
