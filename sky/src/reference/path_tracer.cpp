// Independent CPU ground truth for sky luminance (see path_tracer.h). Everything here is written
// from the model definition, not from the renderer's shared GLSL, so that the two can disagree.
//
// Glossary: r = distance to the planet centre, h = altitude, nu = cos(camera ray, sun direction),
// tau = optical depth, sigma_bar = majorant of the extinction (1/m).
#include "zenith/sky/reference/path_tracer.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <numbers>
#include <thread>
#include <utility>

#include "reference/monte_carlo.h"

namespace zenith::sky::reference {
namespace {

using monte_carlo::DirectionAround;
using monte_carlo::ParallelFor;
using monte_carlo::SplitMix64;

// This tracer's random streams (monte_carlo::StreamSeed's salt).
std::uint64_t StreamSeed(std::uint64_t seed, std::uint64_t index) {
    return monte_carlo::StreamSeed(seed, index, 0x2545f4914f6cdd1dULL);
}

constexpr double kPi = std::numbers::pi;
// Relative slack on majorants so that rounding in the bound can never put sigma_t above it.
constexpr double kMajorantSlack = 1.0 + 1e-9;
// A path is ended after this many vertices even with max_bounces = 0; with Russian roulette
// the probability of reaching it is far below anything measurable.
constexpr int kMaxVerticesUnbounded = 1 << 20;
// Throughput below which a path plays Russian roulette at null collisions.
constexpr double kRouletteThroughput = 0.05;

double MaxComponent(const glm::dvec3& v) { return std::max({v.x, v.y, v.z}); }
double SumComponents(const glm::dvec3& v) { return v.x + v.y + v.z; }

double TentDensity(const Atmosphere& atmosphere, double altitude) {
    const double half_width = 0.5 * atmosphere.absorption_width;
    if (!(half_width > 0.0)) return 0.0;
    return std::max(0.0, 1.0 - std::abs(altitude - atmosphere.absorption_center) / half_width);
}

// Times in (t_min, t_max) where the ray crosses the spheres at the absorbing layer's kinks
// (bottom, peak, top of the tent): sigma_t has a corner there, so quadratures split there.
void AddTentBreakpoints(const Atmosphere& atmosphere, const glm::dvec3& origin,
                        const glm::dvec3& direction, double t_min, double t_max,
                        std::vector<double>& points) {
    const double half_width = 0.5 * atmosphere.absorption_width;
    if (!(half_width > 0.0)) return;
    for (const double altitude :
         {atmosphere.absorption_center - half_width, atmosphere.absorption_center,
          atmosphere.absorption_center + half_width}) {
        const double radius = atmosphere.bottom_radius + altitude;
        if (!(radius > 0.0)) continue;
        if (const auto hits = IntersectSphere(origin, direction, radius)) {
            for (const double t : {hits->t_near, hits->t_far}) {
                if (t > t_min && t < t_max) points.push_back(t);
            }
        }
    }
}

// --- Adaptive Gauss-Kronrod 7-15 (QUADPACK qk15 nodes and weights) ---------------------------

constexpr std::array<double, 8> kKronrodNodes = {
    0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
    0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
    0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
    0.207784955007898467600689403773245, 0.000000000000000000000000000000000};
constexpr std::array<double, 8> kKronrodWeights = {
    0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
    0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
    0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
    0.204432940075298892414161999234649, 0.209482141084727828012999174891714};
// 7-point Gauss weights, at the odd-indexed Kronrod nodes (1, 3, 5) and the centre.
constexpr std::array<double, 4> kGaussWeights = {
    0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
    0.381830050505118944950369775488975, 0.417959183673469387755102040816327};

struct Panel {
    double a;
    double b;
    glm::dvec3 value;
    glm::dvec3 error;
};

template <class F>
Panel Gk15(const F& f, double a, double b) {
    const double centre = 0.5 * (a + b);
    const double half = 0.5 * (b - a);
    const glm::dvec3 f_centre = f(centre);
    glm::dvec3 kronrod = kKronrodWeights[7] * f_centre;
    glm::dvec3 gauss = kGaussWeights[3] * f_centre;
    for (std::size_t i = 0; i < 7; ++i) {
        const double dx = half * kKronrodNodes[i];
        const glm::dvec3 sum = f(centre - dx) + f(centre + dx);
        kronrod += kKronrodWeights[i] * sum;
        if (i % 2 == 1) gauss += kGaussWeights[i / 2] * sum;
    }
    return {a, b, kronrod * half, glm::abs(kronrod - gauss) * half};
}

// Global adaptive refinement (bisect the panel of largest error) over the intervals between
// consecutive `points`, until every channel meets max(absolute, relative |I|).
template <class F>
glm::dvec3 IntegrateAdaptive(const F& f, const std::vector<double>& points,
                             double relative_tolerance, double absolute_tolerance) {
    constexpr std::size_t kMaxPanels = 4000;
    std::vector<Panel> panels;
    for (std::size_t i = 0; i + 1 < points.size(); ++i) {
        if (points[i + 1] > points[i]) panels.push_back(Gk15(f, points[i], points[i + 1]));
    }
    const auto by_error = [](const Panel& x, const Panel& y) {
        return MaxComponent(x.error) < MaxComponent(y.error);
    };
    std::make_heap(panels.begin(), panels.end(), by_error);
    for (;;) {
        glm::dvec3 value{0.0}, error{0.0};
        for (const Panel& panel : panels) {
            value += panel.value;
            error += panel.error;
        }
        const glm::dvec3 allowed =
            glm::max(glm::dvec3(absolute_tolerance), relative_tolerance * glm::abs(value));
        if (panels.empty() || glm::all(glm::lessThanEqual(error, allowed)) ||
            panels.size() >= kMaxPanels) {
            return value;
        }
        std::pop_heap(panels.begin(), panels.end(), by_error);
        const Panel worst = panels.back();
        panels.pop_back();
        const double middle = 0.5 * (worst.a + worst.b);
        if (!(middle > worst.a && middle < worst.b)) return value;  // cannot split further
        panels.push_back(Gk15(f, worst.a, middle));
        std::push_heap(panels.begin(), panels.end(), by_error);
        panels.push_back(Gk15(f, middle, worst.b));
        std::push_heap(panels.begin(), panels.end(), by_error);
    }
}

// --- Ray segments and majorants --------------------------------------------------------------

struct Segment {
    double length;
    bool hits_ground;
};

// From a point inside the atmosphere to where the ray leaves it: the ground or the top.
// on_ground: the origin is on the ground and the ray points up, so it cannot meet the ground.
Segment SegmentToBoundary(const Atmosphere& atmosphere, const glm::dvec3& origin,
                          const glm::dvec3& direction, bool on_ground) {
    if (!on_ground) {
        if (const auto ground = IntersectSphere(origin, direction, atmosphere.bottom_radius)) {
            if (ground->t_near > 0.0) return {ground->t_near, true};
            // An origin a rounding error below the ground, heading down, is on it.
            if (ground->t_far > 0.0 && glm::dot(origin, direction) < 0.0) return {0.0, true};
        }
    }
    const auto top = IntersectSphere(origin, direction, atmosphere.top_radius);
    return {top ? std::max(0.0, top->t_far) : 0.0, false};
}

// Upper bound of max over channels of sigma_t on origin + t direction, t in [t0, t1]: the
// exponential densities peak at the lowest point, the tent at the altitude nearest its centre.
double ExtinctionBound(const Atmosphere& atmosphere, const glm::dvec3& origin,
                       const glm::dvec3& direction, double t0, double t1) {
    const double t_closest = std::clamp(-glm::dot(origin, direction), t0, t1);
    const double r_min = glm::length(origin + t_closest * direction);
    const double r_max =
        std::max(glm::length(origin + t0 * direction), glm::length(origin + t1 * direction));
    const double h_min = r_min - atmosphere.bottom_radius;
    const double h_max = r_max - atmosphere.bottom_radius;
    const double rayleigh = std::exp(-h_min / atmosphere.rayleigh_scale_height);
    const double mie = std::exp(-h_min / atmosphere.mie_scale_height);
    const double tent =
        TentDensity(atmosphere, std::clamp(atmosphere.absorption_center, h_min, h_max));
    const glm::dvec3 bound = atmosphere.rayleigh_scattering * rayleigh +
                             atmosphere.MieExtinction() * mie +
                             atmosphere.absorption_extinction * tent;
    return MaxComponent(bound) * kMajorantSlack;
}

// Radii of the shells that cut free-flight segments into pieces with their own majorant, so that
// tentative collisions follow the density (which spans e^-80 over the Earth's atmosphere) instead
// of the density at the segment's lowest point: geometric in altitude from a quarter of the
// smallest scale height, plus the absorbing layer's kinks.
std::vector<double> MajorantShellRadii(const Atmosphere& atmosphere) {
    std::vector<double> radii;
    const double thickness = atmosphere.top_radius - atmosphere.bottom_radius;
    const double scale_height =
        std::min(atmosphere.rayleigh_scale_height, atmosphere.mie_scale_height);
    if (scale_height > 0.0) {
        for (double h = 0.25 * scale_height; h < thickness; h *= std::numbers::sqrt2) {
            radii.push_back(atmosphere.bottom_radius + h);
        }
    }
    const double half_width = 0.5 * atmosphere.absorption_width;
    if (half_width > 0.0) {
        for (const double h :
             {atmosphere.absorption_center - half_width, atmosphere.absorption_center,
              atmosphere.absorption_center + half_width}) {
            if (h > 0.0 && h < thickness) radii.push_back(atmosphere.bottom_radius + h);
        }
    }
    return radii;
}

// Tentative collisions along one free-flight segment [0, length] under a piecewise-constant
// majorant: constant between shell crossings, and re-bounded on the rest of the piece at every
// tentative collision. Both are valid because the exponential distance is memoryless and each
// majorant bounds sigma_t wherever it is used (Woodcock tracking with a piecewise majorant).
//
// The majorant is the bound times scale = max(factor, ...), raised so that at least
// min_collisions tentative collisions are expected on the segment: in optically thin air, where
// next-event estimation happens at every tentative collision, this samples the in-scattering
// integral instead of almost never.
class Tracker {
  public:
    Tracker(const Atmosphere& atmosphere, const std::vector<double>& shell_radii,
            const glm::dvec3& origin, const glm::dvec3& direction, double length, double factor,
            double min_collisions)
        : atmosphere_(atmosphere),
          origin_(origin),
          direction_(direction),
          length_(length),
          scale_(std::max(1.0, factor)) {
        for (const double radius : shell_radii) {
            if (const auto hits = IntersectSphere(origin, direction, radius)) {
                for (const double t : {hits->t_near, hits->t_far}) {
                    if (t > 0.0 && t < length) cuts_.push_back(t);
                }
            }
        }
        std::sort(cuts_.begin(), cuts_.end());
        cuts_.push_back(length);
        if (min_collisions > 0.0) {
            double expected = 0.0;
            double t = 0.0;
            for (const double cut : cuts_) {
                expected += ExtinctionBound(atmosphere, origin, direction, t, cut) * (cut - t);
                t = cut;
            }
            if (expected > 0.0) scale_ = std::max(scale_, min_collisions / expected);
        }
    }

    // Advances t to the next tentative collision and returns its majorant; 0 at the segment end.
    double Next(Rng& rng, double& t) {
        for (;;) {
            while (cuts_[next_cut_] <= t && next_cut_ + 1 < cuts_.size()) ++next_cut_;
            const double end = cuts_[next_cut_];
            if (t >= length_) return 0.0;
            const double sigma_bar =
                scale_ * ExtinctionBound(atmosphere_, origin_, direction_, t, end);
            if (sigma_bar > 0.0) {
                const double candidate = t - std::log1p(-rng.Uniform()) / sigma_bar;
                if (candidate < end) {
                    t = candidate;
                    return sigma_bar;
                }
            }
            t = end;
            if (end >= length_) return 0.0;
        }
    }

  private:
    const Atmosphere& atmosphere_;
    glm::dvec3 origin_;
    glm::dvec3 direction_;
    double length_;
    std::vector<double> cuts_;
    std::size_t next_cut_ = 0;
    double scale_;
};

glm::dvec3 ExtinctionAt(const Atmosphere& atmosphere, const glm::dvec3& position) {
    return EvaluateMedium(atmosphere, glm::length(position) - atmosphere.bottom_radius).extinction;
}

bool PlanetHidesSun(const Atmosphere& atmosphere, const glm::dvec3& position,
                    const glm::dvec3& sun_direction) {
    const double b = glm::dot(position, sun_direction);
    if (b >= 0.0) return false;  // the sun is above the local horizon plane of the centre
    const glm::dvec3 closest = position - b * sun_direction;
    return glm::dot(closest, closest) < atmosphere.bottom_radius * atmosphere.bottom_radius;
}

// --- Path tracer -----------------------------------------------------------------------------

struct PathContext {
    const Atmosphere& atmosphere;
    const PathTraceOptions& options;
    glm::dvec3 sun_direction;
    std::vector<double> shell_radii;
};

// Novák et al. 2014, ratio tracking: unbiased transmittance as the product of null-collision
// probabilities at tentative collisions under a piecewise majorant.
glm::dvec3 RatioTrackingTransmittance(const Atmosphere& atmosphere,
                                      const std::vector<double>& shell_radii,
                                      const glm::dvec3& origin, const glm::dvec3& direction,
                                      double length, double factor, Rng& rng) {
    glm::dvec3 transmittance{1.0};
    Tracker tracker(atmosphere, shell_radii, origin, direction, length, factor, 0.0);
    double t = 0.0;
    for (double sigma_bar; (sigma_bar = tracker.Next(rng, t)) > 0.0;) {
        const glm::dvec3 sigma_t = ExtinctionAt(atmosphere, origin + t * direction);
        transmittance *= glm::max(glm::dvec3(0.0), 1.0 - sigma_t / sigma_bar);
        if (!(MaxComponent(transmittance) > 0.0)) break;
    }
    return transmittance;
}

glm::dvec3 ShadowTransmittance(const PathContext& context, const glm::dvec3& position, Rng& rng) {
    const Atmosphere& atmosphere = context.atmosphere;
    if (PlanetHidesSun(atmosphere, position, context.sun_direction)) return glm::dvec3(0.0);
    if (!context.options.ratio_tracking_shadows) {
        return SunTransmittance(atmosphere, position, context.sun_direction,
                                context.options.shadow_relative_tolerance);
    }
    const auto top = IntersectSphere(position, context.sun_direction, atmosphere.top_radius);
    const double length = top ? std::max(0.0, top->t_far) : 0.0;
    return RatioTrackingTransmittance(atmosphere, context.shell_radii, position,
                                      context.sun_direction, length,
                                      context.options.majorant_factor, rng);
}

// One path from the camera; returns its luminance estimate (cd/m² per channel).
//
// Free flight is weighted delta tracking with the spectral (RGB) extension of Kutz et al. 2017
// ("Spectral and decomposition tracking"): one scalar majorant sigma_bar >= max_c sigma_t,c; at
// each tentative collision the path scatters with probability P_s = Σ w σs / (Σ w σs + Σ w σn)
// (history-aware, w the per-channel throughput), else goes on (null collision); the weights
// w σ / (sigma_bar P) keep every channel unbiased, and their sum never grows. Absorption stays
// in the weights, so with no further vertex allowed this is ratio tracking (Novák et al. 2014),
// whose relative variance is about e^(τ / s) - 1 for a majorant s times sigma_t: hence
// majorant_factor. The majorant is piecewise constant between altitude shells and re-bounded
// at every tentative collision.
//
// Next-event estimation toward the sun is done at every tentative collision with its expected
// weight σs/sigma_bar (not only where the path happens to scatter), and at ground hits. With
// min_collisions_per_segment the majorant is raised in thin media, which turns the single-
// scattering part into a randomised quadrature along the ray.
glm::dvec3 TracePath(const PathContext& context, glm::dvec3 origin, glm::dvec3 direction,
                     Rng& rng) {
    const Atmosphere& atmosphere = context.atmosphere;
    const PathTraceOptions& options = context.options;
    const glm::dvec3& sun = context.sun_direction;
    const int max_vertices = options.max_bounces > 0 ? options.max_bounces : kMaxVerticesUnbounded;
    glm::dvec3 throughput{1.0};
    glm::dvec3 luminance{0.0};
    bool on_ground = false;
    for (int vertices = 0;;) {
        const Segment segment = SegmentToBoundary(atmosphere, origin, direction, on_ground);
        const bool can_scatter = vertices + 1 < max_vertices;
        const double nu = glm::dot(direction, sun);
        const double rayleigh_phase = RayleighPhase(nu);
        const double mie_phase = CornetteShanksPhase(nu, atmosphere.mie_g);
        Tracker tracker(atmosphere, context.shell_radii, origin, direction, segment.length,
                        options.majorant_factor, options.min_collisions_per_segment);
        double t = 0.0;
        bool scattered = false;
        for (double sigma_bar; (sigma_bar = tracker.Next(rng, t)) > 0.0;) {
            const glm::dvec3 x = origin + t * direction;
            const Medium medium =
                EvaluateMedium(atmosphere, glm::length(x) - atmosphere.bottom_radius);
            // Hillaire 2020, Eq. 3, with the collision's expected scattering weight σs/σ̄.
            const glm::dvec3 sun_transmittance = ShadowTransmittance(context, x, rng);
            if (MaxComponent(sun_transmittance) > 0.0) {
                luminance += throughput *
                             (medium.rayleigh_scattering * rayleigh_phase +
                              medium.mie_scattering * mie_phase) *
                             sun_transmittance * atmosphere.solar_illuminance / sigma_bar;
            }
            // Scattering or null collision, with probabilities ∝ Σ_c w_c σ_x,c; absorption
            // stays in the weights (ratio tracking when no further vertex is allowed).
            const glm::dvec3 sigma_s = medium.Scattering();
            const glm::dvec3 sigma_n = glm::max(glm::dvec3(0.0), sigma_bar - medium.extinction);
            const double m_s = can_scatter ? SumComponents(throughput * sigma_s) : 0.0;
            const double m_n = SumComponents(throughput * sigma_n);
            if (!(m_s + m_n > 0.0)) return luminance;  // absorbed in every channel
            if (rng.Uniform() * (m_s + m_n) >= m_s) {
                throughput *= sigma_n * ((m_s + m_n) / (sigma_bar * m_n));
                // Russian roulette once little is left: every tentative collision further
                // costs a shadow ray.
                const double left = MaxComponent(throughput);
                if (left < kRouletteThroughput) {
                    if (rng.Uniform() * kRouletteThroughput >= left) return luminance;
                    throughput *= kRouletteThroughput / left;
                }
                continue;
            }
            // Real scattering: lobe chosen by the throughput-weighted Rayleigh share, direction
            // from that lobe, weight f / q with q the mixture pdf.
            const double rayleigh_share =
                SumComponents(throughput * medium.rayleigh_scattering) / m_s;
            const double cos_theta = rng.Uniform() < rayleigh_share
                                         ? SampleRayleighCosine(rng.Uniform())
                                         : SampleCornetteShanksCosine(atmosphere.mie_g, rng);
            const double p_rayleigh = RayleighPhase(cos_theta);
            const double p_mie = CornetteShanksPhase(cos_theta, atmosphere.mie_g);
            const double pdf = rayleigh_share * p_rayleigh + (1.0 - rayleigh_share) * p_mie;
            throughput *=
                (medium.rayleigh_scattering * p_rayleigh + medium.mie_scattering * p_mie) *
                ((m_s + m_n) / (sigma_bar * m_s * pdf));
            direction = DirectionAround(direction, cos_theta, 2.0 * kPi * rng.Uniform());
            origin = x;
            on_ground = false;
            scattered = true;
            break;
        }
        if (!scattered) {
            if (!segment.hits_ground || !options.ground) return luminance;  // space or black
            glm::dvec3 p = origin + segment.length * direction;
            p *= atmosphere.bottom_radius / glm::length(p);
            const glm::dvec3 normal = p / atmosphere.bottom_radius;
            const double cos_sun = glm::dot(normal, sun);
            if (cos_sun > 0.0) {
                luminance += throughput * atmosphere.ground_albedo / kPi * cos_sun *
                             ShadowTransmittance(context, p, rng) * atmosphere.solar_illuminance;
            }
            if (!can_scatter) return luminance;
            // Lambertian: cosine-weighted direction, weight (ρ/π cos) / (cos/π) = ρ.
            throughput *= atmosphere.ground_albedo;
            const double u = rng.Uniform();
            direction = DirectionAround(normal, std::sqrt(1.0 - u), 2.0 * kPi * rng.Uniform());
            origin = p;
            on_ground = true;
        }
        ++vertices;
        if (!(MaxComponent(throughput) > 0.0) || vertices >= max_vertices) return luminance;
        if (vertices >= options.russian_roulette_start) {
            const double survival = std::min(1.0, MaxComponent(throughput));
            if (rng.Uniform() >= survival) return luminance;
            throughput /= survival;
        }
    }
}

// Moves a camera above the atmosphere to where its ray enters it; false if it never does (or
// the camera is inside the planet, which sees nothing).
bool EnterAtmosphere(const Atmosphere& atmosphere, glm::dvec3& position,
                     const glm::dvec3& direction) {
    const double r = glm::length(position);
    if (r < atmosphere.bottom_radius) return false;
    if (r <= atmosphere.top_radius) return true;
    const auto top = IntersectSphere(position, direction, atmosphere.top_radius);
    if (!top || !(top->t_far > 0.0)) return false;
    position += std::max(0.0, top->t_near) * direction;
    // Rounding may leave it a hair outside, where the exit distance would be lost.
    const double r_entry = glm::length(position);
    if (r_entry > atmosphere.top_radius) position *= atmosphere.top_radius / r_entry;
    return true;
}

// --- Single scattering: adaptive Dormand-Prince 5(4) -----------------------------------------

// State along the camera ray: optical depth from the camera and in-scattered luminance / E.
struct State {
    glm::dvec3 tau{0.0};
    glm::dvec3 luminance{0.0};
    State operator+(const State& o) const { return {tau + o.tau, luminance + o.luminance}; }
    State operator*(double s) const { return {tau * s, luminance * s}; }
};

// Dormand & Prince 1980 tableau (the RK5(4)7M pair).
constexpr double kA21 = 1.0 / 5.0;
constexpr double kA31 = 3.0 / 40.0, kA32 = 9.0 / 40.0;
constexpr double kA41 = 44.0 / 45.0, kA42 = -56.0 / 15.0, kA43 = 32.0 / 9.0;
constexpr double kA51 = 19372.0 / 6561.0, kA52 = -25360.0 / 2187.0, kA53 = 64448.0 / 6561.0,
                 kA54 = -212.0 / 729.0;
constexpr double kA61 = 9017.0 / 3168.0, kA62 = -355.0 / 33.0, kA63 = 46732.0 / 5247.0,
                 kA64 = 49.0 / 176.0, kA65 = -5103.0 / 18656.0;
constexpr double kB1 = 35.0 / 384.0, kB3 = 500.0 / 1113.0, kB4 = 125.0 / 192.0,
                 kB5 = -2187.0 / 6784.0, kB6 = 11.0 / 84.0;
// 5th minus 4th order weights, for the error estimate.
constexpr double kE1 = 71.0 / 57600.0, kE3 = -71.0 / 16695.0, kE4 = 71.0 / 1920.0,
                 kE5 = -17253.0 / 339200.0, kE6 = 22.0 / 525.0, kE7 = -1.0 / 40.0;

// Absolute error floor of the in-scattered luminance / E (1/sr): 1e-25 of the sun, far below
// anything displayable, keeps the controller from chasing relative precision in darkness.
constexpr double kLuminanceFloor = 1e-25;

template <class F>
void IntegrateDormandPrince(const F& f, double a, double b, double relative_tolerance, State& y) {
    if (!(b > a)) return;
    double h = (b - a) / 16.0;
    double t = a;
    State k1 = f(t, y);
    for (int steps = 0; t < b && steps < 1000000; ++steps) {
        const bool last = t + h >= b;
        if (last) h = b - t;
        const State k2 = f(t + h / 5.0, y + k1 * (h * kA21));
        const State k3 = f(t + h * 3.0 / 10.0, y + (k1 * kA31 + k2 * kA32) * h);
        const State k4 = f(t + h * 4.0 / 5.0, y + (k1 * kA41 + k2 * kA42 + k3 * kA43) * h);
        const State k5 =
            f(t + h * 8.0 / 9.0, y + (k1 * kA51 + k2 * kA52 + k3 * kA53 + k4 * kA54) * h);
        const State k6 =
            f(t + h, y + (k1 * kA61 + k2 * kA62 + k3 * kA63 + k4 * kA64 + k5 * kA65) * h);
        const State y_new = y + (k1 * kB1 + k3 * kB3 + k4 * kB4 + k5 * kB5 + k6 * kB6) * h;
        const State k7 = f(t + h, y_new);
        const State error = (k1 * kE1 + k3 * kE3 + k4 * kE4 + k5 * kE5 + k6 * kE6 + k7 * kE7) * h;
        // An optical-depth error is a relative luminance error, so tau is held to an absolute
        // tolerance (relative once tau > 1); the luminance to a relative one.
        const glm::dvec3 tau_scale =
            relative_tolerance * glm::max(glm::dvec3(1.0), glm::abs(y_new.tau));
        const glm::dvec3 luminance_scale =
            relative_tolerance * glm::max(glm::abs(y.luminance), glm::abs(y_new.luminance)) +
            kLuminanceFloor;
        const double norm = std::max(MaxComponent(glm::abs(error.tau) / tau_scale),
                                     MaxComponent(glm::abs(error.luminance) / luminance_scale));
        // A step too short to move t is taken whatever its error (it cannot be refined).
        const bool stalled = t + h == t || h < 1e-12 * (b - a);
        if (norm <= 1.0 || stalled) {
            t = last ? b : t + h;
            y = y_new;
            k1 = k7;  // first-same-as-last
        }
        const double factor = norm > 0.0 ? 0.9 * std::pow(norm, -0.2) : 5.0;
        h *= std::clamp(factor, 0.2, 5.0);
    }
}

}  // namespace

// --- Public: medium, phase functions, sampling -----------------------------------------------

Medium EvaluateMedium(const Atmosphere& atmosphere, double altitude) {
    const double rayleigh = std::exp(-altitude / atmosphere.rayleigh_scale_height);
    const double mie = std::exp(-altitude / atmosphere.mie_scale_height);
    Medium medium;
    medium.rayleigh_scattering = atmosphere.rayleigh_scattering * rayleigh;
    medium.mie_scattering = atmosphere.mie_scattering * mie;
    medium.extinction = medium.rayleigh_scattering + atmosphere.MieExtinction() * mie +
                        atmosphere.absorption_extinction * TentDensity(atmosphere, altitude);
    return medium;
}

double RayleighPhase(double cos_theta) {
    return 3.0 / (16.0 * kPi) * (1.0 + cos_theta * cos_theta);  // Hillaire 2020, §4
}

double CornetteShanksPhase(double cos_theta, double g) {
    // Hillaire 2020, §4 (Cornette & Shanks 1992).
    const double g2 = g * g;
    const double denominator = std::max(1e-300, 1.0 + g2 - 2.0 * g * cos_theta);
    return 3.0 / (8.0 * kPi) * (1.0 - g2) * (1.0 + cos_theta * cos_theta) /
           ((2.0 + g2) * denominator * std::sqrt(denominator));
}

double CornetteShanksMeanCosine(double g) {
    const double g2 = g * g;
    return 3.0 * g * (4.0 + g2) / (5.0 * (2.0 + g2));
}

Rng::Rng(std::uint64_t seed) {
    std::uint64_t state = seed;
    for (std::uint64_t& word : s_) word = SplitMix64(state);
}

std::uint64_t Rng::NextU64() {
    const auto rotl = [](std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); };
    const std::uint64_t result = rotl(s_[1] * 5, 7) * 9;
    const std::uint64_t t = s_[1] << 17;
    s_[2] ^= s_[0];
    s_[3] ^= s_[1];
    s_[1] ^= s_[2];
    s_[0] ^= s_[3];
    s_[2] ^= t;
    s_[3] = rotl(s_[3], 45);
    return result;
}

double Rng::Uniform() { return static_cast<double>(NextU64() >> 11) * 0x1.0p-53; }

double SampleRayleighCosine(double u) {
    // CDF (μ³ + 3μ + 4) / 8 = u, i.e. μ³ + 3μ - 2q = 0 with q = 4u - 2; one real root.
    const double q = 4.0 * u - 2.0;
    const double s = std::sqrt(q * q + 1.0);
    return std::clamp(std::cbrt(q + s) + std::cbrt(q - s), -1.0, 1.0);
}

double SampleCornetteShanksCosine(double g, Rng& rng) {
    // CS / HG = 3 (1 + μ²) / (2 (2 + g²)) <= 3 / (2 + g²): accept with (1 + μ²) / 2.
    for (;;) {
        const double u = rng.Uniform();
        double mu;
        if (std::abs(g) < 1e-6) {
            mu = 1.0 - 2.0 * u;
        } else {
            // Inverse CDF of Henyey-Greenstein in μ.
            const double s = (1.0 - g * g) / (1.0 - g + 2.0 * g * u);
            mu = std::clamp((1.0 + g * g - s * s) / (2.0 * g), -1.0, 1.0);
        }
        if (2.0 * rng.Uniform() < 1.0 + mu * mu) return mu;
    }
}

// --- Public: geometry and transmittance ------------------------------------------------------

std::optional<SphereHits> IntersectSphere(const glm::dvec3& origin, const glm::dvec3& direction,
                                          double radius) {
    // Through the closest point rather than b² - c: |origin|² and radius² are ~4e13 m², and
    // their difference would lose most of its digits near grazing.
    const double b = glm::dot(origin, direction);
    const glm::dvec3 closest = origin - b * direction;
    const double distance = glm::length(closest);
    if (distance > radius) return std::nullopt;
    const double half_chord = std::sqrt((radius - distance) * (radius + distance));
    return SphereHits{-b - half_chord, -b + half_chord};
}

glm::dvec3 OpticalDepth(const Atmosphere& atmosphere, const glm::dvec3& origin,
                        const glm::dvec3& direction, double length, double relative_tolerance) {
    if (!(length > 0.0)) return glm::dvec3(0.0);
    std::vector<double> points{0.0, length};
    AddTentBreakpoints(atmosphere, origin, direction, 0.0, length, points);
    std::sort(points.begin(), points.end());
    const auto f = [&](double t) { return ExtinctionAt(atmosphere, origin + t * direction); };
    return IntegrateAdaptive(f, points, relative_tolerance, 1e-300);
}

namespace {

// T(x, x + t_atmo l) whether or not the planet is in the way.
glm::dvec3 SunTransmittanceThroughAir(const Atmosphere& atmosphere, const glm::dvec3& position,
                                      const glm::dvec3& sun_direction, double relative_tolerance) {
    const auto top = IntersectSphere(position, sun_direction, atmosphere.top_radius);
    if (!top || !(top->t_far > 0.0)) return glm::dvec3(1.0);
    const double start = std::max(0.0, top->t_near);  // from above the atmosphere: enter first
    const glm::dvec3 entry = position + start * sun_direction;
    return glm::exp(
        -OpticalDepth(atmosphere, entry, sun_direction, top->t_far - start, relative_tolerance));
}

}  // namespace

glm::dvec3 SunTransmittance(const Atmosphere& atmosphere, const glm::dvec3& position,
                            const glm::dvec3& sun_direction, double relative_tolerance) {
    if (PlanetHidesSun(atmosphere, position, sun_direction)) return glm::dvec3(0.0);
    return SunTransmittanceThroughAir(atmosphere, position, sun_direction, relative_tolerance);
}

// --- Public: single scattering ---------------------------------------------------------------

glm::dvec3 SingleScattering(const Atmosphere& atmosphere, const glm::dvec3& position,
                            const glm::dvec3& direction, const glm::dvec3& sun_direction,
                            const SingleScatteringOptions& options) {
    const glm::dvec3 d = glm::normalize(direction);
    const glm::dvec3 sun = glm::normalize(sun_direction);
    glm::dvec3 origin = position;
    if (!EnterAtmosphere(atmosphere, origin, d)) return glm::dvec3(0.0);
    const Segment segment = SegmentToBoundary(atmosphere, origin, d, false);

    // The integrand jumps where the ray enters or leaves the planet's shadow, the cylinder of
    // radius bottom_radius behind the planet along the sun axis: split the integral there.
    std::vector<double> points{0.0, segment.length};
    AddTentBreakpoints(atmosphere, origin, d, 0.0, segment.length, points);
    {
        const glm::dvec3 o_perp = origin - glm::dot(origin, sun) * sun;
        const glm::dvec3 d_perp = d - glm::dot(d, sun) * sun;
        const double a = glm::dot(d_perp, d_perp);
        const double b = glm::dot(o_perp, d_perp);
        const double c =
            glm::dot(o_perp, o_perp) - atmosphere.bottom_radius * atmosphere.bottom_radius;
        const double discriminant = b * b - a * c;
        if (a > 0.0 && discriminant > 0.0) {
            const double root = std::sqrt(discriminant);
            for (const double t : {(-b - root) / a, (-b + root) / a}) {
                if (t > 0.0 && t < segment.length && glm::dot(origin + t * d, sun) < 0.0) {
                    points.push_back(t);
                }
            }
        }
    }
    std::sort(points.begin(), points.end());

    const double nu = glm::dot(d, sun);
    const double rayleigh_phase = RayleighPhase(nu);
    const double mie_phase = CornetteShanksPhase(nu, atmosphere.mie_g);
    // Hillaire 2020, Eq. 1-4 as an ODE in t: dτ/dt = σt, dL/dt = e^{-τ} σs p S (E applied last).
    // Vis (Eq. 4) is constant on each interval between breakpoints and taken at its middle, so
    // that rounding in the breakpoints cannot leave a jump inside an interval.
    bool lit = true;
    const auto f = [&](double t, const State& y) {
        const glm::dvec3 x = origin + t * d;
        const Medium medium = EvaluateMedium(atmosphere, glm::length(x) - atmosphere.bottom_radius);
        State derivative;
        derivative.tau = medium.extinction;
        if (!lit) return derivative;
        const glm::dvec3 sun_transmittance =
            SunTransmittanceThroughAir(atmosphere, x, sun, options.sun_relative_tolerance);
        derivative.luminance =
            glm::exp(-y.tau) *
            (medium.rayleigh_scattering * rayleigh_phase + medium.mie_scattering * mie_phase) *
            sun_transmittance;
        return derivative;
    };
    State y;
    for (std::size_t i = 0; i + 1 < points.size(); ++i) {
        lit = !PlanetHidesSun(atmosphere, origin + 0.5 * (points[i] + points[i + 1]) * d, sun);
        IntegrateDormandPrince(f, points[i], points[i + 1], options.relative_tolerance, y);
    }
    glm::dvec3 luminance = y.luminance * atmosphere.solar_illuminance;
    if (options.ground && segment.hits_ground) {
        glm::dvec3 p = origin + segment.length * d;
        p *= atmosphere.bottom_radius / glm::length(p);
        const double cos_sun = glm::dot(p, sun) / atmosphere.bottom_radius;
        if (cos_sun > 0.0) {
            luminance += glm::exp(-y.tau) * atmosphere.ground_albedo / kPi * cos_sun *
                         SunTransmittance(atmosphere, p, sun, options.sun_relative_tolerance) *
                         atmosphere.solar_illuminance;
        }
    }
    return luminance;
}

// --- Public: path tracing --------------------------------------------------------------------

namespace {

// Mean and standard error of `samples` paths: fixed chunks with their own streams, summed in
// chunk order, so the result does not depend on the number of threads or their scheduling.
// make_path() is called once per chunk and returns the path's estimator, value(rng).
template <class MakePath>
PathTraceResult Accumulate(const PathTraceOptions& options, const MakePath& make_path) {
    PathTraceResult result;
    result.samples = std::max<std::int64_t>(options.samples, 0);
    if (result.samples == 0) return result;
    constexpr std::int64_t kChunk = 64;
    const std::int64_t chunks = (result.samples + kChunk - 1) / kChunk;
    std::vector<std::pair<glm::dvec3, glm::dvec3>> sums(static_cast<std::size_t>(chunks));
    ParallelFor(chunks, options.threads, [&](std::int64_t chunk) {
        Rng rng(StreamSeed(options.seed, static_cast<std::uint64_t>(chunk)));
        auto path = make_path();
        glm::dvec3 sum{0.0}, sum_squares{0.0};
        const std::int64_t end = std::min(result.samples, (chunk + 1) * kChunk);
        for (std::int64_t i = chunk * kChunk; i < end; ++i) {
            const glm::dvec3 value = path(rng);
            sum += value;
            sum_squares += value * value;
        }
        sums[static_cast<std::size_t>(chunk)] = {sum, sum_squares};
    });
    glm::dvec3 sum{0.0}, sum_squares{0.0};
    for (const auto& [chunk_sum, chunk_squares] : sums) {
        sum += chunk_sum;
        sum_squares += chunk_squares;
    }
    const double n = static_cast<double>(result.samples);
    result.luminance = sum / n;
    if (result.samples > 1) {
        const glm::dvec3 variance = glm::max(
            glm::dvec3(0.0), (sum_squares - n * result.luminance * result.luminance) / (n - 1.0));
        result.standard_error = glm::sqrt(variance / n);
    }
    return result;
}

// A ray that misses the atmosphere: no light, from every path.
PathTraceResult Missed(const PathTraceOptions& options) {
    PathTraceResult result;
    result.samples = options.samples;
    return result;
}

}  // namespace

PathTraceResult PathTrace(const Atmosphere& atmosphere, const glm::dvec3& position,
                          const glm::dvec3& direction, const glm::dvec3& sun_direction,
                          const PathTraceOptions& options) {
    if (options.samples <= 0) return {};
    const glm::dvec3 d = glm::normalize(direction);
    glm::dvec3 origin = position;
    if (!EnterAtmosphere(atmosphere, origin, d)) return Missed(options);
    const PathContext context{atmosphere, options, glm::normalize(sun_direction),
                              MajorantShellRadii(atmosphere)};
    return Accumulate(options,
                      [&] { return [&](Rng& rng) { return TracePath(context, origin, d, rng); }; });
}

PathTraceResult PathTraceUniformSky(const Atmosphere& atmosphere, const glm::dvec3& position,
                                    const glm::dvec3& direction, const PathTraceOptions& options) {
    if (options.samples <= 0) return {};
    const glm::dvec3 d = glm::normalize(direction);
    glm::dvec3 origin = position;
    if (!EnterAtmosphere(atmosphere, origin, d)) return Missed(options);
    const PathContext context{atmosphere, options, glm::dvec3(0.0, 0.0, 1.0),
                              MajorantShellRadii(atmosphere)};
    // A uniform radiance of 1 on the top of the atmosphere is a sun of illuminance 1 from every
    // direction of the sphere: 4 pi times the mean over uniformly drawn sun directions.
    return Accumulate(options, [&] {
        return [&, local = context](Rng& rng) mutable {
            const double cos_theta = 1.0 - 2.0 * rng.Uniform();
            local.sun_direction =
                DirectionAround(glm::dvec3(0.0, 0.0, 1.0), cos_theta, 2.0 * kPi * rng.Uniform());
            return 4.0 * kPi * TracePath(local, origin, d, rng) / atmosphere.solar_illuminance;
        };
    });
}

// --- Public: camera and images ---------------------------------------------------------------

glm::dvec3 CameraRayDirection(const Camera& camera, int x, int y) {
    const glm::dvec3 forward = glm::normalize(camera.forward);
    const glm::dvec3 right = glm::normalize(glm::cross(forward, camera.up));
    const glm::dvec3 up = glm::cross(right, forward);
    const double tan_half = std::tan(0.5 * camera.vertical_fov);
    const double aspect = static_cast<double>(camera.width) / static_cast<double>(camera.height);
    const double u = (2.0 * (x + 0.5) / camera.width - 1.0) * tan_half * aspect;
    const double v = (1.0 - 2.0 * (y + 0.5) / camera.height) * tan_half;
    return glm::normalize(forward + u * right + v * up);
}

glm::dvec3 Image::At(int x, int y) const {
    const std::size_t i = 3 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                               static_cast<std::size_t>(x));
    return {rgb[i], rgb[i + 1], rgb[i + 2]};
}

namespace {

template <class PixelFunction>
Image RenderImage(const Camera& camera, int threads, const PixelFunction& pixel) {
    Image image;
    image.width = camera.width;
    image.height = camera.height;
    const std::int64_t count = static_cast<std::int64_t>(camera.width) * camera.height;
    image.rgb.assign(static_cast<std::size_t>(3 * count), 0.0f);
    ParallelFor(count, threads, [&](std::int64_t i) {
        const int x = static_cast<int>(i % camera.width);
        const int y = static_cast<int>(i / camera.width);
        const glm::dvec3 value = pixel(i, CameraRayDirection(camera, x, y));
        for (std::size_t c = 0; c < 3; ++c) {
            image.rgb[3 * static_cast<std::size_t>(i) + c] =
                static_cast<float>(value[static_cast<glm::length_t>(c)]);
        }
    });
    return image;
}

}  // namespace

Image RenderSingleScattering(const Atmosphere& atmosphere, const Camera& camera,
                             const glm::dvec3& sun_direction,
                             const SingleScatteringOptions& options, int threads) {
    return RenderImage(camera, threads, [&](std::int64_t, const glm::dvec3& direction) {
        return SingleScattering(atmosphere, camera.position, direction, sun_direction, options);
    });
}

Image RenderPathTraced(const Atmosphere& atmosphere, const Camera& camera,
                       const glm::dvec3& sun_direction, const PathTraceOptions& options,
                       int threads, Image* standard_error) {
    std::vector<glm::dvec3> errors(static_cast<std::size_t>(camera.width) *
                                   static_cast<std::size_t>(camera.height));
    Image image = RenderImage(camera, threads, [&](std::int64_t i, const glm::dvec3& direction) {
        PathTraceOptions pixel_options = options;
        pixel_options.threads = 1;
        pixel_options.seed = StreamSeed(options.seed, static_cast<std::uint64_t>(i));
        const PathTraceResult result =
            PathTrace(atmosphere, camera.position, direction, sun_direction, pixel_options);
        errors[static_cast<std::size_t>(i)] = result.standard_error;
        return result.luminance;
    });
    if (standard_error) {
        standard_error->width = image.width;
        standard_error->height = image.height;
        standard_error->rgb.resize(image.rgb.size());
        for (std::size_t i = 0; i < errors.size(); ++i) {
            for (std::size_t c = 0; c < 3; ++c) {
                standard_error->rgb[3 * i + c] =
                    static_cast<float>(errors[i][static_cast<glm::length_t>(c)]);
            }
        }
    }
    return image;
}

}  // namespace zenith::sky::reference
