// The stars (and a Sun narrower than a pixel): one point a pixel wide per source, at its pixel's
// centre (AtmospherePasses' SplatPoints works out where and how bright), added up by blending
// into the points' texture that the composite reads.
layout(location = 0) in vec2 ndc;
// cd/m^2: T E over the pixel's solid angle; a: its Y when part of a resolved disk (extended)
layout(location = 1) in vec4 luminance;
layout(location = 0) flat out vec4 point_luminance;

void main() {
    gl_Position = vec4(ndc, 0.0, 1.0);
    point_luminance = luminance;
}
