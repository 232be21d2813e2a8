// The clouds' reconstruction, one fragment per pixel (ReconstructCloudPixel).
layout(location = 0) out vec4 out_cloud;

void main() { out_cloud = ReconstructCloudPixel(ivec2(gl_FragCoord.xy)); }
