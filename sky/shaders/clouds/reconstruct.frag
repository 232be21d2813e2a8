// Full-resolution clouds from this frame's trace and the previous frames (H16 §6.1, F16
// §5.5.3). A pixel traced this frame takes its new value, averaged with its reprojected history
// (history_weight) so the per-frame jitter integrates over time; any other pixel takes its
// reprojected history. Reprojection follows the cloud: the point at the clouds' mean depth (or
// the direction alone, for clear sky) is projected into the previous camera, which handles
// rotation and flight at any speed. Where there is no history (first frame, a cut, a point
// outside the previous view), the pixel falls back to this frame's trace, upsampled. There is
// no depth test for disocclusion: a cloud's mean depth jumps between neighbouring pixels at
// every edge and with every jitter, so such a test threw away good history (measured: a static
// view never converged), while what it would catch, one cloud sliding behind another, changes
// over many frames at flight speeds and is refreshed within block^2 frames.
layout(location = 0) out vec4 out_cloud;

// The previous frame's texture coordinate of the point at `depth` km along `view` (the
// direction alone when depth <= 0); false when it was outside the previous view.
bool Reproject(vec3 view, float depth, out vec2 uv) {
    mat3 previous_view = mat3(previous_view_from_frame[0].xyz, previous_view_from_frame[1].xyz,
                              previous_view_from_frame[2].xyz);
    vec3 v = depth > 0.0 ? previous_view * (view * depth - previous_camera_offset_km)
                         : previous_view * view;
    if (!(v.z < 0.0)) return false;
    vec2 ndc = vec2(v.x / (-v.z * previous_tan_half_fov * previous_aspect),
                    v.y / (-v.z * previous_tan_half_fov));
    uv = 0.5 * ndc + 0.5;
    return all(greaterThanEqual(uv, vec2(0.0))) && all(lessThanEqual(uv, vec2(1.0)));
}

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    ivec2 cell = pixel / block;
    bool traced = all(equal(pixel - cell * block, trace_offset));
    // This frame's trace around the pixel: the cell's own value, or the four nearest cells
    // (the trace is sampled at pixel cell * block + trace_offset).
    vec2 trace_uv = (vec2(pixel - trace_offset) / float(block) + 0.5) / vec2(trace_size);
    vec4 current =
        traced ? texelFetch(cloud_trace, cell, 0) : textureLod(cloud_trace, trace_uv, 0.0);
    float depth = CloudTraceDepth(pixel);

    vec3 view = CameraDirection(vec2(pixel), vec2(output_size));
    vec2 uv;
    bool valid = history_valid != 0 && Reproject(view, depth, uv);
    vec4 history = valid ? textureLod(cloud_history, uv, 0.0) : vec4(0.0);
    if (traced) {
        out_cloud = valid ? mix(current, history, history_weight) : current;
    } else {
        out_cloud = valid ? history : current;
    }
}
