#include "clouds/cloud_parameters.h"

#include <algorithm>
#include <cmath>
#include <mutex>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

#include "clouds/slab_transfer.h"
#include "reference/cloud_functions.h"
#include "zenith/base/error.h"

namespace zenith::sky {
namespace {

void Require(bool ok, const char* field, double value, const char* expected) {
    if (!ok) {
        std::ostringstream text;
        text << "CloudSettings::" << field << " = " << value << " (expected " << expected << ")";
        throw ArgumentError(text.str());
    }
}

static_assert(ref::kCloudSlabTableSize == kCloudSlabTableSize);

// The node (depth i, cosine j) of table t in CloudSlabTableNodes, and the nodes' optical depths
// and cosines (clouds/functions.glsl, CloudSlabTables).
std::size_t SlabNode(int table, int depth, int cosine) {
    return static_cast<std::size_t>((table * kCloudSlabTableSize + cosine) * kCloudSlabTableSize +
                                    depth);
}
double SlabNodeDepth(int depth) { return (std::exp2(depth) - 1.0) / 8.0; }
double SlabNodeCosine(int cosine) {
    const double v = double(cosine) / (kCloudSlabTableSize - 1);
    return 0.05 + 0.95 * v * v;
}

// The beam's cosine m less mu0 (CloudBeamCosine) at each node: from the exact slab's R (and
// T = 1 - R; ConservativeSlabTransfer) and CloudSlabReflectanceTransmittance's R, linear in m,
//   m = 2/3 - (R (4/3 + (1 - g) tau_total) - (1 - g) tau_total) / (1 - e(tau_total)),
// kept within [-0.6, 2] so that the field's flux A stays positive (m > -2/3 is enough) whatever
// the phase. Node 0 (tau_total = 0, where m no longer matters) takes node 1's.
void ComputeBeamOffsets(const ref::CloudScatteringParameters& p, double g, double f,
                        CloudSlabTableNodes& table) {
    std::vector<double> cosines;
    for (int j = 0; j < kCloudSlabTableSize; ++j) cosines.push_back(SlabNodeCosine(j));
    for (int i = 1; i < kCloudSlabTableSize; ++i) {
        const double tau = SlabNodeDepth(i);
        const std::vector<SlabTransfer> exact =
            ConservativeSlabTransfer(p.forward_g, p.backward_g, p.lobe_weight, tau, cosines);
        for (int j = 0; j < kCloudSlabTableSize; ++j) {
            const double mu0 = SlabNodeCosine(j);
            const double r = exact[static_cast<std::size_t>(j)].reflectance;
            const double e_total = std::exp(-(1.0 - f) * tau / mu0);
            const double m =
                2.0 / 3.0 - (r * (4.0 / 3.0 + (1.0 - g) * tau) - (1.0 - g) * tau) / (1.0 - e_total);
            table[SlabNode(1, i, j)] = std::clamp(m, -0.6, 2.0) - mu0;
        }
    }
    for (int j = 0; j < kCloudSlabTableSize; ++j) {
        table[SlabNode(1, 0, j)] = table[SlabNode(1, 1, j)];
    }
}

// The lit face's table: the renderer's source (clouds/functions.glsl, CloudSunScattering, first
// order and diffuse field, the lit face's source off) through a homogeneous non-absorbing slab of
// optical depth tau_total over a black ground, the sun at cosine mu0 (the diffuse field's beam
// at the node's cosine from `table`'s other half), by its formal solution:
// the flux leaving the slab is the source integrated over depth and the sphere of directions,
// attenuated by exp(-depth to the face / |mu|).
// - Directions: cells uniform in the vertical cosine mu (equal solid angles) and in the azimuth
//   from the light's vertical plane over [0, pi] (the problem is symmetric about it); each
//   cell's phase functions averaged over kLitFaceSubsamples^2 points, so the forward lobe (g up
//   to 0.99) is integrated over its cells, not sampled at their centres, and renormalised to 1.
// - Depths: kDepths intervals, denser at both faces (t = tau_total (1 - cos(pi k / n)) / 2), the
//   source at each interval's middle and its attenuation integrated exactly over it.
// The source is CloudSunScattering's own terms (the dual-lobe first order, the delta-Eddington
// field, the delta peak's light seen through one more scattering, the light scattered once on
// its way out that the peak passes on), combined per cell as it combines them; tests/sky hold
// the result to a separate quadrature of CloudSunScattering itself. The lit face's source
// (CloudTwiceScatteredPhase times the sunlight left, unit scale) goes through the same cells,
// and its scale is the loss over what it sends out: negative where the rest of the source sends
// out more than the slab receives (a Sun grazing the slab, mu0 < 0.13 for the default lobes).
constexpr int kLitFaceCosines = 64;
constexpr int kLitFaceAzimuths = 32;
constexpr int kLitFaceSubsamples = 4;
constexpr int kLitFaceDepths = 200;

void ComputeLitFaceScales(const ref::CloudScatteringParameters& p, double g, double f,
                          CloudSlabTableNodes& table) {
    constexpr double kPi = std::numbers::pi;
    const double d_mu = 2.0 / kLitFaceCosines;
    const double d_phi = kPi / kLitFaceAzimuths;
    const double cell_solid_angle = 2.0 * d_mu * d_phi;  // both sides of the light's plane

    for (int j = 0; j < kCloudSlabTableSize; ++j) {
        const double mu0 = SlabNodeCosine(j);
        const ref::vec3 light(std::sqrt(1.0 - mu0 * mu0), 0.0, mu0);
        // The mean of phase(nu) over each cell, along the light's way out of it (view =
        // -direction of travel), normalised to integrate to 1.
        const auto cell_means = [&](const auto& phase) {
            std::vector<double> means(static_cast<std::size_t>(kLitFaceCosines * kLitFaceAzimuths));
            double sum = 0.0;
            for (int a = 0; a < kLitFaceCosines; ++a) {
                for (int b = 0; b < kLitFaceAzimuths; ++b) {
                    double mean = 0.0;
                    for (int u = 0; u < kLitFaceSubsamples; ++u) {
                        for (int v = 0; v < kLitFaceSubsamples; ++v) {
                            const double mu = -1.0 + (a + (u + 0.5) / kLitFaceSubsamples) * d_mu;
                            const double phi = (b + (v + 0.5) / kLitFaceSubsamples) * d_phi;
                            const double sine = std::sqrt(std::max(1.0 - mu * mu, 0.0));
                            mean += phase(-(sine * std::cos(phi) * light.x + mu * light.z));
                        }
                    }
                    mean /= kLitFaceSubsamples * kLitFaceSubsamples;
                    means[static_cast<std::size_t>(a * kLitFaceAzimuths + b)] = mean;
                    sum += mean * cell_solid_angle;
                }
            }
            for (double& mean : means) mean /= sum;
            return means;
        };
        // The dual lobe (first order), the delta peak's light seen through one more
        // scattering, and the lit face's source summed over each cosine's row of cells (it is
        // the same at every depth).
        const std::vector<double> first = cell_means([&](double nu) {
            return ref::CloudDualLobePhase(p.forward_g, p.backward_g, p.lobe_weight, nu);
        });
        const std::vector<double> peak = cell_means([&](double nu) {
            return ref::CloudForwardThenScatteredPhase(p.forward_g, p.backward_g, p.lobe_weight,
                                                       nu);
        });
        const std::vector<double> forward_twice = cell_means([&](double nu) {
            return ref::CloudHenyeyGreensteinPhase(p.forward_g * p.forward_g, nu);
        });
        const std::vector<double> twice = cell_means([&](double nu) {
            return ref::CloudTwiceScatteredPhase(p.forward_g, p.backward_g, p.lobe_weight, nu);
        });
        std::vector<double> twice_rows(kLitFaceCosines, 0.0);
        for (std::size_t cell = 0; cell < twice.size(); ++cell) {
            twice_rows[cell / kLitFaceAzimuths] += twice[cell];
        }
        // Node 0 (tau_total = 0) stays 0: the loss vanishes faster than the source's light.
        for (int i = 1; i < kCloudSlabTableSize; ++i) {
            const double tau_total = SlabNodeDepth(i);
            const double beam = mu0 + table[SlabNode(1, i, j)];
            double renderer = 0.0, lit_face = 0.0;
            for (int k = 0; k < kLitFaceDepths; ++k) {
                const double t0 = 0.5 * tau_total * (1.0 - std::cos(kPi * k / kLitFaceDepths));
                const double t1 =
                    0.5 * tau_total * (1.0 - std::cos(kPi * (k + 1) / kLitFaceDepths));
                const double t = 0.5 * (t0 + t1);
                const double direct = std::exp(-t / mu0);
                const ref::vec2 diffuse =
                    ref::CloudDiffuseRadiance(g, f, t, tau_total, mu0, beam, 0.0);
                const double scaled = std::exp(-(1.0 - f) * t / mu0) - direct;
                for (int a = 0; a < kLitFaceCosines; ++a) {
                    const double mu = -1.0 + (a + 0.5) * d_mu;  // travel, up > 0
                    const double m = std::abs(mu);
                    const double escape = mu > 0.0 ? m * (std::exp(-t0 / m) - std::exp(-t1 / m))
                                                   : m * (std::exp(-(tau_total - t1) / m) -
                                                          std::exp(-(tau_total - t0) / m));
                    const double field = diffuse.x - g * mu * diffuse.y;  // mu_view = -mu
                    const double along_view =
                        f * ref::CloudAlongViewLight(t / mu0, t, tau_total - t, mu0, -mu);
                    double source = 0.0;
                    for (int b = 0; b < kLitFaceAzimuths; ++b) {
                        const auto cell = static_cast<std::size_t>(a * kLitFaceAzimuths + b);
                        // CloudSunScattering's phase of the light passed on along the view,
                        // from the cells' means.
                        const double passed = std::max(peak[cell] - f * forward_twice[cell], 0.0);
                        source += first[cell] * direct +
                                  std::max(field + peak[cell] * scaled, 0.0) + passed * along_view;
                    }
                    renderer += cell_solid_angle * source * escape;
                    lit_face += cell_solid_angle * twice_rows[static_cast<std::size_t>(a)] *
                                direct * escape;
                }
            }
            const double loss = 1.0 - std::exp(-tau_total / mu0) - renderer / mu0;
            table[SlabNode(0, i, j)] = loss / (lit_face / mu0);
        }
    }
}

CloudSlabTableNodes ComputeSlabTables(const CloudSettings& s) {
    ref::CloudScatteringParameters p{};
    p.forward_g = s.forward_g;
    p.backward_g = s.backward_g;
    p.lobe_weight = s.lobe_weight;
    const double g = ref::CloudAsymmetry(p);
    const double f = ref::CloudDeltaFraction(p);
    CloudSlabTableNodes table{};
    ComputeBeamOffsets(p, g, f, table);
    ComputeLitFaceScales(p, g, f, table);
    return table;
}

}  // namespace

CloudSlabTableNodes CloudSlabTables(const CloudSettings& s) {
    // Each costs tens of milliseconds; the last few phase functions' are kept (a host sweeping
    // them costs that per change, and no more memory).
    constexpr std::size_t kKept = 8;
    static std::mutex mutex;
    static std::vector<std::pair<glm::dvec3, CloudSlabTableNodes>> cache;
    const glm::dvec3 key(s.forward_g, s.backward_g, s.lobe_weight);
    CloudSlabTableNodes tables{};
    {
        const std::lock_guard<std::mutex> lock(mutex);
        const auto cached = std::find_if(cache.begin(), cache.end(),
                                         [&](const auto& entry) { return entry.first == key; });
        if (cached != cache.end()) {
            tables = cached->second;
        } else {
            if (cache.size() == kKept) cache.erase(cache.begin());
            cache.emplace_back(key, ComputeSlabTables(s));
            tables = cache.back().second;
        }
    }
    if (!s.lit_face_source) {
        std::fill_n(tables.begin(), kCloudSlabTableSize * kCloudSlabTableSize, 0.0);
    }
    return tables;
}

void CloudSettings::Validate() const {
    Require(std::isfinite(extinction) && extinction > 0.0 && extinction <= 10.0, "extinction",
            extinction, "0 < 1/m <= 10");
    Require(albedo >= 0.0 && albedo <= 1.0, "albedo", albedo, "[0, 1]");
    Require(forward_g > -1.0 && forward_g < 1.0, "forward_g", forward_g, "(-1, 1)");
    Require(backward_g > -1.0 && backward_g < 1.0, "backward_g", backward_g, "(-1, 1)");
    Require(lobe_weight >= 0.0 && lobe_weight <= 1.0, "lobe_weight", lobe_weight, "[0, 1]");
    Require(multiple_scattering >= 0.0 && multiple_scattering <= 1.0, "multiple_scattering",
            multiple_scattering, "[0, 1]");
    Require(ambient_scale >= 0.0 && ambient_scale <= 10.0, "ambient_scale", ambient_scale,
            "[0, 10]");
    Require(shape_period >= 100.0 && shape_period <= 1e6, "shape_period", shape_period,
            "100 m .. 1000 km");
    Require(detail_period >= 10.0 && detail_period <= 1e5, "detail_period", detail_period,
            "10 m .. 100 km");
    Require(erosion >= 0.0 && erosion <= 0.9, "erosion", erosion, "[0, 0.9]");
    Require(min_step >= 1.0 && min_step <= 10000.0, "min_step", min_step, "1 m .. 10 km");
    Require(max_steps >= 1 && max_steps <= 4096, "max_steps", max_steps, "1..4096");
    Require(shadow_steps >= 0 && shadow_steps <= 64, "shadow_steps", shadow_steps, "0..64");
    Require(shadow_first_step > 0.0 && shadow_first_step <= 10000.0, "shadow_first_step",
            shadow_first_step, "0 < m <= 10 km");
    Require(shadow_growth >= 1.0 && shadow_growth <= 4.0, "shadow_growth", shadow_growth, "[1, 4]");
    Require(thick_step_refinement >= 0 && thick_step_refinement <= 3, "thick_step_refinement",
            thick_step_refinement, "0..3");
    Require(min_transmittance >= 0.0 && min_transmittance < 1.0, "min_transmittance",
            min_transmittance, "[0, 1)");
    Require(max_distance > 0.0 && max_distance <= 1e7, "max_distance", max_distance,
            "0 < m <= 10000 km");
    Require(aerial_perspective_steps >= 1 && aerial_perspective_steps <= 256,
            "aerial_perspective_steps", aerial_perspective_steps, "1..256");
    Require(light_shaft_steps >= 0 && light_shaft_steps <= 256, "light_shaft_steps",
            light_shaft_steps, "0..256");
    Require(block >= 1 && block <= 8, "block", block, "1..8");
    Require(history_weight >= 0.0 && history_weight < 1.0, "history_weight", history_weight,
            "[0, 1)");
    Require(shadow_map_size >= 8 && shadow_map_size <= 4096, "shadow_map_size", shadow_map_size,
            "8..4096");
    Require(shadow_map_extent >= 1000.0 && shadow_map_extent <= 1e6, "shadow_map_extent",
            shadow_map_extent, "1 km .. 1000 km");
    Require(shadow_map_steps >= 1 && shadow_map_steps <= 256, "shadow_map_steps", shadow_map_steps,
            "1..256");
    Require(shadow_map_interval >= 1 && shadow_map_interval <= 1000, "shadow_map_interval",
            shadow_map_interval, "1..1000");
    Require(sun_depth_size == 0 || (sun_depth_size >= 8 && sun_depth_size <= 512), "sun_depth_size",
            sun_depth_size, "0 (none) or 8..512");
    Require(sun_depth_levels >= 2 && sun_depth_levels <= 64, "sun_depth_levels", sun_depth_levels,
            "2..64");
    Require(sun_depth_extent >= 1000.0 && sun_depth_extent <= 1e6, "sun_depth_extent",
            sun_depth_extent, "1 km .. 1000 km");
    const int stage = static_cast<int>(pass_stage);
    Require(stage >= static_cast<int>(CloudPassStage::kAuto) &&
                stage <= static_cast<int>(CloudPassStage::kCompute),
            "pass_stage", stage, "0 kAuto, 1 kFragment or 2 kCompute");
}

std::vector<int> CloudLayerOrder(const clouds::Weather& weather, double camera_altitude) {
    std::vector<int> order;
    const int count = static_cast<int>(weather.layers.size());
    for (int i = count - 1; i >= 0; --i) {
        if (weather.layers[static_cast<std::size_t>(i)].base_altitude <= camera_altitude) {
            order.push_back(i);
        }
    }
    for (int i = 0; i < count; ++i) {
        if (weather.layers[static_cast<std::size_t>(i)].base_altitude > camera_altitude) {
            order.push_back(i);
        }
    }
    return order;
}

}  // namespace zenith::sky
