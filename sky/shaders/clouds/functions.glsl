// Cloud density and light transport shared by the GL renderer and the CPU reference (one text,
// two compilers: GLSL 4.50 after clouds/definitions.glsl, C++/GLM double through
// sky/src/reference/cloud_functions.h).
//
// H16  Högfeldt, "Convincing Cloud Rendering", MSc thesis, Chalmers 2016 (seeds/001).
// F16  Hillaire, "Physically Based Sky, Atmosphere and Cloud Rendering in Frostbite",
//      SIGGRAPH 2016 course notes, §5 (seeds/000).
// S15  Schneider, "The Real-Time Volumetric Cloudscapes of Horizon Zero Dawn", SIGGRAPH 2015
//      (the remaps both of the above build on).
//
// Glossary (kilometres inside shaders, converted once from SI by the host):
//   frame            planet-centred, km, +z through the weather map's origin (the renderer
//                    rotates its camera frame into this one, so clouds stay put on the planet)
//   ground           horizontal position on the cloud shell: km along the planet's surface,
//                    x and y along the frame's x and y axes at the origin
//   altitude         km above the sphere of radius bottom_radius
//   height_fraction  position in the layer: 0 at base_altitude, 1 at top_altitude
//   cloud_fraction   position in the local cloud: 0 at its base, 1 at its top
//   density          [0, 1]; extinction = density * the cloud material's extinction (1/km)
//   nu               cosine of the angle between the view direction and the sun direction
// Weather texels (H16 Table 4.2, F16 §5.3.1): R coverage, G precipitation, B cloud type
// (0 stratus, 0.5 cumulus, 1 cumulonimbus), A the local cloud's height as a share of the
// height its type reaches.

// std140-compatible: Numbers only, a multiple of four of them, so a float mirror packs
// identically.
struct CloudLayerParameters {
    Number bottom_radius;     // km, the planet sphere the shell follows
    Number base_altitude;     // km above bottom_radius
    Number top_altitude;      // km above bottom_radius
    Number weather_period;    // km of ground covered by one tile of the weather map
    Number shape_period;      // km covered by one tile of the shape noise along ground x and z
    Number shape_period_y;    // km covered along altitude (H16 §4.3: 32 of 128 texels, so 1/4)
    Number detail_period;     // km covered by one tile of the detail noise, every axis
    Number erosion_strength;  // [0, kCloudMaxErosion]: how much detail noise eats the edges
    Number wind_offset_x;     // km the clouds have moved along ground x (H16 §4.4.2)
    Number wind_offset_y;     // km along ground y
    Number cloud_top_altitude;  // km: the map's clouds reach no higher (clouds::CloudTopFraction)
    Number padding1;
};

// Erosion remaps density from [e, 1] to [0, 1]; e must stay below 1.
const Number kCloudMaxErosion = 0.9;
// The largest light reduction at the base of a raining cloud (H16 §4.4.1).
const Number kCloudMaxPrecipitationDarkening = 0.8;
const int kCloudMaxOctaves = 8;

Number CloudSaturate(Number x) { return clamp(x, 0.0, 1.0); }

// S15: linear map of [lo, hi] onto [new_lo, new_hi], clamped to the new range.
Number CloudRemap(Number x, Number lo, Number hi, Number new_lo, Number new_hi) {
    return clamp(new_lo + (x - lo) / (hi - lo) * (new_hi - new_lo), min(new_lo, new_hi),
                 max(new_lo, new_hi));
}

// ---------------------------------------------------------------------------------------------
// Dome projection (H16 §5.3): the layer is a spherical shell around the planet's centre.

// Ground coordinates of a planet-centred position: azimuthal equidistant about the frame's +z
// axis, i.e. arc length along the sphere of bottom_radius. Every radial column gets one weather
// texel and one noise column, so clouds stand upright on the curved ground and bend over the
// horizon; the tangential stretch, theta / sin(theta) - 1, stays under 0.1% within 500 km.
vec2 CloudGroundCoordinates(IN(CloudLayerParameters) layer, vec3 position) {
    Number s = length(vec2(position.x, position.y));
    if (!(s > 0.0)) return vec2(0.0, 0.0);
    Number theta = atan(s, position.z);
    return vec2(position.x, position.y) * (layer.bottom_radius * theta / s);
}

Number CloudAltitude(IN(CloudLayerParameters) layer, vec3 position) {
    return length(position) - layer.bottom_radius;
}

// ---------------------------------------------------------------------------------------------
// Weather (H16 §4.4, F16 §5.3.1)

struct CloudWeather {
    Number coverage;
    Number precipitation;
    Number type;
    Number height;
};

// The weather map moves with the wind as one offset (H16 §4.4.2); the noise moves with it, so
// clouds drift whole instead of boiling.
vec2 CloudWindShiftedGround(IN(CloudLayerParameters) layer, vec2 ground) {
    return vec2(ground.x + layer.wind_offset_x, ground.y + layer.wind_offset_y);
}

CloudWeather CloudWeatherAt(IN(CloudLayerParameters) layer, IN(WeatherTexture) weather_map,
                            vec2 ground) {
    vec2 shifted = CloudWindShiftedGround(layer, ground);
    vec4 texel = SampleRepeat2D(weather_map, shifted / layer.weather_period);
    CloudWeather w;
    w.coverage = CloudSaturate(texel.x);
    w.precipitation = CloudSaturate(texel.y);
    w.type = CloudSaturate(texel.z);
    w.height = CloudSaturate(texel.w);
    return w;
}

// ---------------------------------------------------------------------------------------------
// Density (H16 Alg. 4.1)

// The share of the layer's thickness a cloud of this type fills at full height: the weather
// map chooses each cloud's height (H16 §4.4, green channel) and F16 §5.3.1 a profile per type.
// Stratus keeps to the bottom quarter, cumulus reaches 60%, cumulonimbus the whole layer.
Number CloudTypeHeightFraction(Number type) {
    Number t = CloudSaturate(type);
    return t < 0.5 ? mix(0.25, 0.6, 2.0 * t) : mix(0.6, 1.0, 2.0 * t - 1.0);
}

// H16 Eq. 5.1 (Alg. 5.3): (x - a)(x - a - h) * -4 / h^2, the parabola with roots at the cloud's
// base a and top a + h and its maximum, 1, at a + h / 2 (H16 Fig. 5.2); zero outside.
Number CloudHeightSignal(Number altitude, Number cloud_base, Number cloud_height) {
    if (!(cloud_height > 0.0)) return 0.0;
    Number one_over_height = 1.0 / cloud_height;
    Number altitude_diff = altitude - cloud_base;
    // Clamped to [0, 1]: zero outside, and rounding must not lift the peak above 1.
    return CloudSaturate(altitude_diff * (altitude_diff - cloud_height) * one_over_height *
                         one_over_height * -4.0);
}

// H16 §4.5.1: a linear increase over the cloud's height that thins its base. Stratus keeps a
// uniform profile; cumulus and above start at 30%.
Number CloudHeightGradient(Number type, Number cloud_fraction) {
    Number bottom = mix(1.0, 0.3, CloudSaturate(2.0 * type));
    return mix(bottom, 1.0, CloudSaturate(cloud_fraction));
}

// Base shape from the shape texture (H16 §4.5): the Worley octaves (G, B, A) as an FBM dilate
// the Perlin-Worley channel (R), S15's form, which F16 §5.4 inherits.
Number CloudShape(vec4 shape_texel) {
    Number worley = shape_texel.y * 0.625 + shape_texel.z * 0.25 + shape_texel.w * 0.125;
    return CloudRemap(shape_texel.x, worley - 1.0, 1.0, 0.0, 1.0);
}

// S15's coverage remap, Remap(base, 1 - c, 1, 0, 1) * c, written as a clamp: there is no
// division, so coverage 0 gives exactly 0 and coverage 1 keeps the base shape. The result never
// exceeds the coverage (H16 §4.5.1 starts from the coverage as density).
Number CloudApplyCoverage(Number base, Number coverage) {
    return clamp(base - (1.0 - coverage), 0.0, coverage);
}

// Detail noise as an erosion amount in [0, 1] (H16 §4.5.2): the Worley FBM, inverted toward the
// cloud's base for wispy edges and as stored (billowing) above.
Number CloudDetail(vec4 detail_texel, Number cloud_fraction) {
    Number fbm = detail_texel.x * 0.625 + detail_texel.y * 0.25 + detail_texel.z * 0.125;
    return mix(1.0 - fbm, fbm, CloudSaturate(4.0 * cloud_fraction));
}

// H16 §4.5.2: erosion as a threshold that removes low densities more. Remap(d, e, 1, 0, 1) is
// at most d for d in [0, 1] (d - e <= d - e d), so erosion only ever removes density.
Number CloudErode(Number density, Number erosion) {
    Number e = clamp(erosion, 0.0, kCloudMaxErosion);
    return CloudSaturate((density - e) / (1.0 - e));
}

struct CloudSample {
    Number density;
    Number height_fraction;
    Number cloud_fraction;
    Number precipitation;
};

// H16 Alg. 4.1 at a ground position and altitude:
//   weather; density = coverage; *= height signal; *= shape; -= detail; *= height gradient,
// with S15's remaps for the coverage and the erosion. Exactly 0 outside the layer and wherever
// the coverage is 0.
CloudSample SampleCloudDensityAt(IN(CloudLayerParameters) layer, IN(WeatherTexture) weather_map,
                                 IN(CloudNoiseTexture) shape_noise,
                                 IN(CloudNoiseTexture) detail_noise, vec2 ground,
                                 Number altitude) {
    CloudSample s;
    s.density = 0.0;
    s.height_fraction =
        (altitude - layer.base_altitude) / (layer.top_altitude - layer.base_altitude);
    s.cloud_fraction = 0.0;
    s.precipitation = 0.0;
    if (!(altitude > layer.base_altitude && altitude < layer.top_altitude)) return s;

    CloudWeather weather = CloudWeatherAt(layer, weather_map, ground);
    s.precipitation = weather.precipitation;
    if (!(weather.coverage > 0.0)) return s;

    Number cloud_height = (layer.top_altitude - layer.base_altitude) *
                          CloudTypeHeightFraction(weather.type) * weather.height;
    Number signal = CloudHeightSignal(altitude, layer.base_altitude, cloud_height);
    if (!(signal > 0.0)) return s;
    s.cloud_fraction = (altitude - layer.base_altitude) / cloud_height;

    vec2 shifted = CloudWindShiftedGround(layer, ground);
    vec3 shape_uvw = vec3(shifted.x / layer.shape_period, altitude / layer.shape_period_y,
                          shifted.y / layer.shape_period);
    Number shape = CloudShape(SampleTexture3D(shape_noise, shape_uvw));
    Number density = CloudApplyCoverage(shape * signal, weather.coverage);
    if (!(density > 0.0)) return s;

    vec3 detail_uvw = vec3(shifted.x, altitude, shifted.y) / layer.detail_period;
    Number detail = CloudDetail(SampleTexture3D(detail_noise, detail_uvw), s.cloud_fraction);
    density = CloudErode(density, layer.erosion_strength * detail);
    density *= CloudHeightGradient(weather.type, s.cloud_fraction);
    // H16 §4.5.1: densities above 1 are clamped.
    s.density = CloudSaturate(density);
    return s;
}

// The same at a planet-centred position (km), through the dome projection.
CloudSample SampleCloudDensity(IN(CloudLayerParameters) layer, IN(WeatherTexture) weather_map,
                               IN(CloudNoiseTexture) shape_noise,
                               IN(CloudNoiseTexture) detail_noise, vec3 position) {
    return SampleCloudDensityAt(layer, weather_map, shape_noise, detail_noise,
                                CloudGroundCoordinates(layer, position),
                                CloudAltitude(layer, position));
}

// H16 §4.4.1: rain clouds are darkened by a gradient, strongest at their base, multiplied with
// the light they scatter; all clouds keep one absorption coefficient. 1 without precipitation.
Number CloudPrecipitationLightScale(Number precipitation, Number cloud_fraction) {
    return 1.0 - kCloudMaxPrecipitationDarkening * CloudSaturate(precipitation) *
                     (1.0 - CloudSaturate(cloud_fraction));
}

// F16 §5.5.1, H16 §5.5.3: ambient light weighted by a linear gradient from the layer's bottom
// to its top; `bottom` in [0, 1] is the share left at the base (F16's bias for ground bounce).
Number CloudAmbientGradient(Number height_fraction, Number bottom) {
    return mix(bottom, 1.0, CloudSaturate(height_fraction));
}

// ---------------------------------------------------------------------------------------------
// Phase functions (sr^-1; each integrates to 1 over the sphere)

// H16 Eq. 5.4.
Number CloudHenyeyGreensteinPhase(Number g, Number nu) {
    Number denominator = 1.0 + g * g - 2.0 * g * nu;
    return (1.0 - g * g) / (4.0 * kPi * denominator * sqrt(denominator));
}

// F16 Eq. 18: lerp(p_hg(g0), p_hg(g1), w), a forward lobe for the silver lining and a backward
// one so clouds seen with the sun behind the camera keep their detail.
Number CloudDualLobePhase(Number g0, Number g1, Number w, Number nu) {
    return mix(CloudHenyeyGreensteinPhase(g0, nu), CloudHenyeyGreensteinPhase(g1, nu), w);
}

// ---------------------------------------------------------------------------------------------
// Scattering: the cloud material (F16 §5.2, §5.4.1) and multiple-scattering octaves (F16 §5.8)

struct CloudScatteringParameters {
    Number forward_g;     // g0 of the dual lobe, (-1, 1)
    Number backward_g;    // g1, (-1, 1)
    Number lobe_weight;   // w, [0, 1]
    Number albedo;        // sigma_s / sigma_t, [0, 1] (F16 §5.2: ~1 for water clouds)
    Number octave_a;      // scattering factor per octave, used as min(a, b)
    Number octave_b;      // extinction factor per octave, (0, 1]
    Number octave_c;      // phase eccentricity factor per octave, [0, 1]
    Number octave_count;  // N in Eq. 19, 1..kCloudMaxOctaves (a Number to keep std140 simple)
};

// F16 §5.8: octave n scatters with sigma_s a^n and is extinguished with sigma_t b^n (Eq. 20).
// a <= b is enforced here, so no octave scatters more than it extinguishes.
Number CloudOctaveScatteringRatio(IN(CloudScatteringParameters) p) {
    return p.octave_b > 0.0 ? min(p.octave_a, p.octave_b) / p.octave_b : 0.0;
}

int CloudOctaveCount(IN(CloudScatteringParameters) p) {
    return clamp(int(p.octave_count), 1, kCloudMaxOctaves);
}

// The single-scattering albedo of octave n, albedo (a / b)^n: the share of the light the octave
// removes from a sun ray that it scatters.
Number CloudOctaveAlbedo(IN(CloudScatteringParameters) p, int n) {
    return p.albedo * pow(CloudOctaveScatteringRatio(p), Number(n));
}

// a <= b keeps each octave within its own albedo, but the octaves add: along a sun ray into a
// deep cloud they scatter sum_n albedo (a/b)^n of the light, which exceeds 1 already for F16's
// a = b = 0.5 with N = 2. Every octave is scaled by 1 / max(1, that sum) so the total scattered
// never exceeds what the sun delivers.
Number CloudOctaveEnergyNormalization(IN(CloudScatteringParameters) p) {
    Number sum = 0.0;
    Number ratio_n = 1.0;
    int count = CloudOctaveCount(p);
    for (int n = 0; n < kCloudMaxOctaves; ++n) {
        if (n >= count) break;
        sum += p.albedo * ratio_n;
        ratio_n *= CloudOctaveScatteringRatio(p);
    }
    return 1.0 / max(sum, 1.0);
}

// Sum over octaves (F16 Eq. 19-20) of a^n T_sun^(b^n) p_n(nu), per unit sigma_s and unit sun
// illuminance: the sun light a sample scatters toward the viewer. sun_optical_depth is the
// optical depth toward the sun (the shadow march); the phase of octave n has its g scaled by
// c^n, the form of Wrenninge et al. (2013) that F16 cites, which keeps every lobe normalised
// (scaling the angle, as F16 Eq. 20 is printed, would not).
Number CloudOctaveSunScattering(IN(CloudScatteringParameters) p, Number sun_optical_depth,
                                Number nu) {
    Number a = min(p.octave_a, p.octave_b);
    Number a_n = 1.0;
    Number b_n = 1.0;
    Number c_n = 1.0;
    Number sum = 0.0;
    int count = CloudOctaveCount(p);
    for (int n = 0; n < kCloudMaxOctaves; ++n) {
        if (n >= count) break;
        sum += a_n * exp(-b_n * sun_optical_depth) *
               CloudDualLobePhase(p.forward_g * c_n, p.backward_g * c_n, p.lobe_weight, nu);
        a_n *= a;
        b_n *= p.octave_b;
        c_n *= p.octave_c;
    }
    return sum * CloudOctaveEnergyNormalization(p);
}

// ---------------------------------------------------------------------------------------------
// Energy-conserving analytic integration (F16 §5.6.3, Eq. 17 and App. C)

// int_0^dt exp(-sigma_t x) dx = (1 - exp(-sigma_t dt)) / sigma_t, written as dt (1 - e^-x) / x so
// that it stays exact as sigma_t -> 0 (F16 clamps sigma_t to an epsilon instead).
Number CloudStepTransmittanceIntegral(Number extinction, Number dt) {
    Number x = extinction * dt;
    return dt * (x < 1e-3 ? 1.0 - x * (0.5 - x / 6.0) : (1.0 - exp(-x)) / x);
}

// One step of F16 Listing 2: a slab of constant extinction (1/km) and source (scattered
// luminance per km, sigma_s L_i) over dt km, in front of which the light has `transmittance`
// left. The slab adds at most source / extinction, whatever dt: the integration conserves
// energy where the naive sum (source * dt) does not.
void CloudIntegrateStep(vec3 source, Number extinction, Number dt, INOUT(vec3) luminance,
                        INOUT(Number) transmittance) {
    luminance += transmittance * CloudStepTransmittanceIntegral(extinction, dt) * source;
    transmittance *= exp(-extinction * dt);
}
