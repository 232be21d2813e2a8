// Independent CPU ground truth for sky luminance: deterministic single scattering and a volumetric
// Monte Carlo path tracer, in double precision, with no lookup table.
//
// This is what the LUT renderer (Hillaire 2020) is measured against, the role the paper's §6 gives
// to "a volumetric path tracer". It shares only the model definition (zenith::sky::Atmosphere) with
// the renderer: density, extinction, phase functions, ray-sphere intersection, transmittance and
// the quadratures are written here again on purpose, so that an error in the shared GLSL/C++ math
// shows up as a disagreement instead of cancelling out.
//
// Conventions: positions in metres from the planet centre, directions unit vectors. `direction`
// is the camera ray (the way the observer looks, opposite to the light's travel); `sun_direction`
// points from the scene towards the sun. The sun is a directional light of illuminance
// atmosphere.solar_illuminance (lux per channel) with no disk, as in the paper's comparison, so a
// camera ray never sees it directly. Results are RGB luminance in cd/m² per channel (lux / sr).
//
// Glossary: r = distance to the planet centre, h = r - bottom_radius (altitude),
// nu = cos(angle between the camera ray and the sun direction), the argument of the phase.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <optional>
#include <vector>

#include "zenith/sky/atmosphere.h"

namespace zenith::sky::reference {

// --- Medium ---------------------------------------------------------------------------------

// Scattering and extinction coefficients at one altitude, 1/m per channel.
struct Medium {
    glm::dvec3 rayleigh_scattering{0.0};
    glm::dvec3 mie_scattering{0.0};
    glm::dvec3 extinction{0.0};  // Rayleigh + Mie (scattering + absorption) + absorbing layer
    glm::dvec3 Scattering() const { return rayleigh_scattering + mie_scattering; }
};

Medium EvaluateMedium(const Atmosphere& atmosphere, double altitude);

// --- Phase functions (1/sr) and their sampling ------------------------------------------------

double RayleighPhase(double cos_theta);
double CornetteShanksPhase(double cos_theta, double g);
// Mean cosine of Cornette-Shanks: 3 g (4 + g²) / (5 (2 + g²)).
double CornetteShanksMeanCosine(double g);

// Small, fast, deterministic generator (xoshiro256**, seeded through SplitMix64).
class Rng {
  public:
    explicit Rng(std::uint64_t seed);
    std::uint64_t NextU64();
    double Uniform();  // [0, 1), 53 bits
  private:
    std::uint64_t s_[4];
};

// Exact inversion of the Rayleigh CDF (a depressed cubic, Cardano).
double SampleRayleighCosine(double u);
// Exact: Henyey-Greenstein proposal, accepted with probability (1 + cos²) / 2.
double SampleCornetteShanksCosine(double g, Rng& rng);

// --- Geometry and transmittance --------------------------------------------------------------

// Distances t_near <= t_far along origin + t direction where the ray meets the sphere of the
// given radius centred at the origin (either may be negative); nullopt if it misses.
struct SphereHits {
    double t_near;
    double t_far;
};
std::optional<SphereHits> IntersectSphere(const glm::dvec3& origin, const glm::dvec3& direction,
                                          double radius);

// Optical depth ∫ σt along origin + t direction, t in [0, length], by adaptive Gauss-Kronrod
// (7-15) with breakpoints at the absorbing layer's kinks; relative tolerance per channel.
glm::dvec3 OpticalDepth(const Atmosphere& atmosphere, const glm::dvec3& origin,
                        const glm::dvec3& direction, double length,
                        double relative_tolerance = 1e-10);

// Hillaire 2020, Eq. 4: S = Vis · T(x, x + t_atmo l); zero when the planet hides the sun.
glm::dvec3 SunTransmittance(const Atmosphere& atmosphere, const glm::dvec3& position,
                            const glm::dvec3& sun_direction, double relative_tolerance = 1e-10);

// --- Single scattering (deterministic) -------------------------------------------------------

struct SingleScatteringOptions {
    // Adds the sun-lit Lambertian ground at the end of the ray (single bounce, ρ/π E cosθ T).
    bool ground = true;
    // Error control of the adaptive Dormand-Prince 5(4) integration along the camera ray.
    double relative_tolerance = 1e-8;
    // Tolerance of each sun transmittance quadrature.
    double sun_relative_tolerance = 1e-10;
};

// Hillaire 2020, Eq. 1-4 with one light and no multiple scattering.
glm::dvec3 SingleScattering(const Atmosphere& atmosphere, const glm::dvec3& position,
                            const glm::dvec3& direction, const glm::dvec3& sun_direction,
                            const SingleScatteringOptions& options = {});

// --- Path tracing (Monte Carlo) --------------------------------------------------------------

struct PathTraceOptions {
    std::int64_t samples = 1024;  // paths
    // Scattering vertices (volume or ground) on a path, next-event estimation included: 1 is
    // single scattering. 0 = unbounded, ended by Russian roulette.
    int max_bounces = 0;
    // Vertices before Russian roulette may end a path (survival = max channel throughput).
    // Paths whose throughput falls below 0.05 also play it at null collisions. Unbounded paths
    // stop at 2^20 vertices, a bias far below anything measurable.
    int russian_roulette_start = 8;
    std::uint64_t seed = 1;
    // Minimum expected number of tentative collisions per free-flight segment: in an optically
    // thin atmosphere the majorant is raised so that every segment still gets in-scattering
    // samples (each tentative collision does next-event estimation), instead of almost none.
    double min_collisions_per_segment = 8.0;
    // Majorant / (bound of sigma_t) between altitude shells, >= 1. Null collisions with weight
    // (1 - sigma_t / majorant) estimate transmittance with relative variance ~ e^(τ/factor) - 1,
    // at a cost ~ factor τ shadow rays: 2 suits the Earth up to 50x denser atmospheres.
    double majorant_factor = 2.0;
    // Sun transmittance of shadow rays: ratio tracking (as the paper's path tracer) or the
    // deterministic quadrature of OpticalDepth (no variance, default).
    bool ratio_tracking_shadows = false;
    double shadow_relative_tolerance = 1e-7;
    bool ground = true;  // false: black ground
    int threads = 1;     // 0: hardware concurrency; result independent of it
};

struct PathTraceResult {
    glm::dvec3 luminance{0.0};       // mean, cd/m² per channel
    glm::dvec3 standard_error{0.0};  // of the mean, per channel
    std::int64_t samples = 0;
};

PathTraceResult PathTrace(const Atmosphere& atmosphere, const glm::dvec3& position,
                          const glm::dvec3& direction, const glm::dvec3& sun_direction,
                          const PathTraceOptions& options = {});

// The light scattered toward `position` along `direction` when the top of the atmosphere is lit
// by a uniform radiance of 1 (per channel) from every direction: the night sky's extraterrestrial
// light, as a sun of unit illuminance from every direction of the sphere (each path draws its
// own). Per unit radiance; the unscattered part, the transmittance to space, is not included.
PathTraceResult PathTraceUniformSky(const Atmosphere& atmosphere, const glm::dvec3& position,
                                    const glm::dvec3& direction,
                                    const PathTraceOptions& options = {});

// --- Camera and images -----------------------------------------------------------------------

struct Camera {
    int width = 64;
    int height = 64;
    double vertical_fov = 1.0;  // rad
    glm::dvec3 position{0.0, 6360e3 + 1.0, 0.0};
    glm::dvec3 forward{0.0, 0.0, -1.0};  // need not be unit
    glm::dvec3 up{0.0, 1.0, 0.0};        // need not be unit nor orthogonal to forward
};

// Ray through the centre of pixel (x, y), y = 0 the top row. A pinhole camera.
glm::dvec3 CameraRayDirection(const Camera& camera, int x, int y);

// Row-major RGB, top row first, 3 floats per pixel.
struct Image {
    int width = 0;
    int height = 0;
    std::vector<float> rgb;
    glm::dvec3 At(int x, int y) const;
};

// threads: 0 = hardware concurrency. Images do not depend on the thread count.
Image RenderSingleScattering(const Atmosphere& atmosphere, const Camera& camera,
                             const glm::dvec3& sun_direction,
                             const SingleScatteringOptions& options = {}, int threads = 0);
// Each pixel is an independent PathTrace with options.samples paths and a seed derived from
// options.seed and the pixel index; standard_error (optional) receives the per-pixel error.
Image RenderPathTraced(const Atmosphere& atmosphere, const Camera& camera,
                       const glm::dvec3& sun_direction, const PathTraceOptions& options = {},
                       int threads = 0, Image* standard_error = nullptr);

}  // namespace zenith::sky::reference
