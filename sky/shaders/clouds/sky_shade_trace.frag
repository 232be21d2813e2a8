// The clouds' sky shade, one fragment per direction (TraceSkyShadeDirection) of a
// sky_shade_size^2 target.
layout(location = 0) out vec4 out_shade;

void main() { out_shade = TraceSkyShadeDirection(ivec2(gl_FragCoord.xy)); }
