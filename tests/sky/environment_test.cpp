// The environment's CPU side (zenith/sky/environment.h) against closed forms: the cube map's
// texels against OpenGL's face-selection table read the other way, their solid angles against
// the sphere's 4 pi, and the L2 spherical-harmonic irradiance against integrals done by hand.
#include "zenith/sky/environment.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "zenith/base/error.h"

namespace zenith::sky {
namespace {

constexpr double kPi = 3.14159265358979323846;

// OpenGL 4.5 §8.13.1, Table 8.19: the face of a direction by its major axis and the face's
// (s, t) = ((sc / |ma| + 1) / 2, (tc / |ma| + 1) / 2).
struct FaceCoordinates {
    int face;
    double s, t;
};
FaceCoordinates SelectFace(const glm::dvec3& r) {
    const glm::dvec3 a = glm::abs(r);
    double sc = 0.0, tc = 0.0, ma = 0.0;
    int face = 0;
    if (a.x >= a.y && a.x >= a.z) {
        face = r.x > 0.0 ? 0 : 1;
        sc = r.x > 0.0 ? -r.z : r.z;
        tc = -r.y;
        ma = a.x;
    } else if (a.y >= a.z) {
        face = r.y > 0.0 ? 2 : 3;
        sc = r.x;
        tc = r.y > 0.0 ? r.z : -r.z;
        ma = a.y;
    } else {
        face = r.z > 0.0 ? 4 : 5;
        sc = r.z > 0.0 ? r.x : -r.x;
        tc = -r.y;
        ma = a.z;
    }
    return {face, 0.5 * (sc / ma + 1.0), 0.5 * (tc / ma + 1.0)};
}

TEST(EnvironmentTest, TexelDirectionsFollowOpenGlsFaceTable) {
    constexpr int kSize = 8;
    for (int face = 0; face < 6; ++face) {
        for (int y = 0; y < kSize; ++y) {
            for (int x = 0; x < kSize; ++x) {
                const double s = (x + 0.5) / kSize, t = (y + 0.5) / kSize;
                const glm::dvec3 d = CubeFaceDirection(face, s, t);
                EXPECT_NEAR(glm::length(d), 1.0, 1e-15);
                const FaceCoordinates back = SelectFace(d);
                EXPECT_EQ(back.face, face) << x << "," << y;
                EXPECT_NEAR(back.s, s, 1e-14);
                EXPECT_NEAR(back.t, t, 1e-14);
            }
        }
    }
    EXPECT_THROW(CubeFaceDirection(6, 0.5, 0.5), ArgumentError);
}

TEST(EnvironmentTest, TexelSolidAnglesCoverTheSphere) {
    for (int size : {1, 3, 16, 64}) {
        double sum = 0.0, smallest = 1e9, largest = 0.0;
        for (int y = 0; y < size; ++y) {
            for (int x = 0; x < size; ++x) {
                const double omega = CubeTexelSolidAngle(x, y, size);
                sum += 6.0 * omega;
                smallest = std::min(smallest, omega);
                largest = std::max(largest, omega);
            }
        }
        EXPECT_NEAR(sum, 4.0 * kPi, 1e-12) << size;
        // The centre texels are the largest, the corners the smallest: 3^(3/2) = 5.2 times
        // smaller in the limit.
        if (size >= 16) {
            EXPECT_GT(largest / smallest, 4.0) << size;
        }
    }
}

// An atlas (size x 6 size) of the radiance `l` at each texel's centre.
LutImage Atlas(int size, const std::function<glm::dvec3(const glm::dvec3&)>& l) {
    LutImage atlas(size, 6 * size);
    for (int face = 0; face < 6; ++face) {
        for (int y = 0; y < size; ++y) {
            for (int x = 0; x < size; ++x) {
                const glm::dvec3 d = CubeFaceDirection(face, (x + 0.5) / size, (y + 0.5) / size);
                atlas.at(x, face * size + y) = glm::vec4(glm::vec3(l(d)), 1.0f);
            }
        }
    }
    return atlas;
}

const glm::dvec3 kNormals[] = {{0, 0, 1},  {0, 0, -1},    {1, 0, 0},
                               {0, -1, 0}, {0.6, 0, 0.8}, {-0.48, 0.64, -0.6}};

TEST(EnvironmentTest, UniformRadianceGivesPiLOnEveryNormal) {
    const glm::dvec3 l(1.0, 2.0, 3.0);
    const SphericalHarmonics9 sh = ProjectToSh(Atlas(32, [&](const glm::dvec3&) { return l; }));
    for (const glm::dvec3& n : kNormals) {
        const glm::dvec3 e = ShIrradiance(sh, n);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(e[c] / (kPi * l[c]), 1.0, 1e-5);
    }
}

// Radiance of degree 1, a + b z: E(n) = pi a + 2 pi b n_z / 3, exactly in L2 harmonics.
TEST(EnvironmentTest, LinearRadianceIsExact) {
    const double a = 2.0, b = 1.5;
    const SphericalHarmonics9 sh =
        ProjectToSh(Atlas(64, [&](const glm::dvec3& d) { return glm::dvec3(a + b * d.z); }));
    for (const glm::dvec3& n : kNormals) {
        const double expected = kPi * a + 2.0 * kPi * b * glm::normalize(n).z / 3.0;
        EXPECT_NEAR(ShIrradiance(sh, n).g / expected, 1.0, 1e-4) << n.x << " " << n.y << " " << n.z;
    }
}

// A sky of uniform radiance over the upper hemisphere and nothing below (a step at the
// horizon): E = pi L (1 + cos theta) / 2 on a normal theta from the zenith. Its l = 2 part
// vanishes and so does the exact irradiance's above l = 1, so L2 harmonics give it exactly; what
// is left is the cube's texels that the horizon cuts, counted wholly on one side.
TEST(EnvironmentTest, UpperHemisphereOnly) {
    const SphericalHarmonics9 sh = ProjectToSh(
        Atlas(64, [](const glm::dvec3& d) { return glm::dvec3(d.z > 0.0 ? 1.0 : 0.0); }));
    for (const glm::dvec3& n : kNormals) {
        const double expected = kPi * (1.0 + glm::normalize(n).z) / 2.0;
        EXPECT_NEAR(ShIrradiance(sh, n).g, expected, 2e-3 * kPi) << n.x << " " << n.y << " " << n.z;
    }
}

TEST(EnvironmentTest, SettingsAreChecked) {
    EnvironmentSettings s;
    EXPECT_FALSE(s.enabled());
    EXPECT_NO_THROW(s.Validate());
    s.size = 8;
    EXPECT_THROW(s.Validate(), ArgumentError);
    s.size = 64;
    s.faces_per_frame = 7;
    EXPECT_THROW(s.Validate(), ArgumentError);
    s.faces_per_frame = 6;
    EXPECT_NO_THROW(s.Validate());
    EXPECT_THROW(ProjectToSh(LutImage(4, 4)), ArgumentError);
}

}  // namespace
}  // namespace zenith::sky
