// The LUTs as the renderer computes them (AtmosphereRenderer on a headless GL context, read
// back), and their parameterisations in physical units. Every mapping between texture
// coordinates and (altitude, view zenith, sun zenith, azimuth, depth) is the renderer's own:
// the shared sky/shaders/atmosphere/functions.glsl compiled as C++ (sky/src/reference), and
// samples between texels use GL_LINEAR + GL_CLAMP_TO_EDGE semantics as the shaders do.
//
// Units: SI (metres, radians) unless the name says otherwise (_deg, _km).
#pragma once

#include <array>
#include <glm/glm.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "zenith/base/error.h"
#include "zenith/sky/atmosphere.h"
#include "zenith/sky/lut.h"

namespace zenith::vis {

// The frame the per-frame LUTs (Sky-View, aerial perspective) are made for: the parameters of
// `zenith render`, with its built-in scene (Zurich at 10 km, looking into the sunset) as default.
struct Scene {
    std::string preset = "earth";  // built-in name or JSON file
    std::string utc = "2024-06-21T19:00:00Z";
    double lat_deg = 47.45;
    double lon_deg = 8.56;
    double height_m = 10000.0;  // above the WGS84 ellipsoid
    double heading_deg = 300.0;
    double pitch_deg = 0.0;
    double roll_deg = 0.0;
    double fov_deg = 60.0;  // vertical
    double aspect = 16.0 / 9.0;
    std::string quality = "pc";  // pc | mobile (Hillaire 2020, Table 2)
};

enum class LutKind {
    kTransmittance,
    kMultipleScattering,
    kIrradiance,
    kSkyView,
    kAerialPerspective
};
inline constexpr std::array<LutKind, 5> kAllLuts = {
    LutKind::kTransmittance, LutKind::kMultipleScattering, LutKind::kIrradiance, LutKind::kSkyView,
    LutKind::kAerialPerspective};
// "transmittance", "multiple-scattering", "irradiance", "sky-view", "aerial-perspective".
std::string_view LutName(LutKind kind);
// Throws zenith::ArgumentError naming the value and the choices.
LutKind ParseLutKind(std::string_view name);

enum class Channel { kR, kG, kB, kLuminance };
Channel ParseChannel(std::string_view name);  // r | g | b | luminance
std::string_view ChannelName(Channel channel);
double ChannelValue(const glm::dvec3& rgb, Channel channel);  // Y = 0.2126 R + 0.7152 G + 0.0722 B

struct Luts {
    sky::Atmosphere atmosphere;
    sky::LutSettings settings;
    sky::Camera camera;
    sky::Lights lights;
    double camera_altitude = 0.0;  // m above the sphere
    double sun_elevation_deg = 0.0;
    std::string gl_description;
    sky::LutImage transmittance;
    sky::LutImage multiple_scattering;
    sky::LutImage irradiance;
    sky::LutImage sky_view;
    sky::LutImage aerial_perspective;

    const sky::LutImage& Image(LutKind kind) const;
};

// Loads the preset, places the camera and the lights as `zenith render` does, creates a headless
// GL context ($ZENITH_GL), runs the renderer's LUT passes and reads every LUT back. The context
// is released before returning, so VTK's own GL context can be made current afterwards.
Luts ComputeLuts(const Scene& scene);

// --- physical coordinates of texel centres (the renderer's inverse mappings) -------------------

// Transmittance texel -> distance from the planet centre r (m) and view zenith cosine mu.
void TransmittanceTexelRMu(const Luts& luts, int x, int y, double* r, double* mu);
// Multiple-scattering texel (in any of its tiles) -> sun zenith cosine mu_s and altitude (m).
void MultipleScatteringTexelMuSAltitude(const Luts& luts, int x, int y, double* mu_s,
                                        double* altitude);
// Irradiance texel -> sun zenith cosine mu_s.
double IrradianceTexelMuS(const Luts& luts, int x);
// Sky-View texel -> view zenith angle and azimuth from the sun (rad), at the camera's altitude.
void SkyViewTexelAngles(const Luts& luts, int x, int y, double* view_zenith, double* azimuth);
// Aerial-perspective cell -> horizontal and vertical angle from the view axis (rad), and slice
// -> depth of its centre (m): (z + 0.5) / N * range.
void AerialPerspectiveCellAngles(const Luts& luts, int x, int y, double* horizontal,
                                 double* vertical);
double AerialPerspectiveSliceDepth(const Luts& luts, int z);

// --- sampling in physical coordinates (forward mappings + GL_LINEAR) ---------------------------

// Transmittance from altitude h (m) along view zenith cosine mu to the top of the atmosphere,
// as the renderer looks it up. NaN where the ray hits the ground (outside the LUT's domain).
glm::dvec3 SampleTransmittance(const Luts& luts, double altitude, double mu);
glm::dvec3 SampleMultipleScattering(const Luts& luts, double altitude, double mu_s);
glm::dvec3 SampleIrradiance(const Luts& luts, double mu_s);
// Luminance per unit illuminance... as stored: cd/m^2 for the scene's lights.
glm::dvec3 SampleSkyView(const Luts& luts, double view_zenith, double azimuth);
// rgb = in-scattered luminance (cd/m^2), a = mean transmittance, at slice z.
glm::dvec4 SampleAerialPerspectiveSlice(const Luts& luts, int z, double horizontal,
                                        double vertical);

// Horizon zenith angle (rad) seen from altitude h (m): rays below it hit the ground.
double HorizonZenithAngle(const Luts& luts, double altitude);

// --- plot data -----------------------------------------------------------------------------

// One curve: x values and RGB values (NaN-free: points outside the domain are left out).
struct Curve {
    std::string label;
    std::vector<double> x;
    std::vector<glm::dvec3> rgb;
};

// Transmittance versus view zenith angle (deg) at `altitude` (m), sampled at the given angles
// (deg); angles whose rays hit the ground are left out.
Curve TransmittanceVersusZenith(const Luts& luts, double altitude,
                                const std::vector<double>& zenith_deg);
// Transmittance versus altitude (km) at a view zenith angle (deg), at the given altitudes (m).
Curve TransmittanceVersusAltitude(const Luts& luts, double zenith_deg,
                                  const std::vector<double>& altitudes);
// The same curves from the independent CPU reference (reference/path_tracer.h: adaptive
// quadrature of the optical depth, no LUT), for overlays.
Curve ReferenceTransmittanceVersusZenith(const sky::Atmosphere& atmosphere, double altitude,
                                         const std::vector<double>& zenith_deg);
Curve ReferenceTransmittanceVersusAltitude(const sky::Atmosphere& atmosphere, double zenith_deg,
                                           const std::vector<double>& altitudes);

// A LUT slice resampled on a regular grid of physical coordinates, for an image plot.
struct Slice {
    std::string title;
    std::string x_title;  // with unit
    std::string y_title;
    std::string value_title;
    int width = 0;
    int height = 0;
    double x0 = 0.0, dx = 1.0, y0 = 0.0, dy = 1.0;  // physical coordinates of sample (0, 0), steps
    std::vector<double> values;                     // x fastest; NaN outside the domain
};

// `slice` selects the aerial-perspective depth slice; `width` x `height` samples. The
// irradiance LUT is one-dimensional: its "slice" has height 1.
Slice MakeSlice(const Luts& luts, LutKind kind, Channel channel, int slice, int width, int height);

}  // namespace zenith::vis
