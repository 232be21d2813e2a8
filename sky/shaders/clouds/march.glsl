// Ray marching the cloud layers (H16 §5.1-5.3, §5.5 and §6.2; F16 §5.5-5.9), shared by the GL
// passes and the CPU reference. Comes after atmosphere/functions.glsl and clouds/functions.glsl.
//
// A caller marches one layer at a time, front to back (CloudLayerInterval orders them), into one
// CloudMarchState, then applies the aerial perspective once at the transmittance-weighted mean
// depth of what it hit (F16 Eq. 21). Positions and directions here are in the cloud frame
// (functions.glsl: planet-centred, km, +z through the weather map's origin); the atmosphere
// only needs radii and cosines, which the rotation from the camera's frame keeps.
//
// llvmpipe runs both sides of an `if` under a mask whether any lane takes it or not, but leaves a
// loop as soon as no lane goes on: the costly lighting of a sample is therefore a loop that runs
// once where there is cloud and not at all where a whole SIMD group sees clear air.

// std140-compatible like CloudLayerParameters: Numbers only, a multiple of four.
struct CloudMarchParameters {
    Number extinction;         // 1/km at density 1 (sigma_t of the cloud material)
    Number min_step;           // km: the primary step of a short crossing
    Number max_steps;          // primary steps per layer crossing at most (H16 §5.2: 64-128)
    Number shadow_steps;       // samples toward each light (F16 §5.5.2: 4; 7 reach 10.2 km)
    Number shadow_first_step;  // km, the first step toward the light...
    Number shadow_growth;      // ...and the factor each next one grows by
    Number ambient_scale;      // F16 §5.5.1's scale of the sky's ambient light, 1 = as estimated
    Number thick_step_refinement;  // halvings of a thick step's shadow march at most (0-3)
    Number min_transmittance;      // the march stops below this (H16 §6.2 early exit)
    Number max_distance;           // km marched in one layer at most (from where the ray enters it)
    Number oriented_slabs;  // 1: the diffuse slab follows the clouds' surface; 0: horizontal
    Number light_shaft_steps;  // samples of CloudAirShadowCorrection per ray, 0: no shafts
    Number column_steps;  // 1: a step's sample stands for its column across it; 0: for a point
    // The far sun-depth volume (CloudFarSunDepth): its square's centre in ground coordinates
    // (km, CloudGroundCoordinates), its side (km, 0: no volume) and the altitudes of its first
    // and last levels (km).
    Number sun_depth_center_x;
    Number sun_depth_center_y;
    Number sun_depth_extent;
    Number sun_depth_base;
    Number sun_depth_top;
    Number padding1;
    Number padding2;
};

// A step of more optical depth than this is lit where its light comes from (MarchCloudLayer),
// with the shadow march's first step halved for each doubling of its optical depth, up to
// CloudMarchParameters::thick_step_refinement times.
const Number kCloudMaxStepOpticalDepth = 1.0;
// A step across its cloud's top or base (not level, CloudColumnIsLevel) of more optical depth
// than this is lit where its light comes from too: at a deck's top with the sun low the light
// scattered once falls off within the step, while the density rises, and the midpoint rule
// lost 14 % of it in a step of optical depth 0.7.
const Number kCloudEdgeStepOpticalDepth = 0.1;
// A slab whose normal is within 26 deg of the vertical takes its depth below from the density
// profile (CloudDepthBelow, exact for a deck) rather than a march.
const Number kCloudVerticalSlab = 0.9;

// What the march has gathered so far, front to back.
struct CloudMarchState {
    vec3 luminance;         // cd/m^2 scattered toward the camera by the clouds
    Number transmittance;   // of the clouds alone, camera to the end of the march
    Number depth_weight;    // F16 Eq. 21: sum of T(x_n) over samples inside cloud...
    Number weighted_depth;  // ...and of T(x_n) t_n (km)
    // The transmittance's profile along the ray, for a host's geometry inside the clouds
    // (CloudOpacityShareInFront): where the first step with cloud starts, and where T fell below
    // CloudProfileThreshold(k) for k = 0..3 (km; -1: not reached).
    Number entry;
    vec4 crossing;
};

CloudMarchState CloudMarchStart() {
    CloudMarchState s;
    s.luminance = vec3(0.0);
    s.transmittance = 1.0;
    s.depth_weight = 0.0;
    s.weighted_depth = 0.0;
    s.entry = -1.0;
    s.crossing = vec4(-1.0);
    return s;
}

// The transmittances whose distances CloudMarchState.crossing records.
Number CloudProfileThreshold(int k) { return k == 0 ? 0.8 : k == 1 ? 0.5 : k == 2 ? 0.2 : 0.05; }

// Records where T fell below each threshold during a step [t0, t0 + dt] that took it from
// `before` to state.transmittance, exponential within the step.
void CloudRecordCrossings(INOUT(CloudMarchState) state, Number t0, Number dt, Number before) {
    if (state.entry < 0.0) state.entry = t0;
    Number after = state.transmittance;
    for (int k = 0; k < 4; ++k) {
        Number threshold = CloudProfileThreshold(k);
        if (state.crossing[k] < 0.0 && before >= threshold && after < threshold) {
            state.crossing[k] = t0 + dt * log(before / threshold) / max(log(before / after), 1e-9);
        }
    }
}

// The share, in [0, 1], of the clouds' opacity 1 - T along a ray that lies in front of distance
// d (km): (1 - T(d)) / (1 - T). T(d) runs through the recorded points (entry, 1) and
// (crossing k, threshold k), exponential between them and past the last one with its slope, never
// below T; from a ray that stays above 0.8, it falls from the entry to T at twice the mean depth.
// A homogeneous medium (fog around the camera) gives its T(d) = exp(-sigma d) exactly; 0 in
// front of the clouds, 1 behind them.
Number CloudOpacityShareInFront(Number entry, Number mean_depth, vec4 crossing,
                                Number transmittance, Number d) {
    if (!(entry >= 0.0) || !(transmittance < 1.0) || !(d > entry)) return 0.0;
    Number t_previous = entry;
    Number log_previous = 0.0;  // ln T at t_previous
    Number slope = 0.0;         // -d ln T / dt of the last segment
    for (int k = 0; k < 4; ++k) {
        if (!(crossing[k] >= 0.0)) continue;
        Number log_threshold = log(CloudProfileThreshold(k));
        Number length_km = max(crossing[k] - t_previous, 1e-9);
        slope = (log_previous - log_threshold) / length_km;
        if (d <= crossing[k]) {
            Number t_d = exp(log_previous - slope * (d - t_previous));
            return CloudSaturate((1.0 - t_d) / (1.0 - transmittance));
        }
        t_previous = crossing[k];
        log_previous = log_threshold;
    }
    if (!(slope > 0.0)) {
        Number end = max(2.0 * mean_depth - entry, entry + 1e-6);
        slope = (log_previous - log(max(transmittance, 1e-6))) / max(end - t_previous, 1e-9);
    }
    Number t_d = max(exp(log_previous - slope * (d - t_previous)), transmittance);
    return CloudSaturate((1.0 - t_d) / (1.0 - transmittance));
}

// The transmittance-weighted mean depth (km) of the clouds hit (F16 Eq. 21), -1 if none.
Number CloudMeanDepth(IN(CloudMarchState) s) {
    return s.depth_weight > 0.0 ? s.weighted_depth / s.depth_weight : -1.0;
}

// Where in its step a pixel's samples fall, in [0, 1): Jimenez's (2014) interleaved gradient
// noise, which has little low-frequency content, shifted by frame_jitter (a Van der Corput
// sequence over frames). Banding from equal steps becomes fine noise that the reprojection
// averages away (F16 §5.5.3).
Number CloudJitter(ivec2 pixel, Number frame_jitter) {
    Number ign =
        fract(52.9829189 * fract(0.06711056 * Number(pixel.x) + 0.00583715 * Number(pixel.y)));
    return fract(ign + frame_jitter);
}

// The part [x, y] (km) of a ray within a layer's shell (H16 §5.1-5.3), from radius r with zenith
// cosine mu at `altitude` above bottom_radius (exact); y < x when the ray misses the layer or
// meets the ground first. The shell is the part of the layer its clouds reach: from the base to
// cloud_top_altitude, above which the density is 0. Below the shell the march starts at the base;
// inside, at the camera; above (up to orbit), at the top; each ends where the ray leaves the
// shell or meets the ground, or max_distance past its start. A ray from above that grazes the
// base sphere without meeting the ground re-enters the layer beyond; that second part (only ever
// seen at the horizon from above the layer) is not marched.
vec2 CloudLayerInterval(IN(CloudLayerParameters) layer, Number r, Number mu, Number altitude,
                        Number max_distance) {
    Number top_altitude = layer.cloud_top_altitude;
    Number base_radius = layer.bottom_radius + layer.base_altitude;
    Number top_radius = layer.bottom_radius + top_altitude;
    Number t_ground = RaySphereDistance(r, mu, altitude, layer.bottom_radius);
    Number t_base = RaySphereDistance(r, mu, altitude - layer.base_altitude, base_radius);
    Number t_top = RaySphereDistance(r, mu, altitude - top_altitude, top_radius);
    vec2 interval = vec2(0.0, -1.0);
    if (altitude < layer.base_altitude) {
        interval = vec2(t_base, t_top);  // both exits: the camera is inside both spheres
    } else if (altitude <= top_altitude) {
        interval = vec2(0.0, t_base >= 0.0 ? t_base : t_top);
    } else if (t_top >= 0.0) {
        // Above: t_top is the entry; the exit is the base sphere, or the top sphere's far root.
        Number b = r * mu;
        Number far_root = -b + SafeSqrt(b * b - (altitude - top_altitude) * (r + top_radius));
        interval = vec2(t_top, t_base >= 0.0 ? t_base : far_root);
    }
    if (t_ground >= 0.0) interval.y = min(interval.y, t_ground);
    interval.y = min(interval.y, interval.x + max_distance);
    return interval;
}

// A march step's samples stand for their column, not for a point: the density through a step
// from altitude `from` to `to` is the mean of the column of its sample `s` (CloudColumnDensity:
// its weather and noise held, the height's parts evaluated) at kCloudColumnPoints heights
// across it. A step that leaves its cloud through the top or the base counts only its part
// inside, and one across a deck's parabolic profile its curve. The sample alone (the midpoint
// rule) put the depth of a dense deck's diffuse light and its thick steps' emission points off,
// and the light below a deck of optical depth 32 up to 17 % too bright (BENCHMARKS.md,
// cloud_reference_report --part decks). A step that stays inside its cloud within a twentieth
// of the cloud's height (a level one, at a cumulus' side) keeps its sample's density: there the
// profile is nearly straight. (With a tenth, the halves of a 120 m step through a 500 m deck
// were level or not by the view's tilt, and the light below a deck of optical depth 32 moved by
// 5 % between a view straight up and one 3 degrees off it.) On llvmpipe the columns cost the
// trace 1.2-1.5x.
const int kCloudColumnPoints = 4;

bool CloudColumnIsLevel(IN(CloudLayerParameters) layer, IN(CloudSample) s, Number from,
                        Number to) {
    if (!(s.detail >= 0.0)) return true;  // no column: fog, rain shafts, clear air
    Number x_from = (from - layer.base_altitude) / s.cloud_height;
    Number x_to = (to - layer.base_altitude) / s.cloud_height;
    return abs(x_to - x_from) < 0.05 && min(x_from, x_to) > 0.0 && max(x_from, x_to) < 1.0;
}

Number CloudStepColumnDensity(IN(CloudLayerParameters) layer, IN(CloudSample) s, Number from,
                              Number to) {
    if (CloudColumnIsLevel(layer, s, from, to)) return s.density;
    // One point per tenth of the cloud's height the step spans, two at least.
    int points = int(clamp(ceil(10.0 * abs(to - from) / s.cloud_height), 2.0,
                           Number(kCloudColumnPoints)));
    Number sum = 0.0;
    for (int k = 0; k < points; ++k) {
        sum += CloudColumnDensity(layer, s, mix(from, to, (Number(k) + 0.5) / Number(points)));
    }
    return sum / Number(points);
}

// The column a step's sample `s` (at `altitude`) stands for beside `neighbour` (the step's other
// sample, or the point a shadow march starts from): its own, or, where it read none because it
// lies above or below the neighbour's cloud while the step may still cross it (a step leaving a
// deck through its top, say), the neighbour's.
CloudSample CloudStepColumn(IN(CloudLayerParameters) layer, IN(CloudSample) s,
                            IN(CloudSample) neighbour, Number altitude) {
    bool beyond = altitude >= layer.base_altitude + neighbour.cloud_height ||
                  altitude <= layer.base_altitude;
    return !(s.detail >= 0.0) && neighbour.detail >= 0.0 && beyond ? neighbour : s;
}

// A precipitation shaft's shadow march crosses the cloud it falls from in equal steps of at
// most kCloudCrossingStep km, 4 to 16 of them (CloudShadowOpticalDepth). Four across a
// thunderstorm's 11 km at a Sun 10 deg up (16 km steps) left the ground's light under
// `cumulonimbus` +118 % against the path tracer, 7 and 16 +98 %. Under overcast_stratus' 500 m
// of drizzling stratus (4-6 such steps) the 27 views are within 6.5 % in the mean; 4, 7 and 16
// steps everywhere gave 6.2, 6.8 and 6.4 % (BENCHMARKS.md, "The shadow march's reach").
const Number kCloudCrossingStep = 0.5;

// Optical depth (extinction times distance, unitless) from p (its sample `origin`) toward a
// light: F16 §5.5.2's short march with steps growing by shadow_growth, each sampled at its
// middle and standing for its column across the step (CloudStepColumnDensity). It covers
// shadow_first_step (g^n - 1) / (g - 1) km, so clouds shade themselves and their neighbours.
// `refinement` r halves the first step r times and adds r steps (the same reach at growth 2):
// the primary march asks for it where it splits an optically thick step, whose samples lie
// within one optical depth of each other and would all see the same coarse first shadow step;
// a negative r doubles it and drops steps, a coarser march (CloudSampleSource's slab depth).
// The full density, with the detail erosion: the cheap sample without it (H16 §6.2) saved
// only 10 % of the trace here and darkened the clouds by 23 % in the mean (measured).
// A precipitation shaft is lit through the cloud it falls from, `cloud_above` (the next layer
// up, clouds::WithPrecipitationShafts; its map is the shaft's): its own part to where the
// light's way leaves it, at origin's density (it is homogeneous in height), then the cloud's
// whole crossing, however long the slant, at equal steps' midpoints (kCloudCrossingStep), as the
// shadow map crosses a layer (CloudLayerShadowDepth). The growing steps, continued from the
// shaft into its cloud, reached 1.2 km from p (four of them) and stopped short of a deck at a
// low Sun (overcast_stratus' 500 m of stratus are 1.7 km across at 17 deg): the ground's light
// under it came out +29 % with the Sun 17 deg up and +110 % at 10 deg against the path tracer
// (BENCHMARKS.md). `reach` gets how far (km) the march went from p, or -1 where it crossed the
// cloud above a shaft to its end (nothing lies beyond it).
Number CloudShadowOpticalDepth(IN(CloudLayerParameters) layer,
                               IN(CloudLayerParameters) cloud_above, IN(WeatherTexture) weather_map,
                               IN(CloudNoiseTexture) shape_noise,
                               IN(CloudNoiseTexture) detail_noise, IN(CloudMarchParameters) march,
                               IN(CloudSample) origin, vec3 p, vec3 light_direction,
                               int refinement, OUT(Number) reach) {
    Number optical_depth = 0.0;
    Number t = 0.0;
    Number step_length = march.shadow_first_step * exp2(-Number(refinement));
    Number growth = march.shadow_growth;
    int steps = int(march.shadow_steps) + refinement;
    CloudLayerParameters marched = layer;
    bool crossing = layer.precipitation_shaft > 0.5;
    if (crossing) {
        Number r = length(p);
        Number mu = dot(p, light_direction) / r;
        Number height = r - layer.bottom_radius;
        vec2 own = CloudLayerInterval(layer, r, mu, height, march.max_distance);
        optical_depth = origin.density * march.extinction * max(own.y - own.x, 0.0);
        vec2 cloud = CloudLayerInterval(cloud_above, r, mu, height, march.max_distance);
        marched = cloud_above;
        steps = int(clamp(ceil((cloud.y - cloud.x) / kCloudCrossingStep), 4.0, 16.0));
        t = cloud.x;
        step_length = max(cloud.y - cloud.x, 0.0) / Number(steps);
        growth = 1.0;
    }
    Number altitude = CloudAltitude(marched, p + light_direction * t);
    for (int i = 0; i < steps; ++i) {
        vec3 q = p + light_direction * (t + 0.5 * step_length);
        CloudSample s = SampleCloudDensity(marched, weather_map, shape_noise, detail_noise, q);
        Number density = s.density;
        for (int c = 0; c < (march.column_steps > 0.0 && !crossing ? 1 : 0); ++c) {
            Number next_altitude = CloudAltitude(marched, p + light_direction * (t + step_length));
            s = CloudStepColumn(marched, s, origin, 0.5 * (altitude + next_altitude));
            density = CloudStepColumnDensity(marched, s, altitude, next_altitude);
            altitude = next_altitude;
        }
        optical_depth += density * march.extinction * step_length;
        t += step_length;
        step_length *= growth;
    }
    reach = crossing ? -1.0 : t;
    return optical_depth;
}

// ---------------------------------------------------------------------------------------------
// The far sun-depth volume: the optical depth toward the main light (MakeCloudLightSet's first)
// through every cloud layer (not the precipitation shafts beneath them), from points of a square of
// sun_depth_extent km around the camera's ground point at evenly spaced altitudes from
// sun_depth_base to sun_depth_top (its levels). The shadow march stands for its reach (10.2 km at
// F16's growth with seven samples); the volume adds what lies beyond it (CloudSampleSource). Under
// `cumulonimbus` with the Sun 10-17 deg up, towers in the shadow of cloud more than 10.2 km away
// toward the Sun were lit as if that cloud were not there: one view 4.7x the path tracer, the
// ground's light 1.6-1.8x (BENCHMARKS.md). Level k's texel holds the depth from its point to where
// the light's ray reaches level k + 1 (CloudSunDepthTexelWay: steps of at most kCloudSunDepthStep
// km, up to kCloudSunDepthMaxSteps of them) plus level k + 1's value there, read from the volume:
// built from the top level down, one level per dispatch, so each ray is marched once however long
// it is (clouds/sun_depth.comp; on the CPU, cloud_trace.h). A way that leaves the square reads its
// edge: beyond it the field is taken as the edge's.
const Number kCloudSunDepthStep = 0.5;
const int kCloudSunDepthMaxSteps = 32;

// The point of the cloud frame above ground coordinates `ground` (km, CloudGroundCoordinates'
// dome projection) at `altitude` km.
vec3 CloudDomePoint(Number bottom_radius, vec2 ground, Number altitude) {
    Number s = length(ground);
    Number theta = s / bottom_radius;
    vec2 along = s > 0.0 ? ground / s : vec2(1.0, 0.0);
    return (bottom_radius + altitude) * vec3(along * sin(theta), cos(theta));
}

Number CloudSunDepthAltitude(IN(CloudMarchParameters) march, int level, int levels) {
    return mix(march.sun_depth_base, march.sun_depth_top,
               Number(level) / Number(max(levels - 1, 1)));
}

// The volume's texture coordinate at p (cloud frame, km): uv across the square, w at the level
// texels' centres (a sampler's linear filter then interpolates between levels).
vec3 CloudSunDepthUvw(IN(CloudMarchParameters) march, IN(CloudLayerParameters) layer, vec3 p,
                      ivec3 size) {
    vec2 center = vec2(march.sun_depth_center_x, march.sun_depth_center_y);
    vec2 uv = (CloudGroundCoordinates(layer, p) - center) / march.sun_depth_extent + vec2(0.5);
    Number level = (CloudAltitude(layer, p) - march.sun_depth_base) /
                   (march.sun_depth_top - march.sun_depth_base) * Number(size.z - 1);
    return vec3(uv, (level + 0.5) / Number(size.z));
}

// Texel `texel` of a volume of `size`: its point p (cloud frame, km), and the way from p toward
// `light` to level texel.z + 1 (km) with where it ends in the volume. The top level's way is
// empty (length 0); a way the ground stops ends there (`above` false: nothing to add).
struct CloudSunDepthWay {
    vec3 origin;
    Number length_km;
    int steps;
    bool above;
    vec3 end_uvw;
};

CloudSunDepthWay CloudSunDepthTexelWay(IN(CloudMarchParameters) march,
                                       IN(CloudLayerParameters) layer, ivec3 texel, ivec3 size,
                                       vec3 light) {
    vec2 uv = (vec2(texel.x, texel.y) + vec2(0.5)) / vec2(size.x, size.y);
    vec2 center = vec2(march.sun_depth_center_x, march.sun_depth_center_y);
    Number altitude = CloudSunDepthAltitude(march, texel.z, size.z);
    CloudSunDepthWay way;
    way.origin = CloudDomePoint(layer.bottom_radius,
                                center + (uv - vec2(0.5)) * march.sun_depth_extent, altitude);
    way.length_km = 0.0;
    way.steps = 0;
    way.above = false;
    way.end_uvw = vec3(0.0);
    if (texel.z + 1 >= size.z) return way;
    Number next = CloudSunDepthAltitude(march, texel.z + 1, size.z);
    Number r = length(way.origin);
    Number mu = dot(way.origin, light) / r;
    Number ground = RaySphereDistance(r, mu, altitude, layer.bottom_radius);
    way.above = !(ground >= 0.0);
    way.length_km = way.above
                        ? RaySphereDistance(r, mu, altitude - next, layer.bottom_radius + next)
                        : ground;
    way.length_km = max(way.length_km, 0.0);
    way.steps = int(clamp(ceil(way.length_km / kCloudSunDepthStep), 1.0,
                          Number(kCloudSunDepthMaxSteps)));
    // At the next level's texel centre exactly, so a linear filter reads that level alone.
    vec3 end = CloudSunDepthUvw(march, layer, way.origin + light * way.length_km, size);
    way.end_uvw = vec3(end.x, end.y, (Number(texel.z + 1) + 0.5) / Number(size.z));
    return way;
}

// How much of a shadow-map texel's own value to take at `uv` rather than the map's mean (or of
// a sun-depth texel's rather than none): faded out over the square's outer 5 % on each side, so
// its edge does not show.
Number CloudShadowMapEdgeWeight(vec2 uv) {
    return clamp((0.5 - max(abs(uv.x - 0.5), abs(uv.y - 0.5))) / 0.05, 0.0, 1.0);
}

// The optical depth toward the main light beyond q, the end of p's shadow march (km, cloud
// frame), from the volume; 0 where there is none (sun_depth_extent 0), above its top level, and
// faded to 0 over its square's outer 5 % (CloudShadowMapEdgeWeight): the march alone, as
// before, where the square does not reach.
Number CloudFarSunDepth(IN(CloudMarchParameters) march, IN(CloudLayerParameters) layer,
                        IN(CloudSunDepthTexture) volume, vec3 q) {
    if (!(march.sun_depth_extent > 0.0)) return 0.0;
    if (CloudAltitude(layer, q) >= march.sun_depth_top) return 0.0;
    vec3 uvw = CloudSunDepthUvw(march, layer, q, TextureSize(volume));
    Number weight = CloudShadowMapEdgeWeight(vec2(uvw.x, uvw.y));
    if (!(weight > 0.0)) return 0.0;
    return weight * SampleTexture3D(volume, uvw).r;
}

// The large-scale cloud field at a ground position and altitude: the density's argument before
// the coverage remap clamps it, with the shape noise at 1 (SampleCloudDensityAt: tower signal +
// coverage - 1, or the anvil's), positive inside the clouds' envelope. Its gradient gives the
// envelope's orientation without the noise's small-scale structure.
Number CloudEnvelope(IN(CloudLayerParameters) layer, IN(WeatherTexture) weather_map, vec2 ground,
                     Number altitude) {
    Number height_fraction =
        (altitude - layer.base_altitude) / (layer.top_altitude - layer.base_altitude);
    CloudWeather w =
        CloudWeatherAt(layer, weather_map, CloudLeanedGround(layer, ground, height_fraction));
    Number cloud_height =
        (layer.top_altitude - layer.base_altitude) * CloudTypeHeightFraction(w.type) * w.height;
    Number convection = CloudConvection(w.type);
    return max(CloudTowerSignal(altitude, layer.base_altitude, cloud_height, convection) +
                   w.coverage - 1.0,
               CloudAnvilSignal(convection, height_fraction) *
                   (convection - (1.0 - kCloudAnvilCoverage)));
}

// The clouds' outward normal at p (cloud frame, km): minus the envelope's gradient, by forward
// differences over 1 % of the weather tile across the ground and 2 % of the layer in altitude
// (four weather reads); straight up where the envelope is flat.
vec3 CloudOutwardNormal(IN(CloudLayerParameters) layer, IN(WeatherTexture) weather_map, vec3 p) {
    Number r = length(p);
    vec3 up = p / r;
    // Ground coordinates run along the frame's x and y near the map's origin (the dome
    // projection), so the tangent plane's x and y axes carry their derivatives.
    vec3 east = normalize(vec3(1.0, 0.0, 0.0) - up * up.x);
    vec3 north = cross(up, east);
    vec2 ground = CloudGroundCoordinates(layer, p);
    Number altitude = r - layer.bottom_radius;
    Number dx = 0.01 * layer.weather_period;
    Number dz = 0.02 * (layer.top_altitude - layer.base_altitude);
    Number f = CloudEnvelope(layer, weather_map, ground, altitude);
    vec3 gradient =
        east * (CloudEnvelope(layer, weather_map, ground + vec2(dx, 0.0), altitude) - f) / dx +
        north * (CloudEnvelope(layer, weather_map, ground + vec2(0.0, dx), altitude) - f) / dx +
        up * (CloudEnvelope(layer, weather_map, ground, altitude + dz) - f) / dz;
    Number magnitude = length(gradient);
    return magnitude > 1e-6 ? -gradient / magnitude : up;
}

// The diffuse light beneath the clouds above the ground point under `up`, scattered toward the
// camera along `view` (cd/m^2, per unit sigma_s): the light field there in P1, I0 + I1 mu, from
// its irradiances down and up by Eddington's closure, I0 = (E_down + E_up) / 2 pi and I1 =
// 3 (E_down - E_up) / 4 pi (as the slab's, CloudSkyScattering), scattered with the phase's
// asymmetry g: I0 + g mu_view I1. E_down is the diffuse light the ground gets, sky_shade.comp's
// cosine-weighted means: the sky's through the clouds (cloud_ground_sky) and the clouds' (pi
// cloud_ground_luminance). E_up is the ground's albedo of that and of the lights' beams through
// the clouds' mean transmittance (cloud_direct).
vec3 CloudLightBeneathClouds(IN(AtmosphereParameters) atmosphere,
                             IN(TransmittanceTexture) transmittance_texture,
                             IN(IrradianceTexture) irradiance_texture, IN(LightSet) lights,
                             int light_count, IN(CloudScatteringParameters) scattering, vec3 up,
                             vec3 view) {
    vec3 down = kPi * lights.cloud_ground_luminance;
    vec3 beams = vec3(0.0);
    for (int l = 0; l < light_count; ++l) {
        Number mu_l = dot(up, lights.light[l].direction);
        down += lights.cloud_ground_sky * lights.light[l].illuminance *
                GetGroundSkyIrradiance(irradiance_texture, mu_l);
        beams += lights.cloud_direct * lights.light[l].illuminance * max(mu_l, 0.0) *
                 GetTransmittanceToSun(atmosphere, transmittance_texture,
                                       atmosphere.bottom_radius, mu_l);
    }
    vec3 going_up = CloudSaturate(scattering.ground_albedo) * (down + beams);
    vec3 i0 = (down + going_up) / (2.0 * kPi);
    vec3 i1 = 3.0 / (4.0 * kPi) * (down - going_up);
    return max(i0 + CloudAsymmetry(scattering) * dot(view, up) * i1, vec3(0.0));
}

// Luminance scattered per km (sigma_s L_i, cd/m^2/km) at a cloud sample p of density `s` seen
// along `view`: for each light, its illuminance at the top of the atmosphere, the atmosphere's
// transmittance from p toward it (which colours sunsets), and CloudSunScattering's first order
// in the clouds' own shadow plus the diffuse light of the slab through p. The slab lies across
// the clouds' outward normal (CloudOutwardNormal), turned to face the light: over a deck it is
// the horizontal plane-parallel slab, whose depth below p comes from the density profile
// (CloudDepthBelow); on the side of a cumulus it stands upright, lit at the cosine between the
// light and the side, and its depth beyond p is marched like the shadow. A horizontal slab lit
// through a cumulus' side made its sunlit face 37 % too dark and its shadowed side 49 % too
// bright against the path tracer (BENCHMARKS.md). A slab across a side lets its diffuse light
// leak out of the cloud's top and base (CloudSlabLeakage), where an infinite one kept it for
// the shadowed side and base, which came out 1.9-2x too bright. Plus the sky's ambient light,
// E_sky / pi from the ground-irradiance LUT as an isotropic radiance on the horizontal slab's
// top (CloudSkyScattering), scaled by ambient_scale (F16 §5.5.1). Raining clouds are not
// darkened toward their base (H16 §4.4.1's factor, down to 0.2 at the base of heavy rain):
// water does not absorb visible light, and a raining cloud is dark by its depth, which the
// transport carries. Under the drizzling overcast_stratus that factor made the ground's light
// 10-12 % and the deck's base 8-14 % darker than the path tracer's (BENCHMARKS.md).
// A precipitation shaft hangs in the air beneath the clouds, and once the clouds' shade is
// known (lights.cloud_shaded) it is lit as that air is: the light scattered once, through the
// cloud it falls from (`cloud_above`, the next layer up, CloudShadowOpticalDepth), and the
// diffuse light beneath the clouds (CloudLightBeneathClouds). Lit through its cloud's slab
// instead, with the depth of the light's way through that cloud, the rain beneath cumulonimbus
// seen 3 deg up was 0.17x the path tracer's (now 0.74x): its light comes in through the open
// sides beneath the storm and bounces between the cloud's base, the rain and the ground
// (BENCHMARKS.md, "Rain lit by the light beneath the clouds"). The shade's own trace, which
// makes those means, still lights a shaft through its cloud's slab, level: the cloud's column
// on top of the shaft's below p. Lit by the Sun through the shaft alone, the drizzle under
// overcast_stratus seen level from 300 m with the Sun 10-17 deg up was 2.6-54x the path
// tracer's.
vec3 CloudSampleSource(IN(AtmosphereParameters) atmosphere,
                       IN(TransmittanceTexture) transmittance_texture,
                       IN(IrradianceTexture) irradiance_texture,
                       IN(CloudLayerParameters) layer, IN(CloudLayerParameters) cloud_above,
                       IN(WeatherTexture) weather_map,
                       IN(CloudNoiseTexture) shape_noise, IN(CloudNoiseTexture) detail_noise,
                       IN(CloudSunDepthTexture) sun_depth,
                       IN(CloudScatteringParameters) scattering, IN(CloudMarchParameters) march,
                       IN(LightSet) lights, int light_count, IN(CloudSample) s, vec3 p, vec3 view,
                       int refinement) {
    Number r = length(p);
    vec3 up = p / r;
    Number sigma_s = scattering.albedo * s.density * march.extinction;
    if (layer.precipitation_shaft > 0.5 && lights.cloud_shaded > 0.5) {
        vec3 light = CloudLightBeneathClouds(atmosphere, transmittance_texture,
                                             irradiance_texture, lights, light_count,
                                             scattering, up, view);
        for (int l = 0; l < light_count; ++l) {
            vec3 direction = lights.light[l].direction;
            Number reach;
            Number optical_depth =
                CloudShadowOpticalDepth(layer, cloud_above, weather_map, shape_noise,
                                        detail_noise, march, s, p, direction, refinement, reach);
            light += lights.light[l].illuminance *
                     GetTransmittanceToSun(atmosphere, transmittance_texture, r,
                                           dot(up, direction)) *
                     CloudDualLobePhase(scattering.forward_g, scattering.backward_g,
                                        scattering.lobe_weight, dot(view, direction)) *
                     exp(-optical_depth);
        }
        return sigma_s * light;
    }
    Number depth_below = CloudDepthBelow(layer, s, r - layer.bottom_radius, march.extinction);
    Number mu_view = dot(view, up);
    vec3 normal = up;
    bool level = !(march.oriented_slabs > 0.0) || layer.precipitation_shaft > 0.5;
    for (int oriented = 0; oriented < (level ? 0 : 1); ++oriented) {
        normal = CloudOutwardNormal(layer, weather_map, p);
    }
    Number leakage = CloudSlabLeakage(layer, s, CloudAsymmetry(scattering), march.extinction,
                                      dot(normal, up));
    vec3 direct = vec3(0.0);
    vec3 ambient = vec3(0.0);
    for (int l = 0; l < light_count; ++l) {
        vec3 direction = lights.light[l].direction;
        Number mu_l = dot(p, direction) / r;
        vec3 atmosphere_transmittance =
            GetTransmittanceToSun(atmosphere, transmittance_texture, r, mu_l);
        Number reach;
        Number optical_depth =
            CloudShadowOpticalDepth(layer, cloud_above, weather_map, shape_noise, detail_noise,
                                    march, s, p, direction, refinement, reach);
        // Beyond the march's reach, the main light's volume (CloudFarSunDepth).
        if (l == 0 && reach >= 0.0) {
            optical_depth += CloudFarSunDepth(march, layer, sun_depth, p + direction * reach);
        }
        // The slab faces the light: the normal or its opposite, whichever the light enters.
        // Beyond p it reaches as deep as a coarser march away from the light's side shows (the
        // shadow march's reach in two samples fewer, from 320 m: five, to 10 km; with four
        // shadow samples it was two, and a quarter of them gave the same cumulus against the
        // path tracer); over a deck, the density profile's depth below p.
        vec3 facing = dot(normal, direction) >= 0.0 ? normal : -normal;
        Number depth_beyond = depth_below;
        for (int side = 0; side < (dot(facing, up) < kCloudVerticalSlab ? 1 : 0); ++side) {
            depth_beyond = CloudShadowOpticalDepth(layer, cloud_above, weather_map, shape_noise,
                                                   detail_noise, march, s, p, -facing, -2,
                                                   reach);
        }
        direct += lights.light[l].illuminance * atmosphere_transmittance *
                  CloudSunScattering(scattering, optical_depth, depth_beyond,
                                     dot(facing, direction), dot(view, direction),
                                     dot(view, facing), leakage);
        // The depth below the cloud's top as the sun's slab has it.
        Number depth_above = optical_depth * max(mu_l, 0.05);
        ambient += lights.light[l].illuminance *
                   GetGroundSkyIrradiance(irradiance_texture, mu_l) / kPi *
                   CloudSkyScattering(scattering, depth_above, depth_above + depth_below, mu_view);
    }
    return sigma_s * (direct + ambient * march.ambient_scale);
}

// Marches [interval.x, interval.y] of the ray origin + t view through one layer with
// min(max_steps, ceil(length / min_step)) equal steps, each sampled at `jitter` in [0, 1) of
// its length (the caller varies it per frame and pixel), integrating with F16's energy-
// conserving step (App. C) into `state`. Stops once the transmittance is below
// min_transmittance and counts the rest as opaque (the light behind, at most that share, is
// dropped: otherwise a Sun of 10^8 cd/m^2 would shine through a thunderstorm at 1 %).
// `cloud_above`: the next layer up, which lights a precipitation shaft (CloudSampleSource).
void MarchCloudLayer(IN(AtmosphereParameters) atmosphere,
                     IN(TransmittanceTexture) transmittance_texture,
                     IN(IrradianceTexture) irradiance_texture,
                     IN(CloudLayerParameters) layer, IN(CloudLayerParameters) cloud_above,
                     IN(WeatherTexture) weather_map, IN(CloudNoiseTexture) shape_noise,
                     IN(CloudNoiseTexture) detail_noise, IN(CloudSunDepthTexture) sun_depth,
                     IN(CloudScatteringParameters) scattering, IN(CloudMarchParameters) march,
                     IN(LightSet) lights, int light_count, vec3 origin, vec3 view,
                     vec2 interval, Number jitter,
                     INOUT(CloudMarchState) state) {
    Number length_km = interval.y - interval.x;
    if (!(length_km > 0.0)) return;
    // Rain and snow (a precipitation shaft) are homogeneous in height and change only with the
    // map, over kilometres: a quarter of the steps, each at least 8 min_step.
    bool shaft = layer.precipitation_shaft > 0.5;
    Number min_step = shaft ? 8.0 * march.min_step : march.min_step;
    Number max_steps = max(shaft ? 0.25 * march.max_steps : march.max_steps, 1.0);
    int steps = int(clamp(ceil(length_km / min_step), 1.0, max_steps));
    Number dt = length_km / Number(steps);
    for (int i = 0; i < steps; ++i) {
        if (state.transmittance < march.min_transmittance) break;
        Number t = interval.x + (Number(i) + jitter) * dt;
        CloudSample s =
            SampleCloudDensity(layer, weather_map, shape_noise, detail_noise, origin + view * t);
        Number step_depth = s.density * march.extinction * dt;
        // An optically thick step is seen only to its first optical depth or so, where its
        // source differs from the middle's (from below, the diffuse light of a dense deck grows
        // tenfold across a 120 m step, and from above the density rises from 0 at the top).
        // There the density is read in the other half of the step too, at the jittered
        // sample's mirror (jitter +- 1/2), each half's sample standing for its column
        // (CloudColumnDensity) at kCloudColumnPoints heights across the half, which gives the
        // step's optical depth in 2 kCloudColumnPoints parts; the one source is taken where the
        // step's light comes from: the same jitter's point of the free-path distribution
        // through the parts (so the frames' jitters still cover the step's integral), lit with
        // a shadow march refined to the step's optical depth and described (cloud fraction,
        // rain) by its half's column at that height. Whether a step is thick is judged by its
        // column too (where the columns are on), not by its sample alone: at a deck's top or
        // base the jitters whose sample lies in the thin edge of a thick step kept that sample's
        // small depth while the others took the step's whole depth, so the edge step emitted
        // too little in the frames' mean (the first scattering off a deck's top with the sun at
        // 60 deg was 16-23 % short, R + T of the renderer's slab 0.971), and so is a step across
        // its cloud's edge (kCloudEdgeStepOpticalDepth).
        Number start = interval.x + Number(i) * dt;
        // The step's altitudes at its start, middle and end, where the columns are on.
        Number altitudes[3];
        for (int e = 0; e < 3; ++e) altitudes[e] = 0.0;
        Number thick_depth = step_depth;
        bool edge = false;
        for (int c = 0; c < (march.column_steps > 0.0 ? 1 : 0); ++c) {
            for (int e = 0; e < 3; ++e) {
                altitudes[e] = CloudAltitude(layer, origin + view * (start + 0.5 * Number(e) * dt));
            }
            thick_depth = max(thick_depth, CloudStepColumnDensity(layer, s, altitudes[0],
                                                                  altitudes[2]) *
                                               march.extinction * dt);
            edge = !CloudColumnIsLevel(layer, s, altitudes[0], altitudes[2]) &&
                   thick_depth > kCloudEdgeStepOpticalDepth;
        }
        int refinement =
            int(min(max(ceil(log2(thick_depth / kCloudMaxStepOpticalDepth)), edge ? 1.0 : 0.0),
                    march.thick_step_refinement));
        CloudSample described = s;
        Number source_scale = 1.0;
        for (int thick = 0; thick < (refinement > 0 ? 1 : 0); ++thick) {
            bool jittered_near = jitter < 0.5;
            Number mirror_t = start + (jitter + (jittered_near ? 0.5 : -0.5)) * dt;
            CloudSample mirror = SampleCloudDensity(layer, weather_map, shape_noise,
                                                    detail_noise, origin + view * mirror_t);
            for (int c = 0; c < (march.column_steps > 0.0 ? 1 : 0); ++c) {
                mirror = CloudStepColumn(layer, mirror, s,
                                         CloudAltitude(layer, origin + view * mirror_t));
            }
            bool level[2];
            for (int h = 0; h < 2; ++h) {
                level[h] = !(march.column_steps > 0.0) ||
                           CloudColumnIsLevel(layer, (h == 0) == jittered_near ? s : mirror,
                                              altitudes[h], altitudes[h + 1]);
            }
            Number depths[2 * kCloudColumnPoints];
            step_depth = 0.0;
            for (int k = 0; k < 2 * kCloudColumnPoints; ++k) {
                int half_index = k / kCloudColumnPoints;
                CloudSample column = (half_index == 0) == jittered_near ? s : mirror;
                Number altitude = mix(altitudes[half_index], altitudes[half_index + 1],
                                      (Number(k % kCloudColumnPoints) + 0.5) /
                                          Number(kCloudColumnPoints));
                depths[k] = (level[half_index] ? column.density
                                               : CloudColumnDensity(layer, column, altitude)) *
                            march.extinction * dt / Number(2 * kCloudColumnPoints);
                step_depth += depths[k];
            }
            // The free path -ln(1 - jitter (1 - e^-step_depth)) in optical depth, through the
            // parts.
            Number path = -log(1.0 - jitter * (1.0 - exp(-step_depth)));
            Number before = 0.0;
            Number fraction = 1.0;
            int part = -1;
            int last = 0;
            for (int k = 0; k < 2 * kCloudColumnPoints; ++k) {
                if (part < 0 && depths[k] > 0.0 && path <= before + depths[k]) {
                    part = k;
                    fraction = (path - before) / depths[k];
                }
                if (depths[k] > 0.0) last = k;
                before += depths[k];
            }
            if (part < 0) part = last;  // rounding: the path ends at the step's last part
            t = start + (Number(part) + fraction) / Number(2 * kCloudColumnPoints) * dt;
            bool emitted_near = part < kCloudColumnPoints;
            CloudSample column = emitted_near == jittered_near ? s : mirror;
            Number altitude = CloudAltitude(layer, origin + view * t);
            // The step's mean density, so that sigma_s / sigma_t stays the albedo.
            s.density = step_depth / (march.extinction * dt);
            // Described by its half's sample (a level half, as the midpoint rule has it, with
            // the step's mean density) or by its half's column at the emission's height.
            described = column;
            described.density = s.density;
            Number density = level[emitted_near ? 0 : 1]
                                 ? 0.0
                                 : CloudColumnDensity(layer, column, altitude);
            if (density > 0.0) {
                described.density = density;
                described.cloud_fraction = (altitude - layer.base_altitude) / column.cloud_height;
                described.height_fraction = (altitude - layer.base_altitude) /
                                            (layer.top_altitude - layer.base_altitude);
            }
            source_scale = described.density > 0.0 ? s.density / described.density : 1.0;
        }
        Number extinction = s.density * march.extinction;
        for (int lit = 0; lit < (s.density > 0.0 ? 1 : 0); ++lit) {
            vec3 source = CloudSampleSource(atmosphere, transmittance_texture, irradiance_texture,
                                            layer, cloud_above, weather_map, shape_noise,
                                            detail_noise, sun_depth, scattering, march,
                                            lights, light_count, described,
                                            origin + view * t, view, refinement) *
                          source_scale;
            state.depth_weight += state.transmittance;
            state.weighted_depth += state.transmittance * t;
            Number before = state.transmittance;
            CloudIntegrateStep(source, extinction, dt, state.luminance, state.transmittance);
            CloudRecordCrossings(state, start, dt, before);
        }
    }
    // Opaque from here on: no Sun disk shining through.
    if (state.transmittance < march.min_transmittance) state.transmittance = 0.0;
}

// The clouds as seen through the atmosphere between them and the camera (F16 §5.9.1): the
// in-scattering L_ap and transmittance T_ap of the segment from the camera to the mean depth,
// ray marched with `steps` steps (the aerial-perspective LUT ends at its range, and clouds lie
// far beyond it), applied once: L = T_ap L_cloud + (1 - T_cloud) L_ap, which replaces the
// share of the sky's in-scattering in front of the clouds that they hide. The caller composites
// (L, T_cloud) over the sky as L + T_cloud sky. `camera`, `view` and `lights` are in the
// atmosphere's frame.
vec4 CloudApplyAerialPerspective(IN(AtmosphereParameters) atmosphere,
                                 IN(TransmittanceTexture) transmittance_texture,
                                 IN(MultipleScatteringTexture) multiple_scattering_texture,
                                 IN(IrradianceTexture) irradiance_texture,
                                 IN(LightSet) lights, vec3 camera, Number camera_altitude,
                                 vec3 view, IN(CloudMarchState) state, int steps) {
    Number depth = CloudMeanDepth(state);
    if (!(depth > 0.0)) return vec4(state.luminance, state.transmittance);
    ScatteringResult segment = IntegrateScatteredLuminance(
        atmosphere, transmittance_texture, multiple_scattering_texture, irradiance_texture,
        lights, camera, camera_altitude, view, 0.0, depth, steps, false);
    return vec4(
        segment.transmittance * state.luminance + (1.0 - state.transmittance) * segment.luminance,
        state.transmittance);
}

// ---------------------------------------------------------------------------------------------
// The ground shadow map (F16 §5.9): a square of `extent` km around the camera's ground point,
// east/north in the camera's tangent plane mapped onto the sphere as arc lengths. Positions are
// planet-centred (km) in the frame of `camera`.

void CloudShadowMapAxes(vec3 camera, OUT(vec3) up, OUT(vec3) east, OUT(vec3) north) {
    up = normalize(camera);
    vec3 e = cross(vec3(0.0, 0.0, 1.0), up);
    east = length(e) > 1e-6 ? normalize(e) : vec3(1.0, 0.0, 0.0);
    north = cross(up, east);
}

// The ground point at shadow-map coordinate uv in [0, 1]^2.
vec3 CloudShadowMapGroundPoint(vec3 camera, Number bottom_radius, Number extent, vec2 uv) {
    vec3 up;
    vec3 east;
    vec3 north;
    CloudShadowMapAxes(camera, up, east, north);
    vec2 offset = (uv - vec2(0.5)) * extent;
    Number arc = length(offset);
    Number theta = arc / bottom_radius;
    vec3 along = arc > 0.0 ? (east * offset.x + north * offset.y) / arc : east;
    return bottom_radius * (up * cos(theta) + along * sin(theta));
}

// Its inverse: the shadow-map coordinate of the ground point at `ground` (outside [0, 1]^2 when
// the map does not reach it). The arc is atan(sin, cos) of the tangential components, which keep
// metres in float where acos of the cosine would not.
vec2 CloudShadowMapUv(vec3 camera, Number bottom_radius, Number extent, vec3 ground) {
    vec3 up;
    vec3 east;
    vec3 north;
    CloudShadowMapAxes(camera, up, east, north);
    vec3 n = normalize(ground);
    vec2 tangent = vec2(dot(n, east), dot(n, north));
    Number s = length(tangent);
    Number arc = atan(s, dot(n, up)) * bottom_radius;
    vec2 offset = s > 0.0 ? tangent * (arc / s) : vec2(0.0);
    return offset / extent + vec2(0.5);
}

// The part [x, y] (km) of a ray from radius r (zenith cosine mu) below the clouds' base, the
// sphere of radius `base_radius`; y < x when it has none.
vec2 CloudBelowBase(Number r, Number mu, Number base_radius) {
    Number discriminant = r * r * (mu * mu - 1.0) + base_radius * base_radius;
    if (!(discriminant > 0.0)) return vec2(0.0, -1.0);
    Number root = sqrt(discriminant);
    return vec2(max(-r * mu - root, 0.0), -r * mu + root);
}

// Light shafts (issue 15 §4): the change of the light scattered once toward the camera along
// `view` in the air below the lowest cloud base (`base` km), where the shadow map gives each
// point its own share of the light through the clouds instead of the map's mean, which the LUTs
// and the composite assume there (LightSet.cloud_direct):
//   sum over the lights of  integral T(camera, x) sigma_s p(nu) E T_light(x) (S(x) - mean) dt
// over the part of [0, t_limit] km below the base. S(x) is the map at the ground point that the
// map's light (`map_light`, its direction in this frame) reaches through x; every cloud is above
// x, so the light's path from there through x meets the same clouds. Like the ground's shadow,
// the map's light stands for every light, and it fades out at the map's edge.
// `steps` samples, each shifted by `jitter` in [0, 1) of its stratum: an unbiased estimate
// whatever the jitter's value where the points the samples are lit from lie within a texel of
// the map of each other. Farther apart they would alias the map's pattern into noise: there the
// map's value fades into its mean (no correction) by 2 texels apart. Looking along the light
// (crepuscular and anticrepuscular rays) those points barely move and a whole ray keeps its
// shafts; across it, a long ray keeps those near the camera. Returns the correction accumulated
// up to a quarter, half, three quarters of the samples' strata and the whole, each with the
// distance it reaches (km): the part in front of a host's geometry interpolates between them.
struct CloudShaftProfile {
    vec4 part[4];  // (rgb: correction from the camera to t, a: t km)
};

CloudShaftProfile CloudAirShadowCorrection(IN(AtmosphereParameters) atmosphere,
                                           IN(TransmittanceTexture) transmittance_texture,
                                           IN(CloudShadowMapTexture) shadow_map,
                                           IN(LightSet) lights, vec3 map_light, Number base,
                                           Number extent, vec3 camera, Number camera_altitude,
                                           vec3 view, Number t_limit, int steps, Number jitter) {
    CloudShaftProfile profile;
    for (int k = 0; k < 4; ++k) profile.part[k] = vec4(0.0);
    Number R = atmosphere.bottom_radius;
    Number r = length(camera);
    Number mu = dot(camera, view) / r;
    vec2 below = CloudBelowBase(r, mu, R + base);
    if (!(below.y > below.x) || !(base > 0.0)) return profile;
    Number t_begin = below.x;
    Number t_end = min(below.y, t_limit);
    Number t_ground = RaySphereDistance(r, mu, camera_altitude, R);
    if (t_ground >= 0.0) t_end = min(t_end, t_ground);
    // Beyond the map's half diagonal (plus the light's slant from the base) nothing is shadowed.
    t_end = min(t_end, t_begin + extent + 4.0 * base);
    if (!(t_end > t_begin)) return profile;

    Number span = t_end - t_begin;
    Number c0 = camera_altitude * (2.0 * R + camera_altitude);
    Number b0 = r * mu;
    // The air's optical depth from the camera to where the shafts begin (a camera above the
    // base looking down), 8 midpoints, then on to each sample.
    vec3 optical_depth = vec3(0.0);
    for (int j = 0; j < (t_begin > 0.0 ? 8 : 0); ++j) {
        Number r_j;
        Number altitude = AltitudeAlongRay(R, c0, b0, t_begin * (Number(j) + 0.5) / 8.0, r_j);
        optical_depth += SampleMedium(atmosphere, altitude).extinction * (t_begin / 8.0);
    }
    Number t_previous = t_begin;
    // Each light's phase functions: the same for every point of the ray.
    vec2 phase[kMaxLights];
    for (int l = 0; l < lights.count; ++l) {
        Number nu = dot(view, lights.light[l].direction);
        phase[l] = vec2(RayleighPhase(nu), CornetteShanksPhase(atmosphere.mie_g, nu));
    }
    // How fast the samples' ground points cross the map: km of map per km of ray (flat ground:
    // moving dt along the ray moves the point the light lights it from by view - light
    // dt_up / light_up).
    Number texel = extent / Number(TextureSize(shadow_map).x);
    vec3 up = camera / r;
    Number map_speed =
        length(view - map_light * (dot(view, up) / max(dot(map_light, up), 0.05)));
    // Samples evenly spaced (warp 1) while they stay within half a texel of the map of each
    // other, then denser near the camera (t ~ u^warp, up to u^2 for rays many texels long),
    // where a shaft is widest on screen.
    Number warp = clamp(1.0 + log2(max(span * map_speed / (0.5 * texel * Number(steps)), 1e-6)),
                        1.0, 2.0);
    vec3 correction = vec3(0.0);
    for (int i = 0; i < steps; ++i) {
        // What the strata before this one gathered, at a quarter, half, three quarters.
        for (int k = 1; k < 4; ++k) {
            if (i == (k * steps) / 4) {
                Number boundary = max(Number(i) / Number(steps), 1e-6);
                profile.part[k - 1] = vec4(correction, t_begin + span * pow(boundary, warp));
            }
        }
        Number u = max((Number(i) + jitter) / Number(steps), 1e-6);  // GLSL's pow(0, y): undefined
        Number t = t_begin + span * pow(u, warp);
        Number dt = span * warp * pow(u, warp - 1.0) / Number(steps);  // dt/du du: the weight
        vec3 p = camera + view * t;
        Number r_p;
        Number altitude = AltitudeAlongRay(R, c0, b0, t, r_p);
        MediumSample s = SampleMedium(atmosphere, altitude);
        // The extinction from the previous sample to this one, taken at this one.
        optical_depth += s.extinction * (t - t_previous);
        t_previous = t;
        // The ground point lit through p by the map's light (r_p^2 - R^2 = altitude (r_p + R)),
        // and the map there.
        Number pl = dot(p, map_light);
        Number d = pl * pl - altitude * (r_p + R);
        if (!(pl > 0.0 && d >= 0.0)) continue;
        vec3 ground = p - map_light * (pl - sqrt(d));
        vec2 uv = CloudShadowMapUv(camera, R, extent, ground);
        Number weight = CloudShadowMapEdgeWeight(uv) *
                        clamp((2.0 * texel - dt * map_speed) / texel, 0.0, 1.0);
        if (!(weight > 0.0)) continue;
        Number shadow = SampleTexture2D(shadow_map, uv).r - lights.cloud_direct;
        vec3 scattered = vec3(0.0);
        for (int l = 0; l < lights.count; ++l) {
            vec3 light = lights.light[l].direction;
            vec3 phase_scattering =
                s.rayleigh_scattering * phase[l].x + s.mie_scattering * phase[l].y;
            scattered += LightIlluminanceAt(lights, l, p) * phase_scattering *
                         GetTransmittanceToSun(atmosphere, transmittance_texture, r_p,
                                               dot(p, light) / r_p);
        }
        correction += exp(-optical_depth) * scattered * (weight * shadow * dt);
    }
    profile.part[3] = vec4(correction, t_end);
    return profile;
}

// Optical depth of one layer along [interval.x, interval.y] km of the ray from `origin` along
// `direction`, the density at the midpoints of `steps` equal steps (0 for an empty interval).
Number CloudRayDepth(IN(CloudLayerParameters) layer, IN(WeatherTexture) weather_map,
                     IN(CloudNoiseTexture) shape_noise, IN(CloudNoiseTexture) detail_noise,
                     IN(CloudMarchParameters) march, vec3 origin, vec3 direction, vec2 interval,
                     int steps) {
    Number length_km = interval.y - interval.x;
    if (!(length_km > 0.0)) return 0.0;
    Number dt = length_km / Number(steps);
    Number optical_depth = 0.0;
    for (int j = 0; j < steps; ++j) {
        vec3 p = origin + direction * (interval.x + (Number(j) + 0.5) * dt);
        optical_depth +=
            SampleCloudDensity(layer, weather_map, shape_noise, detail_noise, p).density *
            march.extinction * dt;
    }
    return optical_depth;
}

// Optical depth of one layer from `origin` (cloud frame, `altitude` km above the ground, exact)
// toward the light, with `steps` samples of the density in the layer: the shadow map's march
// from the ground (no lighting), and the host's sunlight at the aircraft.
Number CloudLayerShadowDepth(IN(CloudLayerParameters) layer, IN(WeatherTexture) weather_map,
                             IN(CloudNoiseTexture) shape_noise, IN(CloudNoiseTexture) detail_noise,
                             IN(CloudMarchParameters) march, vec3 origin, Number altitude,
                             vec3 light_direction, int steps) {
    Number r = length(origin);
    Number mu = dot(origin, light_direction) / r;
    vec2 interval = CloudLayerInterval(layer, r, mu, altitude, march.max_distance);
    return CloudRayDepth(layer, weather_map, shape_noise, detail_noise, march, origin,
                         light_direction, interval, steps);
}

// ---------------------------------------------------------------------------------------------
// The clouds as the air and the ground beneath them see them (F16 §5.9.2, LightSet's cloud_*):
// marched over the upper hemisphere from the ground below the camera and averaged. Direction i
// of n_sqrt^2 about `up`: equal solid angles, cos(theta) and phi each in n_sqrt strata, taken
// at the strata's centres (the same directions every frame, so the averages do not flicker).
// The cosines sum to n_sqrt^2 / 2, so a mean weighted by the cosine is 2 mean(L cos theta).
Number CloudSkyShadeCosine(int i, int n_sqrt) {
    return (Number(i / n_sqrt) + 0.5) / Number(n_sqrt);
}

vec3 CloudSkyShadeDirection(int i, int n_sqrt, vec3 up) {
    vec3 x = SkyViewFrameX(up, vec3(1.0, 0.0, 0.0));
    vec3 y = cross(up, x);
    int row = i / n_sqrt;
    Number cos_theta = CloudSkyShadeCosine(i, n_sqrt);
    Number phi = 2.0 * kPi * (Number(i - row * n_sqrt) + 0.5) / Number(n_sqrt);
    Number sin_theta = SafeSqrt(1.0 - cos_theta * cos_theta);
    return up * cos_theta + x * (sin_theta * cos(phi)) + y * (sin_theta * sin(phi));
}
