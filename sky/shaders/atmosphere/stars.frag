// See stars.vert.
layout(location = 0) flat in vec4 point_luminance;
layout(location = 0) out vec4 out_luminance;

void main() { out_luminance = point_luminance; }
