// The clouds seen from the ground below the camera along the directions of CloudSkyShadeDirection
// (sky_shade_size^2 of the upper hemisphere, one per texel of a sky_shade_size^2 target): (L, T)
// of the layers, nothing in front. sky_shade.comp averages them. A fragment pass like the trace:
// the same march compiled into a compute shader lost the clouds' light on llvmpipe (Mesa 22, L = 0
// for every direction, T wrong; measured against the CPU march), which the fragment pass matches.
layout(location = 0) out vec4 out_shade;

void main() {
    ivec2 texel = ivec2(gl_FragCoord.xy);
    vec3 up = normalize(camera_km);
    mat3 to_weather = WeatherFromFrame();
    vec3 direction =
        CloudSkyShadeDirection(texel.y * sky_shade_size + texel.x, sky_shade_size, up);
    CloudMarchState state = MarchCloudLayers(to_weather * (up * atmosphere.bottom_radius), 0.0,
                                             to_weather * direction, 1e9, 0.5,
                                             cloud_ground_layer_order, cloud_march);
    out_shade = vec4(state.luminance, state.transmittance);
}
