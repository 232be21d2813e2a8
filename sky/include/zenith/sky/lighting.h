// Light at a point of the atmosphere, for a host's own shading (sun/moon illuminance at the
// aircraft, sky ambient). Evaluated on the CPU with the renderer's own functions
// (functions.glsl compiled as C++), so it agrees with what the renderer draws.
#pragma once

#include <glm/glm.hpp>

#include "zenith/sky/atmosphere.h"
#include "zenith/sky/lut.h"

namespace zenith::sky {

// Transmittance from `altitude` (m) toward a light at zenith cosine `mu`, times the fraction of a
// disk of `angular_radius` (rad) above the planet's horizon (smooth across sunset).
glm::dvec3 TransmittanceToLight(const Atmosphere& atmosphere, double altitude, double mu,
                                double angular_radius, int steps = 64);

// Sky irradiance on a horizontal surface on the ground, per unit light illuminance, from the
// renderer's ground-irradiance LUT (RendererInspection::ReadGroundIrradiance), at light zenith
// cosine mu.
glm::dvec3 SampleGroundIrradiance(const LutImage& irradiance, double mu);

}  // namespace zenith::sky
