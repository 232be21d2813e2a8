// The rain or snow at the camera (AtmospherePasses::DrawPrecipitation), for
// precipitation.vert and .frag; its C++ mirror is gl::PrecipitationUniforms.
layout(std140, binding = kPrecipitationBlockBinding) uniform PrecipitationBlock {
    vec4 world_from_box[3];  // columns (xyz): the weather frame's axes in the renderer's frame
    vec3 phase;              // m: (v t - camera) mod box_size, + box_size / 2
    float box_size;          // m
    vec3 box_velocity;       // m/s, the drops' in the box's frame
    float exposure_s;
    float diameter_m;
    float coverage_scale;  // drops drawn for each one here (>= 1)
    int snow;              // 1: flakes, lit as a white Lambertian
    int has_scene_depth;   // 1: hidden behind the host's geometry
};
