// Chandrasekhar's H-function, shared by the tests of the two plane-parallel solutions that meet
// it (the cloud path tracer and the adding-doubling slab).
#pragma once

#include <utility>
#include <vector>

#include "zenith/base/gauss_legendre.h"

namespace zenith::sky::test {

// Chandrasekhar's H-function for isotropic scattering with albedo omega (Radiative Transfer,
// 1950, Ch. V), by the iteration 1/H(mu) = 1 - (omega / 2) mu ∫0^1 H(mu') / (mu + mu') dmu' on
// Gauss-Legendre nodes, then evaluated at any mu by the same formula. It converges for every
// omega <= 1, as 1 / iterations for omega = 1 (conservative scattering: H(1) is 2.90759 after
// 20,000 iterations and 2.90779 after 200,000, where Chandrasekhar's table has 2.90781).
class HFunction {
  public:
    explicit HFunction(double omega, int iterations = 2000) : omega_(omega) {
        // 48-point Gauss-Legendre on [0, 1].
        GaussLegendreRule rule = GaussLegendre(48, 0.0, 1.0);
        nodes_ = std::move(rule.nodes);
        weights_ = std::move(rule.weights);
        h_.assign(nodes_.size(), 1.0);
        for (int iteration = 0; iteration < iterations; ++iteration) {
            std::vector<double> next(h_.size());
            for (std::size_t i = 0; i < h_.size(); ++i) next[i] = (*this)(nodes_[i]);
            h_ = next;
        }
    }
    double operator()(double mu) const {
        double integral = 0.0;
        for (std::size_t j = 0; j < nodes_.size(); ++j) {
            integral += weights_[j] * h_[j] / (mu + nodes_[j]);
        }
        return 1.0 / (1.0 - 0.5 * omega_ * mu * integral);
    }

  private:
    double omega_;
    std::vector<double> nodes_, weights_, h_;
};

}  // namespace zenith::sky::test
