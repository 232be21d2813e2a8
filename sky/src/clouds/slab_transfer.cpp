#include "clouds/slab_transfer.h"

#include <Eigen/Dense>
#include <cmath>
#include <numbers>
#include <sstream>

#include "zenith/base/error.h"
#include "zenith/base/gauss_legendre.h"

namespace zenith::sky {
namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

constexpr int kMoments = 2 * kSlabStreams;  // Legendre moments kept by delta-M
constexpr double kThinLayer = 0x1p-30;      // the first layer's scaled optical depth, at most

// P_0(x) .. P_{kMoments - 1}(x).
VectorXd Legendre(double x) {
    VectorXd p(kMoments);
    p[0] = 1.0;
    p[1] = x;
    for (int l = 2; l < kMoments; ++l) {
        p[l] = ((2.0 * l - 1.0) * x * p[l - 1] - (l - 1.0) * p[l - 2]) / l;
    }
    return p;
}

// Light scattered once in a layer of optical depth d, per unit source p / (4 pi) (or p w / 2 for
// a node's radiance), out of light travelling at cosine `in` to the normal, leaving at cosine
// `out` on the same side as it came in (reflected) or the other (transmitted):
//   reflected:   in / (out + in) (1 - exp(-d (1/out + 1/in)))
//   transmitted: (d / out) exp(-d / out) (1 - exp(-x)) / x,  x = d (1/in - 1/out)
// the second written so that it holds as in -> out.
double ReflectedOnce(double d, double out, double in) {
    return -in / (out + in) * std::expm1(-d * (1.0 / out + 1.0 / in));
}
double TransmittedOnce(double d, double out, double in) {
    const double x = d * (1.0 / in - 1.0 / out);
    const double ratio = std::abs(x) < 1e-12 ? 1.0 : -std::expm1(-x) / x;
    return d / out * std::exp(-d / out) * ratio;
}

}  // namespace

std::vector<SlabTransfer> ConservativeSlabTransfer(double forward_g, double backward_g,
                                                   double lobe_weight, double optical_depth,
                                                   const std::vector<double>& mu0) {
    const auto require = [](bool ok, const char* what, double value, const char* expected) {
        if (ok) return;
        std::ostringstream text;
        text << "ConservativeSlabTransfer: " << what << " = " << value << " (expected " << expected
             << ")";
        throw ArgumentError(text.str());
    };
    require(std::abs(forward_g) < 1.0, "forward_g", forward_g, "(-1, 1)");
    require(std::abs(backward_g) < 1.0, "backward_g", backward_g, "(-1, 1)");
    require(lobe_weight >= 0.0 && lobe_weight <= 1.0, "lobe_weight", lobe_weight, "[0, 1]");
    require(std::isfinite(optical_depth) && optical_depth > 0.0 && optical_depth <= 1e4,
            "optical_depth", optical_depth, "0 < tau <= 1e4");
    for (const double m : mu0) require(m > 0.0 && m <= 1.0, "mu0", m, "(0, 1]");

    // The dual lobe's Legendre moments g0^l and g1^l, delta-M scaled.
    VectorXd moments(kMoments);
    const double f = (1.0 - lobe_weight) * std::pow(forward_g, kMoments) +
                     lobe_weight * std::pow(backward_g, kMoments);
    for (int l = 0; l < kMoments; ++l) {
        const double chi =
            (1.0 - lobe_weight) * std::pow(forward_g, l) + lobe_weight * std::pow(backward_g, l);
        moments[l] = (2.0 * l + 1.0) * (chi - f) / (1.0 - f);
    }
    const double scaled_depth = (1.0 - f) * optical_depth;

    // The azimuthal mean of the phase function between cosines a and b (travel, down > 0),
    // normalised so that its mean over b is 1.
    constexpr int n = kSlabStreams;
    const auto m = static_cast<Eigen::Index>(mu0.size());
    const Eigen::Map<const VectorXd> beam_cosine(mu0.data(), m);
    // Gauss-Legendre on (0, 1), the weights summing to 1.
    const GaussLegendreRule rule = GaussLegendre(n, 0.0, 1.0);
    const Eigen::Map<const VectorXd> mu(rule.nodes.data(), n);
    const Eigen::Map<const VectorXd> weight(rule.weights.data(), n);
    const auto phase = [&](const VectorXd& pa, const VectorXd& pb, bool opposite) {
        double sum = 0.0;
        for (int l = 0; l < kMoments; ++l) {
            sum += moments[l] * pa[l] * pb[l] * (opposite && l % 2 == 1 ? -1.0 : 1.0);
        }
        return sum;
    };
    std::vector<VectorXd> node_legendre, beam_legendre;
    for (int i = 0; i < n; ++i) node_legendre.push_back(Legendre(mu[i]));
    for (const double cosine : mu0) beam_legendre.push_back(Legendre(cosine));

    // The thin first layer: R and T map radiances on the nodes to radiances, the sources are
    // the radiances of the beam's light scattered once (per unit flux normal to the beam).
    int doublings = 0;
    while (std::ldexp(scaled_depth, -doublings) > kThinLayer) ++doublings;
    const double d = std::ldexp(scaled_depth, -doublings);
    MatrixXd r(n, n), t(n, n), up(n, m), down(n, m);
    VectorXd beam(m);
    for (int i = 0; i < n; ++i) {
        const VectorXd& pa = node_legendre[static_cast<std::size_t>(i)];
        for (int j = 0; j < n; ++j) {
            const VectorXd& pb = node_legendre[static_cast<std::size_t>(j)];
            const double scale = 0.5 * weight[j];
            r(i, j) = scale * phase(pa, pb, true) * ReflectedOnce(d, mu[i], mu[j]);
            t(i, j) = scale * phase(pa, pb, false) * TransmittedOnce(d, mu[i], mu[j]) +
                      (i == j ? std::exp(-d / mu[i]) : 0.0);
        }
        for (Eigen::Index k = 0; k < m; ++k) {
            const VectorXd& pb = beam_legendre[static_cast<std::size_t>(k)];
            const double scale = 1.0 / (4.0 * std::numbers::pi);
            up(i, k) = scale * phase(pa, pb, true) * ReflectedOnce(d, mu[i], beam_cosine[k]);
            down(i, k) = scale * phase(pa, pb, false) * TransmittedOnce(d, mu[i], beam_cosine[k]);
        }
    }
    beam = (-d * beam_cosine.cwiseInverse()).array().exp();

    // Doubling: two copies of the layer, the lower lit by the beam the upper lets through;
    // between them the light reflected back and forth sums to (1 - R R)^-1.
    const MatrixXd identity = MatrixXd::Identity(n, n);
    for (int step = 0; step < doublings; ++step) {
        const MatrixXd gain = (identity - r * r).inverse();
        const MatrixXd up_lower = up * beam.asDiagonal();
        const MatrixXd between_down = gain * (down + r * up_lower);
        const MatrixXd between_up = up_lower + r * between_down;
        up += t * between_up;
        down = t * between_down + down * beam.asDiagonal();
        const MatrixXd t_gain = t * gain;
        r += t_gain * r * t;
        t = t_gain * t;
        beam = beam.cwiseProduct(beam);
    }

    std::vector<SlabTransfer> fluxes;
    const VectorXd flux_weight = 2.0 * std::numbers::pi * weight.cwiseProduct(mu);
    for (Eigen::Index k = 0; k < m; ++k) {
        fluxes.push_back({flux_weight.dot(up.col(k)) / beam_cosine[k],
                          flux_weight.dot(down.col(k)) / beam_cosine[k] +
                              std::exp(-scaled_depth / beam_cosine[k])});
    }
    return fluxes;
}

}  // namespace zenith::sky
