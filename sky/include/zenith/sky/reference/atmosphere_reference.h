// CPU evaluation of the renderer's own atmosphere code (sky/shaders/atmosphere/functions.glsl
// compiled as C++ in double precision): the LUTs and per-pixel ray marching, texel for texel
// what the GL renderer computes. Used for GPU-vs-CPU parity tests and as ground truth for the
// LUT convergence tests; the independent physical reference is reference/path_tracer.h.
#pragma once

#include <glm/glm.hpp>
#include <memory>

#include "zenith/sky/atmosphere.h"
#include "zenith/sky/lut.h"

namespace zenith::sky::reference {

class AtmosphereReference {
  public:
    // Builds the transmittance, multiple-scattering and ground-irradiance LUTs.
    AtmosphereReference(const Atmosphere& atmosphere, const LutSettings& settings = {});
    ~AtmosphereReference();
    AtmosphereReference(AtmosphereReference&&) noexcept;
    AtmosphereReference& operator=(AtmosphereReference&&) noexcept;

    const LutImage& transmittance() const;
    const LutImage& multiple_scattering() const;
    const LutImage& ground_irradiance() const;

    // Per-frame LUTs for a camera position (m, planet-centred) and the lights.
    LutImage SkyView(const glm::dvec3& camera, const Lights& lights) const;
    LutImage AerialPerspective(const Camera& camera, const Lights& lights) const;

    // Transmittance from radius r (m) along zenith cosine mu to the top: LUT lookup, and the
    // direct integration with `steps` segments (no LUT).
    glm::dvec3 TransmittanceFromLut(double r, double mu) const;
    glm::dvec3 TransmittanceIntegrated(double r, double mu, int steps) const;

    // In-scattered luminance (rgb) and mean transmittance (a) from `origin` to `distance` m along
    // `direction`, marched with `steps` steps, ground not included (an aerial-perspective froxel).
    glm::dvec4 InScattering(const glm::dvec3& origin, const glm::dvec3& direction,
                            const Lights& lights, double distance, int steps) const;

    // Luminance (cd/m^2) along a view ray by ray marching with `steps` steps, ground included.
    glm::dvec3 RayMarch(const glm::dvec3& origin, const glm::dvec3& direction, const Lights& lights,
                        int steps) const;
    // Single scattering alone: RayMarch's march with an empty multiple-scattering LUT and no
    // light from the ground, what the path tracer's one-vertex paths carry
    // (PathTraceOptions::max_bounces = 1).
    glm::dvec3 SingleScattering(const glm::dvec3& origin, const glm::dvec3& direction,
                                const Lights& lights, int steps) const;
    // Luminance read from a Sky-View LUT made by SkyView(camera, lights).
    glm::dvec3 SampleSkyView(const LutImage& sky_view, const glm::dvec3& camera,
                             const glm::dvec3& sun_direction, const glm::dvec3& direction) const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace zenith::sky::reference
