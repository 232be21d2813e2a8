// The sky around the camera for a host's own shading (issue 16): an environment cube map of the
// sky's luminance, clouds included, for reflections, and its irradiance as L2 spherical
// harmonics (Ramamoorthi & Hanrahan 2001, "An Efficient Representation for Irradiance
// Environment Maps") for diffuse light on any normal.
//
// What is in it: the sky as the composite draws it (the Sky-View LUT inside the atmosphere, a ray
// march above it; our ground below the horizon; the night sky's diffuse light; with weather the
// clouds along each texel, traced like the frame's, and their shadow on the ground) without the
// Sun's and the Moon's disks, the stars and the light shafts. The disks are the host's direct
// lights (SkyLighting's sun/moon illuminance and directions): in a cube map of 64 texels a side
// the Sun would be a 3-degree blob holding most of the day's light, which a diffuse or glossy
// lookup would count a second time.
//
// Conventions: directions in the renderer's world frame (SkySystem: the aircraft's ENU frame,
// x east, y north, z up); the cube map follows OpenGL's face order and orientation (GL 4.5
// §8.13, Table 8.19), so a host samples it with texture(samplerCube, direction). Luminance in
// cd/m^2 (RGBA32F, no clipping), irradiance in lux.
#pragma once

#include <array>
#include <glm/glm.hpp>

#include "zenith/sky/lut.h"

namespace zenith::sky {

struct EnvironmentSettings {
    // Texels per side of each face; 0: no environment (the default: it costs a host that does
    // not sample it ~7 % of a cloudy frame). 16..1024. The cube has a full mip chain
    // (glGenerateMipmap of the box filter after each round) for rough reflections.
    int size = 0;
    // Faces drawn per Update, 1..6: a round of the six takes 6 / faces_per_frame frames, after
    // which the mip levels and the spherical harmonics are made again. The sky changes slowly, so
    // spreading it over frames costs a host a sixth per frame.
    int faces_per_frame = 1;
    bool enabled() const { return size > 0; }
    // Throws zenith::ArgumentError naming the field, its value and the allowed range.
    void Validate() const;
};

// Real spherical harmonics of RGB luminance up to l = 2, coefficient i of (l, m) in the order
// (0,0), (1,-1), (1,0), (1,1), (2,-2), (2,-1), (2,0), (2,1), (2,2); L_lm = integral of L Y_lm over
// the sphere (cd/m^2 sr).
struct SphericalHarmonics9 {
    std::array<glm::dvec3, 9> coefficients{};
};

// Y_lm(direction) for a unit direction, in that order: 0.282095; 0.488603 (y, z, x);
// 1.092548 (xy, yz), 0.315392 (3z^2 - 1), 1.092548 xz, 0.546274 (x^2 - y^2).
std::array<double, 9> ShBasis(const glm::dvec3& direction);

// Irradiance (lux) on a surface with unit normal `normal` lit by radiance `sh`:
// E(n) = sum A_l L_lm Y_lm(n) with the clamped cosine's A_0 = pi, A_1 = 2 pi / 3, A_2 = pi / 4
// (Ramamoorthi & Hanrahan 2001, Eq. 7-8). Exact for radiance of degree <= 1; for a sky, whose
// horizon is a step, within a few percent (tests/sky/environment_gl_test.cpp measures it).
glm::dvec3 ShIrradiance(const SphericalHarmonics9& sh, const glm::dvec3& normal);

// The unit direction through (s, t) in [0, 1]^2 of cube face `face` (0..5: +X, -X, +Y, -Y, +Z,
// -Z), OpenGL's convention: s along the face image's rows (x), t down its columns (y, row 0 first).
glm::dvec3 CubeFaceDirection(int face, double s, double t);

// The solid angle (sr) of texel (x, y) of a face `size` texels a side, exact (the six faces'
// texels sum to 4 pi): the area element 1 / (1 + u^2 + v^2)^(3/2) integrated over the texel's
// [u0, u1] x [v0, v1] of the face's [-1, 1]^2 is F(u1, v1) - F(u0, v1) - F(u1, v0) + F(u0, v0),
// F(u, v) = atan(u v / sqrt(1 + u^2 + v^2)).
double CubeTexelSolidAngle(int x, int y, int size);

// The projection of a cube map given as an atlas (width size, height 6 size: face f in rows
// f size .. (f + 1) size - 1, as RendererInspection::ReadEnvironment returns it) onto
// ShBasis: L_lm = sum over texels of L Y_lm(texel centre) x its solid angle.
SphericalHarmonics9 ProjectToSh(const LutImage& atlas);

}  // namespace zenith::sky
