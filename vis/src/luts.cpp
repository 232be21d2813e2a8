#include "luts.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "reference/atmosphere_functions.h"
#include "reference/lut_texture.h"
#include "shader_parameters.h"
#include "zenith/base/error.h"
#include "zenith/geo/ephemeris.h"
#include "zenith/geo/observer.h"
#include "zenith/geo/time.h"
#include "zenith/sky/atmosphere_renderer.h"
#include "zenith/sky/gl/context.h"
#include "zenith/sky/inspection.h"
#include "zenith/sky/lighting.h"
#include "zenith/sky/reference/path_tracer.h"
#include "zenith/sky/sky_state.h"

namespace zenith::vis {
namespace ref = zenith::sky::ref;
namespace {

constexpr double kKm = 1000.0;
constexpr double kDeg = 0.017453292519943295;  // rad per degree
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

ref::AtmosphereParameters Parameters(const Luts& luts) {
    return sky::MakeShaderParameters<ref::AtmosphereParameters>(luts.atmosphere);
}

double TexelCentre(int i, int n) { return (i + 0.5) / n; }

}  // namespace

std::string_view LutName(LutKind kind) {
    switch (kind) {
        case LutKind::kTransmittance:
            return "transmittance";
        case LutKind::kMultipleScattering:
            return "multiple-scattering";
        case LutKind::kIrradiance:
            return "irradiance";
        case LutKind::kSkyView:
            return "sky-view";
        case LutKind::kAerialPerspective:
            return "aerial-perspective";
    }
    return "?";
}

LutKind ParseLutKind(std::string_view name) {
    for (LutKind kind : kAllLuts) {
        if (name == LutName(kind)) return kind;
    }
    throw ArgumentError(fmt::format(
        "--lut = '{}' is not a LUT (expected transmittance, multiple-scattering, irradiance, "
        "sky-view or aerial-perspective)",
        name));
}

Channel ParseChannel(std::string_view name) {
    if (name == "r") return Channel::kR;
    if (name == "g") return Channel::kG;
    if (name == "b") return Channel::kB;
    if (name == "luminance" || name == "y") return Channel::kLuminance;
    throw ArgumentError(
        fmt::format("--channel = '{}' is not a channel (expected r, g, b or luminance)", name));
}

std::string_view ChannelName(Channel channel) {
    switch (channel) {
        case Channel::kR:
            return "R";
        case Channel::kG:
            return "G";
        case Channel::kB:
            return "B";
        case Channel::kLuminance:
            return "luminance";
    }
    return "?";
}

double ChannelValue(const glm::dvec3& rgb, Channel channel) {
    switch (channel) {
        case Channel::kR:
            return rgb.r;
        case Channel::kG:
            return rgb.g;
        case Channel::kB:
            return rgb.b;
        case Channel::kLuminance:
            return 0.2126 * rgb.r + 0.7152 * rgb.g + 0.0722 * rgb.b;
    }
    return kNaN;
}

const sky::LutImage& Luts::Image(LutKind kind) const {
    switch (kind) {
        case LutKind::kTransmittance:
            return transmittance;
        case LutKind::kMultipleScattering:
            return multiple_scattering;
        case LutKind::kIrradiance:
            return irradiance;
        case LutKind::kSkyView:
            return sky_view;
        case LutKind::kAerialPerspective:
            return aerial_perspective;
    }
    return transmittance;
}

Luts ComputeLuts(const Scene& scene) {
    Luts luts;
    luts.atmosphere = sky::LoadAtmosphere(scene.preset);
    if (scene.quality == "pc") {
        luts.settings = sky::LutSettings::Pc();
    } else if (scene.quality == "mobile") {
        luts.settings = sky::LutSettings::Mobile();
    } else {
        throw ArgumentError(fmt::format("--quality = '{}' is not a quality (expected pc or mobile)",
                                        scene.quality));
    }
    sky::FrameSetup setup;
    setup.time = geo::TimeFromIso8601(scene.utc);
    setup.observer = geo::Observer(scene.lat_deg, scene.lon_deg, scene.height_m);
    setup.attitude = geo::Attitude::FromDegrees(scene.heading_deg, scene.pitch_deg, scene.roll_deg);
    setup.vertical_fov = scene.fov_deg * kDeg;
    setup.aspect = scene.aspect;
    const sky::SkyFrame frame = sky::BuildSkyFrame(geo::Ephemeris(), setup, luts.atmosphere);
    luts.camera = frame.view.camera;
    luts.lights = frame.scene.lights;
    luts.camera_altitude = glm::length(luts.camera.position) - luts.atmosphere.bottom_radius;
    luts.sun_elevation_deg = frame.sun_elevation / kDeg;

    auto context = sky::gl::CreateHeadlessContextFromEnvironment();
    luts.gl_description = context->description();
    {
        sky::AtmosphereRenderer renderer(luts.atmosphere, luts.settings);
        renderer.Update(frame.scene, frame.view);
        const sky::RendererInspection inspect(renderer);
        luts.transmittance = inspect.ReadTransmittance();
        luts.multiple_scattering = inspect.ReadMultipleScattering();
        luts.irradiance = inspect.ReadGroundIrradiance();
        luts.sky_view = inspect.ReadSkyView();
        luts.aerial_perspective = inspect.ReadAerialPerspective();
    }  // GL objects are freed while the context is still current
    context->ReleaseCurrent();
    return luts;
}

// --- texel centres -> physical coordinates -----------------------------------------------------

void TransmittanceTexelRMu(const Luts& luts, int x, int y, double* r, double* mu) {
    const glm::ivec2 size(luts.transmittance.size);
    double r_km = 0.0, mu_value = 0.0;
    ref::GetRMuFromTransmittanceTextureUv(Parameters(luts),
                                          ref::vec2(TexelCentre(x, size.x), TexelCentre(y, size.y)),
                                          size, r_km, mu_value);
    *r = r_km * kKm;
    *mu = mu_value;
}

void MultipleScatteringTexelMuSAltitude(const Luts& luts, int x, int y, double* mu_s,
                                        double* altitude) {
    // Each of the LUT's tiles (functions.glsl: MultipleScatteringTexel) has the same coordinates.
    const glm::ivec2 size = luts.settings.multiple_scattering_size;
    x %= size.x;
    const ref::AtmosphereParameters p = Parameters(luts);
    *mu_s = ref::SunCosineFromUnitRange(
        ref::GetUnitRangeFromTextureCoord(TexelCentre(x, size.x), size.x));
    // v = h / (R_t - R) (H20 §5.5), the inverse of GetMultipleScatteringTextureUv's x_h.
    *altitude = ref::GetUnitRangeFromTextureCoord(TexelCentre(y, size.y), size.y) *
                (p.top_radius - p.bottom_radius) * kKm;
}

double IrradianceTexelMuS(const Luts& luts, int x) {
    // GetGroundSkyIrradiance's u, inverted.
    const int n = luts.irradiance.size.x;
    return ref::SunCosineFromUnitRange(ref::GetUnitRangeFromTextureCoord(TexelCentre(x, n), n));
}

void SkyViewTexelAngles(const Luts& luts, int x, int y, double* view_zenith, double* azimuth) {
    const glm::ivec2 size(luts.sky_view.size);
    ref::GetViewFromSkyViewTextureUv(Parameters(luts), luts.camera_altitude / kKm,
                                     ref::vec2(TexelCentre(x, size.x), TexelCentre(y, size.y)),
                                     size, *view_zenith, *azimuth);
}

void AerialPerspectiveCellAngles(const Luts& luts, int x, int y, double* horizontal,
                                 double* vertical) {
    // interface.glsl CameraDirection: view = (ndc.x tan(fov/2) aspect, ndc.y tan(fov/2), -1).
    const glm::ivec3 size = luts.aerial_perspective.size;
    const double t = std::tan(0.5 * luts.camera.vertical_fov);
    const double ndc_x = 2.0 * TexelCentre(x, size.x) - 1.0;
    const double ndc_y = 2.0 * TexelCentre(y, size.y) - 1.0;
    *horizontal = std::atan(ndc_x * t * luts.camera.aspect);
    *vertical = std::atan(ndc_y * t);
}

double AerialPerspectiveSliceDepth(const Luts& luts, int z) {
    return TexelCentre(z, luts.aerial_perspective.size.z) * luts.settings.aerial_perspective_range;
}

// --- physical coordinates -> samples -----------------------------------------------------------

double HorizonZenithAngle(const Luts& luts, double altitude) {
    return ref::HorizonZenithAngle(Parameters(luts), altitude / kKm);
}

glm::dvec3 SampleTransmittance(const Luts& luts, double altitude, double mu) {
    const ref::AtmosphereParameters p = Parameters(luts);
    const double r = p.bottom_radius + altitude / kKm;
    if (ref::RayIntersectsGround(p, r, mu)) return glm::dvec3(kNaN);
    const ref::Texture2D texture = ref::FromImage(luts.transmittance);
    return ref::GetTransmittanceToTopAtmosphereBoundary(p, texture, r, mu);
}

glm::dvec3 SampleMultipleScattering(const Luts& luts, double altitude, double mu_s) {
    const ref::AtmosphereParameters p = Parameters(luts);
    return ref::GetMultipleScattering(p, ref::FromImage(luts.multiple_scattering),
                                      p.bottom_radius + altitude / kKm, mu_s);
}

glm::dvec3 SampleIrradiance(const Luts& luts, double mu_s) {
    return sky::SampleGroundIrradiance(luts.irradiance, mu_s);
}

glm::dvec3 SampleSkyView(const Luts& luts, double view_zenith, double azimuth) {
    const glm::ivec2 size(luts.sky_view.size);
    const ref::vec2 uv = ref::GetSkyViewTextureUv(Parameters(luts), luts.camera_altitude / kKm,
                                                  view_zenith, azimuth, size);
    return glm::dvec3(ref::FromImage(luts.sky_view, true).Sample(uv));
}

glm::dvec4 SampleAerialPerspectiveSlice(const Luts& luts, int z, double horizontal,
                                        double vertical) {
    const double t = std::tan(0.5 * luts.camera.vertical_fov);
    const double u = 0.5 + 0.5 * std::tan(horizontal) / (t * luts.camera.aspect);
    const double v = 0.5 + 0.5 * std::tan(vertical) / t;
    return ref::FromImage(luts.aerial_perspective, false, z).Sample(ref::vec2(u, v));
}

// --- curves ----------------------------------------------------------------------------------

Curve TransmittanceVersusZenith(const Luts& luts, double altitude,
                                const std::vector<double>& zenith_deg) {
    Curve curve;
    curve.label = fmt::format("h = {:g} km", altitude / kKm);
    const ref::AtmosphereParameters p = Parameters(luts);
    const ref::Texture2D texture = ref::FromImage(luts.transmittance);
    const double r = p.bottom_radius + altitude / kKm;
    for (double angle : zenith_deg) {
        const double mu = std::cos(angle * kDeg);
        if (ref::RayIntersectsGround(p, r, mu)) continue;
        curve.x.push_back(angle);
        curve.rgb.push_back(ref::GetTransmittanceToTopAtmosphereBoundary(p, texture, r, mu));
    }
    return curve;
}

Curve TransmittanceVersusAltitude(const Luts& luts, double zenith_deg,
                                  const std::vector<double>& altitudes) {
    Curve curve;
    curve.label = fmt::format("zenith {:g} deg", zenith_deg);
    const ref::AtmosphereParameters p = Parameters(luts);
    const ref::Texture2D texture = ref::FromImage(luts.transmittance);
    const double mu = std::cos(zenith_deg * kDeg);
    for (double altitude : altitudes) {
        const double r = p.bottom_radius + altitude / kKm;
        if (ref::RayIntersectsGround(p, r, mu)) continue;
        curve.x.push_back(altitude / kKm);
        curve.rgb.push_back(ref::GetTransmittanceToTopAtmosphereBoundary(p, texture, r, mu));
    }
    return curve;
}

namespace {
// Transmittance from a point at `altitude` toward the unit direction at `zenith_deg`, by the
// path tracer's own quadrature; NaN when the ray meets the ground.
double ReferenceMuDeg(double zenith_deg) { return std::cos(zenith_deg * kDeg); }
glm::dvec3 ReferenceTransmittance(const sky::Atmosphere& atmosphere, double altitude, double mu) {
    const glm::dvec3 position(0.0, 0.0, atmosphere.bottom_radius + altitude);
    const glm::dvec3 direction(std::sqrt(std::max(0.0, 1.0 - mu * mu)), 0.0, mu);
    return sky::reference::SunTransmittance(atmosphere, position, direction, 1e-8);
}
bool HitsGround(const sky::Atmosphere& atmosphere, double altitude, double mu) {
    const double r = atmosphere.bottom_radius + altitude;
    const double R = atmosphere.bottom_radius;
    return mu < 0.0 && r * r * (mu * mu - 1.0) + R * R >= 0.0;
}
}  // namespace

Curve ReferenceTransmittanceVersusZenith(const sky::Atmosphere& atmosphere, double altitude,
                                         const std::vector<double>& zenith_deg) {
    Curve curve;
    curve.label = fmt::format("h = {:g} km (reference)", altitude / kKm);
    for (double angle : zenith_deg) {
        const double mu = ReferenceMuDeg(angle);
        if (HitsGround(atmosphere, altitude, mu)) continue;
        curve.x.push_back(angle);
        curve.rgb.push_back(ReferenceTransmittance(atmosphere, altitude, mu));
    }
    return curve;
}

Curve ReferenceTransmittanceVersusAltitude(const sky::Atmosphere& atmosphere, double zenith_deg,
                                           const std::vector<double>& altitudes) {
    Curve curve;
    curve.label = fmt::format("zenith {:g} deg (reference)", zenith_deg);
    const double mu = ReferenceMuDeg(zenith_deg);
    for (double altitude : altitudes) {
        if (HitsGround(atmosphere, altitude, mu)) continue;
        curve.x.push_back(altitude / kKm);
        curve.rgb.push_back(ReferenceTransmittance(atmosphere, altitude, mu));
    }
    return curve;
}

// --- slices ----------------------------------------------------------------------------------

Slice MakeSlice(const Luts& luts, LutKind kind, Channel channel, int slice, int width, int height) {
    Slice s;
    s.width = width;
    s.height = kind == LutKind::kIrradiance ? 1 : height;
    s.values.assign(static_cast<std::size_t>(s.width) * static_cast<std::size_t>(s.height), kNaN);
    const ref::AtmosphereParameters p = Parameters(luts);
    const double top = (p.top_radius - p.bottom_radius) * kKm;
    const std::string channel_name(ChannelName(channel));
    auto grid = [&](double x0, double x1, double y0, double y1) {
        s.x0 = x0;
        s.dx = s.width > 1 ? (x1 - x0) / (s.width - 1) : 1.0;
        s.y0 = y0;
        s.dy = s.height > 1 ? (y1 - y0) / (s.height - 1) : 1.0;
    };
    auto set = [&](int i, int j, double value) {
        s.values[static_cast<std::size_t>(j) * static_cast<std::size_t>(s.width) +
                 static_cast<std::size_t>(i)] = value;
    };
    switch (kind) {
        case LutKind::kTransmittance: {
            s.title = fmt::format("Transmittance to the top of the atmosphere ({}), {}",
                                  channel_name, luts.atmosphere.name);
            s.x_title = "view zenith angle (deg)";
            s.y_title = "altitude (km)";
            s.value_title = std::string("T");  // not = "T": GCC 12 -Wrestrict false positive
            grid(0.0, 180.0, 0.0, top / kKm);
            const ref::Texture2D texture = ref::FromImage(luts.transmittance);
            for (int j = 0; j < s.height; ++j) {
                const double r = p.bottom_radius + s.y0 + j * s.dy;
                for (int i = 0; i < s.width; ++i) {
                    const double mu = std::cos((s.x0 + i * s.dx) * kDeg);
                    if (ref::RayIntersectsGround(p, r, mu)) continue;  // NaN: ray hits ground
                    set(i, j,
                        ChannelValue(
                            ref::GetTransmittanceToTopAtmosphereBoundary(p, texture, r, mu),
                            channel));
                }
            }
            break;
        }
        case LutKind::kMultipleScattering: {
            s.title = fmt::format("Multiple scattering Psi_ms ({}), {}", channel_name,
                                  luts.atmosphere.name);
            s.x_title = "sun zenith angle (deg)";
            s.y_title = "altitude (km)";
            s.value_title = "Psi_ms (per unit illuminance)";
            grid(0.0, 180.0, 0.0, top / kKm);
            const ref::Texture2D texture = ref::FromImage(luts.multiple_scattering);
            for (int j = 0; j < s.height; ++j) {
                const double r = p.bottom_radius + s.y0 + j * s.dy;
                for (int i = 0; i < s.width; ++i) {
                    const double mu_s = std::cos((s.x0 + i * s.dx) * kDeg);
                    set(i, j,
                        ChannelValue(ref::GetMultipleScattering(p, texture, r, mu_s), channel));
                }
            }
            break;
        }
        case LutKind::kIrradiance: {
            s.title =
                fmt::format("Ground sky irradiance ({}), {}", channel_name, luts.atmosphere.name);
            s.x_title = "sun zenith angle (deg)";
            s.y_title = "";
            s.value_title = "E_sky (per unit illuminance)";
            grid(0.0, 180.0, 0.0, 0.0);
            for (int i = 0; i < s.width; ++i) {
                set(i, 0,
                    ChannelValue(SampleIrradiance(luts, std::cos((s.x0 + i * s.dx) * kDeg)),
                                 channel));
            }
            break;
        }
        case LutKind::kSkyView: {
            s.title = fmt::format("Sky-View ({}), {} at h = {:.1f} km, sun elevation {:.1f} deg",
                                  channel_name, luts.atmosphere.name, luts.camera_altitude / kKm,
                                  luts.sun_elevation_deg);
            s.x_title = "azimuth from the sun (deg)";
            s.y_title = "view elevation (deg)";
            s.value_title = "luminance (cd/m^2)";
            grid(0.0, 360.0, -90.0, 90.0);
            const ref::Texture2D texture = ref::FromImage(luts.sky_view, true);
            const double altitude_km = luts.camera_altitude / kKm;
            const glm::ivec2 size(luts.sky_view.size);
            for (int j = 0; j < s.height; ++j) {
                const double view_zenith = (90.0 - (s.y0 + j * s.dy)) * kDeg;
                for (int i = 0; i < s.width; ++i) {
                    const double azimuth = std::fmod((s.x0 + i * s.dx) * kDeg, 2.0 * ref::kPi);
                    const ref::vec2 uv =
                        ref::GetSkyViewTextureUv(p, altitude_km, view_zenith, azimuth, size);
                    set(i, j, ChannelValue(ref::vec3(texture.Sample(uv)), channel));
                }
            }
            break;
        }
        case LutKind::kAerialPerspective: {
            const int slices = luts.aerial_perspective.size.z;
            if (slice < 0 || slice >= slices) {
                throw ArgumentError(fmt::format("--slice = {} is out of range (expected 0..{})",
                                                slice, slices - 1));
            }
            s.title = fmt::format("Aerial perspective slice {} (depth {:.1f} km), {} ({})", slice,
                                  AerialPerspectiveSliceDepth(luts, slice) / kKm, channel_name,
                                  luts.atmosphere.name);
            s.x_title = "horizontal angle from the view axis (deg)";
            s.y_title = "vertical angle from the view axis (deg)";
            s.value_title = "in-scattered luminance (cd/m^2)";
            const double half_v = 0.5 * luts.camera.vertical_fov;
            const double half_h = std::atan(std::tan(half_v) * luts.camera.aspect);
            grid(-half_h / kDeg, half_h / kDeg, -half_v / kDeg, half_v / kDeg);
            const ref::Texture2D texture = ref::FromImage(luts.aerial_perspective, false, slice);
            const double t = std::tan(half_v);
            for (int j = 0; j < s.height; ++j) {
                const double v = 0.5 + 0.5 * std::tan((s.y0 + j * s.dy) * kDeg) / t;
                for (int i = 0; i < s.width; ++i) {
                    const double u =
                        0.5 + 0.5 * std::tan((s.x0 + i * s.dx) * kDeg) / (t * luts.camera.aspect);
                    set(i, j, ChannelValue(ref::vec3(texture.Sample(ref::vec2(u, v))), channel));
                }
            }
            break;
        }
    }
    return s;
}

}  // namespace zenith::vis
