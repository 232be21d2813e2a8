// Gauss-Legendre quadrature: the n-point rule on [-1, 1], exact for polynomials of degree up to
// 2n - 1. Shared by the eclipse's limb-darkened disk integrals (geo) and the clouds' exact slab
// (sky, clouds/slab_transfer.h).
#pragma once

#include <vector>

namespace zenith {

struct GaussLegendreRule {
    std::vector<double> nodes;    // ascending, in (-1, 1)
    std::vector<double> weights;  // summing to 2
};

// n >= 1; nodes and weights by Newton's method on P_n (Numerical Recipes' gauleg scheme,
// written anew), to ~1e-15.
GaussLegendreRule GaussLegendre(int n);

}  // namespace zenith
