// Atmosphere physics shared by the GL renderer and the CPU reference (one text, two compilers:
// GLSL 4.50 here, C++/GLM double through sky/src/reference/shared_math.h).
//
// Hillaire, "A Scalable and Production Ready Sky and Atmosphere Rendering Technique", EGSR 2020
// (cited as H20), on the LUT parameterisation of Bruneton, "Precomputed Atmospheric Scattering:
// a New Implementation" (2017) (cited as B17).
//
// Glossary (units: kilometres inside shaders; converted once from SI by the host):
//   r     distance from the planet centre           h      altitude above the ground, r - R
//   mu    cosine of the view zenith angle           mu_s   cosine of the sun zenith angle
//   nu    cosine of the angle between view and sun  R, R_t bottom (ground) and top radii
//   T     transmittance                              sigma  coefficients, 1/km
// Light transport quantities are per unit light illuminance: multiply by lux to get cd/m^2.

// std140-compatible: every vec3 is followed by one Number, so the C++ float mirror
// (sky/src/gl/atmosphere_uniforms.h) packs identically.
struct AtmosphereParameters {
    vec3 rayleigh_scattering;
    Number rayleigh_scale_height;
    vec3 mie_scattering;
    Number mie_scale_height;
    vec3 mie_extinction;
    Number mie_g;
    vec3 absorption_extinction;
    Number absorption_center;
    vec3 ground_albedo;
    Number absorption_half_width;
    vec3 solar_illuminance;
    Number sun_angular_radius;
    Number bottom_radius;
    Number top_radius;
    Number padding0;
    Number padding1;
};

// ---------------------------------------------------------------------------------------------
// Geometry

Number ClampCosine(Number mu) { return clamp(mu, -1.0, 1.0); }
Number SafeSqrt(Number a) { return sqrt(max(a, 0.0)); }

// Distance along a ray from radius r with zenith cosine mu to the top boundary (B17 Eq. for
// d_top): the positive root of |p + d v| = R_t.
Number DistanceToTopAtmosphereBoundary(IN(AtmosphereParameters) atmosphere, Number r, Number mu) {
    Number discriminant = r * r * (mu * mu - 1.0) + atmosphere.top_radius * atmosphere.top_radius;
    return max(-r * mu + SafeSqrt(discriminant), 0.0);
}

Number DistanceToBottomAtmosphereBoundary(IN(AtmosphereParameters) atmosphere, Number r,
                                          Number mu) {
    Number discriminant =
        r * r * (mu * mu - 1.0) + atmosphere.bottom_radius * atmosphere.bottom_radius;
    return max(-r * mu - SafeSqrt(discriminant), 0.0);
}

bool RayIntersectsGround(IN(AtmosphereParameters) atmosphere, Number r, Number mu) {
    return mu < 0.0 && r * r * (mu * mu - 1.0) +
                               atmosphere.bottom_radius * atmosphere.bottom_radius >= 0.0;
}

// Nearest t >= 0 where a ray from radius r along zenith cosine mu meets the sphere of `radius`,
// or -1 if it does not. `delta` is r - radius, given separately because the caller often knows it
// exactly (the camera's altitude) while in float r - radius is quantised to the ulp of r (0.5 m
// at 6360 km). The roots use the stable form, so a grazing ray from a few metres up keeps its
// ground distance (the textbook -b - sqrt(b^2 - c) cancels there).
Number RaySphereDistance(Number r, Number mu, Number delta, Number radius) {
    Number b = r * mu;
    Number c = delta * (r + radius);  // r^2 - radius^2
    if (c >= 0.0 && b >= 0.0) return -1.0;  // on or outside the sphere, moving away
    Number discriminant = b * b - c;
    if (discriminant < 0.0) return -1.0;
    Number s = sqrt(discriminant);
    if (c > 0.0) return c / (-b + s);  // outside, moving inward (b < 0): the near root
    return -b + s;                      // inside (or on it, moving inward): the exit
}

Number RaySphereIntersectNearest(vec3 origin, vec3 direction, Number radius) {
    Number r = length(origin);
    return RaySphereDistance(r, dot(origin, direction) / r, r - radius, radius);
}

// ---------------------------------------------------------------------------------------------
// The medium (H20 §4 and Table 1)

Number RayleighDensity(IN(AtmosphereParameters) atmosphere, Number altitude) {
    return exp(-altitude / atmosphere.rayleigh_scale_height);
}

Number MieDensity(IN(AtmosphereParameters) atmosphere, Number altitude) {
    return exp(-altitude / atmosphere.mie_scale_height);
}

// Tent of full width 2 * half_width centred at absorption_center (H20 §4, ozone).
Number AbsorptionDensity(IN(AtmosphereParameters) atmosphere, Number altitude) {
    return max(0.0, 1.0 - abs(altitude - atmosphere.absorption_center) /
                              atmosphere.absorption_half_width);
}

struct MediumSample {
    vec3 rayleigh_scattering;
    vec3 mie_scattering;
    vec3 scattering;
    vec3 extinction;
};

MediumSample SampleMedium(IN(AtmosphereParameters) atmosphere, Number altitude) {
    Number rayleigh = RayleighDensity(atmosphere, altitude);
    Number mie = MieDensity(atmosphere, altitude);
    Number absorption = AbsorptionDensity(atmosphere, altitude);
    MediumSample s;
    s.rayleigh_scattering = atmosphere.rayleigh_scattering * rayleigh;
    s.mie_scattering = atmosphere.mie_scattering * mie;
    s.scattering = s.rayleigh_scattering + s.mie_scattering;
    s.extinction = s.rayleigh_scattering + atmosphere.mie_extinction * mie +
                   atmosphere.absorption_extinction * absorption;
    return s;
}

// (1 - exp(-x)) / x for optical depths x >= 0, accurate for tiny x too: a 10 cm step through air
// has x ~ 1e-6, where 1 - exp(-x) keeps only a few percent in float. The analytic per-step
// integral of Hillaire (2015) is dt * StepIntegralFactor(sigma_t * dt).
Number StepIntegralFactor(Number x) {
    return x < 1e-3 ? 1.0 - x * (0.5 - x / 6.0) : (1.0 - exp(-x)) / x;
}

vec3 StepIntegral(vec3 extinction, Number dt) {
    vec3 x = extinction * dt;
    return dt * vec3(StepIntegralFactor(x.x), StepIntegralFactor(x.y), StepIntegralFactor(x.z));
}

// ---------------------------------------------------------------------------------------------
// Phase functions (sr^-1; each integrates to 1 over the sphere)

Number RayleighPhase(Number nu) { return 3.0 / (16.0 * kPi) * (1.0 + nu * nu); }

// Cornette & Shanks (1992), as in H20 and B17.
Number CornetteShanksPhase(Number g, Number nu) {
    Number k = 3.0 / (8.0 * kPi) * (1.0 - g * g) / (2.0 + g * g);
    return k * (1.0 + nu * nu) / pow(max(1.0 + g * g - 2.0 * g * nu, 1e-6), 1.5);
}

Number IsotropicPhase() { return 1.0 / (4.0 * kPi); }

// ---------------------------------------------------------------------------------------------
// Texture coordinates: a value in [0, 1] maps to texel centres, so the first and last texel
// hold the exact end values (B17 "GetTextureCoordFromUnitRange").

Number GetTextureCoordFromUnitRange(Number x, int texture_size) {
    return 0.5 / Number(texture_size) + x * (1.0 - 1.0 / Number(texture_size));
}

Number GetUnitRangeFromTextureCoord(Number u, int texture_size) {
    return (u - 0.5 / Number(texture_size)) / (1.0 - 1.0 / Number(texture_size));
}

// ---------------------------------------------------------------------------------------------
// Transmittance LUT (H20 §5.2, parameterised as B17 §"Transmittance"): x_r from the distance to
// the horizon, x_mu from the distance to the top boundary between its minimum and maximum, so
// the texels concentrate near the horizon where transmittance varies fastest.

vec2 GetTransmittanceTextureUvFromRMu(IN(AtmosphereParameters) atmosphere, Number r, Number mu,
                                      ivec2 size) {
    Number H = sqrt(atmosphere.top_radius * atmosphere.top_radius -
                    atmosphere.bottom_radius * atmosphere.bottom_radius);
    Number rho = SafeSqrt(r * r - atmosphere.bottom_radius * atmosphere.bottom_radius);
    Number d = DistanceToTopAtmosphereBoundary(atmosphere, r, mu);
    Number d_min = atmosphere.top_radius - r;
    Number d_max = rho + H;
    Number x_mu = (d - d_min) / (d_max - d_min);
    Number x_r = rho / H;
    return vec2(GetTextureCoordFromUnitRange(x_mu, size.x),
                GetTextureCoordFromUnitRange(x_r, size.y));
}

void GetRMuFromTransmittanceTextureUv(IN(AtmosphereParameters) atmosphere, vec2 uv, ivec2 size,
                                      OUT(Number) r, OUT(Number) mu) {
    Number x_mu = GetUnitRangeFromTextureCoord(uv.x, size.x);
    Number x_r = GetUnitRangeFromTextureCoord(uv.y, size.y);
    Number H = sqrt(atmosphere.top_radius * atmosphere.top_radius -
                    atmosphere.bottom_radius * atmosphere.bottom_radius);
    Number rho = H * x_r;
    r = sqrt(rho * rho + atmosphere.bottom_radius * atmosphere.bottom_radius);
    Number d_min = atmosphere.top_radius - r;
    Number d_max = rho + H;
    Number d = d_min + x_mu * (d_max - d_min);
    mu = d == 0.0 ? 1.0 : (H * H - rho * rho - d * d) / (2.0 * r * d);
    mu = ClampCosine(mu);
}

// Mean of an exponential between two samples: exact for a density that varies exponentially
// along the segment, as exp(-h/H) does along a vertical ray.
Number LogMean(Number a, Number b) {
    // Densities that underflowed, or nearly equal ones (where the quotient is 0/0), take the
    // arithmetic mean, which the log mean tends to.
    if (a <= 0.0 || b <= 0.0) return 0.5 * (a + b);
    Number ratio = a / b;
    if (abs(ratio - 1.0) < 1e-3) return 0.5 * (a + b);
    return (a - b) / log(ratio);
}

// Optical depth to the top boundary with `steps` segments (H20 Table 2: 40). Each exponential
// component is integrated as an exponential between the segment ends and the tent by the
// trapezoidal rule, so a vertical ray reproduces the closed form exactly (the tent's kinks fall
// on segment ends there), where a plain trapezoid over 2.5 km steps overestimates the 1.2 km Mie
// layer's depth by a third.
vec3 ComputeOpticalDepthToTopAtmosphereBoundary(IN(AtmosphereParameters) atmosphere, Number r,
                                                Number mu, int steps) {
    Number dx = DistanceToTopAtmosphereBoundary(atmosphere, r, mu) / Number(steps);
    Number rayleigh = 0.0;
    Number mie = 0.0;
    Number absorption = 0.0;
    Number previous_rayleigh = RayleighDensity(atmosphere, r - atmosphere.bottom_radius);
    Number previous_mie = MieDensity(atmosphere, r - atmosphere.bottom_radius);
    Number previous_absorption = AbsorptionDensity(atmosphere, r - atmosphere.bottom_radius);
    for (int i = 1; i <= steps; ++i) {
        Number d_i = Number(i) * dx;
        Number h_i = sqrt(d_i * d_i + 2.0 * r * mu * d_i + r * r) - atmosphere.bottom_radius;
        Number rayleigh_i = RayleighDensity(atmosphere, h_i);
        Number mie_i = MieDensity(atmosphere, h_i);
        Number absorption_i = AbsorptionDensity(atmosphere, h_i);
        rayleigh += LogMean(previous_rayleigh, rayleigh_i) * dx;
        mie += LogMean(previous_mie, mie_i) * dx;
        absorption += 0.5 * (previous_absorption + absorption_i) * dx;
        previous_rayleigh = rayleigh_i;
        previous_mie = mie_i;
        previous_absorption = absorption_i;
    }
    return atmosphere.rayleigh_scattering * rayleigh + atmosphere.mie_extinction * mie +
           atmosphere.absorption_extinction * absorption;
}

vec3 ComputeTransmittanceToTopAtmosphereBoundary(IN(AtmosphereParameters) atmosphere, Number r,
                                                 Number mu, int steps) {
    return exp(-ComputeOpticalDepthToTopAtmosphereBoundary(atmosphere, r, mu, steps));
}

// The LUT texel for texture coordinate uv (one compute-shader invocation).
vec3 ComputeTransmittanceTexel(IN(AtmosphereParameters) atmosphere, vec2 uv, ivec2 size,
                               int steps) {
    Number r;
    Number mu;
    GetRMuFromTransmittanceTextureUv(atmosphere, uv, size, r, mu);
    return ComputeTransmittanceToTopAtmosphereBoundary(atmosphere, r, mu, steps);
}

vec3 GetTransmittanceToTopAtmosphereBoundary(IN(AtmosphereParameters) atmosphere,
                                             IN(TransmittanceTexture) transmittance_texture,
                                             Number r, Number mu) {
    vec2 uv =
        GetTransmittanceTextureUvFromRMu(atmosphere, r, mu, TextureSize(transmittance_texture));
    return vec3(SampleTexture2D(transmittance_texture, uv));
}

// Transmittance toward the sun, including the fraction of the solar disk above the planet's
// horizon (B17 "GetTransmittanceToSun"): this is what makes the Earth's shadow soft.
vec3 GetTransmittanceToSun(IN(AtmosphereParameters) atmosphere,
                           IN(TransmittanceTexture) transmittance_texture, Number r,
                           Number mu_s) {
    Number sin_theta_h = atmosphere.bottom_radius / r;
    Number cos_theta_h = -sqrt(max(1.0 - sin_theta_h * sin_theta_h, 0.0));
    Number visible = smoothstep(-sin_theta_h * atmosphere.sun_angular_radius,
                                sin_theta_h * atmosphere.sun_angular_radius, mu_s - cos_theta_h);
    return GetTransmittanceToTopAtmosphereBoundary(atmosphere, transmittance_texture, r, mu_s) *
           visible;
}

// Transmittance from a camera (km, planet-centred; `camera_altitude` exact) to space along
// `direction`, 0 when the ground is in the way: what the atmosphere does to the light of the Sun,
// the Moon and the stars on their way in. From space, the chord's transmittance (1 if it misses).
vec3 TransmittanceToSpace(IN(AtmosphereParameters) atmosphere,
                          IN(TransmittanceTexture) transmittance_texture,
                          vec3 camera, Number camera_altitude, vec3 direction) {
    Number r = length(camera);
    Number mu = dot(camera, direction) / r;
    if (RaySphereDistance(r, mu, camera_altitude, atmosphere.bottom_radius) >= 0.0) {
        return vec3(0.0);
    }
    Number shell = atmosphere.top_radius - atmosphere.bottom_radius;
    if (camera_altitude <= shell) {
        return GetTransmittanceToTopAtmosphereBoundary(atmosphere, transmittance_texture, r, mu);
    }
    Number t_top = RaySphereDistance(r, mu, camera_altitude - shell, atmosphere.top_radius);
    if (t_top < 0.0) return vec3(1.0);
    vec3 entry = camera + direction * t_top;
    return GetTransmittanceToTopAtmosphereBoundary(atmosphere, transmittance_texture,
                                                   atmosphere.top_radius,
                                                   dot(entry, direction) / length(entry));
}

// Transmittance from a camera (km, planet-centred; `camera_altitude` exact) to the ground
// `distance` km along `direction`, a ray that meets it: T(r_g, -mu_g) / T(r, -mu), both rays
// leaving the atmosphere upward (B17 "GetTransmittance"); from space, from where the ray enters.
vec3 TransmittanceToGround(IN(AtmosphereParameters) atmosphere,
                           IN(TransmittanceTexture) transmittance_texture, vec3 camera,
                           Number camera_altitude, vec3 direction, Number distance) {
    Number r = length(camera);
    Number mu = dot(camera, direction) / r;
    Number shell = atmosphere.top_radius - atmosphere.bottom_radius;
    if (camera_altitude > shell) {
        Number t_top = RaySphereDistance(r, mu, camera_altitude - shell, atmosphere.top_radius);
        mu = (r * mu + t_top) / atmosphere.top_radius;
        r = atmosphere.top_radius;
        distance -= t_top;
    }
    Number mu_ground = ClampCosine((r * mu + distance) / atmosphere.bottom_radius);
    vec3 from_ground = GetTransmittanceToTopAtmosphereBoundary(
        atmosphere, transmittance_texture, atmosphere.bottom_radius, -mu_ground);
    vec3 from_camera = GetTransmittanceToTopAtmosphereBoundary(
        atmosphere, transmittance_texture, r, -mu);
    return min(from_ground / max(from_camera, vec3(1e-30)), vec3(1.0));
}

// ---------------------------------------------------------------------------------------------
// Multiple-scattering LUT (H20 §5.5): v = h / (R_t - R) as in the paper, but u = 0.5 + 0.5 sign(mu_s)
// sqrt(|mu_s|) instead of 0.5 + 0.5 mu_s: Psi_ms falls steeply through twilight, and with the
// paper's linear u, 32 texels put 3.6 deg of sun elevation per texel at the horizon, where linear
// interpolation overshot the Earth's shadow sky by half (tests/sky/accuracy_test.cpp). The ground
// irradiance LUT below uses the same u for the same reason.

Number UnitRangeFromSunCosine(Number mu_s) {
    return clamp(0.5 + 0.5 * sign(mu_s) * sqrt(abs(mu_s)), 0.0, 1.0);
}

Number SunCosineFromUnitRange(Number u) {
    Number x = 2.0 * u - 1.0;
    return ClampCosine(sign(x) * x * x);
}

vec2 GetMultipleScatteringTextureUv(IN(AtmosphereParameters) atmosphere, Number r, Number mu_s,
                                    ivec2 size) {
    Number x_mu_s = UnitRangeFromSunCosine(mu_s);
    Number x_h = clamp((r - atmosphere.bottom_radius) /
                           (atmosphere.top_radius - atmosphere.bottom_radius), 0.0, 1.0);
    return vec2(GetTextureCoordFromUnitRange(x_mu_s, size.x),
                GetTextureCoordFromUnitRange(x_h, size.y));
}

// The light of orders >= 2 arriving at a point, per unit light illuminance, in the point's frame
// (z up, x toward the light's azimuth): its mean over the sphere, psi = (1 / 4 pi) int L dw (H20's
// Psi_ms), and its second moments q = (1 / 4 pi) int L w w^T dw, of which the light's vertical
// plane of symmetry leaves xx, zz and xz (q_yy = psi - q_xx - q_zz; q = psi / 3 I where the light
// is isotropic). The second moments are what Rayleigh's phase sees of the field (its Legendre
// terms are P0 and P2): H20 scatters psi isotropically, which past sunset lost 20-60 % of the
// anti-solar horizon's light, where the shadowed air's light comes from the sunward sky and
// reaches the eye by backscattering (1.5x isotropic; tests/bench/twilight_orders_report.cpp).
struct MultipleScatteringSample {
    vec3 psi;
    vec3 q_xx;
    vec3 q_zz;
    vec3 q_xz;
};

// The LUT holds three tiles of LutSettings::multiple_scattering_size side by side:
// (psi, q_xz.r), (q_xx, q_xz.g), (q_zz, q_xz.b). A texel centre of one tile is never filtered
// with another's (GetTextureCoordFromUnitRange keeps half a texel from each edge).
vec4 MultipleScatteringTexel(IN(MultipleScatteringSample) m, int tile) {
    if (tile == 0) return vec4(m.psi, m.q_xz.x);
    if (tile == 1) return vec4(m.q_xx, m.q_xz.y);
    return vec4(m.q_zz, m.q_xz.z);
}

MultipleScatteringSample MultipleScatteringFromTexels(vec4 t0, vec4 t1, vec4 t2) {
    MultipleScatteringSample m;
    m.psi = vec3(t0);
    m.q_xx = vec3(t1);
    m.q_zz = vec3(t2);
    m.q_xz = vec3(t0.w, t1.w, t2.w);
    return m;
}

// a + b * scale, per moment.
MultipleScatteringSample AddMultipleScattering(IN(MultipleScatteringSample) a,
                                               IN(MultipleScatteringSample) b, vec3 scale) {
    MultipleScatteringSample m;
    m.psi = a.psi + b.psi * scale;
    m.q_xx = a.q_xx + b.q_xx * scale;
    m.q_zz = a.q_zz + b.q_zz * scale;
    m.q_xz = a.q_xz + b.q_xz * scale;
    return m;
}

MultipleScatteringSample NoMultipleScattering() {
    MultipleScatteringSample m;
    m.psi = vec3(0.0);
    m.q_xx = vec3(0.0);
    m.q_zz = vec3(0.0);
    m.q_xz = vec3(0.0);
    return m;
}

MultipleScatteringSample GetMultipleScatteringSample(
    IN(AtmosphereParameters) atmosphere, IN(MultipleScatteringTexture) multiple_scattering_texture,
    Number r, Number mu_s) {
    ivec2 size = TextureSize(multiple_scattering_texture);
    size.x /= kMultipleScatteringTiles;
    vec2 uv = GetMultipleScatteringTextureUv(atmosphere, r, mu_s, size);
    Number tile = 1.0 / Number(kMultipleScatteringTiles);
    return MultipleScatteringFromTexels(
        SampleTexture2D(multiple_scattering_texture, vec2(uv.x * tile, uv.y)),
        SampleTexture2D(multiple_scattering_texture, vec2((uv.x + 1.0) * tile, uv.y)),
        SampleTexture2D(multiple_scattering_texture, vec2((uv.x + 2.0) * tile, uv.y)));
}

// Psi_ms alone, for light scattered as if isotropically (the eclipse's umbra, the clouds).
vec3 GetMultipleScattering(IN(AtmosphereParameters) atmosphere,
                           IN(MultipleScatteringTexture) multiple_scattering_texture, Number r,
                           Number mu_s) {
    return GetMultipleScatteringSample(atmosphere, multiple_scattering_texture, r, mu_s).psi;
}

// The multiply scattered light that medium sample `s` at unit `up` (its zenith) scatters along
// direction `o` or -o (the second moments do not tell them apart), per unit illuminance of the
// light in `light_direction`: Rayleigh's share with its phase over the moments, the aerosols'
// isotropically with coefficient mie_weight * sigma_s (1 to render; 1 - g where orders >= 3
// transfer, ComputeScatteringOrderTexel).
vec3 MultipleScatteringInScattering(IN(MultipleScatteringSample) m, IN(MediumSample) s, vec3 up,
                                    vec3 light_direction, vec3 o, Number mie_weight) {
    Number mu_l = dot(up, light_direction);
    vec3 horizontal = light_direction - up * mu_l;
    Number horizontal_length = length(horizontal);
    Number o_z = dot(o, up);
    // Overhead light: q is symmetric about the zenith and any horizontal axis serves.
    Number o_x = horizontal_length > 1e-6 ? dot(o, horizontal) / horizontal_length : 0.0;
    Number o_y2 = max(1.0 - o_x * o_x - o_z * o_z, 0.0);
    vec3 q_yy = m.psi - m.q_xx - m.q_zz;
    // o^T q o; Rayleigh's phase 3 / (16 pi) (1 + cos^2) integrated against L gives
    // 3/4 (psi + o^T q o), which is psi for an isotropic field.
    vec3 along = m.q_xx * (o_x * o_x) + q_yy * o_y2 + m.q_zz * (o_z * o_z) +
                 m.q_xz * (2.0 * o_x * o_z);
    return s.rayleigh_scattering * (0.75 * (m.psi + along)) +
           s.mie_scattering * (mie_weight * m.psi);
}

// Direction i of n on the unit sphere: the Fibonacci (golden-angle) spiral, equal solid angle per
// point and n distinct zenith angles. H20 asks for 64 uniformly distributed directions; a
// sqrt(n) x sqrt(n) grid in (cos theta, phi) has only sqrt(n) distinct zenith angles, which with
// the sun overhead (an azimuthally symmetric integrand) left Psi_ms 14 % (of its peak) off its
// converged value; the spiral is within 0.8 % (tests/sky/atmosphere_lut_test.cpp).
vec3 UniformSphereDirection(int i, int n) {
    Number cos_theta = 1.0 - (2.0 * Number(i) + 1.0) / Number(n);
    Number sin_theta = SafeSqrt(1.0 - cos_theta * cos_theta);
    Number phi = Number(i) * 2.39996322972865332;  // pi (3 - sqrt 5), the golden angle
    return vec3(sin_theta * cos(phi), sin_theta * sin(phi), cos_theta);
}

// One order of the multiple scattering for one texel: the light that has scattered k - 1 times,
// arriving at the texel's point, as MultipleScatteringSample (order k's psi and moments); and
// f_ms, the share of isotropic light the air around scatters back (H20 Eq. 5-8). Integrated over
// `sqrt_directions`^2 directions with `steps` ray-marching steps each. Order 2 (H20's
// L_2nd_order) scatters the sun's light, through the transmittance LUT, Rayleigh with its phase
// and the aerosols isotropically; order k > 2 scatters order k - 1's, read from `previous_order`
// (a LUT of the same layout; unused for order 2) by MultipleScatteringInScattering.
//
// H20 stops at order 2 and sums the rest as a geometric series, Psi_ms = L_2 / (1 - f_ms) (Eq.
// 9-10): every further order the same share f_ms of the one before, as if the light of each were
// spread like order 2's. Past sunset it is not: order 2 lives in the sunlit upper air, order 3
// already reaches down into Earth's shadow. Iterating a few orders and summing the series only
// after them (ScatteringOrdersSum) recovered a third to two thirds of the blue that H20 lost at
// the sunset horizon (tests/bench/twilight_orders_report.cpp).
// The directions order k integrates over: sqrt_directions^2 for order 2, whose light arrives from
// the bright sunward sky in a band as narrow as a few degrees past sunset; a quarter as many
// (at least 16) for later orders, whose light is the sky's scattered light again, spread
// smoothly. The twilight grid's p95 moved by under a point, and the static LUTs cost a third
// less (BENCHMARKS.md).
int ScatteringOrderDirections(int order, int sqrt_directions) {
    int sqrt_n = order == 2 ? sqrt_directions : max(sqrt_directions / 2, 4);
    return sqrt_n * sqrt_n;
}

struct ScatteringOrder {
    MultipleScatteringSample light;
    vec3 transfer;  // f_ms
};

// The directions first, first + stride, ... of the texel's (the GL pass spreads them over a
// work group and sums its invocations'; the CPU takes them all, first 0 and stride 1).
ScatteringOrder ComputeScatteringOrderTexel(IN(AtmosphereParameters) atmosphere,
                                            IN(TransmittanceTexture) transmittance_texture,
                                            IN(MultipleScatteringTexture) previous_order,
                                            int order, vec2 uv, ivec2 size, int sqrt_directions,
                                            int steps, int first, int stride) {
    Number x_mu_s = GetUnitRangeFromTextureCoord(uv.x, size.x);
    Number x_h = GetUnitRangeFromTextureCoord(uv.y, size.y);
    Number mu_s = SunCosineFromUnitRange(x_mu_s);
    Number r = atmosphere.bottom_radius +
               clamp(x_h, 0.0, 1.0) * (atmosphere.top_radius - atmosphere.bottom_radius);
    // Keep the sample strictly inside the shell so rays from the ground start above it.
    r = clamp(r, atmosphere.bottom_radius + 1e-4, atmosphere.top_radius - 1e-4);
    vec3 position = vec3(0.0, 0.0, r);
    vec3 sun_direction = vec3(SafeSqrt(1.0 - mu_s * mu_s), 0.0, mu_s);

    int n = ScatteringOrderDirections(order, sqrt_directions);
    ScatteringOrder result;
    result.light = NoMultipleScattering();
    result.transfer = vec3(0.0);
    for (int i = first; i < n; i += stride) {
        vec3 direction = UniformSphereDirection(i, n);
        Number mu = direction.z;
        bool hits_ground = RayIntersectsGround(atmosphere, r, mu);
        Number t_max = hits_ground ? DistanceToBottomAtmosphereBoundary(atmosphere, r, mu)
                                   : DistanceToTopAtmosphereBoundary(atmosphere, r, mu);
        Number dt = t_max / Number(steps);
        vec3 throughput = vec3(1.0);
        vec3 l = vec3(0.0);
        vec3 l_f = vec3(0.0);
        for (int j = 0; j < steps; ++j) {
            Number t = (Number(j) + 0.5) * dt;
            vec3 p = position + direction * t;
            Number r_p = length(p);
            MediumSample s = SampleMedium(atmosphere, r_p - atmosphere.bottom_radius);
            vec3 step_transmittance = exp(-s.extinction * dt);
            Number mu_s_p = dot(p, sun_direction) / r_p;
            // Energy-conserving integration over the step (Hillaire 2015): the integral of
            // exp(-sigma_t t) over [0, dt] times the in-scattering source.
            vec3 integral = StepIntegral(s.extinction, dt);
            // Orders >= 3 transfer the aerosols' light isotropically with their reduced
            // scattering coefficient (1 - g) sigma_s: for forward-peaked dust the isotropic
            // medium transporting the same light is the reduced one (similarity relation, van de
            // Hulst); light scattered forward is light not yet scattered. Without it Mars' dusty
            // sky (g = 0.65) came out 1.5x the path tracer's.
            if (order == 2) {
                vec3 sun = GetTransmittanceToSun(atmosphere, transmittance_texture, r_p, mu_s_p);
                vec3 phase_scattering =
                    s.rayleigh_scattering * RayleighPhase(dot(direction, sun_direction)) +
                    s.mie_scattering * IsotropicPhase();
                l += throughput * phase_scattering * sun * integral;  // Eq. 6
            } else {
                MultipleScatteringSample m =
                    GetMultipleScatteringSample(atmosphere, previous_order, r_p, mu_s_p);
                l += throughput *
                     MultipleScatteringInScattering(m, s, p / r_p, sun_direction, direction,
                                                    1.0 - atmosphere.mie_g) *
                     integral;
            }
            l_f += throughput * (s.scattering - s.mie_scattering * atmosphere.mie_g) *
                   integral;  // Eq. 8
            throughput *= step_transmittance;
        }
        if (hits_ground && order == 2) {
            // Lambertian ground lit by the sun (the L_o term of Eq. 6). Like H20's f_ms, later
            // orders leave out the light the ground reflects again.
            vec3 p = position + direction * t_max;
            vec3 n_ground = normalize(p);
            Number mu_s_ground = dot(n_ground, sun_direction);
            vec3 sun = GetTransmittanceToSun(atmosphere, transmittance_texture,
                                             atmosphere.bottom_radius, mu_s_ground);
            l += throughput * sun * max(mu_s_ground, 0.0) * atmosphere.ground_albedo / kPi;
        }
        // Eq. 5 and 7 with p_u = 1 / (4 pi) and a solid angle of 4 pi / n per direction; the
        // moments the same with w w^T.
        MultipleScatteringSample arriving;
        arriving.psi = l;
        arriving.q_xx = l * (direction.x * direction.x);
        arriving.q_zz = l * (direction.z * direction.z);
        arriving.q_xz = l * (direction.x * direction.z);
        result.light = AddMultipleScattering(result.light, arriving, vec3(1.0 / Number(n)));
        result.transfer += l_f / Number(n);
    }
    return result;
}

// Psi_ms and its moments once orders 2 .. K are known: `sum` theirs, `last` order K's, which
// carries the orders beyond it as H20's geometric series, order K f_ms / (1 - f_ms), and
// `column`, what a plane-parallel column solved to all orders finds those orders to hold beyond
// its own series (sky/src/multiple_scattering_column.h), added as isotropic light and never
// below none. Where the air is optically thick the series loses the light that diffuses through
// hundreds of orders (the `thick` preset kept 17 % of its red and < 0.1 % of its blue). With
// K = 2 and no column psi is H20's L_2 / (1 - f_ms) (Eq. 10).
MultipleScatteringSample ScatteringOrdersSum(IN(MultipleScatteringSample) sum,
                                             IN(ScatteringOrder) last, vec3 column) {
    vec3 f_ms = min(last.transfer, vec3(0.999));
    MultipleScatteringSample m = AddMultipleScattering(sum, last.light, f_ms / (vec3(1.0) - f_ms));
    vec3 isotropic = max(column, -m.psi);
    m.psi += isotropic;
    m.q_xx += isotropic / 3.0;
    m.q_zz += isotropic / 3.0;
    return m;
}

// The LUT once order k of K is in: order k's light added to `sum_before`, the LUT after order
// k - 1 (not read when k = 2), and after order K the orders beyond it (ScatteringOrdersSum, with
// the column's correction at this texel).
MultipleScatteringSample AccumulateScatteringOrder(IN(MultipleScatteringSample) sum_before,
                                                   IN(ScatteringOrder) order, int k, int last,
                                                   vec3 column) {
    MultipleScatteringSample sum = order.light;
    if (k > 2) sum = AddMultipleScattering(sum_before, order.light, vec3(1.0));
    if (k == last) sum = ScatteringOrdersSum(sum, order, column);
    return sum;
}

// ---------------------------------------------------------------------------------------------
// Sky irradiance on the ground, per unit light illuminance, as a function of the light's zenith
// cosine (u = UnitRangeFromSunCosine(mu_s), as the multiple-scattering LUT): lets the ground be lit
// by the sky as well as by the sun, which H20 leaves to the engine. Filled by integrating the
// scattered luminance over the upper hemisphere. Through civil twilight it falls by a factor ~3
// per degree of sun depression; with u = 0.5 + 0.5 mu_s, 64 texels (1.8 deg each at the
// horizon) overshot it by up to half between texel centres (accuracy_report --grid illuminance).

vec3 GetGroundSkyIrradiance(IN(IrradianceTexture) irradiance_texture, Number mu_s) {
    vec2 uv = vec2(GetTextureCoordFromUnitRange(UnitRangeFromSunCosine(mu_s),
                                                TextureSize(irradiance_texture).x),
                   0.5);
    return vec3(SampleTexture2D(irradiance_texture, uv));
}

// ---------------------------------------------------------------------------------------------
// Scattered luminance along a view ray (H20 Eq. 11) for up to two directional lights (sun and
// moon, N_light = 2). Used by the Sky-View and aerial-perspective LUTs and, with more steps, by
// per-pixel ray marching for views from space.

struct Light {
    vec3 direction;     // unit, toward the light
    Number padding0;
    vec3 illuminance;   // lux at the top of the atmosphere
    Number padding1;
};

// Light 0 is the Sun (the Sky-View LUT's azimuth origin); light 1, when count is 2, the Moon.
// A loop over `count` rather than a branch per light: llvmpipe runs both sides of a branch under
// a mask, but stops a loop when no lane goes on, so a disabled Moon costs nothing.
//
// The clouds above, as the air and the ground beneath them see them (F16 §5.9.2, Eq. 22:
// L_ap = L_ap Tr_cloud + L_cloud). Below cloud_base (km above the ground; 0 without clouds) each
// light's direct part is scaled by cloud_direct, the clouds' mean transmittance toward the main
// light over the ground around the camera, its sky-scattered part by cloud_sky, the clouds' mean
// transmittance over the upper hemisphere, and the clouds' own light is added as an isotropic
// source: cloud_luminance, their mean luminance over that hemisphere (clouds/sky_shade.comp).
// The ground, a horizontal surface, gets the same means weighted by the cosine from the zenith
// (cloud_ground_sky, cloud_ground_luminance: its irradiance from the clouds is pi times the
// latter): an overcast deck is brighter overhead than toward the horizon, and the uniform mean
// gave the ground 10 % too little of its light. cloud_shaded is 1 once these members hold
// sky_shade.comp's means, 0 before (the clouds' own pass that makes them reads 0).
struct LightSet {
    Light light[kMaxLights];
    int count;
    Number cloud_base;
    Number cloud_direct;
    Number cloud_sky;
    vec3 cloud_luminance;
    Number cloud_ground_sky;
    vec3 cloud_ground_luminance;
    Number cloud_shaded;
    // A solar eclipse (eclipse 1; 0 without): light 0 lights each point of the air (and the
    // ground) by what the Moon leaves of the Sun's disk there, from eclipse_sun_illuminance, the
    // unobscured Sun (light 0's illuminance is what is left at the camera). The Moon's shadow is
    // the cone along light 0's direction through the Moon's centre: eclipse_axis_point is the
    // axis's point nearest the camera (km, planet-centred), eclipse_axis_distance the Moon's
    // centre's distance from it along the axis (km), the radii those of the disks seen from the
    // camera (rad; a few hundred km away they differ by < 0.1 %).
    vec3 eclipse_sun_illuminance;
    int eclipse;
    vec3 eclipse_axis_point;
    Number eclipse_axis_distance;
    Number eclipse_sun_radius;
    Number eclipse_moon_radius;
    Number padding1;
    Number padding2;
    // The Sun's illuminance behind the multiply scattered light around the camera
    // (EclipsedSkyIlluminance at the camera, on the CPU: sky::EclipseAroundIlluminance).
    vec3 eclipse_around_illuminance;
    Number padding3;
    // The limb-darkened Sun's light left over its uniform disk's area left (rgb; a unused), at
    // x = x_in + (x_out - x_in) (i / (kEclipseLimbSamples - 1))^2 between the disks' inner and
    // outer contacts (x the separation in Sun radii, x_in = |1 - k|, x_out = 1 + k, k the Moon's
    // radius in Sun radii): geo::CoveredFluxFraction's, 0.1-0.7 for the thin crescents near
    // totality, 1 when the disks just touch (sky::EclipseLimbTable).
    vec4 eclipse_limb[kEclipseLimbSamples];
    // The night sky's illuminance on the horizontal ground (lux; NightSkyGroundIrradiance:
    // airglow, zodiacal light, starlight, their glow in the air, light pollution), 0 by day.
    vec3 night_ground_irradiance;
    Number padding4;
};

// Fraction of a uniform disk of radius 1 that a disk of radius k, its centre x away, leaves
// uncovered (the two-circle intersection in closed form; geo::DiskOverlapArea's). The Sun's
// limb darkening multiplies it (LimbDarkenedRatio).
Number UncoveredDiskFraction(Number k, Number x) {
    if (x >= 1.0 + k) return 1.0;
    if (x <= abs(1.0 - k)) return k >= 1.0 ? 0.0 : 1.0 - k * k;
    Number c1 = clamp((x * x + 1.0 - k * k) / (2.0 * x), -1.0, 1.0);
    Number c2 = clamp((x * x + k * k - 1.0) / (2.0 * x * k), -1.0, 1.0);
    Number q = (-x + 1.0 + k) * (x + 1.0 - k) * (x - 1.0 + k) * (x + 1.0 + k);
    Number area = acos(c1) + k * k * acos(c2) - 0.5 * sqrt(max(q, 0.0));
    return clamp(1.0 - area / kPi, 0.0, 1.0);
}

// LightSet.eclipse_limb interpolated at separation x (Sun radii) for a Moon of k Sun radii;
// inside the antumbra of an annular eclipse its inner value (the ring's ratio varies there by
// < 7 %), outside the outer contact 1.
vec3 LimbDarkenedRatio(IN(LightSet) lights, Number k, Number x) {
    Number x_in = abs(1.0 - k);
    Number s = sqrt(clamp((x - x_in) / (1.0 + k - x_in), 0.0, 1.0)) *
               Number(kEclipseLimbSamples - 1);
    int i = min(int(s), kEclipseLimbSamples - 2);
    vec4 a = lights.eclipse_limb[i];
    vec4 b = lights.eclipse_limb[i + 1];
    return mix(vec3(a.x, a.y, a.z), vec3(b.x, b.y, b.z), s - Number(i));
}

// The Sun's illuminance at point p (km, planet-centred) in a solar eclipse: the Moon's centre
// appears from p its distance from the shadow's axis over its distance along it away from the
// Sun's; what is left of the disk is the uniform disk's closed form times the limb darkening's
// ratio (within 1 % of geo::CoveredFluxFraction, tests/sky/eclipse_sky_test.cpp).
vec3 EclipsedSunIlluminance(IN(LightSet) lights, vec3 p) {
    vec3 q = p - lights.eclipse_axis_point;
    Number along = dot(q, lights.light[0].direction);
    Number offset = length(q - lights.light[0].direction * along);
    Number separation = offset / (lights.eclipse_axis_distance - along);
    Number k = lights.eclipse_moon_radius / lights.eclipse_sun_radius;
    Number x = separation / lights.eclipse_sun_radius;
    return lights.eclipse_sun_illuminance * UncoveredDiskFraction(k, x) *
           LimbDarkenedRatio(lights, k, x);
}

// In a solar eclipse, the Sun's illuminance behind the light multiply scattered at point p:
// that light last scattered in the air around p, not at p, so it carries the Sun's share there.
// Averaged over where it comes from: 4 horizontal directions (along and across the Sun's
// azimuth) at the 2-node Gauss-Laguerre distances of an exponential of the mean free path
// `free_path` (km, 1 / extinction at the ground; the chance that light last scattered at
// distance s is ~exp(-s / free_path)). So the umbra's air, dark to the Sun, is lit by the sunlit air beyond
// it: the second scattering that the per-point shadow leaves out. Horizontal only (upward the
// air thins, downward is ground in the same shadow), with the ground's free path at every
// altitude (the light multiply scattered up there comes mostly from the dense air below): a
// documented approximation, evaluated once per frame at the camera (its 8 shadow evaluations per
// sample tripled the Sky-View LUT's cost) and used for every sample where it exceeds the share
// there (the umbra, ~100 km across, is where it matters; across it the value varies by the
// share at a free path's distance, which the camera's stands for).
vec3 EclipsedSkyIlluminance(IN(LightSet) lights, vec3 p, Number free_path) {
    vec3 up = normalize(p);
    vec3 across = cross(up, lights.light[0].direction);
    Number across_length = length(across);
    // The Sun at the zenith: any horizontal axis.
    across = across_length > 1e-6 ? across / across_length
                                   : normalize(cross(up, vec3(up.y, up.z, up.x)));
    vec3 along = cross(across, up);
    Number near = 0.585786437626905 * free_path;  // 2 - sqrt 2, weight (2 + sqrt 2) / 4
    Number far = 3.414213562373095 * free_path;   // 2 + sqrt 2, weight (2 - sqrt 2) / 4
    vec3 sum = vec3(0.0);
    for (int k = 0; k < 4; ++k) {
        Number sign = k < 2 ? 1.0 : -1.0;
        vec3 e = (k % 2 == 0 ? along : across) * sign;
        sum += 0.853553390593274 * EclipsedSunIlluminance(lights, p + e * near) +
               0.146446609406726 * EclipsedSunIlluminance(lights, p + e * far);
    }
    return sum * 0.25;
}

// Light l's illuminance at point p: its own, or in a solar eclipse the Sun's there. A loop
// rather than a branch (see LightSet): without an eclipse it never runs.
vec3 LightIlluminanceAt(IN(LightSet) lights, int l, vec3 p) {
    vec3 illuminance = lights.light[l].illuminance;
    int eclipsed = l == 0 ? lights.eclipse : 0;
    for (int k = 0; k < eclipsed; ++k) illuminance = EclipsedSunIlluminance(lights, p);
    return illuminance;
}

// A sample at `altitude` (km) lies under the clouds: 1, else 0. A factor rather than a branch
// (see LightSet).
Number UnderClouds(IN(LightSet) lights, Number altitude) {
    return altitude < lights.cloud_base ? 1.0 : 0.0;
}

struct ScatteringResult {
    vec3 luminance;      // cd/m^2 (per the illuminances given)
    vec3 transmittance;  // along the marched segment
};

// In-scattered luminance from one light at point p (position relative to the planet centre),
// its single scattering scaled by `direct` and its multiple scattering by `sky` (the clouds'
// shading, 1 without clouds).
vec3 LightInScattering(IN(AtmosphereParameters) atmosphere,
                       IN(TransmittanceTexture) transmittance_texture,
                       IN(MultipleScatteringTexture) multiple_scattering_texture,
                       IN(MediumSample) s, vec3 p, Number r_p, vec3 view_direction,
                       vec3 light_direction, Number direct, Number sky) {
    Number mu_l = dot(p, light_direction) / r_p;
    Number nu = dot(view_direction, light_direction);
    vec3 transmittance = GetTransmittanceToSun(atmosphere, transmittance_texture, r_p, mu_l);
    vec3 phase_scattering = s.rayleigh_scattering * RayleighPhase(nu) +
                            s.mie_scattering * CornetteShanksPhase(atmosphere.mie_g, nu);
    MultipleScatteringSample m =
        GetMultipleScatteringSample(atmosphere, multiple_scattering_texture, r_p, mu_l);
    return transmittance * phase_scattering * direct +
           MultipleScatteringInScattering(m, s, p / r_p, light_direction, view_direction, 1.0) *
               sky;
}

// The altitude t km along a ray, and in `r` its radius: r(t)^2 - R^2 = c0 + t (2 b0 + t) with
// c0 = h0 (2R + h0) and b0 = r0 mu0 at the ray's origin (altitude h0, exact), so it follows from
// the exact altitude without cancellation (in float, |origin + t d| - R is quantised to 0.5 m,
// which is all there is of a few metres' ray from a runway).
Number AltitudeAlongRay(Number bottom_radius, Number c0, Number b0, Number t, OUT(Number) r) {
    Number excess = max(c0 + t * (2.0 * b0 + t), 0.0);
    r = sqrt(bottom_radius * bottom_radius + excess);
    return excess / (r + bottom_radius);
}

// Marches from `origin` (km, planet-centred; `origin_altitude` its altitude above the ground, exact)
// along unit `direction` over [t_begin, t_limit] km (clipped to the atmosphere) with `steps`
// steps. If `include_ground`, a ray that ends on the ground adds
// the Lambertian ground lit by each light directly and through the sky (irradiance LUT; pass
// include_ground = false while that LUT is being built).
ScatteringResult IntegrateScatteredLuminance(
    IN(AtmosphereParameters) atmosphere, IN(TransmittanceTexture) transmittance_texture,
    IN(MultipleScatteringTexture) multiple_scattering_texture,
    IN(IrradianceTexture) irradiance_texture, IN(LightSet) lights, vec3 origin,
    Number origin_altitude, vec3 direction, Number t_begin, Number t_limit, int steps,
    bool include_ground) {
    ScatteringResult result;
    result.luminance = vec3(0.0);
    result.transmittance = vec3(1.0);

    // The segment inside the atmosphere: from the entry point (if starting outside) to the exit
    // or the ground.
    Number r0 = length(origin);
    Number mu0 = dot(origin, direction) / r0;
    Number shell = atmosphere.top_radius - atmosphere.bottom_radius;
    Number t_start = 0.0;
    if (origin_altitude > shell) {
        Number t_top = RaySphereDistance(r0, mu0, origin_altitude - shell, atmosphere.top_radius);
        if (t_top < 0.0) return result;  // misses the atmosphere
        t_start = t_top;
    }
    Number t_ground =
        RaySphereDistance(r0, mu0, origin_altitude, atmosphere.bottom_radius);
    Number t_end;
    bool ends_on_ground = t_ground >= 0.0;
    if (ends_on_ground) {
        t_end = t_ground;
    } else if (origin_altitude > shell) {
        // Entered from space: leaves through the top again, symmetric about the closest point.
        t_end = -2.0 * r0 * mu0 - t_start;
    } else {
        t_end = RaySphereDistance(r0, mu0, origin_altitude - shell, atmosphere.top_radius);
    }
    if (t_limit < t_end) {
        t_end = t_limit;
        ends_on_ground = false;
    }
    t_start = max(t_start, t_begin);
    if (t_end <= t_start) return result;

    // Sample spacing follows the density. A ray starting in the air that does not reach the
    // ground is densest at its start (it climbs, or runs level into thinner air): segment ends at
    // t = t_end (i / steps)^2, as in Hillaire's implementation. One that ends on the ground is
    // densest at its end: the mirror image. Few steps then still resolve the air near the camera
    // (the paper's mobile setting, 8 steps, was 17 % off the PC sky on the ground with uniform
    // steps). A ray entering from space, or a later segment (aerial perspective), is uniform.
    int spacing = t_start > 0.0 ? 0 : (ends_on_ground ? 2 : 1);
    Number span = t_end - t_start;
    // Each sample's altitude from the exact origin altitude (AltitudeAlongRay).
    Number c0 = origin_altitude * (2.0 * atmosphere.bottom_radius + origin_altitude);
    Number b0 = r0 * mu0;
    for (int i = 0; i < steps; ++i) {
        Number u0 = Number(i) / Number(steps);
        Number u1 = Number(i + 1) / Number(steps);
        if (spacing == 1) {
            u0 = u0 * u0;
            u1 = u1 * u1;
        } else if (spacing == 2) {
            u0 = 1.0 - (1.0 - u0) * (1.0 - u0);
            u1 = 1.0 - (1.0 - u1) * (1.0 - u1);
        }
        Number t0 = t_start + span * u0;
        Number t1 = t_start + span * u1;
        Number dt = t1 - t0;
        // The midpoint with the analytic per-step integral, exact for a constant medium (H20's
        // code samples 0.3 of the way into each step).
        Number t = 0.5 * (t0 + t1);
        vec3 p = origin + direction * t;  // for light directions only
        Number r_p;
        Number altitude = AltitudeAlongRay(atmosphere.bottom_radius, c0, b0, t, r_p);
        MediumSample s = SampleMedium(atmosphere, altitude);
        // Under the clouds: the lights dimmed, the clouds' light scattered isotropically
        // (1/4 pi over the 2 pi sr of the hemisphere: half their mean luminance).
        Number under = UnderClouds(lights, altitude);
        Number direct = 1.0 + under * (lights.cloud_direct - 1.0);
        Number sky = 1.0 + under * (lights.cloud_sky - 1.0);
        vec3 source = s.scattering * lights.cloud_luminance * (0.5 * under);
        for (int l = 0; l < lights.count; ++l) {
            source += LightIlluminanceAt(lights, l, p) *
                      LightInScattering(atmosphere, transmittance_texture,
                                        multiple_scattering_texture, s,
                                        p, r_p, direction, lights.light[l].direction, direct,
                                        sky);
        }
        // A solar eclipse: the multiply scattered part lit by the Sun's share around the
        // camera (EclipsedSkyIlluminance there, once per frame) where that exceeds the share
        // at p: the umbra's air is lit by the sunlit air beyond it; outside the umbra the
        // share at p is already as large. Runs only in an eclipse.
        for (int k = 0; k < lights.eclipse; ++k) {
            vec3 around = max(lights.eclipse_around_illuminance -
                                  EclipsedSunIlluminance(lights, p),
                              vec3(0.0));
            Number mu_sun = dot(p, lights.light[0].direction) / r_p;
            source += around * s.scattering * sky *
                      GetMultipleScattering(atmosphere, multiple_scattering_texture, r_p, mu_sun);
        }
        vec3 step_transmittance = exp(-s.extinction * dt);
        vec3 integral = StepIntegral(s.extinction, dt);
        result.luminance += result.transmittance * source * integral;
        result.transmittance *= step_transmittance;
    }

    if (include_ground && ends_on_ground) {
        vec3 p = origin + direction * t_end;
        vec3 n_ground = normalize(p);
        // Under clouds the ground's sunlight is dimmed like the air's, its skylight by the
        // clouds' transmittance weighted by the cosine, and the clouds light it with irradiance
        // pi times their cosine-weighted mean luminance.
        Number under = UnderClouds(lights, 0.0);
        Number direct = 1.0 + under * (lights.cloud_direct - 1.0);
        Number sky = 1.0 + under * (lights.cloud_ground_sky - 1.0);
        vec3 ground = lights.cloud_ground_luminance * (kPi * under) +
                      lights.night_ground_irradiance * sky;
        for (int l = 0; l < lights.count; ++l) {
            Number mu_l = dot(n_ground, lights.light[l].direction);
            ground += LightIlluminanceAt(lights, l, p) *
                      (max(mu_l, 0.0) * GetTransmittanceToSun(atmosphere, transmittance_texture,
                                                              atmosphere.bottom_radius, mu_l) *
                           direct +
                       GetGroundSkyIrradiance(irradiance_texture, mu_l) * sky);
        }
        // A solar eclipse: the ground's skylight from the air around it, as the air's above.
        for (int k = 0; k < lights.eclipse; ++k) {
            vec3 around = max(lights.eclipse_around_illuminance -
                                  EclipsedSunIlluminance(lights, p),
                              vec3(0.0));
            ground += around * sky *
                      GetGroundSkyIrradiance(irradiance_texture,
                                             dot(n_ground, lights.light[0].direction));
        }
        result.luminance += result.transmittance * ground * atmosphere.ground_albedo / kPi;
    }
    return result;
}

// ---------------------------------------------------------------------------------------------
// Sky-View LUT (H20 §5.3): azimuth relative to the sun across u (full circle: the moon breaks
// the symmetry about the sun's vertical), latitude across v with the horizon in the middle and
// v = 0.5 + 0.5 sign(l) sqrt(|l| / l_max), where l is measured from the geometric horizon at the
// camera's altitude (l_max: to the zenith above, to the nadir below).

// Zenith angle of the geometric horizon seen from `altitude`: pi/2 plus the dip, whose tangent is
// sqrt(h (2R + h)) / R (pi/2 on the ground, approaching pi far away); computed from the altitude
// so that a few metres above the ground keep their dip in float.
Number HorizonZenithAngle(IN(AtmosphereParameters) atmosphere, Number altitude) {
    Number h = max(altitude, 0.0);
    return 0.5 * kPi +
           atan(sqrt(h * (2.0 * atmosphere.bottom_radius + h)), atmosphere.bottom_radius);
}

// uv of a view direction given its zenith angle and its azimuth relative to the sun, [0, 2 pi).
vec2 GetSkyViewTextureUvForHorizon(Number horizon, Number view_zenith, Number azimuth,
                                   ivec2 size) {
    Number v;
    if (view_zenith < horizon) {
        v = 0.5 + 0.5 * sqrt(clamp((horizon - view_zenith) / horizon, 0.0, 1.0));
    } else {
        v = 0.5 - 0.5 * sqrt(clamp((view_zenith - horizon) / (kPi - horizon), 0.0, 1.0));
    }
    return vec2(azimuth / (2.0 * kPi), GetTextureCoordFromUnitRange(v, size.y));
}

vec2 GetSkyViewTextureUv(IN(AtmosphereParameters) atmosphere, Number altitude, Number view_zenith,
                         Number azimuth, ivec2 size) {
    return GetSkyViewTextureUvForHorizon(HorizonZenithAngle(atmosphere, altitude), view_zenith,
                                         azimuth, size);
}

void GetViewFromSkyViewTextureUv(IN(AtmosphereParameters) atmosphere, Number altitude, vec2 uv,
                                 ivec2 size, OUT(Number) view_zenith, OUT(Number) azimuth) {
    Number horizon = HorizonZenithAngle(atmosphere, altitude);
    Number v = clamp(GetUnitRangeFromTextureCoord(uv.y, size.y), 0.0, 1.0);
    if (v >= 0.5) {
        Number x = 2.0 * v - 1.0;
        view_zenith = horizon * (1.0 - x * x);
    } else {
        Number x = 1.0 - 2.0 * v;
        view_zenith = horizon + (kPi - horizon) * x * x;
    }
    azimuth = uv.x * 2.0 * kPi;  // texel centres at (i + 0.5) / width; the u axis wraps
}

// Local frame of the Sky-View LUT at the camera: up = radial direction, x toward the sun's
// azimuth. Returns the world direction for (view_zenith, azimuth). If the sun is at the zenith
// or nadir any x perpendicular to up serves.
vec3 SkyViewFrameX(vec3 up, vec3 sun_direction) {
    vec3 x = sun_direction - up * dot(sun_direction, up);
    Number len = length(x);
    if (len < 1e-6) {
        x = abs(up.z) < 0.9 ? cross(up, vec3(0.0, 0.0, 1.0)) : cross(up, vec3(1.0, 0.0, 0.0));
        len = length(x);
    }
    return x / len;
}

vec3 SkyViewDirection(vec3 up, vec3 frame_x, Number view_zenith, Number azimuth) {
    vec3 frame_y = cross(up, frame_x);
    Number s = sin(view_zenith);
    return up * cos(view_zenith) + frame_x * (s * cos(azimuth)) + frame_y * (s * sin(azimuth));
}

void SkyViewAnglesOfDirection(vec3 up, vec3 frame_x, vec3 direction, OUT(Number) view_zenith,
                              OUT(Number) azimuth) {
    vec3 frame_y = cross(up, frame_x);
    view_zenith = acos(clamp(dot(direction, up), -1.0, 1.0));
    azimuth = atan(dot(direction, frame_y), dot(direction, frame_x));
    if (azimuth < 0.0) azimuth += 2.0 * kPi;
}

// One Sky-View texel: the luminance seen from `camera` (km, planet-centred, inside the
// atmosphere) in the texel's direction, ground included (the planet is part of the distant view).
vec3 ComputeSkyViewTexel(IN(AtmosphereParameters) atmosphere,
                         IN(TransmittanceTexture) transmittance_texture,
                         IN(MultipleScatteringTexture) multiple_scattering_texture,
                         IN(IrradianceTexture) irradiance_texture, IN(LightSet) lights,
                         vec3 camera, Number camera_altitude, vec2 uv, ivec2 size, int steps) {
    vec3 up = normalize(camera);
    vec3 frame_x = SkyViewFrameX(up, lights.light[0].direction);
    Number view_zenith;
    Number azimuth;
    GetViewFromSkyViewTextureUv(atmosphere, camera_altitude, uv, size, view_zenith, azimuth);
    vec3 direction = SkyViewDirection(up, frame_x, view_zenith, azimuth);
    ScatteringResult result = IntegrateScatteredLuminance(
        atmosphere, transmittance_texture, multiple_scattering_texture, irradiance_texture,
        lights, camera, camera_altitude, direction, 0.0, 1e9, steps, true);
    return result.luminance;
}

// The Sky-View lookup with the frame (up, frame_x) and the horizon's zenith angle already known:
// they are the same for every pixel of a frame, so the composite gets them from the host.
vec3 SampleSkyViewInFrame(IN(SkyViewTexture) sky_view_texture, vec3 up, vec3 frame_x,
                          Number horizon, vec3 direction) {
    Number view_zenith;
    Number azimuth;
    SkyViewAnglesOfDirection(up, frame_x, direction, view_zenith, azimuth);
    vec2 uv = GetSkyViewTextureUvForHorizon(horizon, view_zenith, azimuth,
                                            TextureSize(sky_view_texture));
    return vec3(SampleTexture2D(sky_view_texture, uv));
}

vec3 SampleSkyView(IN(AtmosphereParameters) atmosphere, IN(SkyViewTexture) sky_view_texture,
                   vec3 camera, Number camera_altitude, vec3 sun_direction, vec3 direction) {
    vec3 up = normalize(camera);
    return SampleSkyViewInFrame(sky_view_texture, up, SkyViewFrameX(up, sun_direction),
                                HorizonZenithAngle(atmosphere, camera_altitude), direction);
}

// ---------------------------------------------------------------------------------------------
// Ground sky irradiance LUT texel: E_sky(mu_s) = integral over the upper hemisphere of the sky's
// luminance times cos(theta), for a unit sun, from a point on the ground.
// The directions first, first + stride, ... of the texel's, as ComputeScatteringOrderTexel's.
vec3 ComputeGroundIrradianceTexel(IN(AtmosphereParameters) atmosphere,
                                  IN(TransmittanceTexture) transmittance_texture,
                                  IN(MultipleScatteringTexture) multiple_scattering_texture,
                                  IN(IrradianceTexture) unused_irradiance_texture,
                                  ivec2 irradiance_size, Number u, int sqrt_directions, int steps,
                                  int first, int stride) {
    Number mu_s = SunCosineFromUnitRange(GetUnitRangeFromTextureCoord(u, irradiance_size.x));
    // Not named `lights`: that is the uniform block member in the passes.
    LightSet unit_sun;
    unit_sun.light[0].direction = vec3(SafeSqrt(1.0 - mu_s * mu_s), 0.0, mu_s);
    unit_sun.light[0].illuminance = vec3(1.0);
    unit_sun.light[0].padding0 = 0.0;
    unit_sun.light[0].padding1 = 0.0;
    unit_sun.light[1] = unit_sun.light[0];
    unit_sun.count = 1;
    unit_sun.cloud_base = 0.0;  // a clear sky
    unit_sun.cloud_direct = 1.0;
    unit_sun.cloud_sky = 1.0;
    unit_sun.cloud_ground_sky = 1.0;
    unit_sun.cloud_luminance = vec3(0.0);
    unit_sun.cloud_ground_luminance = vec3(0.0);
    unit_sun.cloud_shaded = 0.0;
    unit_sun.eclipse = 0;  // a whole Sun (the other eclipse members are read only with it)
    vec3 origin = vec3(0.0, 0.0, atmosphere.bottom_radius);
    // Upper hemisphere in equal-solid-angle strata: cos(theta) uniform in (0, 1].
    vec3 irradiance = vec3(0.0);
    int n = sqrt_directions * sqrt_directions;
    for (int i = first; i < n; i += stride) {
        Number cos_theta = (Number(i / sqrt_directions) + 0.5) / Number(sqrt_directions);
        Number phi = 2.0 * kPi * (Number(i - (i / sqrt_directions) * sqrt_directions) + 0.5) /
                     Number(sqrt_directions);
        Number sin_theta = SafeSqrt(1.0 - cos_theta * cos_theta);
        vec3 direction = vec3(sin_theta * cos(phi), sin_theta * sin(phi), cos_theta);
        ScatteringResult sky = IntegrateScatteredLuminance(
            atmosphere, transmittance_texture, multiple_scattering_texture,
            unused_irradiance_texture, unit_sun, origin, 0.0, direction, 0.0, 1e9, steps, false);
        irradiance += sky.luminance * cos_theta;
    }
    return irradiance * (2.0 * kPi / Number(n));  // solid angle 2 pi / n per stratum
}

// ---------------------------------------------------------------------------------------------
// Aerial perspective (H20 §5.4): in-scattered luminance (rgb) and mean transmittance (a) from the
// camera to the centre depth of each slice, for each screen cell. A column is marched once, slice
// after slice, composing each segment onto what lies in front of it (L += T L_seg, T *= T_seg),
// which is exact and costs O(slices) rather than O(slices^2) for a march per froxel.

// Reads the froxel volume at screen uv and a distance (km): slice centres are at
// (z + 0.5) / slices * range, and the camera (distance 0) is (L = 0, T = 1). Between two
// neighbouring points (the camera and the first centre, or two centres) the segment is taken as
// homogeneous, which the march made each slice: with the segment's transmittance
// Ts = T1 / T0, a share u of the way in has transmittance T0 Ts^u and in-scattering
// L0 + (L1 - L0) (1 - Ts^u) / (1 - Ts). Linear interpolation is the limit Ts -> 1 (thin air);
// in thick air (visibility under a few slices) it overstates the contrast of a target between
// centres (a black target at a 1 km visibility read 12 % instead of 5 % with 1 km slices).
// Ts is the mean transmittance's (the volume's alpha), exact for grey aerosol. Beyond the range,
// the last slice is used. Returns (luminance, mean transmittance).
vec4 SampleAerialPerspective(IN(AerialPerspectiveTexture) aerial_perspective_texture, vec2 uv,
                             Number distance, Number range, int slices) {
    // s: the distance in slices from the first centre; the camera is at s = -0.5.
    Number s = clamp(max(distance, 0.0) / range * Number(slices) - 0.5, -0.5,
                     Number(slices) - 1.0);
    int z1 = min(int(floor(s)) + 1, slices - 1);
    Number u = z1 == 0 ? 2.0 * (s + 0.5) : clamp(s - Number(z1 - 1), 0.0, 1.0);
    vec4 v1 = SampleTexture3D(aerial_perspective_texture,
                               vec3(uv, (Number(z1) + 0.5) / Number(slices)));
    vec4 v0 = vec4(0.0, 0.0, 0.0, 1.0);
    if (z1 > 0) {
        v0 = SampleTexture3D(aerial_perspective_texture,
                               vec3(uv, (Number(z1) - 0.5) / Number(slices)));
    }
    if (u >= 1.0) return v1;
    Number t0 = max(v0.w, 0.0), t1 = max(v1.w, 0.0);
    // The weight of the far end: (1 - Ts^u) / (1 - Ts), u where the segment is (nearly) clear
    // or nothing is left to see through.
    Number weight = u;
    Number transmittance = mix(t0, t1, u);
    if (t0 > 1e-6 && t1 > 1e-12) {
        Number ts = min(t1 / t0, 1.0);
        Number ts_u = pow(ts, u);
        transmittance = t0 * ts_u;
        if (ts < 0.999) weight = (1.0 - ts_u) / (1.0 - ts);
    }
    vec3 luminance = vec3(v0.x, v0.y, v0.z) + (vec3(v1.x, v1.y, v1.z) - vec3(v0.x, v0.y, v0.z)) * weight;
    return vec4(luminance, transmittance);
}

// Steps within one slice: the full-range step budget spread over the slices, at least one.
int AerialPerspectiveStepsPerSlice(int slices, int full_steps) {
    return max(1, (full_steps + slices - 1) / slices);
}

// Advances `accumulated` (camera to the previous slice) through slice `slice` and returns the
// froxel value. Start a column with luminance 0 and transmittance 1.
vec4 AdvanceAerialPerspective(IN(AtmosphereParameters) atmosphere,
                              IN(TransmittanceTexture) transmittance_texture,
                              IN(MultipleScatteringTexture) multiple_scattering_texture,
                              IN(IrradianceTexture) irradiance_texture,
                              IN(LightSet) lights, vec3 camera, Number camera_altitude,
                              vec3 direction, int slice, int slices, Number range, int full_steps,
                              INOUT(ScatteringResult) accumulated) {
    Number begin = max(Number(slice) - 0.5, 0.0) / Number(slices) * range;
    Number end = (Number(slice) + 0.5) / Number(slices) * range;
    ScatteringResult segment = IntegrateScatteredLuminance(
        atmosphere, transmittance_texture, multiple_scattering_texture, irradiance_texture,
        lights, camera, camera_altitude, direction, begin, end,
        AerialPerspectiveStepsPerSlice(slices, full_steps), false);
    accumulated.luminance += accumulated.transmittance * segment.luminance;
    accumulated.transmittance *= segment.transmittance;
    vec3 t = accumulated.transmittance;
    return vec4(accumulated.luminance, (t.x + t.y + t.z) / 3.0);
}

// ---------------------------------------------------------------------------------------------
// Point-source visibility against the sky (zenith/sky/night_sky.h has the model and sources).

// Threshold illuminance (lux) of a point source against a background of luminance `background`
// (cd/m^2): Hecht (1947) after Schaefer (1990, Eqs. 2-3), I = c1 (1 + sqrt(c2 B))^2 with I in
// foot-candles (10.7639 lux) and B in nanolamberts (1e-5 / pi cd/m^2); the smaller of the night
// (c1 = 10^-9.8, c2 = 10^-1.9) and day (c1 = 10^-8.35, c2 = 10^-5.9) branches.
Number StarThresholdIlluminance(Number background) {
    Number b = max(background, 0.0) * (kPi * 1e5);
    Number night = 1.5848931924611e-10 * (1.0 + sqrt(0.012589254117942 * b)) *
                   (1.0 + sqrt(0.012589254117942 * b));
    Number day = 4.4668359215096e-9 * (1.0 + sqrt(1.2589254117942e-6 * b)) *
                 (1.0 + sqrt(1.2589254117942e-6 * b));
    return min(night, day) * 10.763910416709722;
}

// Share of a point source of `illuminance` (lux) that is seen: 0 at or under the threshold, 1
// from one magnitude (2.512x) above it, linear in magnitude between.
Number StarVisibility(Number illuminance, Number background) {
    Number threshold = StarThresholdIlluminance(background);
    if (!(illuminance > threshold)) return 0.0;
    return min(1.0857362047581294 * log(illuminance / threshold), 1.0);  // 2.5 log10(ratio)
}
