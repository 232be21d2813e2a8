// One invocation per screen cell marches its column of froxels front to back.
layout(local_size_x = kLutGroupSize, local_size_y = kLutGroupSize) in;
layout(binding = kOutputImageUnit, rgba32f) uniform writeonly image3D output_image;

void main() {
    ivec2 cell = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(cell, aerial_perspective_size.xy))) return;
    vec3 direction = CameraDirection(vec2(cell), vec2(aerial_perspective_size.xy));
    ScatteringResult accumulated;
    accumulated.luminance = vec3(0.0);
    accumulated.transmittance = vec3(1.0);
    for (int slice = 0; slice < aerial_perspective_size.z; ++slice) {
        vec4 value = AdvanceAerialPerspective(
            atmosphere, transmittance_texture, multiple_scattering_texture, irradiance_texture,
            lights, camera_km, camera_altitude_km, direction, slice, aerial_perspective_size.z,
            aerial_perspective_range_km, aerial_perspective_steps, accumulated);
        imageStore(output_image, ivec3(cell, slice), value);
    }
}
