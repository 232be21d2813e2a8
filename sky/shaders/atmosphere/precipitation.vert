// Rain or snow around the camera (AtmospherePasses::DrawPrecipitation): each drop a streak, the
// path it falls through during the exposure, in a box of drops around the camera that wraps,
// so the drops stay put in the weather's frame and fall with their speed and the wind. Drawn
// as two triangles a pixel wide, over the frame (blended: frame = L alpha + (1 - alpha) frame).
// A drop of diameter D at a distance where a pixel spans f covers a pixel of its streak for
// 1 / (streak's length in pixels) of the exposure and D / f of its width and length, so its
// streak carries its projected area (pi / 4) (D / f)^2 in all, whatever the exposure: along a
// ray the drops cover sigma / 2 per metre (sigma, the shaft's extinction, is twice their
// cross-section: the other half is diffraction, forward) out to the box's inscribed sphere.
layout(location = 0) flat out vec4 drop;            // rgb: alpha x luminance (cd/m^2), a: alpha
layout(location = 1) out float eye_depth;           // m along the view axis

uint PrecipitationHash(uint x) {
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

vec3 PrecipitationRandom(uint i) {
    return vec3(PrecipitationHash(3u * i), PrecipitationHash(3u * i + 1u),
                PrecipitationHash(3u * i + 2u)) /
           4294967296.0;
}

// The light around a drop under the clouds: the sky's mean radiance over the upper hemisphere
// (the clouds' shade: their light, and the clear sky through them), which a raindrop, a ball
// lens, shows over most of its face; a snowflake reflects the light on the ground's horizontal
// (albedo 0.9).
vec3 PrecipitationLuminance() {
    vec3 clear = vec3(0.0);
    for (int i = 0; i < lights.count; ++i) {
        clear += lights.light[i].illuminance *
                 GetGroundSkyIrradiance(irradiance_texture,
                                        dot(sky_view_up, lights.light[i].direction));
    }
    if (snow != 0) {
        return 0.9 * (clear * lights.cloud_ground_sky + kPi * lights.cloud_ground_luminance) / kPi;
    }
    return lights.cloud_luminance + lights.cloud_sky * clear / kPi;
}

void main() {
    const int kEnd[6] = int[](0, 0, 1, 0, 1, 1);
    const float kSide[6] = float[](-1.0, 1.0, 1.0, -1.0, 1.0, -1.0);
    uint id = uint(gl_VertexID) / 6u;
    int corner = gl_VertexID % 6;
    vec3 box = mod(PrecipitationRandom(id) * box_size + phase, box_size) - 0.5 * box_size;
    mat3 view_from_world = transpose(
        mat3(world_from_view[0].xyz, world_from_view[1].xyz, world_from_view[2].xyz));
    mat3 world_from_box_m =
        mat3(world_from_box[0].xyz, world_from_box[1].xyz, world_from_box[2].xyz);
    vec3 head = view_from_world * (world_from_box_m * box);
    vec3 tail = view_from_world * (world_from_box_m * (box - box_velocity * exposure_s));
    drop = vec4(0.0);
    eye_depth = 0.0;
    const float kNear = 0.1;  // m: a drop nearer the lens is out of focus, not drawn
    float altitude = 1000.0 * camera_altitude_km + dot(world_from_box_m * box, sky_view_up);
    // Out to the box's inscribed sphere, so every ray meets them for the same distance (the
    // cube's corners would show as a pattern), and not under the ground.
    if (head.z > -kNear || tail.z > -kNear || altitude < 0.0 ||
        length(box) > 0.5 * box_size) {
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0);  // clipped
        return;
    }
    vec2 scale = vec2(tan_half_fov * aspect, tan_half_fov);
    vec2 a = head.xy / (-head.z * scale);
    vec2 b = tail.xy / (-tail.z * scale);
    vec2 pixels = 0.5 * vec2(output_size);  // per NDC unit
    vec2 along = (b - a) * pixels;
    float length_px = length(along);
    vec2 direction = length_px > 1e-6 ? along / length_px : vec2(0.0, -1.0);
    float footprint = 0.5 * (-head.z - tail.z) * 2.0 * tan_half_fov / float(output_size.y);
    float size_px = diameter_m / footprint;
    // A pixel wide and long at least, or the drop's size when it is larger (near the lens).
    float width_px = max(size_px, 1.0);
    if (length_px < width_px) {
        b = a + direction * width_px / pixels;
        length_px = width_px;
    }
    vec2 across = vec2(-direction.y, direction.x) * 0.5 * width_px / pixels;
    gl_Position = vec4((kEnd[corner] == 0 ? a : b) + kSide[corner] * across, 0.0, 1.0);
    eye_depth = kEnd[corner] == 0 ? -head.z : -tail.z;
    // Its projected area, (pi / 4) size_px^2 pixels, spread over the quad.
    float alpha =
        min(0.25 * kPi * size_px * size_px / (width_px * length_px) * coverage_scale, 1.0);
    drop = vec4(alpha * PrecipitationLuminance(), alpha);
}
