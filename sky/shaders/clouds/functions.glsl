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
    // (0, 1]: the layer's cloud material's extinction relative to CloudMarchParameters'
    // (clouds::CloudLayer::extinction_scale: 1 for water droplets, ~0.02 for cirrus' ice).
    Number extinction_scale;
    // 1: ground fog (clouds::CloudLayer::ground_fog): homogeneous (no noise), its density the
    // map's coverage from the base to kCloudFogFlat of the layer, falling to 0 at its top.
    Number ground_fog;
    // 1: a precipitation shaft (clouds::CloudLayer::precipitation_shaft): homogeneous, its
    // density CloudPrecipitationShare of the map's G times extinction_scale (heavy rain's or
    // snow's extinction over the cloud material's).
    Number precipitation_shaft;
    // km: how far downwind the clouds reach at the layer's top (clouds::CloudLayer::shear),
    // along ground x and y.
    Number shear_x;
    Number shear_y;
};

// Ground fog is flat to this share of its layer's thickness, then thins linearly to its top.
const Number kCloudFogFlat = 0.8;

// Erosion remaps density from [e, 1] to [0, 1]; e must stay below 1.
const Number kCloudMaxErosion = 0.9;

Number CloudSaturate(Number x) { return clamp(x, 0.0, 1.0); }

// The extinction of precipitation of intensity p (the map's G) over that of heavy
// precipitation (p = 0.9): rain at R(p) = 0.5 x 32^(p / 0.9) mm/h through Marshall-Palmer drops,
// whose extinction grows as R^0.63 (clouds::PrecipitationExtinction), so
// (R(p) / R(0.9))^0.63 = exp(0.63 ln 32 (p / 0.9 - 1)); ramped in over p < 0.1 to give 0 at 0.
Number CloudPrecipitationShare(Number p) {
    return exp(2.1834 * (CloudSaturate(p) / 0.9 - 1.0)) * CloudSaturate(p / 0.1);
}

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

// The wind's shear leans the clouds downwind: at height share h of the layer a column shows the
// weather of the column h^2 shear upwind of it, so a cumulonimbus' anvil spreads downwind of its
// cell and its tower tilts. The noise stays in place: sheared with the weather, its features
// stretched into streaks along the leaning faces.
vec2 CloudLeanedGround(IN(CloudLayerParameters) layer, vec2 ground, Number height_fraction) {
    Number lean = CloudSaturate(height_fraction) * CloudSaturate(height_fraction);
    return ground - lean * vec2(layer.shear_x, layer.shear_y);
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

// Cumulonimbus (types above congestus, 0.75): 0 for every other type, 1 for a cell's core.
// The cells map keeps this type well beyond a tower's cover (clouds/weather.h), so it also
// tells a column that an anvil spreads over it.
Number CloudConvection(Number type) { return CloudSaturate(4.0 * (type - 0.75)); }

// A cumulonimbus tower rises with steep sides to the layer's top (the tropopause) instead of
// H16's bell: its height signal is the parabola steepened k = 1 + 2 convection times and
// clamped at 1, a plateau between a rounded base and top.
Number CloudTowerSignal(Number altitude, Number cloud_base, Number cloud_height,
                        Number convection) {
    return CloudSaturate((1.0 + 2.0 * convection) *
                         CloudHeightSignal(altitude, cloud_base, cloud_height));
}

// Where an anvil begins, as a share of the layer, over a column of convection c (CloudAnvilSignal).
Number CloudAnvilBottom(Number convection) { return 0.95 - 0.2 * convection; }

// The anvil: a cumulonimbus' top spreading under the tropopause (WMO International Cloud
// Atlas, Cb incus), its vertical profile from 0.95 - 0.2 c (c the column's convection: thick
// over the cell, thin at its rim) to 0.985 of the layer, with soft edges; 0 where c is 0.
Number CloudAnvilSignal(Number convection, Number height_fraction) {
    if (!(convection > 0.0)) return 0.0;
    return CloudSaturate((height_fraction - CloudAnvilBottom(convection)) / 0.04) *
           CloudSaturate((0.985 - height_fraction) / 0.015);
}
// The anvil's coverage over the shape noise times the convection (CloudApplyCoverage): its
// edge is ragged where the two fall below 1 - coverage.
const Number kCloudAnvilCoverage = 0.85;
// How high an anvil reaches, as a share of the layer (CloudTopFraction's bound).
const Number kCloudAnvilTop = 0.985;

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

// Detail noise as an erosion amount in [0, 1] (H16 §4.5.2): the Worley FBM (CloudDetailFbm),
// inverted toward the cloud's base for wispy edges and as stored (billowing) above.
Number CloudDetailFbm(vec4 detail_texel) {
    return detail_texel.x * 0.625 + detail_texel.y * 0.25 + detail_texel.z * 0.125;
}

Number CloudDetail(Number fbm, Number cloud_fraction) {
    return mix(1.0 - fbm, fbm, CloudSaturate(4.0 * cloud_fraction));
}

// H16 §4.5.2: erosion as a threshold that removes low densities more. Remap(d, e, 1, 0, 1) is
// at most d for d in [0, 1] (d - e <= d - e d), so erosion only ever removes density.
Number CloudErode(Number density, Number erosion) {
    Number e = clamp(erosion, 0.0, kCloudMaxErosion);
    return CloudSaturate((density - e) / (1.0 - e));
}

// A density sample, and what it read of its column: the weather (coverage, type, the cloud's
// height) and the noise (shape, and the detail's FBM; -1 where the sample did not need them),
// from which CloudColumnDensity gives the density at the column's other heights.
struct CloudSample {
    Number density;
    Number height_fraction;
    Number cloud_fraction;
    Number type;  // the weather's cloud type, which sets the height gradient
    Number coverage;
    Number cloud_height;  // km
    Number shape;         // CloudShape, or -1
    Number detail;        // CloudDetailFbm, or -1
};

// The density at `altitude` of the column `s` was read in (H16 Alg. 4.1's height-dependent
// parts there, the sample's weather and noise values held): exactly s.density at the sample's
// own altitude. 0 where the sample stopped before a value the height needs (above or below its
// cloud, or eroded to nothing by the coverage: no detail read). Rain and snow shafts are
// homogeneous in height.
Number CloudColumnDensity(IN(CloudLayerParameters) layer, IN(CloudSample) s, Number altitude) {
    if (!(altitude > layer.base_altitude && altitude < layer.top_altitude)) return 0.0;
    if (layer.precipitation_shaft > 0.5) return s.density;
    Number height_fraction =
        (altitude - layer.base_altitude) / (layer.top_altitude - layer.base_altitude);
    if (layer.ground_fog > 0.5) {
        return s.coverage * CloudSaturate((1.0 - height_fraction) / (1.0 - kCloudFogFlat)) *
               layer.extinction_scale;
    }
    if (!(s.detail >= 0.0)) return 0.0;
    Number convection = CloudConvection(s.type);
    Number tower = CloudTowerSignal(altitude, layer.base_altitude, s.cloud_height, convection);
    Number anvil = CloudAnvilSignal(convection, height_fraction);
    Number density = max(CloudApplyCoverage(s.shape * tower, s.coverage),
                         anvil * CloudApplyCoverage(s.shape * convection, kCloudAnvilCoverage));
    if (!(density > 0.0)) return 0.0;
    Number cloud_fraction = (altitude - layer.base_altitude) / s.cloud_height;
    density = CloudErode(density, layer.erosion_strength * CloudDetail(s.detail, cloud_fraction));
    density *= CloudHeightGradient(s.type, cloud_fraction);
    // H16 §4.5.1: densities above 1 are clamped. The layer's material then scales it, so that
    // everything that reads density (the march, the shadow map, the path tracer's medium) sees
    // the layer's extinction.
    return CloudSaturate(density) * layer.extinction_scale;
}

// H16 Alg. 4.1 at a ground position and altitude:
//   weather; density = coverage; *= height signal; *= shape; -= detail; *= height gradient,
// with S15's remaps for the coverage and the erosion, and for cumulonimbus a steep tower and
// an anvil (its own coverage over the shape). Exactly 0 outside the layer and wherever the
// coverage is 0.
CloudSample SampleCloudDensityAt(IN(CloudLayerParameters) layer, IN(WeatherTexture) weather_map,
                                 IN(CloudNoiseTexture) shape_noise,
                                 IN(CloudNoiseTexture) detail_noise, vec2 ground,
                                 Number altitude) {
    CloudSample s;
    s.density = 0.0;
    s.height_fraction =
        (altitude - layer.base_altitude) / (layer.top_altitude - layer.base_altitude);
    s.cloud_fraction = 0.0;
    s.type = 0.0;
    s.coverage = 0.0;
    s.cloud_height = 0.0;
    s.shape = -1.0;
    s.detail = -1.0;
    if (!(altitude > layer.base_altitude && altitude < layer.top_altitude)) return s;

    CloudWeather weather =
        CloudWeatherAt(layer, weather_map, CloudLeanedGround(layer, ground, s.height_fraction));
    if (layer.precipitation_shaft > 0.5) {
        // Rain or snow: as dense at every height as the intensity says.
        s.cloud_fraction = s.height_fraction;
        s.density = CloudPrecipitationShare(weather.precipitation) * layer.extinction_scale;
        return s;
    }
    s.type = weather.type;
    s.coverage = weather.coverage;
    if (!(weather.coverage > 0.0)) return s;
    if (layer.ground_fog > 0.5) {
        // Fog: as dense at the ground as the coverage says, whatever the noise, so that its
        // extinction there (and the visibility in it) is the one the layer was given.
        s.cloud_fraction = s.height_fraction;
        s.density = CloudColumnDensity(layer, s, altitude);
        return s;
    }

    s.cloud_height = (layer.top_altitude - layer.base_altitude) *
                     CloudTypeHeightFraction(weather.type) * weather.height;
    Number convection = CloudConvection(weather.type);
    Number tower = CloudTowerSignal(altitude, layer.base_altitude, s.cloud_height, convection);
    Number anvil = CloudAnvilSignal(convection, s.height_fraction);
    if (!(max(tower, anvil) > 0.0)) return s;
    s.cloud_fraction = (altitude - layer.base_altitude) / s.cloud_height;

    vec2 shifted = CloudWindShiftedGround(layer, ground);
    vec3 shape_uvw = vec3(shifted.x / layer.shape_period, altitude / layer.shape_period_y,
                          shifted.y / layer.shape_period);
    s.shape = CloudShape(SampleTexture3D(shape_noise, shape_uvw));
    if (!(max(CloudApplyCoverage(s.shape * tower, weather.coverage),
              anvil * CloudApplyCoverage(s.shape * convection, kCloudAnvilCoverage)) > 0.0)) {
        return s;
    }
    vec3 detail_uvw = vec3(shifted.x, altitude, shifted.y) / layer.detail_period;
    s.detail = CloudDetailFbm(SampleTexture3D(detail_noise, detail_uvw));
    s.density = CloudColumnDensity(layer, s, altitude);
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

// The density model's own vertical profile, H16 Eq. 5.1's parabola times the height gradient
// b + (1 - b) x, 4 x (1 - x) (b + (1 - b) x) at cloud_fraction x, integrated from the base to x
// in units of the cloud's height:
//   4 (b (x^2 / 2 - x^3 / 3) + (1 - b)(x^3 / 3 - x^4 / 4)),  (1 + b) / 3 at the top.
Number CloudProfileIntegral(Number b, Number x) {
    Number x2 = x * x;
    return 4.0 * (b * (x2 / 2.0 - x2 * x / 3.0) + (1.0 - b) * (x2 * x / 3.0 - x2 * x2 / 4.0));
}

// The altitude (km) where an anvil's overhang ends below (CloudAnvilBottom), for a sample in the
// anvil over clear air: no tower in its column at the anvil's bottom (CloudColumnDensity's tower
// term 0 there: too low, or cut away by the coverage). -1 for every other sample; where a tower
// reaches the anvil, the column is one cloud down to the layer's base.
Number CloudOverhangBottom(IN(CloudLayerParameters) layer, IN(CloudSample) s) {
    Number convection = CloudConvection(s.type);
    Number bottom_fraction = CloudAnvilBottom(convection);
    if (!(convection > 0.0) || !(s.height_fraction > bottom_fraction)) return -1.0;
    Number bottom = mix(layer.base_altitude, layer.top_altitude, bottom_fraction);
    Number tower = CloudTowerSignal(bottom, layer.base_altitude, s.cloud_height, convection);
    return CloudApplyCoverage(s.shape * tower, s.coverage) > 0.0 ? -1.0 : bottom;
}

// Optical depth from a cloud sample straight down to its cloud's base, without a march: the
// profile's integral (CloudProfileIntegral) up to the sample, scaled by the sample's density
// over that profile, as if the column below had the sample's shape and coverage. Exact for a
// cloud whose density is the profile alone (a flat deck of uniform noise); a march of four more
// density samples cost 25 % of the trace.
Number CloudDepthBelow(IN(CloudLayerParameters) layer, IN(CloudSample) s, Number altitude,
                       Number extinction) {
    Number x = CloudSaturate(s.cloud_fraction);
    if (!(x > 0.0) || !(s.density > 0.0)) return 0.0;
    // Fog (flat below kCloudFogFlat) and precipitation: the sample's density holds down to the
    // layer's base.
    if (layer.ground_fog > 0.5 || layer.precipitation_shaft > 0.5) {
        return extinction * s.density * (altitude - layer.base_altitude);
    }
    // An anvil's overhang over clear air: its own depth below the sample, at the sample's
    // density. The column's profile down to the base put the overhang's underside deep in a
    // cloud reaching the layer's base (beneath `cumulonimbus`, 2.2x the path tracer's;
    // BENCHMARKS.md, "The anvil's overhang").
    Number overhang = CloudOverhangBottom(layer, s);
    if (overhang >= 0.0) return extinction * s.density * max(altitude - overhang, 0.0);
    Number b = CloudHeightGradient(s.type, 0.0);
    Number profile = 4.0 * x * (1.0 - x) * mix(b, 1.0, x);
    Number cloud_height = (altitude - layer.base_altitude) / x;
    return extinction * min(s.density / max(profile, 0.05), 1.0) * cloud_height *
           CloudProfileIntegral(b, x);
}

// The transverse buckling B (per unit optical depth) of the diffuse light in a slab across a
// cloud's side, from the cloud's own height: in the diffusion limit light in a body of finite
// size leaks out of it like an absorption that keeps a diffusion length 1 / B, B^2 the sum of
// (pi / width)^2 over the directions across the slab, each width its optical depth plus twice
// the extrapolation length 0.7104 / (1 - g) (Case & Zweifel). The vertical is one of them by
// 1 - (normal . up)^2 of its square; its width is the column of the sample's cloud at full
// density, its height times the layer's extinction times the profile integrated base to top
// (CloudProfileIntegral): the cloud's size, not the eroded sample's; for an anvil's overhang
// (CloudOverhangBottom), the overhang's own height at full density. The
// horizontal ones, which the weather map would have to show, are left out (infinite), as is
// the whole of a deck, whose slab is level, and of fog and precipitation.
Number CloudSlabLeakage(IN(CloudLayerParameters) layer, IN(CloudSample) s, Number g,
                        Number extinction, Number normal_up) {
    if (!(s.detail >= 0.0) || layer.ground_fog > 0.5 || layer.precipitation_shaft > 0.5) {
        return 0.0;
    }
    Number overhang = CloudOverhangBottom(layer, s);
    Number height =
        overhang >= 0.0
            ? max(mix(layer.base_altitude, layer.top_altitude, kCloudAnvilTop) - overhang, 0.0)
            : s.cloud_height * CloudProfileIntegral(CloudHeightGradient(s.type, 0.0), 1.0);
    Number column = extinction * layer.extinction_scale * height;
    Number width = column + 2.0 * 0.7104 / (1.0 - g);
    return kPi / width * sqrt(max(1.0 - normal_up * normal_up, 0.0));
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

// The angular distribution of light scattered twice by the dual lobe, the directions of the two
// scatterings aside: Henyey-Greenstein's Legendre moments are g^l, so p_hg(a) convolved with
// p_hg(b) over the sphere is p_hg(a b), and the dual lobe convolved with itself is the mix of
// p_hg(g0^2), p_hg(g0 g1) and p_hg(g1^2) with weights (1 - w)^2, 2 w (1 - w) and w^2.
Number CloudTwiceScatteredPhase(Number g0, Number g1, Number w, Number nu) {
    return (1.0 - w) * (1.0 - w) * CloudHenyeyGreensteinPhase(g0 * g0, nu) +
           2.0 * w * (1.0 - w) * CloudHenyeyGreensteinPhase(g0 * g1, nu) +
           w * w * CloudHenyeyGreensteinPhase(g1 * g1, nu);
}

// The same for light the forward lobe alone scattered first (what delta-Eddington keeps in the
// direct beam, CloudSunScattering): p_hg(g0) convolved with the dual lobe, the mix of
// p_hg(g0^2) and p_hg(g0 g1) with weights 1 - w and w.
Number CloudForwardThenScatteredPhase(Number g0, Number g1, Number w, Number nu) {
    return mix(CloudHenyeyGreensteinPhase(g0 * g0, nu), CloudHenyeyGreensteinPhase(g0 * g1, nu),
               w);
}

// ---------------------------------------------------------------------------------------------
// Scattering: the cloud material (F16 §5.2, §5.4.1) and its multiple scattering
//
// F16 §5.8's octaves cannot carry the light a thick cloud reflects: normalised so that they
// never scatter more than the sun delivers, an overcast deck lost four fifths of its light
// (effective albedo 0.12 where a path tracer finds 0.67). The light is split instead by order:
// the first scattering of the sunlight, with the dual-lobe phase and the march's own shadow
// (silver lining, back-lit detail), and the diffuse light of all higher orders from the
// delta-Eddington solution of a plane-parallel slab through the sample, whose optical depths
// to the cloud's top (toward the sun) the shadow march measures and to its base (straight down)
// the density profile gives (CloudDepthBelow).
//
// JWW76  Joseph, Wiscombe & Weinman, "The delta-Eddington approximation for radiative flux
//        transfer", J. Atmos. Sci. 33, 1976.
// Glossary: tau vertical optical depth from the slab's top, tau_total the slab's, mu0 the
// cosine of the light's zenith angle, g the asymmetry (mean cosine) of the phase function, f the
// share of the scattering kept in the forward peak (CloudDeltaFraction); delta-scaled:
// tau' = (1 - f) tau, g' = (g - f) / (1 - f), so (1 - g') tau' = (1 - g) tau.

// The slab's two tables (CloudSlabTables) hold this many slab optical depths by as many cosines
// of the light: the lit face's source scale and the beam's cosine in the diffuse field's source.
const int kCloudSlabTableSize = 8;

struct CloudScatteringParameters {
    Number forward_g;            // g0 of the dual lobe, (-1, 1)
    Number backward_g;           // g1, (-1, 1)
    Number lobe_weight;          // w, [0, 1]
    Number albedo;               // sigma_s / sigma_t, [0, 1] (F16 §5.2: ~1 for water clouds)
    Number multiple_scattering;  // [0, 1]: share of the diffuse field added (1 physical, 0 none)
    Number ground_albedo;        // [0, 1]: the Lambertian ground under the slab (luminance)
    Number padding1;
    Number padding2;
    // CloudSlabTables' nodes, four to a vec4: node (depth i, cosine j) of table t is number
    // (t kCloudSlabTableSize + j) kCloudSlabTableSize + i. All 0 turns the lit face's source off
    // and leaves JWW76's beam.
    vec4 slab_tables[2 * kCloudSlabTableSize * kCloudSlabTableSize / 4];
};

// The dual lobe's mean cosine, (1 - w) g0 + w g1: all that the diffuse field keeps of the phase
// function. Clamped at 0: delta-scaling is for forward-peaked phase functions.
Number CloudAsymmetry(IN(CloudScatteringParameters) p) {
    return clamp(mix(p.forward_g, p.backward_g, p.lobe_weight), 0.0, 0.99);
}

// The share f of the scattering that delta-Eddington puts in its forward peak: the phase
// function's second Legendre moment (JWW76 Eq. 4-5, whose f = g^2 is that moment for one
// Henyey-Greenstein lobe), (1 - w) g0^2 + w g1^2 for the dual lobe, bounded by g so that the
// scaled phase keeps g' = (g - f) / (1 - f) >= 0 (the dual lobe's moment is at least g^2). The
// default lobes give 0.475, so f = g = 0.47 and an isotropic scaled phase, where g^2 = 0.22 had
// left most of the forward lobe's light to the nearly isotropic P1 field (BENCHMARKS.md,
// cloud_reference_report --part thin).
Number CloudDeltaFraction(IN(CloudScatteringParameters) p) {
    Number moment = mix(p.forward_g * p.forward_g, p.backward_g * p.backward_g, p.lobe_weight);
    return min(moment, CloudAsymmetry(p));
}

// JWW76 Eq. 2-5 for single-scattering albedo 1: the Eddington radiance I0 + mu I1 of the
// diffuse light (mu along the downward vertical) at depth tau in a slab of depth tau_total,
// per unit illuminance normal to the light, with no diffuse light entering at the top
// (I0 + 2/3 I1 = 0) (Marshak) and a Lambertian ground of albedo a at the base, which returns
// a times the diffuse and direct flux it gets: (1 - a) I0 - 2/3 (1 + a) I1 = a mu0 e / pi. The
// conservative solution is linear in depth plus the direct beam's exponential (for any f); with
// k = 3 mu0 / (4 pi) and e(tau) = exp(-tau' / mu0):
//   I1 = A - k e(tau),  I0 = B - (1 - g) A tau - k m e(tau),
//   A = (1 - a) k ((m + 2/3) - e(tau_total) (m - 2/3)) / (4/3 + (1 - a)(1 - g) tau_total),
//   B = k (m + 2/3) - 2/3 A.
// `beam` is m, the cosine the beam's source term carries: mu0 in JWW76, where the scaled
// phase's first moment g' mu0 sends the beam's first scattering down; m = mu0 (1 - g' + g_b)
// for a source of first moment g_b mu0 (two-stream: gamma3 = (2/3 + mu0 - m) 3/4). The slab's
// R (CloudSlabReflectanceTransmittance) falls by (1 - e(tau_total)) / (4/3 + (1 - g) tau_total)
// per unit m. CloudBeamCosine gives the m of the exact slab.
// Returns (I0, I1); both vanish as tau_total -> 0 over a black ground (thin clouds scatter
// once).
vec2 CloudDiffuseRadiance(Number g, Number f, Number tau, Number tau_total, Number mu0,
                          Number beam, Number ground_albedo) {
    Number k = 3.0 * mu0 / (4.0 * kPi);
    Number e = exp(-(1.0 - f) * tau / mu0);
    Number e_total = exp(-(1.0 - f) * tau_total / mu0);
    Number absorbed = 1.0 - CloudSaturate(ground_albedo);
    Number a = absorbed * k * ((beam + 2.0 / 3.0) - e_total * (beam - 2.0 / 3.0)) /
               (4.0 / 3.0 + absorbed * (1.0 - g) * tau_total);
    Number b = k * (beam + 2.0 / 3.0) - 2.0 / 3.0 * a;
    return vec2(b - (1.0 - g) * a * tau - k * beam * e, a - k * e);
}

// The same in a slab of finite width, whose diffuse light also leaks out sideways: in the
// diffusion limit a transverse buckling B (per unit optical depth; pi / the cloud's width) acts
// on the light along the normal as an absorption that keeps the diffusion length 1 / B, so the
// P1 equations are solved with the single-scattering albedo w < 1 that gives
// lambda^2 = 3 (1 - w)(1 - w g') = (B / (1 - f))^2 in the delta-scaled depth (JWW76 Eq. 2-3):
//   I0 = C1 exp(-lambda (tau_total - tau)) + C2 exp(-lambda tau) + alpha e(tau),
//   I1 = -P (C1 exp(-lambda (tau_total - tau)) - C2 exp(-lambda tau)) + beta e(tau),
// P = lambda / (1 - w g'), with the particular solution alpha, beta of the direct beam (its
// source's first moment (m / mu0 - 1 + g') mu0, as CloudDiffuseRadiance's) and C1, C2 from the
// same boundary conditions. B -> 0 is CloudDiffuseRadiance.
vec2 CloudLeakingDiffuseRadiance(Number g, Number f, Number tau, Number tau_total, Number mu0,
                                 Number beam, Number ground_albedo, Number leakage) {
    if (!(leakage * tau_total > 1e-3)) {
        return CloudDiffuseRadiance(g, f, tau, tau_total, mu0, beam, ground_albedo);
    }
    Number lambda = leakage / (1.0 - f);
    // Away from the particular solution's pole (lambda mu0 = 1), and within what an albedo in
    // [0, 1] can give (3 (1 - w)(1 - w g') <= 3): only a cloud under an optical depth or so
    // across, whose diffuse light is small anyway, leaks this fast.
    lambda = min(lambda, min(0.5 / mu0, 1.5));
    // w from 3 (1 - w)(1 - w g') = lambda^2: gs w^2 - (1 + gs) w + 1 - lambda^2 / 3 = 0, the
    // root at 1 for lambda = 0.
    Number gs = (g - f) / (1.0 - f);
    Number qb = 1.0 + gs;
    Number qc = 1.0 - lambda * lambda / 3.0;
    Number w = gs > 1e-6 ? (qb - sqrt(max(qb * qb - 4.0 * gs * qc, 0.0))) / (2.0 * gs) : qc;
    Number p_ratio = lambda / (1.0 - w * gs);
    Number c = 3.0 * w / (4.0 * kPi);
    Number alpha = c * mu0 * (beam + mu0 * gs * (1.0 - w)) / (lambda * lambda * mu0 * mu0 - 1.0);
    Number beta = mu0 * (3.0 * (1.0 - w) * alpha - c);
    Number ts = (1.0 - f) * tau;
    Number total = (1.0 - f) * tau_total;
    Number e = exp(-ts / mu0);
    Number e_total = exp(-total / mu0);
    Number big_e = exp(-lambda * total);
    Number a = CloudSaturate(ground_albedo);
    Number m11 = big_e * (1.0 - 2.0 / 3.0 * p_ratio);
    Number m12 = 1.0 + 2.0 / 3.0 * p_ratio;
    Number r1 = -(alpha + 2.0 / 3.0 * beta);
    Number m21 = (1.0 - a) + 2.0 / 3.0 * (1.0 + a) * p_ratio;
    Number m22 = big_e * ((1.0 - a) - 2.0 / 3.0 * (1.0 + a) * p_ratio);
    Number r2 = e_total * (a * mu0 / kPi - (1.0 - a) * alpha + 2.0 / 3.0 * (1.0 + a) * beta);
    Number det = m11 * m22 - m12 * m21;
    Number c1 = (r1 * m22 - m12 * r2) / det;
    Number c2 = (m11 * r2 - m21 * r1) / det;
    Number x1 = exp(-lambda * (total - ts));
    Number x2 = exp(-lambda * ts);
    return vec2(c1 * x1 + c2 * x2 + alpha * e, -p_ratio * (c1 * x1 - c2 * x2) + beta * e);
}

// The slab's reflectance R (upward flux at the top over mu0 E) and transmittance T = 1 - R
// (direct and diffuse) over a black ground from the same solution: the closed form the march is
// tested against.
//   R = ((1 - g) tau_total + (2/3 - m)(1 - e(tau_total))) / (4/3 + (1 - g) tau_total).
vec2 CloudSlabReflectanceTransmittance(Number g, Number f, Number tau_total, Number mu0,
                                       Number beam) {
    Number e_total = exp(-(1.0 - f) * tau_total / mu0);
    Number r = ((1.0 - g) * tau_total + (2.0 / 3.0 - beam) * (1.0 - e_total)) /
               (4.0 / 3.0 + (1.0 - g) * tau_total);
    return vec2(r, 1.0 - r);
}

// The sky's light, an isotropic radiance L on the slab's top, per unit L and unit sigma_s,
// scattered toward the viewer: JWW76 with diffuse incidence, pi (I0 + 2/3 I1) = pi L at the
// top and the ground's condition at the base, (1 - a) I0 = 2/3 (1 + a) I1, give a constant flux
// and a linear mean radiance:
//   I1 = A = (1 - a) L / (4/3 + (1 - a)(1 - g) tau_total),  I0 = L - 2/3 A - (1 - g) A tau,
// and I0 + g mu_view I1 as for the sun. This replaces F16 §5.5.1's linear gradient over the
// layer's height, which dimmed the top of a deck filling the layer's bottom quarter to half.
Number CloudSkyScattering(IN(CloudScatteringParameters) p, Number tau, Number tau_total,
                          Number mu_view) {
    Number g = CloudAsymmetry(p);
    Number absorbed = 1.0 - CloudSaturate(p.ground_albedo);
    Number a = absorbed / (4.0 / 3.0 + absorbed * (1.0 - g) * tau_total);
    return max(1.0 - 2.0 / 3.0 * a - (1.0 - g) * a * tau + g * mu_view * a, 0.0);
}

// The slab's tables at (tau_total, mu0), both read from one cell of nodes: x the lit face's
// source scale c, y the beam's cosine in the diffuse field less mu0 (CloudBeamCosine).
// The lit face's source is the light the renderer's source misses (CloudSunScattering).
// Through a homogeneous non-absorbing slab, its formal solution sends out less than the slab
// receives: 1.3, 7.6 and 10.5 % of the incident flux at mu0 = 1, 0.5 and 0.25 from tau_total =
// 10 on, all of it missing from the reflected light (the transmitted light is the closed form's
// to four digits), and up to 18 % on both sides of slabs of optical depth 0.5-4: a P1 radiance
// cannot carry the first orders' forward-peaked light, and a finer march gives the same. The
// path tracer finds the same shortfall (deck and thin-slab grids, BENCHMARKS.md). It is put
// back where it is lost, near the lit face, with the light's own attenuation and the angular
// spread of twice-scattered light: c(tau_total, mu0) p2(nu) exp(-tau / mu0) per unit sigma_s,
// with c sized so that this source's escaping light equals the shortfall. Where the Sun grazes
// the slab (mu0 < 0.13 for the default lobes) the rest of the source sends out more than the
// slab receives, and c < 0 takes the excess back.
// The tables are sized on the host for the current phase function (clouds/cloud_parameters.cpp,
// CloudSlabTables) and read bilinearly on u = log2(1 + 8 tau_total) (nodes tau_total = 0,
// 0.125, 0.375, ... 15.875; constant beyond, where they no longer depend on depth) and
// v = sqrt((mu0 - 0.05) / 0.95) (nodes 1/7 apart: closest where the Sun grazes the slab, mu0 =
// 0.05, 0.069, 0.13, 0.22 ... 1).
Number CloudSlabTableNode(IN(CloudScatteringParameters) p, int table, int depth, int cosine) {
    int k = (table * kCloudSlabTableSize + cosine) * kCloudSlabTableSize + depth;
    return p.slab_tables[k / 4][k % 4];
}

vec2 CloudSlabTables(IN(CloudScatteringParameters) p, Number tau_total, Number mu0) {
    Number last = Number(kCloudSlabTableSize - 1);
    Number u = clamp(log2(1.0 + 8.0 * tau_total), 0.0, last);
    Number v = sqrt(clamp((mu0 - 0.05) / 0.95, 0.0, 1.0)) * last;
    int i = min(int(u), kCloudSlabTableSize - 2);
    int j = min(int(v), kCloudSlabTableSize - 2);
    Number fu = u - Number(i);
    Number fv = v - Number(j);
    vec2 lower = vec2(0.0);
    vec2 upper = vec2(0.0);
    for (int t = 0; t < 2; ++t) {
        lower[t] = mix(CloudSlabTableNode(p, t, i, j), CloudSlabTableNode(p, t, i + 1, j), fu);
        upper[t] =
            mix(CloudSlabTableNode(p, t, i, j + 1), CloudSlabTableNode(p, t, i + 1, j + 1), fu);
    }
    return mix(lower, upper, fv);
}

// The beam's cosine m in the diffuse field's source (CloudDiffuseRadiance) with which the
// field's slab of optical depth tau_total transmits (so, R + T being 1, reflects) what the exact
// plane-parallel solution for the current phase function does (adding-doubling on the host,
// clouds/slab_transfer.h). JWW76's m = mu0 lets too much light through at a grazing Sun, 6, 11
// and 17 % at mu0 = 0.29, 0.17 and 0.1 against the path tracer at every depth from 2 to 20
// (BENCHMARKS.md): the light its forward peak scatters a little above the horizontal leaves
// through the top, where the scaled beam carries it down. For the default lobes the exact
// slab's m is 1.00-1.04 at mu0 = 1, 0.24-0.28 at 0.32 and -0.11 to -0.04 at 0.05, nearly the
// same at every depth.
Number CloudBeamCosine(IN(CloudScatteringParameters) p, Number tau_total, Number mu0) {
    return mu0 + CloudSlabTables(p, tau_total, mu0).y;
}

// The light scattered once that reaches a point of a homogeneous slab on its way to the camera,
// per unit phase and unit sunlight at the slab's face, the point sun_optical_depth below it
// toward the Sun: scattered at each point behind it along the view, up to the slab's face there,
// each with its own sunlight exp(-depth / mu0), and attenuated on the way:
// exp(-sun_optical_depth) int_0^l exp(-a s) ds (optical depth s along the view), with l the
// slab's depth behind the point / |mu_view| and a = 1 + |mu_view| / mu0 for light from below
// (from deeper, dimmer points), 1 - |mu_view| / mu0 from above. tau: the point's depth below the
// lit face (sun_optical_depth mu0); mu_view as CloudSunScattering's (< 0: the light travels up,
// toward the lit face). It grows as the view nears the slab's plane, to the slab's whole width.
// Written as (exp(-sun_optical_depth) - exp(-sun_optical_depth - a l)) / a, whose exponents are
// never positive (sun_optical_depth + a l = sun_optical_depth mu0 / |mu_view| with a < 0): the
// integral alone overflows deep in a cloud seen more steeply than the Sun, and times the
// sunlight's 0 there made a NaN (a rain shaft lit through a cumulonimbus' core, optical depth
// 2,500 toward a Sun 17 deg up).
Number CloudAlongViewLight(Number sun_optical_depth, Number tau, Number depth_below, Number mu0,
                           Number mu_view) {
    Number m = max(abs(mu_view), 1e-3);
    bool from_below = mu_view < 0.0;
    Number l = (from_below ? depth_below : tau) / m;
    Number a = from_below ? 1.0 + m / mu0 : 1.0 - m / mu0;
    Number sun = exp(-sun_optical_depth);
    return abs(a * l) < 1e-4 ? sun * l : (sun - exp(-(sun_optical_depth + a * l))) / a;
}

// Light scattered toward the viewer per unit sigma_s and unit illuminance (normal to the light)
// by a cloud sample with optical depth sun_optical_depth toward the light (the shadow march) and
// depth_below through its slab away from the lit face (straight down to the base, for a deck),
// the light at cosine mu0 to the slab's normal (its zenith cosine, for a deck):
// - first order: the sunlight left after the shadow, with the dual-lobe phase p(nu);
// - higher orders: the sample's slab, tau = sun_optical_depth mu0 below the top, tau_total =
//   tau + depth_below. Its diffuse light, scattered with the true phase, adds I0 + g mu_view I1
//   (the delta peak, f of the scattering, only passes the diffuse light on, which the view's
//   unscaled extinction needs back: f I + (1 - f)(I0 + g' mu I1) = I0 + g mu I1 in P1). The
//   light the delta peak kept in the scaled beam, exp(-tau' / mu0) - exp(-tau / mu0), has been
//   scattered by the forward lobe and lies spread about the light's direction by it, not on
//   it: the view takes all of it with the true phase over that spread, p_hg(g0) convolved with
//   the dual lobe (CloudForwardThenScatteredPhase; the scaled lobe (1 - f) p_hg(g') took only
//   what leaves the peak). The light scattered once on its way to the camera, which the
//   delta peak passes on along the view: f of it, seen with its spread by the forward lobe
//   (the same convolution, since it commutes, less the f p_hg(g0^2) of light scattered forward
//   twice that the peak's term holds; at least 0) and counted along the slab's extent behind
//   the sample (CloudAlongViewLight). The P1 field's f I spreads that light evenly over the
//   view's cosine; it runs longest near the slab's plane and comes out there (in decks of
//   optical depth 0.06-1 the light scattered more than once was 0.63-0.82x the path tracer's
//   15 deg off the plane and 1.24-1.52x near its normal, BENCHMARKS.md). And the lit face's
//   source (CloudSlabTables' x), with the twice-scattered phase p2.
// nu = dot(view, light); mu_view = dot(view, normal), the cosine between the light's way to the
// camera (-view) and the slab's inward normal (down, for a deck). mu0 is clamped to 0.05: a
// light grazing the slab still enters it. `leakage` is the slab's transverse buckling
// (CloudSlabLeakage; 0: an infinite slab), through which its diffuse light leaks out sideways
// (CloudLeakingDiffuseRadiance); the lit face's source is sized for the infinite slab.
Number CloudSunScattering(IN(CloudScatteringParameters) p, Number sun_optical_depth,
                          Number depth_below, Number mu0, Number nu, Number mu_view,
                          Number leakage) {
    Number single = CloudDualLobePhase(p.forward_g, p.backward_g, p.lobe_weight, nu) *
                    exp(-sun_optical_depth);
    Number g = CloudAsymmetry(p);
    Number f = CloudDeltaFraction(p);
    Number mu = max(mu0, 0.05);
    Number tau = sun_optical_depth * mu;
    vec2 slab = CloudSlabTables(p, tau + depth_below, mu);
    vec2 diffuse = CloudLeakingDiffuseRadiance(g, f, tau, tau + depth_below, mu, mu + slab.y,
                                               p.ground_albedo, leakage);
    Number spread = CloudForwardThenScatteredPhase(p.forward_g, p.backward_g, p.lobe_weight, nu);
    Number peak = spread * (exp(-(1.0 - f) * sun_optical_depth) - exp(-sun_optical_depth));
    Number passed =
        max(spread - f * CloudHenyeyGreensteinPhase(p.forward_g * p.forward_g, nu), 0.0) * f *
        CloudAlongViewLight(sun_optical_depth, tau, depth_below, mu, mu_view);
    Number lit_face = slab.x *
                      CloudTwiceScatteredPhase(p.forward_g, p.backward_g, p.lobe_weight, nu) *
                      exp(-sun_optical_depth);
    return single + p.multiple_scattering *
                        max(max(diffuse.x + g * mu_view * diffuse.y + peak, 0.0) + passed +
                                lit_face,
                            0.0);
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
