// The clouds in front of a host's geometry at each pixel of a listed cell (CloudsToGeometry);
// T = -1 (not marched) where the pixel shows sky.
layout(location = 0) out vec4 out_clouds;

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    float distance_km = SceneDistanceKm(pixel);
    out_clouds = distance_km > 0.0 ? CloudsToGeometry(pixel, distance_km)
                                   : vec4(0.0, 0.0, 0.0, -1.0);
}
