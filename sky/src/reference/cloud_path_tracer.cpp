// Independent Monte Carlo reference for clouds (see cloud_path_tracer.h). Only the medium comes
// from the renderer (the cloud density of clouds/functions.glsl compiled as C++); the transport
// below is written from the radiative transfer equation, not from the renderer's march.
//
// Glossary: sigma_t extinction, sigma_s scattering, sigma_bar majorant (all 1/m, or 1/unit in
// the slab), tau optical depth, mu0 cosine of the sun's zenith angle, E0 the sun's irradiance
// normal to its beam. A "camera path" starts at the camera and looks for the sun (adjoint
// transport); a "photon" starts at the sun (slab only).
#include "zenith/sky/reference/cloud_path_tracer.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <thread>
#include <utility>

#include "clouds/cloud_parameters.h"
#include "reference/cloud_functions.h"
#include "reference/monte_carlo.h"
#include "zenith/base/error.h"
#include "zenith/sky/reference/path_tracer.h"

namespace zenith::sky::reference {
namespace {

using monte_carlo::DirectionAround;
using monte_carlo::ParallelFor;

// This tracer's random streams (monte_carlo::StreamSeed's salt).
std::uint64_t StreamSeed(std::uint64_t seed, std::uint64_t index) {
    return monte_carlo::StreamSeed(seed, index, 0x6a09e667f3bcc909ULL);
}

constexpr double kPi = std::numbers::pi;
constexpr double kMajorantSlack = 1.0 + 1e-9;
// A path is ended after this many vertices; with roulette and escape far beyond anything
// measurable (a conservative slab of tau = 1000 needs ~1e6 scatterings to cross).
constexpr int kMaxVertices = 1 << 22;
// Ratio tracking plays roulette once its estimate falls below this.
constexpr double kRatioRoulette = 0.1;
constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr glm::dvec3 kRec709{0.2126, 0.7152, 0.0722};

// Independent stream for (seed, index).
// Duff et al. 2017, "Building an orthonormal basis, revisited".
glm::dvec3 CosineWeighted(const glm::dvec3& normal, Rng& rng) {
    const double u = rng.Uniform();
    return DirectionAround(normal, std::sqrt(1.0 - u), 2.0 * kPi * rng.Uniform());
}

// Per-path estimates, summed in fixed chunks with their own streams and reduced in chunk order:
// results do not depend on the thread count or scheduling.
struct Moments {
    glm::dvec3 sum{0.0};
    glm::dvec3 sum_squares{0.0};
    double y_sum = 0.0;
    double y_sum_squares = 0.0;
    double vertices = 0.0;
};

template <class PathFunction>
CloudPathTraceResult RunPaths(const CloudPathTraceOptions& options, const PathFunction& path) {
    const auto start = std::chrono::steady_clock::now();
    CloudPathTraceResult result;
    result.samples = std::max<std::int64_t>(options.samples, 0);
    if (result.samples == 0) return result;
    constexpr std::int64_t kChunk = 256;
    const std::int64_t chunks = (result.samples + kChunk - 1) / kChunk;
    std::vector<Moments> moments(static_cast<std::size_t>(chunks));
    ParallelFor(chunks, options.threads, [&](std::int64_t chunk) {
        Rng rng(StreamSeed(options.seed, static_cast<std::uint64_t>(chunk)));
        Moments m;
        const std::int64_t end = std::min(result.samples, (chunk + 1) * kChunk);
        for (std::int64_t i = chunk * kChunk; i < end; ++i) {
            int vertices = 0;
            const glm::dvec3 value = path(rng, vertices);
            const double y = glm::dot(kRec709, value);
            m.sum += value;
            m.sum_squares += value * value;
            m.y_sum += y;
            m.y_sum_squares += y * y;
            m.vertices += vertices;
        }
        moments[static_cast<std::size_t>(chunk)] = m;
    });
    Moments total;
    for (const Moments& m : moments) {
        total.sum += m.sum;
        total.sum_squares += m.sum_squares;
        total.y_sum += m.y_sum;
        total.y_sum_squares += m.y_sum_squares;
        total.vertices += m.vertices;
    }
    const double n = static_cast<double>(result.samples);
    result.radiance = total.sum / n;
    result.luminance = total.y_sum / n;
    result.mean_vertices = total.vertices / n;
    if (result.samples > 1) {
        const glm::dvec3 variance =
            glm::max(glm::dvec3(0.0),
                     (total.sum_squares - n * result.radiance * result.radiance) / (n - 1.0));
        result.standard_error = glm::sqrt(variance / n);
        const double y_variance = std::max(
            0.0, (total.y_sum_squares - n * result.luminance * result.luminance) / (n - 1.0));
        result.luminance_error = std::sqrt(y_variance / n);
    }
    result.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
}

// --- Media for the one transport below ---------------------------------------------------------
//
// A medium gives, for one colour channel:
//   Exit(x, d, on_ground)      distance to where the ray leaves the domain, and whether there it
//                              meets the ground (Lambertian, may be black) or escapes
//   Pieces(x, d, length, out)  the ray [0, length] cut into pieces with a constant majorant each
//   At(x)                      extinction and the scattering coefficients of each component
//   GroundNormal(x), ground_albedo, sun

struct Exit {
    double length;
    bool ground;
};

struct Piece {
    double end;
    double majorant;
};

// Scattering by component: cloud (CloudPhase), Rayleigh, Mie (Cornette-Shanks).
struct Collision {
    double extinction = 0.0;
    double cloud = 0.0;
    double rayleigh = 0.0;
    double mie = 0.0;
    double Scattering() const { return cloud + rayleigh + mie; }
};

// The plane-parallel slab: z in [0, tau], unit extinction, the ground at z = 0.
struct SlabMedium {
    double tau;
    double albedo;
    double majorant;
    CloudPhase phase;
    double mie_g = 0.0;
    glm::dvec3 sun;
    double ground_albedo;
    bool black_ground;

    Exit ExitFrom(const glm::dvec3& x, const glm::dvec3& d, bool) const {
        if (d.z > 0.0) return {std::max(0.0, (tau - x.z) / d.z), false};
        if (d.z < 0.0) return {std::max(0.0, x.z / -d.z), true};
        return {kInfinity, false};
    }
    void Pieces(const glm::dvec3&, const glm::dvec3&, double length,
                std::vector<Piece>& out) const {
        out.clear();
        out.push_back({length, majorant});
    }
    Collision At(const glm::dvec3&) const { return {1.0, albedo, 0.0, 0.0}; }
    glm::dvec3 GroundNormal(const glm::dvec3&) const { return {0.0, 0.0, 1.0}; }
    bool SunHidden(const glm::dvec3&) const { return !(sun.z > 0.0); }
};

double AirBound(const Atmosphere& a, int c, double h_min, double h_max) {
    const double half_width = 0.5 * a.absorption_width;
    double tent = 0.0;
    if (half_width > 0.0) {
        const double h = std::clamp(a.absorption_center, h_min, h_max);
        tent = std::max(0.0, 1.0 - std::abs(h - a.absorption_center) / half_width);
    }
    return (a.rayleigh_scattering[c] * std::exp(-h_min / a.rayleigh_scale_height) +
            a.MieExtinction()[c] * std::exp(-h_min / a.mie_scale_height) +
            a.absorption_extinction[c] * tent) *
           kMajorantSlack;
}

// The spherical planet with its air and cloud layers, for channel c.
struct PlanetMedium {
    const CloudScene& scene;
    const std::vector<double>& shell_radii;  // sorted, every piece boundary
    int c;
    CloudPhase phase;
    double mie_g;
    glm::dvec3 sun;
    double ground_albedo;
    bool black_ground;

    const Atmosphere& air() const { return scene.atmosphere; }

    Exit ExitFrom(const glm::dvec3& x, const glm::dvec3& d, bool on_ground) const {
        if (!on_ground) {
            if (const auto g = IntersectSphere(x, d, air().bottom_radius)) {
                if (g->t_near > 0.0) return {g->t_near, true};
                if (g->t_far > 0.0 && glm::dot(x, d) < 0.0) return {0.0, true};
            }
        }
        const auto top = IntersectSphere(x, d, air().top_radius);
        return {top ? std::max(0.0, top->t_far) : 0.0, false};
    }

    void Pieces(const glm::dvec3& x, const glm::dvec3& d, double length,
                std::vector<Piece>& out) const {
        out.clear();
        std::vector<double> cuts;
        cuts.reserve(2 * shell_radii.size() + 1);
        for (const double radius : shell_radii) {
            if (const auto hits = IntersectSphere(x, d, radius)) {
                for (const double t : {hits->t_near, hits->t_far}) {
                    if (t > 0.0 && t < length) cuts.push_back(t);
                }
            }
        }
        std::sort(cuts.begin(), cuts.end());
        cuts.push_back(length);
        double t0 = 0.0;
        for (const double t1 : cuts) {
            if (!(t1 > t0)) continue;
            double majorant = 0.0;
            if (scene.air) {
                const double t_closest = std::clamp(-glm::dot(x, d), t0, t1);
                const double r_min = glm::length(x + t_closest * d);
                const double r_max = std::max(glm::length(x + t0 * d), glm::length(x + t1 * d));
                majorant +=
                    AirBound(air(), c, r_min - air().bottom_radius, r_max - air().bottom_radius);
            }
            if (scene.clouds != nullptr) {
                const double r_mid = glm::length(x + 0.5 * (t0 + t1) * d);
                for (const CloudField::Shell& shell : scene.clouds->shells()) {
                    if (r_mid > shell.inner_radius && r_mid < shell.outer_radius) {
                        majorant += shell.majorant;
                    }
                }
            }
            out.push_back({t1, majorant});
            t0 = t1;
        }
    }

    Collision At(const glm::dvec3& x) const {
        Collision collision;
        if (scene.air) {
            const Medium m = EvaluateMedium(air(), glm::length(x) - air().bottom_radius);
            collision.extinction = m.extinction[c];
            collision.rayleigh = m.rayleigh_scattering[c];
            collision.mie = m.mie_scattering[c];
        }
        if (scene.clouds != nullptr) {
            const double sigma_t = scene.clouds->Extinction(x);
            if (sigma_t > 0.0) {
                collision.extinction += sigma_t;
                collision.cloud = sigma_t * scene.clouds->Albedo();
            }
        }
        return collision;
    }
    glm::dvec3 GroundNormal(const glm::dvec3& x) const { return glm::normalize(x); }
    bool SunHidden(const glm::dvec3& x) const {
        const double b = glm::dot(x, sun);
        if (b >= 0.0) return false;
        const glm::dvec3 closest = x - b * sun;
        return glm::dot(closest, closest) < air().bottom_radius * air().bottom_radius;
    }
};

// Ratio tracking (Novák et al. 2014): an unbiased estimate of the transmittance from x toward
// the sun, with roulette once it is small.
template <class M>
double SunTransmittanceEstimate(const M& m, const glm::dvec3& x, bool on_ground, Rng& rng,
                                std::vector<Piece>& pieces) {
    if (m.SunHidden(x)) return 0.0;
    const Exit exit = m.ExitFrom(x, m.sun, on_ground);
    if (exit.ground) return 0.0;
    m.Pieces(x, m.sun, exit.length, pieces);
    double transmittance = 1.0;
    double t = 0.0;
    for (const Piece& piece : pieces) {
        if (piece.majorant > 0.0) {
            for (;;) {
                t -= std::log1p(-rng.Uniform()) / piece.majorant;
                if (t >= piece.end) break;
                const double sigma_t = m.At(x + t * m.sun).extinction;
                transmittance *= std::max(0.0, 1.0 - sigma_t / piece.majorant);
                if (transmittance < kRatioRoulette) {
                    if (rng.Uniform() * kRatioRoulette >= transmittance) return 0.0;
                    transmittance = kRatioRoulette;
                }
            }
        }
        t = piece.end;
    }
    return transmittance;
}

// Delta tracking (Woodcock): distance to the next real collision along [0, length], or
// kInfinity if the ray gets through.
template <class M>
double FreeFlight(const M& m, const glm::dvec3& x, const glm::dvec3& d, double length, Rng& rng,
                  std::vector<Piece>& pieces, Collision& collision) {
    m.Pieces(x, d, length, pieces);
    double t = 0.0;
    for (const Piece& piece : pieces) {
        if (piece.majorant > 0.0) {
            for (;;) {
                t -= std::log1p(-rng.Uniform()) / piece.majorant;
                if (t >= piece.end) break;
                collision = m.At(x + t * d);
                if (rng.Uniform() * piece.majorant < collision.extinction) return t;
            }
        }
        t = piece.end;
    }
    return kInfinity;
}

// Phase of the mixture at a collision, 1/sr.
template <class M>
double MixturePhase(const M& m, const Collision& collision, double cos_theta) {
    const double sigma_s = collision.Scattering();
    if (!(sigma_s > 0.0)) return 0.0;
    double p = 0.0;
    if (collision.cloud > 0.0) p += collision.cloud * CloudPhaseValue(m.phase, cos_theta);
    if (collision.rayleigh > 0.0) p += collision.rayleigh * RayleighPhase(cos_theta);
    if (collision.mie > 0.0) p += collision.mie * CornetteShanksPhase(cos_theta, m.mie_g);
    return p / sigma_s;
}

// Component chosen in proportion to its sigma_s, then its phase sampled exactly: a sample of
// the mixture phase, so the path weight does not change.
template <class M>
double SampleMixtureCosine(const M& m, const Collision& collision, Rng& rng) {
    const double u = rng.Uniform() * collision.Scattering();
    if (u < collision.cloud) return SampleCloudPhaseCosine(m.phase, rng.Uniform(), rng.Uniform());
    if (u < collision.cloud + collision.rayleigh) return SampleRayleighCosine(rng.Uniform());
    return SampleCornetteShanksCosine(m.mie_g, rng);
}

// One camera path from x along d: the radiance it brings back per unit E0 (1/sr), in the
// medium's channel. Next-event estimation toward the sun at every scattering vertex and ground
// hit; the sun is never hit directly (no disk), so there is no double counting.
template <class M>
double TraceCameraPath(const M& m, glm::dvec3 x, glm::dvec3 d, bool on_ground, Rng& rng,
                       const CloudPathTraceOptions& options, int& vertices) {
    const int max_vertices = options.max_bounces > 0 ? options.max_bounces : kMaxVertices;
    std::vector<Piece> pieces;
    pieces.reserve(64);
    double weight = 1.0;
    double radiance = 0.0;
    for (vertices = 0; vertices < max_vertices;) {
        const Exit exit = m.ExitFrom(x, d, on_ground);
        Collision collision;
        const double t = FreeFlight(m, x, d, exit.length, rng, pieces, collision);
        if (t < kInfinity) {
            x += t * d;
            on_ground = false;
            const double sigma_s = collision.Scattering();
            if (!(sigma_s > 0.0)) return radiance;  // absorbed
            weight *= sigma_s / collision.extinction;
            const double transmittance = SunTransmittanceEstimate(m, x, false, rng, pieces);
            if (transmittance > 0.0) {
                radiance += weight * MixturePhase(m, collision, glm::dot(d, m.sun)) * transmittance;
            }
            d = DirectionAround(d, SampleMixtureCosine(m, collision, rng),
                                2.0 * kPi * rng.Uniform());
        } else {
            if (!exit.ground || m.black_ground) return radiance;
            x += exit.length * d;
            const glm::dvec3 normal = m.GroundNormal(x);
            const double cos_sun = glm::dot(normal, m.sun);
            if (cos_sun > 0.0) {
                const double transmittance = SunTransmittanceEstimate(m, x, true, rng, pieces);
                radiance += weight * m.ground_albedo / kPi * cos_sun * transmittance;
            }
            // Cosine-weighted bounce: weight (rho / pi cos) / (cos / pi) = rho.
            weight *= m.ground_albedo;
            d = CosineWeighted(normal, rng);
            on_ground = true;
        }
        ++vertices;
        if (!(weight > 0.0)) return radiance;
        if (vertices >= options.russian_roulette_start) {
            const double survival = std::min(1.0, weight);
            if (rng.Uniform() >= survival) return radiance;
            weight /= survival;
        }
    }
    return radiance;
}

CloudPhase SlabPhase(const SlabProblem& p) { return p.phase; }

SlabMedium MakeSlab(const SlabProblem& problem) {
    if (!(problem.optical_depth > 0.0) || !(problem.mu0 > 0.0 && problem.mu0 <= 1.0) ||
        !(problem.majorant_factor >= 1.0)) {
        throw ArgumentError(
            "SlabProblem: optical_depth must be > 0, mu0 in (0, 1], majorant_factor >= 1");
    }
    SlabMedium m{};
    m.tau = problem.optical_depth;
    m.albedo = problem.single_scattering_albedo;
    m.majorant = problem.majorant_factor * kMajorantSlack;
    m.phase = SlabPhase(problem);
    m.sun = glm::dvec3(std::sqrt(std::max(0.0, 1.0 - problem.mu0 * problem.mu0)), 0.0, problem.mu0);
    m.ground_albedo = problem.ground_albedo;
    m.black_ground = !(problem.ground_albedo > 0.0);
    return m;
}

glm::dvec3 Channel(int c, double value) {
    glm::dvec3 v(0.0);
    v[c] = value;
    return v;
}

}  // namespace

// --- Phase functions --------------------------------------------------------------------------

double HenyeyGreensteinPhase(double cos_theta, double g) {
    const double denominator = std::max(1e-300, 1.0 + g * g - 2.0 * g * cos_theta);
    return (1.0 - g * g) / (4.0 * kPi * denominator * std::sqrt(denominator));
}

double SampleHenyeyGreensteinCosine(double g, double u) {
    if (std::abs(g) < 1e-6) return 1.0 - 2.0 * u;
    // Inverse of the CDF in cos_theta (e.g. Pharr et al., PBRT 3rd ed., §15.2.3).
    const double s = (1.0 - g * g) / (1.0 - g + 2.0 * g * u);
    return std::clamp((1.0 + g * g - s * s) / (2.0 * g), -1.0, 1.0);
}

double CloudPhaseValue(const CloudPhase& phase, double cos_theta) {
    const double forward = HenyeyGreensteinPhase(cos_theta, phase.forward_g);
    if (!(phase.lobe_weight > 0.0)) return forward;
    return (1.0 - phase.lobe_weight) * forward +
           phase.lobe_weight * HenyeyGreensteinPhase(cos_theta, phase.backward_g);
}

double SampleCloudPhaseCosine(const CloudPhase& phase, double u_lobe, double u) {
    return SampleHenyeyGreensteinCosine(
        u_lobe < phase.lobe_weight ? phase.backward_g : phase.forward_g, u);
}

// --- Cloud field ------------------------------------------------------------------------------

struct CloudField::Impl {
    std::vector<ref::CloudLayerParameters> layers;  // km
    std::vector<ref::RepeatTexture2D> weather_maps;
    ref::Texture3D shape;
    ref::Texture3D detail;
    double extinction = 0.0;  // 1/m at density 1
    double albedo = 1.0;
    CloudPhase phase;
    std::vector<Shell> shells;
    double bottom_radius = 0.0;

    ref::CloudSample Sample(const glm::dvec3& position, std::size_t* layer_index) const {
        const ref::vec3 km = position / 1000.0;
        const double r = glm::length(position);
        for (std::size_t i = 0; i < layers.size(); ++i) {
            if (r > shells[i].inner_radius && r < shells[i].outer_radius) {
                if (layer_index != nullptr) *layer_index = i;
                return ref::SampleCloudDensity(layers[i], weather_maps[i], shape, detail, km);
            }
        }
        return ref::CloudSample{0.0, 0.0, 0.0, 0.0, 0.0, 0.0, -1.0, -1.0};
    }
};

CloudField::CloudField(const clouds::Weather& weather, const CloudSettings& settings,
                       const clouds::CloudNoise& noise, double bottom_radius,
                       const CloudFieldOptions& options)
    : impl_(std::make_unique<Impl>()) {
    settings.Validate();
    clouds::Validate(weather);
    Impl& m = *impl_;
    m.extinction = settings.extinction;
    m.albedo = settings.albedo;
    m.phase = CloudPhase{settings.forward_g, settings.backward_g, settings.lobe_weight};
    m.bottom_radius = bottom_radius;
    m.shape = ref::ToTexture(noise.shape);
    m.detail = ref::ToTexture(noise.detail);
    for (const clouds::CloudLayer& layer : weather.layers) {
        const clouds::WeatherMap map = clouds::BuildWeatherMap(layer);
        const double top_fraction = clouds::LayerTopFraction(layer, map);
        m.layers.push_back(MakeCloudLayerParameters<ref::CloudLayerParameters>(
            layer, top_fraction, settings, bottom_radius, options.time));
        m.weather_maps.push_back(ref::ToTexture(map));
        double max_coverage = 0.0;
        for (const glm::vec4& texel : map.texels) {
            max_coverage = std::max(max_coverage, std::clamp(double(texel.x), 0.0, 1.0));
        }
        const double top =
            layer.base_altitude + (layer.top_altitude - layer.base_altitude) * top_fraction;
        m.shells.push_back(
            {bottom_radius + layer.base_altitude, bottom_radius + top,
             settings.extinction * layer.extinction_scale * max_coverage * kMajorantSlack});
    }
}

CloudField::~CloudField() = default;
CloudField::CloudField(CloudField&&) noexcept = default;
CloudField& CloudField::operator=(CloudField&&) noexcept = default;

double CloudField::Density(const glm::dvec3& position) const {
    return impl_->Sample(position, nullptr).density;
}

double CloudField::Extinction(const glm::dvec3& position) const {
    return impl_->extinction * Density(position);
}

double CloudField::Albedo() const { return impl_->albedo; }

const CloudPhase& CloudField::phase() const { return impl_->phase; }
const std::vector<CloudField::Shell>& CloudField::shells() const { return impl_->shells; }

double CloudField::MeanVerticalOpticalDepth(int n, int steps) const {
    const Impl& m = *impl_;
    if (m.layers.empty() || n < 1 || steps < 1) return 0.0;
    const double period = m.layers[0].weather_period * 1000.0;  // m
    double sum = 0.0;
    for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) {
            // A column at ground (x, y) around the map's origin, as the dome projection maps it.
            const double gx = ((i + 0.5) / n - 0.5) * period;
            const double gy = ((j + 0.5) / n - 0.5) * period;
            const double s = std::hypot(gx, gy);
            const double theta = s / m.bottom_radius;
            glm::dvec3 up(0.0, 0.0, 1.0);
            if (s > 0.0) {
                up =
                    glm::dvec3(std::sin(theta) * gx / s, std::sin(theta) * gy / s, std::cos(theta));
            }
            for (const Shell& shell : m.shells) {
                const double dr = (shell.outer_radius - shell.inner_radius) / steps;
                for (int k = 0; k < steps; ++k) {
                    sum += Extinction(up * (shell.inner_radius + (k + 0.5) * dr)) * dr;
                }
            }
        }
    }
    return sum / (static_cast<double>(n) * n);
}

// --- Clouds in the atmosphere -----------------------------------------------------------------

namespace {

std::vector<double> PlanetShellRadii(const CloudScene& scene) {
    const Atmosphere& a = scene.atmosphere;
    std::vector<double> radii;
    const double thickness = a.top_radius - a.bottom_radius;
    if (scene.air) {
        // Geometric in altitude from a quarter of the smallest scale height: the bound on each
        // piece follows the exponential density (as path_tracer.cpp's majorant shells).
        const double scale_height = std::min(a.rayleigh_scale_height, a.mie_scale_height);
        for (double h = 0.25 * scale_height; h < thickness; h *= std::numbers::sqrt2) {
            radii.push_back(a.bottom_radius + h);
        }
        const double half_width = 0.5 * a.absorption_width;
        for (const double h : {a.absorption_center - half_width, a.absorption_center,
                               a.absorption_center + half_width}) {
            if (half_width > 0.0 && h > 0.0 && h < thickness) radii.push_back(a.bottom_radius + h);
        }
    }
    if (scene.clouds != nullptr) {
        for (const CloudField::Shell& shell : scene.clouds->shells()) {
            radii.push_back(shell.inner_radius);
            radii.push_back(shell.outer_radius);
        }
    }
    std::sort(radii.begin(), radii.end());
    return radii;
}

PlanetMedium MakePlanet(const CloudScene& scene, const std::vector<double>& radii, int c) {
    return PlanetMedium{scene,
                        radii,
                        c,
                        scene.clouds != nullptr ? scene.clouds->phase() : CloudPhase{},
                        scene.atmosphere.mie_g,
                        glm::normalize(scene.sun_direction),
                        scene.atmosphere.ground_albedo[c],
                        !scene.ground || !(scene.atmosphere.ground_albedo[c] > 0.0)};
}

// Moves a camera above the atmosphere to where its ray enters it; false if it never does.
bool EnterAtmosphere(const Atmosphere& a, glm::dvec3& position, const glm::dvec3& direction) {
    const double r = glm::length(position);
    if (r < a.bottom_radius) return false;
    if (r <= a.top_radius) return true;
    const auto top = IntersectSphere(position, direction, a.top_radius);
    if (!top || !(top->t_far > 0.0)) return false;
    position += std::max(0.0, top->t_near) * direction;
    const double r_entry = glm::length(position);
    if (r_entry > a.top_radius) position *= a.top_radius / r_entry;
    return true;
}

}  // namespace

CloudPathTraceResult CloudPathTrace(const CloudScene& scene, const glm::dvec3& position,
                                    const glm::dvec3& direction,
                                    const CloudPathTraceOptions& options) {
    const glm::dvec3 d = glm::normalize(direction);
    glm::dvec3 origin = position;
    if (!EnterAtmosphere(scene.atmosphere, origin, d)) {
        CloudPathTraceResult empty;
        empty.samples = options.samples;
        return empty;
    }
    const bool on_ground = glm::length(origin) <= scene.atmosphere.bottom_radius * (1.0 + 1e-12);
    const std::vector<double> radii = PlanetShellRadii(scene);
    const std::array<PlanetMedium, 3> media{
        MakePlanet(scene, radii, 0), MakePlanet(scene, radii, 1), MakePlanet(scene, radii, 2)};
    return RunPaths(options, [&](Rng& rng, int& vertices) {
        const int c = std::min(2, static_cast<int>(3.0 * rng.Uniform()));
        const double value = TraceCameraPath(media[static_cast<std::size_t>(c)], origin, d,
                                             on_ground, rng, options, vertices);
        return Channel(c, 3.0 * value * scene.atmosphere.solar_illuminance[c]);
    });
}

CloudPathTraceResult CloudHorizontalIlluminance(const CloudScene& scene, const glm::dvec3& position,
                                                const CloudPathTraceOptions& options) {
    glm::dvec3 origin = position;
    const glm::dvec3 normal = glm::normalize(position);
    const bool on_ground = glm::length(origin) <= scene.atmosphere.bottom_radius * (1.0 + 1e-12);
    const std::vector<double> radii = PlanetShellRadii(scene);
    const std::array<PlanetMedium, 3> media{
        MakePlanet(scene, radii, 0), MakePlanet(scene, radii, 1), MakePlanet(scene, radii, 2)};
    return RunPaths(options, [&](Rng& rng, int& vertices) {
        const int c = std::min(2, static_cast<int>(3.0 * rng.Uniform()));
        const PlanetMedium& m = media[static_cast<std::size_t>(c)];
        std::vector<Piece> pieces;
        double value = 0.0;
        const double cos_sun = glm::dot(normal, m.sun);
        if (cos_sun > 0.0) {
            value += cos_sun * SunTransmittanceEstimate(m, origin, on_ground, rng, pieces);
        }
        const glm::dvec3 d = CosineWeighted(normal, rng);
        value += kPi * TraceCameraPath(m, origin, d, on_ground, rng, options, vertices);
        return Channel(c, 3.0 * value * scene.atmosphere.solar_illuminance[c]);
    });
}

// --- Slab -------------------------------------------------------------------------------------

SlabFluxes SlabFluxesFromRadiance(const SlabProblem& problem,
                                  const CloudPathTraceOptions& options) {
    const SlabMedium m = MakeSlab(problem);
    SlabFluxes fluxes;
    fluxes.direct_transmittance = std::exp(-problem.optical_depth / problem.mu0);
    const glm::dvec3 top(0.0, 0.0, m.tau);
    const glm::dvec3 bottom(0.0, 0.0, 0.0);
    // R: cosine-weighted directions leaving the top, traced back into the slab.
    const CloudPathTraceResult r = RunPaths(options, [&](Rng& rng, int& vertices) {
        const glm::dvec3 leaving = CosineWeighted(glm::dvec3(0.0, 0.0, 1.0), rng);
        return glm::dvec3(kPi / problem.mu0 *
                          TraceCameraPath(m, top, -leaving, false, rng, options, vertices));
    });
    CloudPathTraceOptions t_options = options;
    t_options.seed = StreamSeed(options.seed, 0x7472616e73ULL);
    const CloudPathTraceResult t = RunPaths(t_options, [&](Rng& rng, int& vertices) {
        const glm::dvec3 leaving = CosineWeighted(glm::dvec3(0.0, 0.0, -1.0), rng);
        return glm::dvec3(kPi / problem.mu0 *
                          TraceCameraPath(m, bottom, -leaving, true, rng, options, vertices));
    });
    fluxes.reflectance = r.radiance.x;
    fluxes.reflectance_error = r.standard_error.x;
    fluxes.transmittance = t.radiance.x + fluxes.direct_transmittance;
    fluxes.transmittance_error = t.standard_error.x;
    fluxes.samples = r.samples;
    fluxes.seconds = r.seconds + t.seconds;
    return fluxes;
}

SlabFluxes SlabFluxesFromPhotons(const SlabProblem& problem, const CloudPathTraceOptions& options) {
    const SlabMedium m = MakeSlab(problem);
    SlabFluxes fluxes;
    fluxes.direct_transmittance = std::exp(-problem.optical_depth / problem.mu0);
    // Each photon scores (up at the top, down at the bottom) in the x and y channels; absorption
    // is analog (the photon ends with probability 1 - albedo), so scores are counts.
    const CloudPathTraceResult result = RunPaths(options, [&](Rng& rng, int& vertices) {
        std::vector<Piece> pieces;
        glm::dvec3 x(0.0, 0.0, m.tau);
        glm::dvec3 d = -m.sun;
        double up = 0.0;
        double down = 0.0;
        for (vertices = 0; vertices < kMaxVertices; ++vertices) {
            const Exit exit = m.ExitFrom(x, d, false);
            Collision collision;
            const double t = FreeFlight(m, x, d, exit.length, rng, pieces, collision);
            if (t < kInfinity) {
                x += t * d;
                if (rng.Uniform() >= m.albedo) break;
                d = DirectionAround(d,
                                    SampleCloudPhaseCosine(m.phase, rng.Uniform(), rng.Uniform()),
                                    2.0 * kPi * rng.Uniform());
            } else if (!exit.ground) {
                up += 1.0;
                break;
            } else {
                down += 1.0;
                if (m.black_ground || rng.Uniform() >= m.ground_albedo) break;
                x = glm::dvec3(x.x + exit.length * d.x, x.y + exit.length * d.y, 0.0);
                d = CosineWeighted(glm::dvec3(0.0, 0.0, 1.0), rng);
            }
        }
        return glm::dvec3(up, down, 0.0);
    });
    fluxes.reflectance = result.radiance.x;
    fluxes.reflectance_error = result.standard_error.x;
    fluxes.transmittance = result.radiance.y;
    fluxes.transmittance_error = result.standard_error.y;
    fluxes.samples = result.samples;
    fluxes.seconds = result.seconds;
    return fluxes;
}

SlabRadianceResult SlabRadiance(const SlabProblem& problem, double mu, double phi,
                                const CloudPathTraceOptions& options) {
    const SlabMedium m = MakeSlab(problem);
    const double sin_theta = std::sqrt(std::max(0.0, 1.0 - mu * mu));
    const glm::dvec3 leaving(sin_theta * std::cos(phi), sin_theta * std::sin(phi), mu);
    const bool from_top = mu > 0.0;
    const glm::dvec3 camera(0.0, 0.0, from_top ? m.tau : 0.0);
    const CloudPathTraceResult result = RunPaths(options, [&](Rng& rng, int& vertices) {
        return glm::dvec3(TraceCameraPath(m, camera, -leaving, !from_top, rng, options, vertices));
    });
    return {result.radiance.x, result.standard_error.x, result.samples};
}

}  // namespace zenith::sky::reference
