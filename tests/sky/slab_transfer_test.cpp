// The adding-doubling slab (clouds/slab_transfer.h), which the renderer's diffuse field is fitted
// to, against what a plane-parallel solution must meet: energy conservation in a non-absorbing
// slab, single scattering in a thin one, van de Hulst's table for a Henyey-Greenstein slab, and
// Chandrasekhar's escape function for a thick isotropic slab lit at a grazing angle, where the
// delta-Eddington closed form is furthest off.
#include "clouds/slab_transfer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "h_function.h"
#include "reference/cloud_functions.h"
#include "zenith/base/error.h"

namespace zenith::sky {
namespace {

constexpr double kPi = std::numbers::pi;

struct Phase {
    double forward_g, backward_g, lobe_weight;
};

TEST(SlabTransfer, ANonAbsorbingSlabReflectsOrTransmitsAllItReceives) {
    for (const Phase& p : {Phase{0.0, 0.0, 0.0}, Phase{0.85, 0.0, 0.0}, Phase{0.8, -0.3, 0.3},
                           Phase{0.95, -0.2, 0.1}}) {
        for (const double tau : {0.01, 1.0, 10.0, 100.0}) {
            const std::vector<double> cosines = {1.0, 0.5, 0.1, 0.02};
            const std::vector<SlabTransfer> fluxes =
                ConservativeSlabTransfer(p.forward_g, p.backward_g, p.lobe_weight, tau, cosines);
            for (std::size_t k = 0; k < cosines.size(); ++k) {
                EXPECT_NEAR(fluxes[k].reflectance + fluxes[k].transmittance, 1.0, 1e-5)
                    << "g0 " << p.forward_g << " tau " << tau << " mu0 " << cosines[k];
                EXPECT_GT(fluxes[k].reflectance, 0.0);
            }
        }
    }
}

// tau = 1e-3: the light scattered once up out of the slab, the renderer's phase function
// (which the slab reads only through its Legendre moments) averaged over the azimuth by
// quadrature: R = 2 pi / mu0 ∫ mu L(mu) dmu with
// L = E <p>(mu) mu0 / (mu + mu0) (1 - exp(-tau (1/mu + 1/mu0))). Twice-scattered light is
// O(tau^2 ln tau) of it.
TEST(SlabTransfer, AThinSlabReflectsWhatItScattersOnce) {
    constexpr double kTau = 1e-3;
    for (const Phase& p : {Phase{0.0, 0.0, 0.0}, Phase{0.8, -0.3, 0.3}}) {
        for (const double mu0 : {1.0, 0.4, 0.1}) {
            double reflected = 0.0;
            constexpr int kCosines = 4000, kAzimuths = 360;
            for (int i = 0; i < kCosines; ++i) {
                const double mu = (i + 0.5) / kCosines;
                double phase = 0.0;
                for (int j = 0; j < kAzimuths; ++j) {
                    const double phi = 2.0 * kPi * (j + 0.5) / kAzimuths;
                    const double cosine =
                        -mu * mu0 + std::sqrt((1.0 - mu * mu) * (1.0 - mu0 * mu0)) * std::cos(phi);
                    phase +=
                        ref::CloudDualLobePhase(p.forward_g, p.backward_g, p.lobe_weight, cosine);
                }
                phase /= kAzimuths;
                const double radiance =
                    phase * mu0 / (mu + mu0) * -std::expm1(-kTau * (1.0 / mu + 1.0 / mu0));
                reflected += 2.0 * kPi * mu * radiance / kCosines;
            }
            reflected /= mu0;
            const double r =
                ConservativeSlabTransfer(p.forward_g, p.backward_g, p.lobe_weight, kTau, {mu0})[0]
                    .reflectance;
            EXPECT_NEAR(r, reflected, 0.01 * reflected) << "g0 " << p.forward_g << " mu0 " << mu0;
        }
    }
}

// van de Hulst 1980, "Multiple Light Scattering", Table 37 (Henyey-Greenstein g = 0.75,
// omega = 1, mu0 = 1, black ground), as reproduced by DISORT's test problem 3 (Stamnes et al.
// 1988), per incident flux pi: tau = 1, diffuse flux up at the top 0.247374, down at the base
// 1.73849; tau = 8, 1.59096 and 1.54958. (The cloud path tracer meets the same table:
// cloud_path_tracer_test.cpp.)
TEST(SlabTransfer, MatchesVanDeHulstTable37) {
    for (const auto& [tau, up, down] :
         {std::tuple{1.0, 0.247374, 1.73849}, std::tuple{8.0, 1.59096, 1.54958}}) {
        const SlabTransfer fluxes = ConservativeSlabTransfer(0.75, 0.0, 0.0, tau, {1.0})[0];
        EXPECT_NEAR(fluxes.reflectance, up / kPi, 1e-4) << "tau " << tau;
        EXPECT_NEAR(fluxes.transmittance - std::exp(-tau), down / kPi, 1e-4) << "tau " << tau;
    }
}

// A thick conservative slab of isotropic scatterers transmits t(mu0) = 4 K(mu0) / (3 (tau +
// 2 q0)) of the light (van de Hulst 1980, Ch. 9; King 1987), the escape function K(mu) =
// (sqrt 3 / 4) H(mu) with Chandrasekhar's conservative H-function and q0 = 0.710446 (Hopf's
// constant), up to terms exponentially small in tau. Its dependence on mu0 at a grazing beam is
// what the delta-Eddington closed form misses (it has (2/3 + mu0) / (4/3 + tau): 6 % more light
// through at mu0 = 0.1 here).
TEST(SlabTransfer, AThickIsotropicSlabTransmitsByTheEscapeFunction) {
    const test::HFunction h(1.0, 200000);
    ASSERT_NEAR(h(1.0), 2.90781, 5e-5);  // Chandrasekhar 1950, Table XIII
    constexpr double kHopf = 0.710446;
    for (const double tau : {20.0, 40.0}) {
        const std::vector<double> cosines = {1.0, 0.6, 0.3, 0.1, 0.05, 0.02};
        const std::vector<SlabTransfer> fluxes =
            ConservativeSlabTransfer(0.0, 0.0, 0.0, tau, cosines);
        for (std::size_t k = 0; k < cosines.size(); ++k) {
            const double expected = h(cosines[k]) / std::sqrt(3.0) / (tau + 2.0 * kHopf);
            EXPECT_NEAR(fluxes[k].transmittance, expected, 5e-4 * expected)
                << "tau " << tau << " mu0 " << cosines[k];
        }
    }
}

TEST(SlabTransfer, RejectsWhatItCannotSolve) {
    EXPECT_THROW(ConservativeSlabTransfer(1.0, 0.0, 0.0, 1.0, {1.0}), ArgumentError);
    EXPECT_THROW(ConservativeSlabTransfer(0.5, 0.0, 1.5, 1.0, {1.0}), ArgumentError);
    EXPECT_THROW(ConservativeSlabTransfer(0.5, 0.0, 0.0, 0.0, {1.0}), ArgumentError);
    EXPECT_THROW(ConservativeSlabTransfer(0.5, 0.0, 0.0, NAN, {1.0}), ArgumentError);
    EXPECT_THROW(ConservativeSlabTransfer(0.5, 0.0, 0.0, 1.0, {0.0}), ArgumentError);
    EXPECT_THROW(ConservativeSlabTransfer(0.5, 0.0, 0.0, 1.0, {1.5}), ArgumentError);
}

}  // namespace
}  // namespace zenith::sky
