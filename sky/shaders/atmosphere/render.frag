// Final sky image: the Sky-View LUT inside the atmosphere (ZENITH_RAY_MARCH 0), or per-pixel ray
// marching above it (ZENITH_RAY_MARCH 1; the host picks the program), with the stars; then, as a
// second additive pass over each disk (ZENITH_DISKS 1), the Sun and the Moon. Writes linear
// luminance, cd/m^2. A fragment pass over a full-screen triangle: it can draw into a host's
// framebuffer, and llvmpipe's fragment path is several times faster than compute image stores.
// With weather (ZENITH_CLOUDS 1, after the cloud files) it also lays this frame's clouds,
// reconstructed at full resolution (clouds/reconstruct.frag), over everything they hide: the
// sky, the stars, our own ground with their shadow on it, the disks, and the aerial perspective
// in front of the host's geometry where they are nearer than it. In this pass rather than one
// of their own, since on llvmpipe a full-resolution pass costs 4 ms before it does anything.
layout(location = 0) out vec4 out_luminance;

// Solar limb darkening, Hestroffer & Magnan (1998) 5th-order polynomial in mu = cos of the angle
// from the disk centre, at 680/550/440 nm (Hillaire 2016, Appendix B), divided by its mean over
// the disk (2 * sum a_k / (k + 2)) so the disk still integrates to the Sun's illuminance.
vec3 SunLimbDarkening(float center_to_edge) {
    float mu = sqrt(max(1.0 - center_to_edge * center_to_edge, 0.0));
    vec3 a0 = vec3(0.34685, 0.26073, 0.15248);
    vec3 a1 = vec3(1.37539, 1.27428, 1.38517);
    vec3 a2 = vec3(-2.04425, -1.30352, -1.49615);
    vec3 a3 = vec3(2.70493, 1.47085, 1.99886);
    vec3 a4 = vec3(-1.94290, -0.96618, -1.48155);
    vec3 a5 = vec3(0.55999, 0.26384, 0.44119);
    vec3 factor = a0 + mu * (a1 + mu * (a2 + mu * (a3 + mu * (a4 + mu * a5))));
    vec3 disk_mean = 2.0 * (a0 / 2.0 + a1 / 3.0 + a2 / 4.0 + a3 / 5.0 + a4 / 6.0 + a5 / 7.0);
    return factor / disk_mean;
}

// The direction in the unrefracted sky of what is seen along `direction` near a disk that
// refraction shows at `apparent` (its geometric centre `geometric`), squeezed vertically by
// `vertical_scale` (ApparentPlace): the offsets from the apparent centre along the local
// horizontal and vertical, the vertical one unsqueezed, put around the geometric centre. The
// identity without refraction. `up` is the camera's zenith.
vec3 UnrefractedDirection(vec3 direction, vec3 apparent, vec3 geometric, float vertical_scale,
                          vec3 up) {
    vec3 vertical = up - apparent * dot(up, apparent);
    vec3 geometric_vertical = up - geometric * dot(up, geometric);
    if (dot(vertical, vertical) < 1e-12 || dot(geometric_vertical, geometric_vertical) < 1e-12) {
        return direction;  // at the zenith, where refraction vanishes
    }
    vertical = normalize(vertical);
    geometric_vertical = normalize(geometric_vertical);
    return normalize(dot(direction, apparent) * geometric +
                     dot(direction, cross(vertical, apparent)) *
                         cross(geometric_vertical, geometric) +
                     dot(direction, vertical) / vertical_scale * geometric_vertical);
}

// The sunlight reaching the point of the Moon at `moon_km` (planet-centred): in a lunar eclipse
// the table's value at its distance from the shadow's axis, the Earth-Sun line (ShadowSunlight
// on the CPU); else moon_sunlight.
vec3 MoonSunlight(vec3 moon_km) {
    if (moon_shadow_enabled == 0) return moon_sunlight;
    vec3 sun = lights.light[0].direction;
    float axis = length(moon_km - dot(moon_km, sun) * sun);
    float span = moon_shadow_axis_max_km - moon_shadow_axis_min_km;
    float f = clamp(span > 0.0 ? (axis - moon_shadow_axis_min_km) / span : 0.0, 0.0, 1.0) *
              float(kMoonShadowSamples - 1);
    int i = min(int(f), kMoonShadowSamples - 2);
    return mix(moon_shadow[i].rgb, moon_shadow[i + 1].rgb, f - float(i));
}

// Luminance of the Moon's disk along `direction`: a Lambertian sphere lit by the Sun, so the lit
// side faces the Sun whatever the phase (Hillaire 2016 §4.2 leaves this to the artist), and in a
// lunar eclipse each point by the sunlight the Earth's shadow leaves it.
vec3 MoonLuminance(vec3 direction) {
    if (dot(direction, moon_direction) <= cos_moon_radius) return vec3(0.0);
    // The sphere at unit distance with radius sin(angular radius); nearest hit along the ray.
    float rho = sin(moon_angular_radius);
    float b = dot(direction, moon_direction);
    float t = b - sqrt(max(b * b - (1.0 - rho * rho), 0.0));
    vec3 normal = normalize(direction * t - moon_direction);
    return lights.light[0].illuminance * MoonSunlight(camera_km + direction * (t * moon_distance_km)) *
           (moon_albedo / kPi) * max(dot(normal, lights.light[0].direction), 0.0);
}

// The Sun in a solar eclipse (LightSet.eclipse): the disk at its unobscured luminance where the
// Moon does not cover it, and around it the corona: Baumbach's (1937) mean K+F corona,
// I(r) / I(disk centre) = 1e-6 (0.0532 r^-2.5 + 1.425 r^-7 + 2.565 r^-17), r in solar radii
// (Allen's Astrophysical Quantities, 4th ed., §14.x; ~1.3e-6 at 1.1 radii, its whole light
// ~1.4e-6 of the Sun's, about the full Moon's), faded out between 4 and 6 radii, where the disk
// pass's box ends. Nothing behind the Moon. Angles from chord lengths: an acos of a float cosine
// near 1 resolves only 3.5e-4 rad, 7 % of the Sun's radius.
vec3 EclipsedSunLuminance(vec3 direction) {
    float moon_chord = 2.0 * sin(0.5 * moon_angular_radius);
    if (length(direction - moon_direction) < moon_chord) return vec3(0.0);
    float radius = lights.eclipse_sun_radius;
    float x = 2.0 * asin(0.5 * length(direction - lights.light[0].direction)) / radius;
    float half_sin = sin(0.5 * radius);
    vec3 mean = lights.eclipse_sun_illuminance / (4.0 * kPi * half_sin * half_sin);
    if (x < 1.0) return mean * SunLimbDarkening(x);
    float corona = 1e-6 * (0.0532 * pow(x, -2.5) + 1.425 * pow(x, -7.0) + 2.565 * pow(x, -17.0));
    return mean * SunLimbDarkening(0.0) * (corona * (1.0 - smoothstep(4.0, 6.0, x)));
}

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy) - ivec2(viewport_x, viewport_y);
    vec3 direction = CameraDirection(vec2(pixel), vec2(output_size));
#if ZENITH_SCENE_DEPTH
    float distance_km = SceneDistanceKm(pixel);
    bool geometry = distance_km > 0.0;  // nearer than the far plane
#endif

#if ZENITH_DISKS
    // The Sun and the Moon, drawn additively over the sky in a second pass scissored to their
    // disks: llvmpipe runs a shader's branches whether taken or not, so this code in the sky pass
    // cost every pixel 12 ms at 720p.
  #if ZENITH_SCENE_DEPTH
    if (geometry) discard;  // behind the host's geometry
  #endif
    vec3 beyond = vec3(0.0);
    // Each disk in its own unrefracted sky, so its shape, limb, phase and eclipse are computed
    // there (the transmittance below is along the ray seen).
    vec3 sun_sky = UnrefractedDirection(direction, sun_disk_direction, lights.light[0].direction,
                                        sun_disk_scale, sky_view_up);
    vec3 moon_sky = UnrefractedDirection(direction, moon_disk_direction, moon_direction,
                                         moon_disk_scale, sky_view_up);
    float cos_sun = dot(sun_sky, lights.light[0].direction);
    if (draw_sun_disk != 0 && lights.eclipse != 0) {
        beyond += EclipsedSunLuminance(sun_sky);
    } else if (draw_sun_disk != 0 && cos_sun > cos_sun_radius) {
        float angle = acos(clamp(cos_sun, -1.0, 1.0));
        float solid_angle = 2.0 * kPi * (1.0 - cos_sun_radius);
        beyond += lights.light[0].illuminance / solid_angle *
                  SunLimbDarkening(angle / atmosphere.sun_angular_radius);
    }
    if (moon_enabled != 0) beyond += MoonLuminance(moon_sky);
    out_luminance = vec4(beyond * TransmittanceToSpace(atmosphere, transmittance_texture, camera_km,
                                                       camera_altitude_km, direction),
                         0.0);
  #if ZENITH_CLOUDS
    out_luminance.rgb *= texelFetch(cloud_history, pixel, 0).a;
  #endif
#else
    vec3 luminance = SkyLuminance(direction, ZENITH_RAY_MARCH != 0);
    // Stars (and a Sun narrower than a pixel): luminance already attenuated on the CPU by the
    // same TransmittanceToSpace. Seen only as far as they stand out of the sky behind them: the
    // pixel's illuminance is its luminance times its solid angle (SplatPoints' measure).
    if (stars_enabled != 0) {
        vec4 points = texelFetch(star_texture, pixel, 0);
        vec3 stars = points.rgb;
        if (star_visibility != 0) {
            vec2 ndc = 2.0 * (vec2(pixel) + 0.5) / vec2(output_size) - 1.0;
            vec2 t = vec2(ndc.x * tan_half_fov * aspect, ndc.y * tan_half_fov);
            float solid_angle = 4.0 * tan_half_fov * tan_half_fov * aspect /
                                (float(output_size.x) * float(output_size.y)) /
                                pow(1.0 + dot(t, t), 1.5);
            vec3 y = vec3(0.2126, 0.7152, 0.0722);  // linear sRGB luminance
            // Points fade in at the eye's threshold; a resolved planet's disk (its share of
            // the pixel in alpha) is an extended source, added as it is.
            float extended = clamp(points.a / max(dot(stars, y), 1e-30), 0.0, 1.0);
            stars *= mix(StarVisibility(dot(stars, y) * solid_angle, dot(luminance, y)), 1.0,
                         extended);
        }
        luminance += stars;
    }
  #if ZENITH_CLOUDS
    vec4 clouds = texelFetch(cloud_history, pixel, 0);  // (L, T), premultiplied
  #endif

  #if ZENITH_SCENE_DEPTH
    // The host's geometry: where its depth is nearer than the far plane, the output is the
    // aerial perspective in front of it, premultiplied for blending (ONE, SRC_ALPHA):
    // framebuffer = in-scattered + transmittance * the host's colour (H20 §5.4).
    if (geometry) {
        vec4 air = SampleAerialPerspective(
            aerial_perspective_texture, (vec2(pixel) + 0.5) / vec2(output_size), distance_km,
            aerial_perspective_range_km, aerial_perspective_size.z);
    #if ZENITH_CLOUDS
        // Only the clouds in front of the geometry (all of them behind a cloud, none in front,
        // a part inside one or in fog).
        clouds = CloudsInFrontOf(pixel, distance_km, clouds);
        // The light shafts up to the geometry: in front of those clouds from below the base.
        vec3 shafts = CloudLightShaftsTo(pixel, direction, distance_km);
        float behind = camera_altitude_km < lights.cloud_base ? 1.0 : clouds.a;
        air = vec4(clouds.rgb + clouds.a * air.rgb + behind * shafts, clouds.a * air.a);
    #endif
        out_luminance = air;
        return;
    }
  #endif
  #if ZENITH_CLOUDS
    float r = length(camera_km);
    bool ground = RaySphereDistance(r, dot(camera_km, direction) / r, camera_altitude_km,
                                    atmosphere.bottom_radius) >= 0.0;
    if (ground) luminance += CloudGroundShadow(pixel);
    // The light shafts lie below the clouds' base: in front of the clouds from a camera below
    // it, behind them (seen through their gaps) from a camera above it.
    vec3 shafts = CloudLightShafts(pixel);
    luminance = clouds.rgb + clouds.a * luminance +
                (camera_altitude_km < lights.cloud_base ? shafts : clouds.a * shafts);
  #endif
  #if ZENITH_SCENE_DEPTH
    out_luminance = vec4(luminance, 0.0);
  #else
    out_luminance = vec4(luminance, 1.0);
  #endif
#endif
}
