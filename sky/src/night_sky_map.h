// The renderer's side of zenith/sky/night_sky.h: the diffuse night light through the atmosphere
// along a direction (the CPU twin of what the composite adds), and the per-frame map of it in the
// Sky-View LUT's parameterisation that the composite samples.
#pragma once

#include <glm/glm.hpp>
#include <vector>

#include "reference/shared_math.h"
#include "zenith/sky/atmosphere.h"
#include "zenith/sky/night_sky.h"

namespace zenith::sky {

// cd/m^2, linear sRGB, at a camera (km, planet-centred; its altitude exact) along `direction`:
// the airglow through van Rhijn's slant path and the atmosphere's transmittance, zodiacal light
// and starlight through the transmittance to space, and the light pollution (night_sky.h).
// 0 when night.enabled or its settings' enabled is false.
glm::dvec3 NightSkyLuminance(const NightSky& night, const Atmosphere& atmosphere,
                             const ref::TransmittanceTexture& transmittance,
                             const glm::dvec3& camera_km, double camera_altitude_km,
                             const glm::dvec3& direction);

// NightSkyGroundIrradiance (night_sky.h) over the renderer's transmittance LUT as kept on the CPU.
glm::dvec3 NightSkyGroundIrradiance(const NightSky& night, const Atmosphere& atmosphere,
                                    const ref::TransmittanceTexture& transmittance,
                                    const glm::dvec3& position);

// NightSkyLuminance at the texel centres of a `size` map in the Sky-View LUT's parameterisation
// (its frame: up the camera's radial direction, x toward the Sun's azimuth).
void FillNightSkyMap(const NightSky& night, const Atmosphere& atmosphere,
                     const ref::TransmittanceTexture& transmittance, const glm::dvec3& camera_km,
                     double camera_altitude_km, const glm::dvec3& sun_direction, glm::ivec2 size,
                     std::vector<glm::vec4>& texels);

}  // namespace zenith::sky
