// The cloud passes' uniform block and textures, after atmosphere/interface.glsl. One C++ mirror
// in sky/src/gl/cloud_uniforms.h, checked with static_assert against std140 and by
// tests/sky/gl_bindings_gl_test.cpp against the linked programs; units, bindings and
// kCloudMaxLayers: bindings.glsl.

layout(std140, binding = kCloudBlockBinding) uniform CloudBlock {
    CloudLayerParameters cloud_layers[kCloudMaxLayers];
    CloudScatteringParameters cloud_scattering;
    CloudMarchParameters cloud_march;
    LightSet cloud_lights;               // the lights with directions in the weather frame
    vec4 weather_from_frame[3];          // rotation, columns (xyz)
    vec4 previous_view_from_frame[3];    // rotation: this frame -> the previous camera's view
    // The previous camera minus this one, in this frame: computed in double on the CPU, since
    // camera_km is thousands of km from the planet's centre, where a float's step is 0.5 m.
    vec3 previous_camera_offset_km;
    float previous_tan_half_fov;
    ivec2 trace_size;                    // cells of the trace, each block x block pixels
    ivec2 trace_offset;                  // the pixel of each block traced this frame
    int block;
    int cloud_layer_count;
    int cloud_light_count;
    int history_valid;
    float frame_jitter;                  // this frame's shift of the samples along the rays
    float history_weight;
    float previous_aspect;
    int cloud_aerial_perspective_steps;
    float shadow_map_extent_km;
    int shadow_map_size;
    int shadow_map_steps;
    int sky_shade_size;               // directions per side of the sky_shade passes
    // The layers in the order a ray from the camera meets them (CloudLayerOrder on the CPU: the
    // camera's layer and those below it downward, then those above upward). The same for every
    // pixel, so the weather maps are indexed by a dynamically uniform index, as GLSL requires
    // (CloudWeatherMap, below).
    ivec4 cloud_layer_order;
    ivec4 cloud_ground_layer_order;  // the same from the ground (the sky shade's origin)
};

layout(binding = kShapeNoiseUnit) uniform sampler3D shape_noise;
layout(binding = kDetailNoiseUnit) uniform sampler3D detail_noise;
layout(binding = kWeatherMapsUnit) uniform sampler2D weather_maps[kCloudMaxLayers];
// Layer i's weather map as the march takes it (WeatherTexture, definitions.glsl).
#ifdef CLOUD_COMPUTE_STAGE
#define CloudWeatherMap(i) (i)
vec4 SampleRepeat2D(int map, vec2 uv) {
    if (map == 0) return textureLod(weather_maps[0], uv, 0.0);
    if (map == 1) return textureLod(weather_maps[1], uv, 0.0);
    if (map == 2) return textureLod(weather_maps[2], uv, 0.0);
    return textureLod(weather_maps[3], uv, 0.0);
}
#else
#define CloudWeatherMap(i) weather_maps[i]
#endif
// cloud_trace: rgb luminance, a transmittance; cloud_trace_depth: r, mean depth (km), -1 for
// none, g where the ray enters cloud (km); cloud_trace_profile: where its transmittance fell below
// CloudProfileThreshold(0..3) (km, -1 for never); cloud_shadow_map: r, transmittance to the
// light; cloud_ground_shadow: rgb, ground_shadow.frag's values, one per trace cell;
// cloud_air_shadow: light_shafts.frag's CloudShaftProfile, one texture per part.
layout(binding = kCloudTraceUnit) uniform sampler2D cloud_trace;
layout(binding = kCloudTraceDepthUnit) uniform sampler2D cloud_trace_depth;
layout(binding = kCloudTraceProfileUnit) uniform sampler2D cloud_trace_profile;
// (L, T) of the clouds in front of a host's geometry at the pixels marched on their own rays
// (clouds/geometry_march.frag), T = -1 elsewhere; full resolution.
layout(binding = kCloudGeometryUnit) uniform sampler2D cloud_geometry;
layout(binding = kCloudHistoryUnit) uniform sampler2D cloud_history;
layout(binding = kCloudShadowMapUnit) uniform sampler2D cloud_shadow_map;
// r: the optical depth toward the main light beyond the shadow march (CloudFarSunDepth).
layout(binding = kCloudSunDepthUnit) uniform sampler3D cloud_sun_depth;
layout(binding = kCloudGroundShadowUnit) uniform sampler2D cloud_ground_shadow;
layout(binding = kCloudAirShadowUnit) uniform sampler2D cloud_air_shadow[4];

// The clouds' mean depth (km, -1 for none) at a full-resolution pixel: its trace cell's own, the
// depth to reproject with and to test against a host's geometry (a bilinear one would mix clouds
// with clear sky at every edge).
float CloudTraceDepth(ivec2 pixel) {
    return texelFetch(cloud_trace_depth, min(pixel / block, trace_size - 1), 0).r;
}

// A trace cell's ray: the clouds' mean depth and entry (km), the transmittance's profile and
// the transmittance.
struct CloudCellRay {
    vec2 depth;
    vec4 crossing;
    float transmittance;
};

CloudCellRay CloudCellRayAt(ivec2 cell) {
    CloudCellRay ray;
    ray.depth = texelFetch(cloud_trace_depth, cell, 0).rg;
    ray.crossing = texelFetch(cloud_trace_profile, cell, 0);
    ray.transmittance = texelFetch(cloud_trace, cell, 0).a;
    return ray;
}

// The share of the clouds' opacity in front of a host's geometry `distance` km along a trace
// cell's ray (CloudOpacityShareInFront over its profile and transmittance): 0 for geometry in
// front of the clouds, 1 behind them, and in between inside them (fog around the camera, a cloud
// the geometry pierces).
float CloudCellShareInFront(CloudCellRay ray, float distance) {
    if (!(ray.depth.r > 0.0)) return 0.0;
    return CloudOpacityShareInFront(ray.depth.g, ray.depth.r, ray.crossing, ray.transmittance,
                                    distance);
}

// The change of our own ground's luminance by the clouds' shadow at a full-resolution pixel whose
// ray meets the ground: ground_shadow.frag's values, one per trace cell at its centre, filtered.
vec3 CloudGroundShadow(ivec2 pixel) {
    vec2 uv = (vec2(pixel) + 0.5) / (float(block) * vec2(trace_size));
    return texture(cloud_ground_shadow, uv).rgb;
}

// The light shafts at a full-resolution pixel: light_shafts.frag's values, one per cell of
// kCloudLightShaftCell x kCloudLightShaftCell trace cells at its centre, filtered: the whole ray.
vec2 CloudLightShaftUv(ivec2 pixel) {
    vec2 cells = vec2(textureSize(cloud_air_shadow[0], 0));
    return (vec2(pixel) + 0.5) / (float(kCloudLightShaftCell * block) * cells);
}

vec3 CloudLightShafts(ivec2 pixel) {
    if (!(cloud_march.light_shaft_steps >= 1.0)) return vec3(0.0);  // the pass did not run
    return texture(cloud_air_shadow[3], CloudLightShaftUv(pixel)).rgb;
}

// ...and up to `distance` km along `view` (a host's geometry there): piecewise linear between
// where the ray goes below the base and the profile's parts.
vec3 CloudLightShaftsTo(ivec2 pixel, vec3 view, float distance) {
    if (!(cloud_march.light_shaft_steps >= 1.0)) return vec3(0.0);
    float r = length(camera_km);
    vec2 below = CloudBelowBase(r, dot(camera_km, view) / r,
                                atmosphere.bottom_radius + lights.cloud_base);
    if (!(below.y > below.x)) return vec3(0.0);
    vec2 uv = CloudLightShaftUv(pixel);
    vec4 previous = vec4(0.0, 0.0, 0.0, below.x);
    for (int k = 0; k < 4; ++k) {
        vec4 part = texture(cloud_air_shadow[k], uv);
        if (distance <= part.a) {
            float f = clamp((distance - previous.a) / max(part.a - previous.a, 1e-6), 0.0, 1.0);
            return mix(previous.rgb, part.rgb, f);
        }
        previous = part;
    }
    return previous.rgb;
}

mat3 WeatherFromFrame() {
    return mat3(weather_from_frame[0].xyz, weather_from_frame[1].xyz, weather_from_frame[2].xyz);
}

// Marches every layer, in `order`, along `direction` from `origin` (both in the cloud frame;
// `altitude` km above the ground, exact) up to `distance` km with `march`'s steps: the clouds
// alone, front to back.
CloudMarchState MarchCloudLayers(vec3 origin, float altitude, vec3 direction, float distance,
                                 float jitter, ivec4 order, CloudMarchParameters march) {
    float r = length(origin);
    float mu = dot(origin, direction) / r;
    CloudMarchState state = CloudMarchStart();
    for (int k = 0; k < cloud_layer_count; ++k) {
        int i = order[k];
        vec2 interval = CloudLayerInterval(cloud_layers[i], r, mu, altitude, march.max_distance);
        interval.y = min(interval.y, distance);
        MarchCloudLayer(atmosphere, transmittance_texture, irradiance_texture, cloud_layers[i],
                        cloud_layers[min(i + 1, cloud_layer_count - 1)], CloudWeatherMap(i),
                        shape_noise, detail_noise, cloud_sun_depth, cloud_scattering, march,
                        cloud_lights, cloud_light_count, origin, direction, interval, jitter,
                        state);
    }
    return state;
}

// The clouds along `view` (this frame's world direction) from the camera up to `distance` km
// (a host's geometry; 1e9 for the whole ray), with the aerial perspective at their mean depth.
// Returns (L, T), and the march's state (CloudMeanDepth: the mean depth in km, -1 where no cloud
// was met; the transmittance's profile).
vec4 TraceClouds(vec3 view, float distance, float jitter, CloudMarchParameters march,
                 out CloudMarchState state) {
    mat3 to_weather = WeatherFromFrame();
    state = MarchCloudLayers(to_weather * camera_km, camera_altitude_km, to_weather * view,
                             distance, jitter, cloud_layer_order, march);
    return CloudApplyAerialPerspective(atmosphere, transmittance_texture,
                                       multiple_scattering_texture,
                                       irradiance_texture, lights, camera_km,
                                       camera_altitude_km, view, state,
                                       cloud_aerial_perspective_steps);
}

// The cloud trace (H16 §6.1; trace.frag and trace.comp, CloudSettings::pass_stage): one cell
// per block x block pixels, each marching the ray through the pixel of its block chosen for this
// frame (trace_offset); with block 1 every pixel is traced. `cloud` is (L, T) of the clouds with
// aerial perspective applied, `depth` their mean depth and where the ray enters cloud (km), and
// `profile` the transmittance's profile (CloudMarchState.crossing).
struct CloudTraceCell {
    vec4 cloud;
    vec4 depth;
    vec4 profile;
};

CloudTraceCell TraceCloudCell(ivec2 cell) {
    ivec2 pixel = cell * block + trace_offset;
    CloudMarchState state;
    CloudTraceCell result;
    result.cloud = TraceClouds(CameraDirection(vec2(pixel), vec2(output_size)), 1e9,
                               CloudJitter(pixel, frame_jitter), cloud_march, state);
    result.depth = vec4(CloudMeanDepth(state), state.entry, 0.0, 0.0);
    result.profile = state.crossing;
    return result;
}

// The previous frame's texture coordinate of the point at `depth` km along `view` (the
// direction alone when depth <= 0); false when it was outside the previous view.
bool CloudReproject(vec3 view, float depth, out vec2 uv) {
    mat3 previous_view = mat3(previous_view_from_frame[0].xyz, previous_view_from_frame[1].xyz,
                              previous_view_from_frame[2].xyz);
    vec3 v = depth > 0.0 ? previous_view * (view * depth - previous_camera_offset_km)
                         : previous_view * view;
    if (!(v.z < 0.0)) return false;
    vec2 ndc = vec2(v.x / (-v.z * previous_tan_half_fov * previous_aspect),
                    v.y / (-v.z * previous_tan_half_fov));
    uv = 0.5 * ndc + 0.5;
    return all(greaterThanEqual(uv, vec2(0.0))) && all(lessThanEqual(uv, vec2(1.0)));
}

// The clouds at a full-resolution pixel from this frame's trace and the previous frames (H16 §6.1,
// F16 §5.5.3; reconstruct.frag and .comp, in the trace's stage). A pixel traced this frame takes
// its new value, averaged with its reprojected history (history_weight) so the per-frame jitter
// integrates over time; any other pixel takes its reprojected history. Reprojection follows the
// cloud: the point at the clouds' mean depth (or the direction alone, for clear sky) is projected
// into the previous camera, which handles rotation and flight at any speed. Where there is no
// history (first frame, a cut, a point outside the previous view), the pixel falls back to this
// frame's trace, upsampled. There is no depth test for disocclusion: a cloud's mean depth jumps
// between neighbouring pixels at every edge and with every jitter, so such a test threw away good
// history (measured: a static view never converged), while what it would catch, one cloud sliding
// behind another, changes over many frames at flight speeds and is refreshed within block^2 frames.
vec4 ReconstructCloudPixel(ivec2 pixel) {
    ivec2 cell = pixel / block;
    bool traced = all(equal(pixel - cell * block, trace_offset));
    // This frame's trace around the pixel: the cell's own value, or the four nearest cells
    // (the trace is sampled at pixel cell * block + trace_offset).
    vec2 trace_uv = (vec2(pixel - trace_offset) / float(block) + 0.5) / vec2(trace_size);
    vec4 current =
        traced ? texelFetch(cloud_trace, cell, 0) : textureLod(cloud_trace, trace_uv, 0.0);
    float depth = CloudTraceDepth(pixel);

    vec3 view = CameraDirection(vec2(pixel), vec2(output_size));
    vec2 uv;
    bool valid = history_valid != 0 && CloudReproject(view, depth, uv);
    vec4 history = valid ? textureLod(cloud_history, uv, 0.0) : vec4(0.0);
    if (traced) return valid ? mix(current, history, history_weight) : current;
    return valid ? history : current;
}

// What the clouds do to the light beneath them, one direction (sky_shade_trace.frag and .comp,
// in the trace's stage): (L, T) of the layers seen from the ground below the camera along
// CloudSkyShadeDirection `texel` (sky_shade_size^2 of the upper hemisphere, equal solid
// angles), nothing in front. sky_shade.comp averages them.
vec4 TraceSkyShadeDirection(ivec2 texel) {
    vec3 up = normalize(camera_km);
    mat3 to_weather = WeatherFromFrame();
    vec3 direction =
        CloudSkyShadeDirection(texel.y * sky_shade_size + texel.x, sky_shade_size, up);
    CloudMarchState state = MarchCloudLayers(to_weather * (up * atmosphere.bottom_radius), 0.0,
                                             to_weather * direction, 1e9, 0.5,
                                             cloud_ground_layer_order, cloud_march);
    return vec4(state.luminance, state.transmittance);
}

// A host's geometry `distance` km along a full-resolution pixel's ray, and the clouds in front of
// it. One trace ray speaks for each cell of block x block pixels: the clouds' share of opacity in
// front of the geometry is its cell's (CloudCellShareInFront). Where the geometry's edge meets a
// cloud's (a peak rising out of a deck, a tower's top in fog), that one ray would draw the cloud
// over all of the cell's pixels or none, in blocks that change with the traced pixel (halos,
// combs): there the cells around the pixel disagree, and the pixel's own ray is marched
// (clouds/geometry_list.frag lists the cells holding such pixels, clouds/geometry_march.* march
// them). The disagreement is the spread of the shares of the pixel's cell and its four
// neighbours times the opacity of the clouds along the pixel's whole ray (where that is small,
// the share hardly matters); the marched clouds take over from the cell's between spreads of
// kCloudShareSpread / 2 and 3 kCloudShareSpread / 2, so that a pixel whose spread lies near the
// limit does not flip between the two (a depth differing in its last bits did).
const float kCloudShareSpread = 0.1;

// The rays of a cell and its four neighbours (the same for all its pixels).
struct CloudCellNeighbourhood {
    CloudCellRay ray[5];
};

CloudCellNeighbourhood CloudCellNeighbourhoodAt(ivec2 cell) {
    const ivec2 kOffsets[5] =
        ivec2[5](ivec2(0, 0), ivec2(-1, 0), ivec2(1, 0), ivec2(0, -1), ivec2(0, 1));
    CloudCellNeighbourhood n;
    for (int k = 0; k < 5; ++k) {
        n.ray[k] = CloudCellRayAt(clamp(cell + kOffsets[k], ivec2(0), trace_size - 1));
    }
    return n;
}

// The weight of the pixel's own ray (0: its cell's share alone).
float CloudOwnRayWeight(CloudCellNeighbourhood cells, ivec2 pixel, float distance) {
    float opacity = 1.0 - texelFetch(cloud_history, pixel, 0).a;
    float least = 1.0, most = 0.0;
    for (int k = 0; k < 5; ++k) {
        float s = CloudCellShareInFront(cells.ray[k], distance);
        least = min(least, s);
        most = max(most, s);
    }
    return smoothstep(0.5 * kCloudShareSpread, 1.5 * kCloudShareSpread, (most - least) * opacity);
}

// `clouds`, the pixel's clouds along the whole ray, times its cell's share (cells.ray[0]).
vec4 CloudsByShare(CloudCellRay cell, float distance, vec4 clouds) {
    float share = CloudCellShareInFront(cell, distance);
    return vec4(clouds.rgb * share, 1.0 - (1.0 - clouds.a) * share);
}

// The pixel's own ray marched up to the geometry, (L, T) premultiplied, this frame's jitter
// placing its samples, with a quarter of the trace's shortest step: its result is not averaged
// over frames like the trace's (one in 25 geometry pixels where a peak leaves a deck's top was
// 0.05-0.1 off in transmittance with the trace's steps); mixed with CloudsByShare by the weight.
vec4 CloudsToGeometry(ivec2 pixel, float distance) {
    CloudCellNeighbourhood cells = CloudCellNeighbourhoodAt(min(pixel / block, trace_size - 1));
    vec4 by_share = CloudsByShare(cells.ray[0], distance, texelFetch(cloud_history, pixel, 0));
    float weight = CloudOwnRayWeight(cells, pixel, distance);
    if (!(weight > 0.0)) return by_share;
    CloudMarchParameters march = cloud_march;
    march.min_step *= 0.25;
    CloudMarchState state;
    vec4 own = TraceClouds(CameraDirection(vec2(pixel), vec2(output_size)), distance,
                           CloudJitter(pixel, frame_jitter), march, state);
    return mix(by_share, own, weight);
}

// The clouds in front of the geometry, (L, T) premultiplied: those geometry_march.frag found for
// the pixel, or `clouds` times its cell's share.
vec4 CloudsInFrontOf(ivec2 pixel, float distance, vec4 clouds) {
    vec4 marched = texelFetch(cloud_geometry, pixel, 0);
    if (marched.a >= 0.0) return marched;
    return CloudsByShare(CloudCellRayAt(min(pixel / block, trace_size - 1)), distance, clouds);
}

// The clouds' shadow on the ground the atmosphere drew (F16 §5.9), as a change of what the
// camera sees along `view`: the ground's direct light was dimmed by the clouds' mean
// transmittance toward the light (LightSet.cloud_direct); where the shadow map reaches, the
// local transmittance replaces it (faded out over the outer 5 % of the map on each side, so
// its edge does not show). Zero where the ray misses the ground.
vec3 GroundShadowCorrection(vec3 view) {
    float r = length(camera_km);
    float mu = dot(camera_km, view) / r;
    float t = RaySphereDistance(r, mu, camera_altitude_km, atmosphere.bottom_radius);
    if (!(t >= 0.0 && lights.cloud_base > 0.0)) return vec3(0.0);
    vec3 ground = camera_km + view * t;
    vec2 uv = CloudShadowMapUv(camera_km, atmosphere.bottom_radius, shadow_map_extent_km, ground);
    float weight = CloudShadowMapEdgeWeight(uv);
    float shadow = texture(cloud_shadow_map, uv).r;
    vec3 n = normalize(ground);
    vec3 direct = vec3(0.0);
    for (int l = 0; l < lights.count; ++l) {
        float mu_l = dot(n, lights.light[l].direction);
        direct += lights.light[l].illuminance * max(mu_l, 0.0) *
                  GetTransmittanceToSun(atmosphere, transmittance_texture,
                                        atmosphere.bottom_radius, mu_l);
    }
    return weight * (shadow - lights.cloud_direct) * direct * atmosphere.ground_albedo / kPi *
           TransmittanceToGround(atmosphere, transmittance_texture, camera_km,
                                 camera_altitude_km, view, t);
}

// Light shafts along `view` (CloudAirShadowCorrection): the air below the clouds lit where the
// shadow map lets the main light through, shaded where it does not. `jitter` places the samples.
CloudShaftProfile CloudAirShadow(vec3 view, float jitter) {
    if (!(cloud_march.light_shaft_steps >= 1.0) || cloud_light_count == 0) {
        CloudShaftProfile none;
        for (int k = 0; k < 4; ++k) none.part[k] = vec4(0.0);
        return none;
    }
    vec3 map_light = transpose(WeatherFromFrame()) * cloud_lights.light[0].direction;
    return CloudAirShadowCorrection(atmosphere, transmittance_texture, cloud_shadow_map, lights,
                                    map_light, lights.cloud_base, shadow_map_extent_km, camera_km,
                                    camera_altitude_km, view, 1e9,
                                    int(cloud_march.light_shaft_steps), jitter);
}

// The clouds' shadow on our own ground at trace cell `texel`'s centre (ground_shadow.frag and
// .comp, in the trace's stage): the shadow map's texels are hundreds of metres wide, so the
// composite interpolates these instead of working it out for every pixel (which cost llvmpipe
// 19 ms at 720p).
vec3 GroundShadowCell(ivec2 texel) {
    vec2 pixel = vec2(texel) * float(block) + 0.5 * float(block - 1);
    return GroundShadowCorrection(CameraDirection(pixel, vec2(output_size)));
}

// The light shafts (CloudAirShadow) at the centre of shaft cell `texel`, kCloudLightShaftCell^2
// trace cells (light_shafts.frag and .comp, in the trace's stage), which the composite
// interpolates (CloudLightShafts, CloudLightShaftsTo): they vary over the shadow map's texels,
// hundreds of metres, and cost llvmpipe 44 ms at 720p worked out per trace cell. The samples
// keep their place from frame to frame (nothing here averages a moving jitter away).
CloudShaftProfile LightShaftCell(ivec2 texel) {
    int cell = kCloudLightShaftCell * block;
    vec2 pixel = vec2(texel) * float(cell) + 0.5 * float(cell - 1);
    return CloudAirShadow(CameraDirection(pixel, vec2(output_size)), CloudJitter(texel, 0.0));
}
