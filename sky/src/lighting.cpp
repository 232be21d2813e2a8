#include "zenith/sky/lighting.h"

#include <algorithm>

#include "reference/atmosphere_functions.h"
#include "shader_parameters.h"

namespace zenith::sky {

glm::dvec3 TransmittanceToLight(const Atmosphere& atmosphere, double altitude, double mu,
                                double angular_radius, int steps) {
    auto a = MakeShaderParameters<ref::AtmosphereParameters>(atmosphere);
    a.sun_angular_radius = angular_radius;
    const double r = std::clamp(a.bottom_radius + altitude / 1000.0, a.bottom_radius, a.top_radius);
    // The same visible fraction of the disk as GetTransmittanceToSun, with the transmittance
    // integrated along the ray (no LUT); below the horizon the path is the grazing one.
    const double sin_h = a.bottom_radius / r;
    const double cos_h = -std::sqrt(std::max(1.0 - sin_h * sin_h, 0.0));
    const double visible =
        ref::smoothstep(-sin_h * angular_radius, sin_h * angular_radius, mu - cos_h);
    if (!(visible > 0.0)) return glm::dvec3(0.0);
    return ref::ComputeTransmittanceToTopAtmosphereBoundary(a, r, std::max(mu, cos_h), steps) *
           visible;
}

glm::dvec3 SampleGroundIrradiance(const LutImage& irradiance, double mu) {
    const int n = irradiance.size.x;
    if (n <= 0) return glm::dvec3(0.0);
    // Texel i holds mu = 2 (i / (n - 1)) - 1 (GetTextureCoordFromUnitRange's centres).
    const double x = std::clamp(0.5 + 0.5 * mu, 0.0, 1.0) * (n - 1);
    const int i0 = std::min(static_cast<int>(x), n - 1), i1 = std::min(i0 + 1, n - 1);
    const double f = x - i0;
    return glm::mix(glm::dvec3(irradiance.at(i0, 0)), glm::dvec3(irradiance.at(i1, 0)), f);
}

}  // namespace zenith::sky
