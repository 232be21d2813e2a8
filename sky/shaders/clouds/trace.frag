// The cloud trace as a fragment pass: one fragment per trace cell (TraceCloudCell).
layout(location = 0) out vec4 out_cloud;
layout(location = 1) out vec4 out_depth;
layout(location = 2) out vec4 out_profile;

void main() {
    CloudTraceCell cell = TraceCloudCell(ivec2(gl_FragCoord.xy));
    out_cloud = cell.cloud;
    out_depth = cell.depth;
    out_profile = cell.profile;
}
