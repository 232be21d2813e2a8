// The environment (zenith/sky/environment.h): texels of an atlas of the six cube faces side by
// side, face f in rows f * environment_size .. (f + 1) * environment_size - 1, each the sky's
// luminance along its centre's direction (OpenGL's cube map convention, as CubeFaceDirection)
// as render.frag draws it, without the Sun's and the Moon's disks, the stars and the light
// shafts: the Sky-View LUT inside the atmosphere (ZENITH_RAY_MARCH 0) or a ray march above it,
// the night sky's light, and with weather (ZENITH_CLOUDS 1) the clouds traced along each texel
// (the sample positions at the middle of the jitter) and their shadow on our ground. A fragment
// pass, as the cloud trace (sky_shade_trace.frag says why).
layout(location = 0) out vec4 out_luminance;

void main() {
    vec3 direction = EnvironmentDirection(ivec2(gl_FragCoord.xy));
    vec3 luminance = SkyLuminance(direction, ZENITH_RAY_MARCH != 0);
#if ZENITH_CLOUDS
    CloudMarchState state;
    vec4 clouds = TraceClouds(direction, 1e9, 0.5, cloud_march, state);
    luminance = clouds.rgb + clouds.a * (luminance + GroundShadowCorrection(direction));
#endif
    out_luminance = vec4(luminance, 1.0);
}
