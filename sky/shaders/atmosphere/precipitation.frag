// See precipitation.vert. Behind the host's geometry (its depth, when given) nothing is drawn.
layout(location = 0) flat in vec4 drop;
layout(location = 1) in float eye_depth;
layout(location = 0) out vec4 out_luminance;

void main() {
    if (has_scene_depth != 0) {
        ivec2 pixel = ivec2(gl_FragCoord.xy) - ivec2(viewport_x, viewport_y);
        float depth = texelFetch(scene_depth_texture, pixel, 0).r;
        bool geometry = scene_depth_reversed != 0 ? depth > 0.0 : depth < 1.0;
        if (geometry &&
            scene_near_m / (scene_depth_offset + scene_depth_slope * depth) < eye_depth) {
            discard;
        }
    }
    out_luminance = vec4(drop.rgb, 1.0 - drop.a);  // premultiplied: L alpha + (1 - alpha) frame
}
