// Independent Monte Carlo reference for clouds: a volumetric path tracer through the cloud field,
// the atmosphere around it and a Lambertian ground, in double precision, with scattering of
// unlimited order (issue 15, part 1).
//
// What it shares with the renderer: only the medium's definition. The cloud density is the
// renderer's own H16 Alg. 4.1 (sky/shaders/clouds/functions.glsl compiled as C++, evaluated on
// the CPU over the same weather maps and noise volumes), times CloudSettings::extinction; the
// phase function is the renderer's dual-lobe Henyey-Greenstein (F16 Eq. 18) with the same
// parameters; the single-scattering albedo is CloudSettings::albedo. The air is the independent
// atmosphere reference's medium (path_tracer.h: EvaluateMedium, Rayleigh and Cornette-Shanks
// phases). What it re-implements on purpose: everything about transport. No shadow march, no
// octaves, no ambient term, no LUT: free flights by delta tracking (Woodcock) under a majorant
// that is piecewise constant between spherical shells (the cloud layers' base and cloud top, and
// altitude shells for the air), sun transmittance by ratio tracking (Novák et al. 2014) under the
// same majorant, next-event estimation toward the sun at every scattering vertex and at the
// ground, phase sampling by exact inversion, Russian roulette on the path weight only (no
// bounce limit, unbiased). The renderer's march/lighting code (reference/cloud_march.h,
// cloud_trace.h) is not used.
//
// Units and conventions: positions in metres, planet-centred, in the weather frame (z through
// the weather map's origin, x east and y north there, which is the renderer's frame when the
// weather origin is the observer: sky_state.h WeatherFrame). `direction` is the camera ray;
// `sun_direction` points toward the sun. The sun is a directional source without a disk at the
// top of the atmosphere (illuminance atmosphere.solar_illuminance, lux per channel, unless
// overridden), so a camera ray never sees it directly; the light it delivers below is attenuated
// by the air and the clouds in the transport. Results are RGB radiance in cd/m² per channel
// (lux / sr), as path_tracer.h reports, plus Rec.709 luminance Y = 0.2126 R + 0.7152 G +
// 0.0722 B, each with the standard error of the mean estimated from the paths.
//
// Colour: each path carries one channel, chosen uniformly ("hero channel"), and contributes
// 3x its estimate in that channel (unbiased per channel). The cloud is grey; the air is not.
//
// Slab mode (SlabFluxes, SlabRadiance) runs the same free-flight, scattering, next-event and
// roulette code in a plane-parallel homogeneous slab of optical depth tau (unit extinction,
// thickness tau), for the closed forms and published tables that validate it.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <memory>
#include <vector>

#include "zenith/sky/atmosphere.h"
#include "zenith/sky/atmosphere_renderer.h"
#include "zenith/sky/clouds/noise.h"
#include "zenith/sky/clouds/weather.h"

namespace zenith::sky::reference {

// --- Phase functions (1/sr, normalised over the sphere) ---------------------------------------

// Henyey & Greenstein 1941. cos_theta between the incoming and outgoing propagation directions.
double HenyeyGreensteinPhase(double cos_theta, double g);
// Exact inverse CDF of Henyey-Greenstein in cos_theta, u in [0, 1).
double SampleHenyeyGreensteinCosine(double g, double u);

// The renderer's dual lobe (F16 Eq. 18): (1 - w) HG(forward_g) + w HG(backward_g).
// lobe_weight = 0 is plain Henyey-Greenstein with forward_g.
struct CloudPhase {
    double forward_g = 0.8;
    double backward_g = -0.3;
    double lobe_weight = 0.3;
};
double CloudPhaseValue(const CloudPhase& phase, double cos_theta);
// Lobe chosen with probability (1 - w, w), then its exact inverse CDF: samples CloudPhaseValue.
double SampleCloudPhaseCosine(const CloudPhase& phase, double u_lobe, double u);

// --- The cloud medium -------------------------------------------------------------------------

struct CloudFieldOptions {
    double time = 0.0;  // s of wind since the weather's epoch (CloudView::time)
};

// The clouds of a Weather as the renderer defines them: density in [0, 1] from the weather maps
// and noise volumes (functions.glsl SampleCloudDensity), extinction = density *
// settings.extinction, scattering = albedo * extinction, phase from settings.
class CloudField {
  public:
    CloudField(const clouds::Weather& weather, const CloudSettings& settings,
               const clouds::CloudNoise& noise, double bottom_radius,
               const CloudFieldOptions& options = {});
    ~CloudField();
    CloudField(CloudField&&) noexcept;
    CloudField& operator=(CloudField&&) noexcept;

    // Density in [0, 1] and extinction (1/m) at a planet-centred position (m, weather frame).
    double Density(const glm::dvec3& position) const;
    double Extinction(const glm::dvec3& position) const;
    // Single-scattering albedo of the clouds (settings.albedo), the same everywhere.
    double Albedo() const;
    const CloudPhase& phase() const;

    // Shells that hold all the density of each layer, bottom to top: radii (m) from the
    // layer's base to its clouds' top (CloudTopFraction), and a majorant of the extinction in
    // it (1/m): settings.extinction times the largest coverage texel (density <= coverage).
    struct Shell {
        double inner_radius;
        double outer_radius;
        double majorant;
    };
    const std::vector<Shell>& shells() const;

    // Mean vertical optical depth of the field over one weather-map tile of the lowest layer
    // around ground (0, 0): n x n columns, each integrated with `steps` midpoint samples per
    // layer. A description of a deck for reports, not used by the transport.
    double MeanVerticalOpticalDepth(int n = 32, int steps = 256) const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

// --- Clouds in the atmosphere -----------------------------------------------------------------

struct CloudScene {
    Atmosphere atmosphere;               // air, ground (ground_albedo), sun (solar_illuminance)
    const CloudField* clouds = nullptr;  // not owned; nullptr: a clear sky
    glm::dvec3 sun_direction{0.0, 0.0, 1.0};  // toward the sun, weather frame
    bool air = true;     // false: vacuum around the clouds (the air neither scatters nor absorbs)
    bool ground = true;  // false: a black ground
};

struct CloudPathTraceOptions {
    std::int64_t samples = 4096;  // paths
    std::uint64_t seed = 1;
    int threads = 2;  // 0: hardware concurrency; the result does not depend on it
    // Vertices before Russian roulette on the path weight (survival = min(1, weight)).
    int russian_roulette_start = 4;
    // Scattering orders kept (volume and ground vertices): 1 is single scattering. 0: all.
    int max_bounces = 0;
};

struct CloudPathTraceResult {
    glm::dvec3 radiance{0.0};        // cd/m² per channel (or lux for illuminances)
    glm::dvec3 standard_error{0.0};  // of the mean, per channel
    double luminance = 0.0;          // Rec.709 Y of radiance
    double luminance_error = 0.0;    // standard error of Y
    std::int64_t samples = 0;
    double mean_vertices = 0.0;  // scattering + ground vertices per path
    double seconds = 0.0;        // wall time
};

// Radiance arriving at `position` from `direction` (the camera ray). A camera above the
// atmosphere is moved to where its ray enters it.
CloudPathTraceResult CloudPathTrace(const CloudScene& scene, const glm::dvec3& position,
                                    const glm::dvec3& direction,
                                    const CloudPathTraceOptions& options = {});

// Illuminance (lux) on a horizontal surface facing up at `position` (radially outward): the sun
// through air and clouds (ratio tracking) plus pi times the mean radiance over cosine-weighted
// directions of the upper hemisphere. On the ground when position is at the ground's radius.
CloudPathTraceResult CloudHorizontalIlluminance(const CloudScene& scene, const glm::dvec3& position,
                                                const CloudPathTraceOptions& options = {});

// --- Plane-parallel slab (validation) ---------------------------------------------------------

// A homogeneous slab of optical depth tau over a Lambertian ground (albedo 0: black, the light
// leaving the slab's bottom is lost), lit at its top by a collimated beam of irradiance E0
// (normal to the beam) from cos(zenith) = mu0.
struct SlabProblem {
    double optical_depth = 1.0;
    CloudPhase phase{0.85, 0.0, 0.0};  // plain HG by default
    double single_scattering_albedo = 1.0;
    double ground_albedo = 0.0;
    double mu0 = 1.0;  // (0, 1]
    // Majorant / extinction >= 1: above 1, the free flights take null collisions too (tests).
    double majorant_factor = 1.0;
};

struct SlabFluxes {
    // Fluxes per incident flux mu0 E0: R upward at the top, T downward at the bottom (direct
    // beam included; every crossing counted, so with a bright ground T can exceed 1 - R).
    double reflectance = 0.0;
    double reflectance_error = 0.0;
    double transmittance = 0.0;
    double transmittance_error = 0.0;
    double direct_transmittance = 0.0;  // e^(-tau / mu0), exact
    std::int64_t samples = 0;           // per flux
    double seconds = 0.0;
};

// From camera paths (the estimator CloudPathTrace uses): R = (pi / mu0) <L / E0> over
// cosine-weighted directions leaving the top, T likewise under the bottom plus the direct beam.
SlabFluxes SlabFluxesFromRadiance(const SlabProblem& problem,
                                  const CloudPathTraceOptions& options = {});
// From light paths (analog photons counted where they cross the top and the bottom): a second,
// independent estimator of the same fluxes.
SlabFluxes SlabFluxesFromPhotons(const SlabProblem& problem,
                                 const CloudPathTraceOptions& options = {});

struct SlabRadianceResult {
    double value = 0.0;  // L / E0, 1/sr
    double standard_error = 0.0;
    std::int64_t samples = 0;
};

// Diffuse radiance leaving the slab in direction (mu, phi): mu > 0 up from its top (reflected),
// mu < 0 down from its bottom (transmitted, direct beam excluded). phi is the azimuth of that
// direction from the sun's azimuth: phi = 0 and mu = mu0 is exact backscatter toward the sun.
SlabRadianceResult SlabRadiance(const SlabProblem& problem, double mu, double phi,
                                const CloudPathTraceOptions& options = {});

}  // namespace zenith::sky::reference
