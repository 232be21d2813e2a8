// The light shafts, one fragment per shaft cell (LightShaftCell), one target per part.
layout(location = 0) out vec4 out_quarter;
layout(location = 1) out vec4 out_half;
layout(location = 2) out vec4 out_three_quarters;
layout(location = 3) out vec4 out_whole;

void main() {
    CloudShaftProfile profile = LightShaftCell(ivec2(gl_FragCoord.xy));
    out_quarter = profile.part[0];
    out_half = profile.part[1];
    out_three_quarters = profile.part[2];
    out_whole = profile.part[3];
}
