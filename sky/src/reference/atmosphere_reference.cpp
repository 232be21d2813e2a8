#include "zenith/sky/reference/atmosphere_reference.h"

#include <utility>

#include "multiple_scattering_column.h"
#include "reference/atmosphere_functions.h"
#include "reference/lut_texture.h"
#include "reference/monte_carlo.h"
#include "shader_parameters.h"

namespace zenith::sky::reference {
namespace {

using ref::FromImage;
using ref::Texture2D;
using ref::ToImage;

constexpr double kKm = 1000.0;

glm::dvec2 TexelCentre(int x, int y, glm::ivec2 size) {
    return {(x + 0.5) / size.x, (y + 0.5) / size.y};
}

}  // namespace

struct AtmosphereReference::Impl {
    ref::AtmosphereParameters atmosphere;
    LutSettings settings;
    LutImage transmittance_image, multiple_scattering_image, irradiance_image;
    Texture2D transmittance, multiple_scattering, irradiance;

    double AltitudeKm(const glm::dvec3& position) const {
        return glm::length(position) / kKm - atmosphere.bottom_radius;
    }

    // The lights as the renderer passes them for a camera (or ray origin) at `position` (m).
    ref::LightSet ToLightSet(const Lights& lights, const glm::dvec3& position) const {
        return MakeLightSet<ref::LightSet>(lights, position);
    }
};

AtmosphereReference::AtmosphereReference(const Atmosphere& atmosphere, const LutSettings& settings)
    : impl_(std::make_unique<Impl>()) {
    Validate(atmosphere);
    settings.Validate();
    Impl& d = *impl_;
    d.atmosphere = MakeShaderParameters<ref::AtmosphereParameters>(atmosphere);
    d.settings = settings;

    Texture2D t(settings.transmittance_size.x, settings.transmittance_size.y);
    for (int y = 0; y < t.height(); ++y) {
        for (int x = 0; x < t.width(); ++x) {
            const ref::vec3 value = ref::ComputeTransmittanceTexel(
                d.atmosphere, TexelCentre(x, y, settings.transmittance_size),
                settings.transmittance_size, settings.transmittance_steps);
            t.at(x, y) = ref::vec4(value, 1.0);
        }
    }
    d.transmittance_image = ToImage(t);
    d.transmittance = FromImage(d.transmittance_image);

    // Orders 2 .. K (ComputeScatteringOrderTexel), each from the one before, as
    // AtmospherePasses::BuildMultipleScattering dispatches them.
    const glm::ivec2 ms_size = settings.multiple_scattering_size;
    const glm::ivec2 wide = settings.multiple_scattering_texture_size();
    Texture2D ms(wide.x, wide.y), order(wide.x, wide.y), next(wide.x, wide.y);
    const Texture2D column =
        FromImage(MultipleScatteringColumnCorrection(atmosphere, d.transmittance, settings));
    for (int k = 2; k <= settings.multiple_scattering_orders; ++k) {
        // Rows on every core: this LUT is most of the reference's construction.
        monte_carlo::ParallelFor(ms_size.y, 0, [&](std::int64_t row) {
            const int y = static_cast<int>(row);
            for (int x = 0; x < ms_size.x; ++x) {
                const ref::ScatteringOrder o = ref::ComputeScatteringOrderTexel(
                    d.atmosphere, d.transmittance, order, k, TexelCentre(x, y, ms_size), ms_size,
                    settings.multiple_scattering_directions_sqrt,
                    settings.multiple_scattering_steps, 0, 1);
                const auto texel = [&](Texture2D& lut, int tile) -> ref::vec4& {
                    return lut.at(x + tile * ms_size.x, y);
                };
                const ref::MultipleScatteringSample sum = ref::AccumulateScatteringOrder(
                    ref::MultipleScatteringFromTexels(texel(ms, 0), texel(ms, 1), texel(ms, 2)), o,
                    k, settings.multiple_scattering_orders, ref::vec3(column.at(x, y)));
                for (int tile = 0; tile < kMultipleScatteringTiles; ++tile) {
                    texel(next, tile) = ref::MultipleScatteringTexel(o.light, tile);
                    texel(ms, tile) = ref::MultipleScatteringTexel(sum, tile);
                }
            }
        });
        std::swap(order, next);
    }
    d.multiple_scattering_image = ToImage(ms);
    d.multiple_scattering = FromImage(d.multiple_scattering_image);

    Texture2D irradiance(settings.irradiance_size.x, settings.irradiance_size.y);
    const Texture2D unused(1, 1);
    for (int y = 0; y < irradiance.height(); ++y) {
        for (int x = 0; x < irradiance.width(); ++x) {
            const ref::vec3 value = ref::ComputeGroundIrradianceTexel(
                d.atmosphere, d.transmittance, d.multiple_scattering, unused,
                settings.irradiance_size, TexelCentre(x, y, settings.irradiance_size).x,
                settings.irradiance_directions_sqrt, settings.irradiance_steps, 0, 1);
            irradiance.at(x, y) = ref::vec4(value, 1.0);
        }
    }
    d.irradiance_image = ToImage(irradiance);
    d.irradiance = FromImage(d.irradiance_image);
}

AtmosphereReference::~AtmosphereReference() = default;
AtmosphereReference::AtmosphereReference(AtmosphereReference&&) noexcept = default;
AtmosphereReference& AtmosphereReference::operator=(AtmosphereReference&&) noexcept = default;

const LutImage& AtmosphereReference::transmittance() const { return impl_->transmittance_image; }
const LutImage& AtmosphereReference::multiple_scattering() const {
    return impl_->multiple_scattering_image;
}
const LutImage& AtmosphereReference::ground_irradiance() const { return impl_->irradiance_image; }

LutImage AtmosphereReference::SkyView(const glm::dvec3& camera, const Lights& lights) const {
    const Impl& d = *impl_;
    const ref::LightSet light_set = d.ToLightSet(lights, camera);
    const glm::ivec2 size = d.settings.sky_view_size;
    LutImage image(size.x, size.y);
    for (int y = 0; y < size.y; ++y) {
        for (int x = 0; x < size.x; ++x) {
            const ref::vec3 value = ref::ComputeSkyViewTexel(
                d.atmosphere, d.transmittance, d.multiple_scattering, d.irradiance, light_set,
                camera / kKm, d.AltitudeKm(camera), TexelCentre(x, y, size), size,
                d.settings.sky_view_steps);
            image.at(x, y) = glm::vec4(glm::vec3(value), 1.0f);
        }
    }
    return image;
}

LutImage AtmosphereReference::AerialPerspective(const Camera& camera, const Lights& lights) const {
    const Impl& d = *impl_;
    const ref::LightSet light_set = d.ToLightSet(lights, camera.position);
    const glm::ivec3 size = d.settings.aerial_perspective_size;
    LutImage image(size.x, size.y, size.z);
    const double range_km = d.settings.aerial_perspective_range / kKm;
    for (int y = 0; y < size.y; ++y) {
        for (int x = 0; x < size.x; ++x) {
            const glm::dvec3 direction =
                camera.Direction(2.0 * (x + 0.5) / size.x - 1.0, 2.0 * (y + 0.5) / size.y - 1.0);
            ref::ScatteringResult accumulated{ref::vec3(0.0), ref::vec3(1.0)};
            for (int z = 0; z < size.z; ++z) {
                const ref::vec4 value = ref::AdvanceAerialPerspective(
                    d.atmosphere, d.transmittance, d.multiple_scattering, d.irradiance, light_set,
                    camera.position / kKm, d.AltitudeKm(camera.position), direction, z, size.z,
                    range_km, d.settings.aerial_perspective_steps, accumulated);
                image.at(x, y, z) = glm::vec4(value);
            }
        }
    }
    return image;
}

glm::dvec3 AtmosphereReference::TransmittanceFromLut(double r, double mu) const {
    return ref::GetTransmittanceToTopAtmosphereBoundary(impl_->atmosphere, impl_->transmittance,
                                                        r / kKm, mu);
}

glm::dvec3 AtmosphereReference::TransmittanceIntegrated(double r, double mu, int steps) const {
    return ref::ComputeTransmittanceToTopAtmosphereBoundary(impl_->atmosphere, r / kKm, mu, steps);
}

glm::dvec4 AtmosphereReference::InScattering(const glm::dvec3& origin, const glm::dvec3& direction,
                                             const Lights& lights, double distance,
                                             int steps) const {
    const Impl& d = *impl_;
    const ref::ScatteringResult r = ref::IntegrateScatteredLuminance(
        d.atmosphere, d.transmittance, d.multiple_scattering, d.irradiance,
        d.ToLightSet(lights, origin), origin / kKm, d.AltitudeKm(origin), direction, 0.0,
        distance / kKm, steps, false);
    return {r.luminance, (r.transmittance.x + r.transmittance.y + r.transmittance.z) / 3.0};
}

glm::dvec3 AtmosphereReference::RayMarch(const glm::dvec3& origin, const glm::dvec3& direction,
                                         const Lights& lights, int steps) const {
    const Impl& d = *impl_;
    return ref::IntegrateScatteredLuminance(d.atmosphere, d.transmittance, d.multiple_scattering,
                                            d.irradiance, d.ToLightSet(lights, origin),
                                            origin / kKm, d.AltitudeKm(origin), direction, 0.0, 1e9,
                                            steps, true)
        .luminance;
}

glm::dvec3 AtmosphereReference::SingleScattering(const glm::dvec3& origin,
                                                 const glm::dvec3& direction, const Lights& lights,
                                                 int steps) const {
    const Impl& d = *impl_;
    const glm::ivec2 size = d.settings.multiple_scattering_texture_size();
    const Texture2D no_multiple_scattering(size.x, size.y);
    const Texture2D no_irradiance(d.irradiance.width(), d.irradiance.height());
    return ref::IntegrateScatteredLuminance(d.atmosphere, d.transmittance, no_multiple_scattering,
                                            no_irradiance, d.ToLightSet(lights, origin),
                                            origin / kKm, d.AltitudeKm(origin), direction, 0.0, 1e9,
                                            steps, true)
        .luminance;
}

glm::dvec3 AtmosphereReference::SampleSkyView(const LutImage& sky_view, const glm::dvec3& camera,
                                              const glm::dvec3& sun_direction,
                                              const glm::dvec3& direction) const {
    const Texture2D texture = FromImage(sky_view, true);
    return ref::SampleSkyView(impl_->atmosphere, texture, camera / kKm, impl_->AltitudeKm(camera),
                              sun_direction, direction);
}

}  // namespace zenith::sky::reference
