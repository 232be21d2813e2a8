// The CPU side of the environment (zenith/sky/environment.h): settings, the spherical-harmonic
// basis and irradiance, the cube map's directions and texel solid angles. The GPU side is
// environment_passes.cpp with atmosphere/environment.frag and atmosphere/environment_sh.comp,
// which tests/sky/environment_gl_test.cpp checks against these.
#include "zenith/sky/environment.h"

#include <cmath>
#include <string>

#include "zenith/base/error.h"

namespace zenith::sky {

void EnvironmentSettings::Validate() const {
    if (size != 0) Require("environment.size", size, "texels", Range::Closed(16, 1024));
    Require("environment.faces_per_frame", faces_per_frame, "", Range::Closed(1, 6));
}

std::array<double, 9> ShBasis(const glm::dvec3& d) {
    return {0.282095,
            0.488603 * d.y,
            0.488603 * d.z,
            0.488603 * d.x,
            1.092548 * d.x * d.y,
            1.092548 * d.y * d.z,
            0.315392 * (3.0 * d.z * d.z - 1.0),
            1.092548 * d.x * d.z,
            0.546274 * (d.x * d.x - d.y * d.y)};
}

glm::dvec3 ShIrradiance(const SphericalHarmonics9& sh, const glm::dvec3& normal) {
    constexpr double kPi = 3.14159265358979323846;
    constexpr std::array<double, 9> kCosineLobe = {
        kPi,       2.0 * kPi / 3.0, 2.0 * kPi / 3.0, 2.0 * kPi / 3.0, kPi / 4.0,
        kPi / 4.0, kPi / 4.0,       kPi / 4.0,       kPi / 4.0};
    const std::array<double, 9> y = ShBasis(glm::normalize(normal));
    glm::dvec3 e(0.0);
    for (std::size_t i = 0; i < 9; ++i) e += kCosineLobe[i] * y[i] * sh.coefficients[i];
    return e;
}

glm::dvec3 CubeFaceDirection(int face, double s, double t) {
    const double u = 2.0 * s - 1.0, v = 2.0 * t - 1.0;  // (sc, tc) / |ma|
    glm::dvec3 d(0.0);
    switch (face) {
        case 0:
            d = {1.0, -v, -u};
            break;
        case 1:
            d = {-1.0, -v, u};
            break;
        case 2:
            d = {u, 1.0, v};
            break;
        case 3:
            d = {u, -1.0, -v};
            break;
        case 4:
            d = {u, -v, 1.0};
            break;
        case 5:
            d = {-u, -v, -1.0};
            break;
        default:
            throw ArgumentError(
                "face", "cube face " + std::to_string(face) + " is out of range (expected 0..5)");
    }
    return glm::normalize(d);
}

double CubeTexelSolidAngle(int x, int y, int size) {
    const auto corner = [](double u, double v) {
        return std::atan2(u * v, std::sqrt(1.0 + u * u + v * v));
    };
    const double u0 = 2.0 * x / size - 1.0, u1 = 2.0 * (x + 1) / size - 1.0;
    const double v0 = 2.0 * y / size - 1.0, v1 = 2.0 * (y + 1) / size - 1.0;
    return corner(u1, v1) - corner(u0, v1) - corner(u1, v0) + corner(u0, v0);
}

SphericalHarmonics9 ProjectToSh(const LutImage& atlas) {
    const int size = atlas.size.x;
    if (!(size > 0 && atlas.size.y == 6 * size && atlas.size.z == 1)) {
        throw ArgumentError("atlas", "an environment atlas is size x 6 size texels, not " +
                                         std::to_string(atlas.size.x) + "x" +
                                         std::to_string(atlas.size.y));
    }
    SphericalHarmonics9 sh;
    for (int face = 0; face < 6; ++face) {
        for (int y = 0; y < size; ++y) {
            for (int x = 0; x < size; ++x) {
                const glm::dvec3 d = CubeFaceDirection(face, (x + 0.5) / size, (y + 0.5) / size);
                const glm::dvec3 l = glm::dvec3(glm::vec3(atlas.at(x, face * size + y))) *
                                     CubeTexelSolidAngle(x, y, size);
                const std::array<double, 9> basis = ShBasis(d);
                for (std::size_t i = 0; i < 9; ++i) sh.coefficients[i] += basis[i] * l;
            }
        }
    }
    return sh;
}

}  // namespace zenith::sky
