layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
layout(binding = 0, rgba32f) uniform writeonly image3D output_image;

void main() {
    ivec3 texel = ivec3(gl_GlobalInvocationID.xyz);
    if (any(greaterThanEqual(texel, aerial_perspective_size.xyz))) return;
    vec3 direction = CameraDirection(vec2(texel.xy), vec2(aerial_perspective_size.xy));
    float distance = (float(texel.z) + 0.5) / float(aerial_perspective_size.z) *
                     aerial_perspective_range_km;
    int steps = AerialPerspectiveSteps(texel.z, aerial_perspective_size.z,
                                       aerial_perspective_steps);
    vec4 value = ComputeAerialPerspective(atmosphere, transmittance_texture, transmittance_size,
                                          multiple_scattering_texture, multiple_scattering_size,
                                          irradiance_texture, irradiance_size, lights, camera_km,
                                          camera_altitude_km, direction, distance, steps);
    imageStore(output_image, texel, value);
}
