// The clouds over the sky (and the Sun, the Moon and the stars): blended premultiplied
// (ONE, SRC_ALPHA), framebuffer = L + T * what is behind. Over the host's geometry
// (ZENITH_SCENE_DEPTH) only the clouds nearer than it are drawn. Where our own ground shows, its
// change by the clouds' shadow (ground_shadow.frag, interpolated between trace cells) is added
// behind the clouds: L + T (ground + change).
layout(location = 0) out vec4 out_luminance;

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy) - ivec2(viewport_x, viewport_y);
    vec4 cloud = texelFetch(cloud_history, pixel, 0);
    bool ground_shows = true;
#if ZENITH_SCENE_DEPTH
    float depth = texelFetch(scene_depth_texture, pixel, 0).r;
    if (depth < 1.0) {
        ground_shows = false;
        float z_ndc = 2.0 * depth - 1.0;
        float eye_depth = 2.0 * scene_near_m * scene_far_m /
                          (scene_far_m + scene_near_m - z_ndc * (scene_far_m - scene_near_m));
        vec2 ndc = 2.0 * (vec2(pixel) + 0.5) / vec2(output_size) - 1.0;
        float distance_km = eye_depth * length(vec3(ndc.x * tan_half_fov * aspect,
                                                    ndc.y * tan_half_fov, 1.0)) / 1000.0;
        float cloud_depth = CloudTraceDepth(pixel);
        if (!(cloud_depth > 0.0 && cloud_depth < distance_km)) cloud = vec4(0.0, 0.0, 0.0, 1.0);
    }
#endif
    vec3 view = CameraDirection(vec2(pixel), vec2(output_size));
    float r = length(camera_km);
    ground_shows = ground_shows && RaySphereDistance(r, dot(camera_km, view) / r,
                                                     camera_altitude_km,
                                                     atmosphere.bottom_radius) >= 0.0;
    vec2 uv = (vec2(pixel) + 0.5) / (float(block) * vec2(trace_size));
    vec3 shadow = ground_shows ? texture(cloud_ground_shadow, uv).rgb : vec3(0.0);
    out_luminance = vec4(cloud.rgb + cloud.a * shadow, cloud.a);
}
