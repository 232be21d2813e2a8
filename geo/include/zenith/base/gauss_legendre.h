// Gauss-Legendre quadrature: the n-point rule on [a, b], exact for polynomials of degree up to
// 2n - 1. Shared by the eclipse's limb-darkened disk integrals (geo) and the clouds' exact slab
// (sky, clouds/slab_transfer.h).
#pragma once

#include <vector>

namespace zenith {

struct GaussLegendreRule {
    std::vector<double> nodes;    // ascending, in (a, b)
    std::vector<double> weights;  // summing to b - a
};

// n >= 1; nodes and weights by Newton's method on P_n (Numerical Recipes' gauleg scheme,
// written anew), to ~1e-15 on [-1, 1], then mapped linearly onto [a, b].
GaussLegendreRule GaussLegendre(int n, double a = -1.0, double b = 1.0);

}  // namespace zenith
