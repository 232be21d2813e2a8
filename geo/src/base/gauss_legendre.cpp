#include "zenith/base/gauss_legendre.h"

#include <cmath>
#include <numbers>
#include <string>

#include "zenith/base/error.h"

namespace zenith {

GaussLegendreRule GaussLegendre(int n, double a, double b) {
    if (n < 1) throw ArgumentError("GaussLegendre: n = " + std::to_string(n) + " (expected >= 1)");
    GaussLegendreRule rule;
    rule.nodes.resize(static_cast<std::size_t>(n));
    rule.weights.resize(static_cast<std::size_t>(n));
    // The roots come in pairs +-z; each is found from the Chebyshev-like first guess.
    for (int i = 0; i < (n + 1) / 2; ++i) {
        double z = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5));
        double dp = 0.0;
        for (int iteration = 0; iteration < 100; ++iteration) {
            double p0 = 1.0, p1 = 0.0;
            for (int j = 1; j <= n; ++j) {
                const double p2 = p1;
                p1 = p0;
                p0 = ((2.0 * j - 1.0) * z * p1 - (j - 1.0) * p2) / j;
            }
            dp = n * (z * p0 - p1) / (z * z - 1.0);
            const double dz = p0 / dp;
            z -= dz;
            if (std::abs(dz) < 1e-15) break;
        }
        const double w = 2.0 / ((1.0 - z * z) * dp * dp);
        rule.nodes[static_cast<std::size_t>(i)] = -z;
        rule.nodes[static_cast<std::size_t>(n - 1 - i)] = z;
        rule.weights[static_cast<std::size_t>(i)] = w;
        rule.weights[static_cast<std::size_t>(n - 1 - i)] = w;
    }
    const double half = 0.5 * (b - a);
    for (std::size_t i = 0; i < rule.nodes.size(); ++i) {
        rule.nodes[i] = a + half * (rule.nodes[i] + 1.0);
        rule.weights[i] *= half;
    }
    return rule;
}

}  // namespace zenith
