// The environment's spherical harmonics (zenith/sky/environment.h: ProjectToSh's sums, on the
// GPU): one work group; each invocation sums L Y_lm dOmega over every kEnvironmentShGroupSize-th
// texel of the atlas environment.frag drew, then the group adds the partial sums up in shared
// memory. Writes coefficient i into environment_sh[i].rgb.
layout(local_size_x = kEnvironmentShGroupSize) in;
layout(binding = kEnvironmentImageUnit, rgba32f) uniform readonly image2D environment_atlas;
layout(std430, binding = kEnvironmentStorageBinding) buffer EnvironmentShStorage {
    vec4 environment_sh[9];
};
shared vec3 partial_sh[kEnvironmentShGroupSize * 9];

// CubeTexelSolidAngle's corner term.
float CubeCorner(float u, float v) { return atan(u * v, sqrt(1.0 + u * u + v * v)); }

void main() {
    int n = environment_size;
    uint self = gl_LocalInvocationID.x;
    vec3 sum[9];
    for (int i = 0; i < 9; ++i) sum[i] = vec3(0.0);
    for (int index = int(self); index < 6 * n * n; index += kEnvironmentShGroupSize) {
        ivec2 texel = ivec2(index % n, index / n);
        vec3 d = EnvironmentDirection(texel);
        int y = texel.y % n;
        float u0 = 2.0 * float(texel.x) / float(n) - 1.0, u1 = u0 + 2.0 / float(n);
        float v0 = 2.0 * float(y) / float(n) - 1.0, v1 = v0 + 2.0 / float(n);
        float solid_angle =
            CubeCorner(u1, v1) - CubeCorner(u0, v1) - CubeCorner(u1, v0) + CubeCorner(u0, v0);
        vec3 l = imageLoad(environment_atlas, texel).rgb * solid_angle;
        sum[0] += 0.282095 * l;
        sum[1] += 0.488603 * d.y * l;
        sum[2] += 0.488603 * d.z * l;
        sum[3] += 0.488603 * d.x * l;
        sum[4] += 1.092548 * d.x * d.y * l;
        sum[5] += 1.092548 * d.y * d.z * l;
        sum[6] += 0.315392 * (3.0 * d.z * d.z - 1.0) * l;
        sum[7] += 1.092548 * d.x * d.z * l;
        sum[8] += 0.546274 * (d.x * d.x - d.y * d.y) * l;
    }
    for (int i = 0; i < 9; ++i) partial_sh[self * 9u + uint(i)] = sum[i];
    for (uint stride = uint(kEnvironmentShGroupSize) / 2u; stride > 0u; stride /= 2u) {
        barrier();
        if (self < stride) {
            for (int i = 0; i < 9; ++i) {
                partial_sh[self * 9u + uint(i)] += partial_sh[(self + stride) * 9u + uint(i)];
            }
        }
    }
    barrier();
    if (self < 9u) environment_sh[self] = vec4(partial_sh[self], 0.0);
}
