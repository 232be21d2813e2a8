#include "zenith/sky/lighting.h"

#include <algorithm>
#include <cmath>

#include "reference/atmosphere_functions.h"
#include "reference/lut_texture.h"
#include "shader_parameters.h"
#include "zenith/geo/eclipse.h"
#include "zenith/geo/refraction.h"

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
    if (irradiance.size.x <= 0) return glm::dvec3(0.0);
    return glm::dvec3(ref::GetGroundSkyIrradiance(ref::FromImage(irradiance), mu));
}

std::array<glm::dvec3, 8> EclipseLimbTable(double moon_over_sun) {
    const double k = moon_over_sun;
    const double x_in = std::abs(1.0 - k), x_out = 1.0 + k;
    std::array<glm::dvec3, 8> table{};
    for (std::size_t i = 0; i < table.size(); ++i) {
        const double s = static_cast<double>(i) / static_cast<double>(table.size() - 1);
        const double x = x_in + (x_out - x_in) * std::max(s * s, 1e-4);
        const double area_left = 1.0 - geo::DiskOverlapArea(1.0, k, x) / ref::kPi;
        for (int c = 0; c < 3; ++c) {
            const double light_left =
                1.0 - geo::CoveredFluxFraction(
                          geo::kSunLimbDarkeningRgb[static_cast<std::size_t>(c)], 1.0, k, x);
            table[i][c] = area_left > 0.0 ? light_left / area_left : 1.0;
        }
    }
    return table;
}

glm::dvec3 EclipseAroundIlluminance(const Atmosphere& atmosphere, const Lights& lights,
                                    const glm::dvec3& camera_position) {
    if (!lights.eclipse.active) return glm::dvec3(0.0);
    const auto a = MakeShaderParameters<ref::AtmosphereParameters>(atmosphere);
    const ref::LightSet set = MakeLightSet<ref::LightSet>(lights, camera_position);
    const double extinction = ref::SampleMedium(a, 0.0).extinction.y;  // 1/km
    const double free_path = std::clamp(1.0 / std::max(extinction, 1e-9), 1.0, 300.0);
    return ref::EclipsedSkyIlluminance(set, camera_position / 1000.0, free_path);
}

glm::dvec3 UmbraRefractedLight(const Atmosphere& atmosphere, double axis_distance,
                               double moon_distance, double sun_angular_radius) {
    const auto a = MakeShaderParameters<ref::AtmosphereParameters>(atmosphere);
    constexpr double kKm = 1000.0;
    constexpr double kEarthRayleighGreen = 13.558e-6;  // 1/m, Atmosphere's default green
    const double nu0 =
        geo::kAirRefractivity * std::sqrt(atmosphere.rayleigh_scattering.y / kEarthRayleighGreen);
    const double radius = a.bottom_radius;              // km
    const double top = a.top_radius - a.bottom_radius;  // km
    const double scale_height = atmosphere.rayleigh_scale_height / kKm;
    const double distance = moon_distance / kKm;
    const double s = sun_angular_radius;
    const double target = std::max(axis_distance / kKm, 0.5 * s * distance);
    const auto bend = [&](double h) {
        return nu0 * std::exp(-h / scale_height) *
               std::sqrt(2.0 * ref::kPi * (radius + h) / scale_height);
    };
    const auto rho = [&](double h) { return radius + h - bend(h) * distance; };
    const auto transmittance = [&](double h) {
        const glm::dvec3 half =
            ref::ComputeTransmittanceToTopAtmosphereBoundary(a, radius + h, 0.0, 64);
        return half * half;
    };
    constexpr int kOffsets = 16;
    glm::dvec3 sum(0.0);
    double weights = 0.0;
    for (int j = 0; j < kOffsets; ++j) {
        const double u = -1.0 + (2.0 * j + 1.0) / kOffsets;  // across the Sun's diameter
        const double w = std::sqrt(1.0 - u * u);
        weights += w;
        const double shift = u * s * distance;  // km at the Moon
        for (const double side : {1.0, -1.0}) {
            // rho(h) + shift = side * target; rho increases with h (refraction weakens upward).
            const double goal = side * target - shift;
            double lo = 0.0, hi = top;
            if (!(goal > rho(lo) && goal < rho(hi))) continue;
            for (int i = 0; i < 60; ++i) {
                const double mid = 0.5 * (lo + hi);
                (rho(mid) < goal ? lo : hi) = mid;
            }
            const double h = 0.5 * (lo + hi);
            const double spread = 1.0 + bend(h) * distance / scale_height;  // d rho / d h
            sum += w * transmittance(h) * (radius + h) / (target * spread);
        }
    }
    return sum / weights;
}

}  // namespace zenith::sky
