layout(local_size_x = kLutGroupSize, local_size_y = kLutGroupSize) in;
layout(binding = kOutputImageUnit, rgba32f) uniform writeonly image2D output_image;

// With the Sun alone the sky is symmetric about the Sun's vertical plane: azimuth phi and
// 2 pi - phi, texel columns x and width - 1 - x, see the same luminance. The host then dispatches
// the first (width + 1) / 2 columns and each invocation writes both; with the Moon (as a light,
// or its shadow in a solar eclipse), every column.
void main() {
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    bool mirrored = lights.count == 1 && lights.eclipse == 0;  // the Moon's shadow is not
    int columns = mirrored ? (sky_view_size.x + 1) / 2 : sky_view_size.x;
    if (texel.x >= columns || texel.y >= sky_view_size.y) return;
    vec2 uv = (vec2(texel) + 0.5) / vec2(sky_view_size);
    vec3 l = ComputeSkyViewTexel(atmosphere, transmittance_texture, multiple_scattering_texture,
                                 irradiance_texture, lights, camera_km,
                                 camera_altitude_km, uv, sky_view_size, sky_view_steps);
    imageStore(output_image, texel, vec4(l, 1.0));
    if (mirrored) {
        imageStore(output_image, ivec2(sky_view_size.x - 1 - texel.x, texel.y), vec4(l, 1.0));
    }
}
