// SI host parameters -> the shaders' kilometre structs (functions.glsl's AtmosphereParameters and
// LightSet), for either side of the shared code: the double CPU mirror or the float std140 GL
// mirror. The conversion happens here once.
#pragma once

#include <type_traits>

#include "zenith/sky/atmosphere.h"
#include "zenith/sky/lut.h"

namespace zenith::sky {

template <typename Parameters>
Parameters MakeShaderParameters(const Atmosphere& a) {
    using Vec3 = decltype(Parameters{}.rayleigh_scattering);
    using Scalar = decltype(Parameters{}.mie_g);
    constexpr double kKm = 1000.0;  // m per km, and (1/m) -> (1/km) is * 1000 too
    Parameters p{};
    p.rayleigh_scattering = Vec3(a.rayleigh_scattering * kKm);
    p.rayleigh_scale_height = Scalar(a.rayleigh_scale_height / kKm);
    p.mie_scattering = Vec3(a.mie_scattering * kKm);
    p.mie_scale_height = Scalar(a.mie_scale_height / kKm);
    p.mie_extinction = Vec3(a.MieExtinction() * kKm);
    p.mie_g = Scalar(a.mie_g);
    p.absorption_extinction = Vec3(a.absorption_extinction * kKm);
    p.absorption_center = Scalar(a.absorption_center / kKm);
    p.ground_albedo = Vec3(a.ground_albedo);
    p.absorption_half_width = Scalar(0.5 * a.absorption_width / kKm);
    p.solar_illuminance = Vec3(a.solar_illuminance);
    p.sun_angular_radius = Scalar(a.sun_angular_radius);
    p.bottom_radius = Scalar(a.bottom_radius / kKm);
    p.top_radius = Scalar(a.top_radius / kKm);
    return p;
}

// The Moon is a light of the atmosphere unless the Sun is above the horizon of `up` (the
// camera's zenith) and outshines it a thousandfold at the top of the atmosphere: the sky's
// moonlight is then under 2e-4 of its sunlight (tests/sky/atmosphere_lut_test.cpp), and with
// the Sun alone the Sky-View LUT is symmetric about the Sun's vertical, so half of it is marched.
inline bool MoonIsLight(const Lights& lights, const glm::dvec3& up) {
    if (!lights.moon_enabled) return false;
    const bool sun_up = glm::dot(glm::normalize(lights.sun_direction), glm::normalize(up)) > 0.0;
    // In a solar eclipse the Sun's light lights the air outside the Moon's shadow all the same.
    const glm::dvec3& sun =
        lights.eclipse.active ? lights.eclipse.unobscured_illuminance : lights.sun_illuminance;
    return !(sun_up && glm::length(lights.moon_illuminance) < 1e-3 * glm::length(sun));
}

template <typename LightSet>
LightSet MakeLightSet(const Lights& lights, const glm::dvec3& up) {
    using Vec3 = decltype(LightSet{}.light[0].direction);
    LightSet l{};
    l.light[0].direction = Vec3(glm::normalize(lights.sun_direction));
    l.light[0].illuminance = Vec3(lights.sun_illuminance);
    l.light[1].direction = Vec3(glm::normalize(lights.moon_direction));
    l.light[1].illuminance = Vec3(lights.moon_illuminance);
    l.count = MoonIsLight(lights, up) ? 2 : 1;
    // No clouds (CloudPasses writes what they do into the GL block each frame).
    l.cloud_base = 0.0;
    l.cloud_direct = 1.0;
    l.cloud_sky = 1.0;
    l.cloud_ground_sky = 1.0;
    l.cloud_shaded = 0.0;
    if (lights.eclipse.active) {
        // The Moon's shadow axis: through its centre along the Sun's direction; its point
        // nearest the camera (`up` is the camera's position) and the Moon's distance from there.
        const glm::dvec3 sun = glm::normalize(lights.sun_direction);
        const glm::dvec3& moon = lights.eclipse.moon_position;
        const glm::dvec3 axis_point = moon + glm::dot(up - moon, sun) * sun;
        using Scalar = decltype(LightSet{}.cloud_base);
        constexpr double kKm = 1000.0;
        l.eclipse = 1;
        l.eclipse_sun_illuminance = Vec3(lights.eclipse.unobscured_illuminance);
        l.eclipse_axis_point = Vec3(axis_point / kKm);
        l.eclipse_axis_distance = Scalar(glm::dot(moon - axis_point, sun) / kKm);
        l.eclipse_sun_radius = Scalar(lights.eclipse.sun_angular_radius);
        l.eclipse_moon_radius = Scalar(lights.eclipse.moon_angular_radius);
        l.eclipse_around_illuminance = Vec3(lights.eclipse.around_illuminance);
        static_assert(sizeof(l.eclipse_limb) / sizeof(l.eclipse_limb[0]) ==
                      std::tuple_size_v<decltype(lights.eclipse.limb_ratio)>);
        for (std::size_t i = 0; i < lights.eclipse.limb_ratio.size(); ++i) {
            using Vec4 = std::remove_reference_t<decltype(l.eclipse_limb[0])>;
            l.eclipse_limb[i] = Vec4(Vec3(lights.eclipse.limb_ratio[i]), Scalar(1.0));
        }
    }
    return l;
}

}  // namespace zenith::sky
