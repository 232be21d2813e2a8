// The clouds' shadow on our own ground, one fragment per trace cell (GroundShadowCell).
layout(location = 0) out vec4 out_shadow;

void main() { out_shadow = vec4(GroundShadowCell(ivec2(gl_FragCoord.xy)), 0.0); }
