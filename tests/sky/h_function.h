// Chandrasekhar's H-function, shared by the tests of the two plane-parallel solutions that meet
// it (the cloud path tracer and the adding-doubling slab).
#pragma once

#include <cmath>
#include <numbers>
#include <vector>

namespace zenith::sky::test {

// Chandrasekhar's H-function for isotropic scattering with albedo omega (Radiative Transfer,
// 1950, Ch. V), by the iteration 1/H(mu) = 1 - (omega / 2) mu ∫0^1 H(mu') / (mu + mu') dmu' on
// Gauss-Legendre nodes, then evaluated at any mu by the same formula. It converges for every
// omega <= 1, as 1 / iterations for omega = 1 (conservative scattering: H(1) is 2.90759 after
// 20,000 iterations and 2.90779 after 200,000, where Chandrasekhar's table has 2.90781).
class HFunction {
  public:
    explicit HFunction(double omega, int iterations = 2000) : omega_(omega) {
        // 48-point Gauss-Legendre on [0, 1] by Newton on P_n.
        constexpr int n = 48;
        for (int i = 0; i < n; ++i) {
            double x = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5));
            double dp = 0.0;
            for (int iteration = 0; iteration < 100; ++iteration) {
                double p0 = 1.0, p1 = x;
                for (int k = 2; k <= n; ++k) {
                    const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
                    p0 = p1;
                    p1 = p2;
                }
                dp = n * (x * p1 - p0) / (x * x - 1.0);
                const double dx = p1 / dp;
                x -= dx;
                if (std::abs(dx) < 1e-15) break;
            }
            nodes_.push_back(0.5 * (x + 1.0));
            weights_.push_back(1.0 / ((1.0 - x * x) * dp * dp));  // 2 / (...) halved for [0, 1]
        }
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
