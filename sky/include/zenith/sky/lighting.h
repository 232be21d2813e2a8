// Light at a point of the atmosphere, for a host's own shading (sun/moon illuminance at the
// aircraft, sky ambient). Evaluated on the CPU with the renderer's own functions
// (functions.glsl compiled as C++), so it agrees with what the renderer draws.
#pragma once

#include <array>
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

// Lights::SolarEclipse::limb_ratio for a Moon of `moon_over_sun` Sun radii: the Sun's
// limb-darkened light left (geo::CoveredFluxFraction, per channel) over its uniform disk's area
// left, at the separations LightSet.eclipse_limb documents (the first just off the inner
// contact, where both vanish).
std::array<glm::dvec3, 8> EclipseLimbTable(double moon_over_sun);

// Lights::SolarEclipse::around_illuminance for `lights` (the rest of their eclipse filled in)
// seen from `camera_position` (m, planet-centred): the shared code's EclipsedSkyIlluminance
// (sky/shaders/atmosphere/functions.glsl) at the camera, with the atmosphere's mean free path
// at the ground.
glm::dvec3 EclipseAroundIlluminance(const Atmosphere& atmosphere, const Lights& lights,
                                    const glm::dvec3& camera_position);

// Sunlight refracted into the Earth's umbra by its air, as a fraction (per channel) of the
// unobscured Sun's illuminance, at a point `axis_distance` (m) from the shadow's axis and
// `moon_distance` (m) behind the Earth; `sun_angular_radius` (rad) the Sun's seen from there.
// A documented simple model (Link's theory of lunar eclipses, reduced):
//  - A ray grazing the planet at tangent height h is bent by delta(h) = nu0 exp(-h/H)
//    sqrt(2 pi (R + h) / H) (the refraction of a grazing ray through an exponential atmosphere,
//    as in stellar-occultation theory, e.g. Elliot & Olkin 1996), with H the atmosphere's
//    Rayleigh scale height and nu0 the ground's refractivity: geo::kAirRefractivity for Earth's
//    air at 15 C, 1013 hPa, 550 nm (Edlen 1966), scaled by the square root of the Rayleigh
//    scattering coefficient for other atmospheres (beta_R ~ (n - 1)^2 / N at a fixed N).
//    Earth: 1.15 deg at the ground, the ~70' of the literature.
//  - It arrives at rho = R + h - delta(h) D from the axis (on the far side when negative); the
//    light of the ring of tangent heights [h, h + dh] spreads over the ring [rho, rho + drho],
//    so the intensity is T(h) (R + h) / (|rho| drho/dh), summed over the heights that reach the
//    point, with T(h) the atmosphere's own transmittance along the grazing path (the
//    transmittance from R + h horizontally to space, squared, with the ozone: this colours it).
//  - The Sun's disk smooths it: averaged over 16 offsets across the Sun's diameter (weighted by
//    its chord); within half the Sun's radius of the axis, where the focusing of a point source
//    diverges, the value there is used.
// Not modelled: clouds and volcanic aerosols, which darken real eclipses; so this umbra is a
// bright one (2022-11-08 at mid-eclipse: 2e-4 of the full Moon's luminance, magnitude ~ -3.5).
glm::dvec3 UmbraRefractedLight(const Atmosphere& atmosphere, double axis_distance,
                               double moon_distance, double sun_angular_radius);

}  // namespace zenith::sky
