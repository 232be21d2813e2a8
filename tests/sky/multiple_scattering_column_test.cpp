// The plane-parallel column that corrects the multiple-scattering LUT's series past its last
// order (sky/src/multiple_scattering_column.h): energy conservation in a non-absorbing slab, the
// cloud path tracer's independent plane-parallel slab with an isotropic phase, absorption and a
// grey ground, and its orders against its all-order solution.
#include "multiple_scattering_column.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "zenith/base/error.h"
#include "zenith/sky/lut.h"
#include "zenith/sky/reference/cloud_path_tracer.h"

namespace zenith::sky {
namespace {

constexpr double kPi = std::numbers::pi;

double E3(double x) {
    const double e1 = -std::expint(-x);
    const double e2 = std::exp(-x) - x * e1;
    return 0.5 * (std::exp(-x) - x * e2);
}

// A homogeneous slab of optical depth `tau` in `n` equal layers over a Lambertian ground, lit at
// its top by a collimated beam of unit irradiance (normal to the beam) from cosine mu0: the flux
// leaving the top (R) and every downward flux reaching the ground (T, the direct beam with it),
// per incident flux mu0.
struct SlabResult {
    double reflectance;
    double transmittance;
};

ScatteringColumn Slab(double tau, int n, double albedo, double ground_albedo) {
    return ScatteringColumn(std::vector<double>(static_cast<std::size_t>(n), tau / n),
                            std::vector<double>(static_cast<std::size_t>(n) + 1, albedo),
                            ground_albedo);
}

// The sunlight's first scattering per unit optical depth at each node (node 0 at the ground).
std::vector<double> FirstScattering(double tau, int n, double albedo, double mu0) {
    std::vector<double> source(static_cast<std::size_t>(n) + 1);
    for (int k = 0; k <= n; ++k) {
        const double depth = tau * (n - k) / n;  // from the top
        source[static_cast<std::size_t>(k)] = albedo * std::exp(-depth / mu0) / (4.0 * kPi);
    }
    return source;
}

SlabResult ColumnSlab(double tau, int n, double albedo, double ground_albedo, double mu0) {
    const ScatteringColumn column = Slab(tau, n, albedo, ground_albedo);
    const std::vector<double> first = FirstScattering(tau, n, albedo, mu0);
    const double direct = std::exp(-tau / mu0) * mu0;  // the flux reaching the ground unscattered
    const std::vector<double> all =
        column.AllOrders(column.FromSource(first, ground_albedo / kPi * direct));
    std::vector<double> source = first;
    for (std::size_t i = 0; i < source.size(); ++i) source[i] += albedo * all[i];
    const glm::dvec2 flux = column.EscapingFlux(source);
    const double down = flux.y + direct;
    // The ground's own light also leaves through the top unscattered: pi L 2 E3(tau).
    const double up = flux.x + ground_albedo * down * 2.0 * E3(tau);
    return {up / mu0, down / mu0};
}

// Scattering conserves the light: a non-absorbing slab over a black ground reflects and transmits
// all it receives. Layers of optical depth 1/16 at most: the exact light near a face changes
// faster than a linear source follows (tau 32 in 128 layers keeps only 97.2 % at mu0 = 1, 107 %
// at mu0 = 0.2 where the direct beam's source falls by e^-1.25 across a layer). In the air the
// column's layers are thinnest where it is densest.
TEST(ScatteringColumn, NonAbsorbingSlabOverABlackGroundKeepsItsEnergy) {
    for (const double tau : {0.5, 4.0, 32.0}) {
        const int layers = std::max(64, static_cast<int>(16.0 * tau));
        for (const double mu0 : {1.0, 0.6, 0.2}) {
            const SlabResult r = ColumnSlab(tau, layers, 1.0, 0.0, mu0);
            EXPECT_NEAR(r.reflectance + r.transmittance, 1.0, 0.005)
                << "tau " << tau << ", mu0 " << mu0 << ": R " << r.reflectance << ", T "
                << r.transmittance;
        }
    }
}

// Against the cloud path tracer's plane-parallel slab (its own Monte Carlo photons, no shared
// code), with the phase made isotropic: reflection and transmission within 1 % plus four of the
// photons' standard errors, with and without absorption and a grey ground.
TEST(ScatteringColumn, MatchesThePathTracersIsotropicSlab) {
    struct Case {
        double tau, albedo, ground_albedo, mu0;
    };
    for (const Case c :
         {Case{1.0, 1.0, 0.0, 1.0}, Case{2.0, 0.9, 0.3, 0.6}, Case{8.0, 0.99, 0.5, 0.3}}) {
        reference::SlabProblem problem;
        problem.optical_depth = c.tau;
        problem.phase = reference::CloudPhase{0.0, 0.0, 0.0};
        problem.single_scattering_albedo = c.albedo;
        problem.ground_albedo = c.ground_albedo;
        problem.mu0 = c.mu0;
        reference::CloudPathTraceOptions options;
        options.samples = 200000;
        options.seed = 7;
        const reference::SlabFluxes photons = reference::SlabFluxesFromPhotons(problem, options);
        const SlabResult column = ColumnSlab(c.tau, 128, c.albedo, c.ground_albedo, c.mu0);
        EXPECT_NEAR(column.reflectance, photons.reflectance,
                    0.01 * photons.reflectance + 4.0 * photons.reflectance_error)
            << "tau " << c.tau << ", albedo " << c.albedo << ", ground " << c.ground_albedo;
        EXPECT_NEAR(column.transmittance, photons.transmittance,
                    0.01 * photons.transmittance + 4.0 * photons.transmittance_error)
            << "tau " << c.tau << ", albedo " << c.albedo << ", ground " << c.ground_albedo;
    }
}

// The orders one by one sum to the all-order solution (a slab of optical depth 3, albedo 0.95:
// the 400th order is 1e-9 of the first).
TEST(ScatteringColumn, OrdersSumToAllOrders) {
    const ScatteringColumn column = Slab(3.0, 64, 0.95, 0.2);
    std::vector<double> order = column.FromSource(FirstScattering(3.0, 64, 0.95, 0.5), 0.01);
    const std::vector<double> all = column.AllOrders(order);
    std::vector<double> sum(order.size(), 0.0);
    for (int k = 0; k < 400; ++k) {
        for (std::size_t i = 0; i < sum.size(); ++i) sum[i] += order[i];
        order = column.NextOrder(order);
    }
    for (std::size_t i = 0; i < sum.size(); ++i) {
        EXPECT_NEAR(sum[i], all[i], 1e-7 * all[i]) << "layer " << i;
    }
}

TEST(ScatteringColumn, LayersAreBounded) {
    LutSettings settings;
    for (const int layers : {0, 16, 512}) {
        settings.multiple_scattering_column_layers = layers;
        EXPECT_NO_THROW(settings.Validate()) << layers;
    }
    for (const int layers : {-1, 8, 513}) {
        settings.multiple_scattering_column_layers = layers;
        EXPECT_THROW(settings.Validate(), ArgumentError) << layers;
    }
}

}  // namespace
}  // namespace zenith::sky
