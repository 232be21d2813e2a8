// The orders of the multiple scattering past the LUT's last one, from a plane-parallel column
// solved to all orders: what H20's geometric series misses where the air is optically thick.
//
// The multiple-scattering LUT (atmosphere/functions.glsl, ComputeScatteringOrderTexel) integrates
// orders 2 .. K over the sphere and carries the rest as H20's series, order K f_ms / (1 - f_ms)
// (Eq. 9-10): each further order the share f_ms of the one before that the air around a point
// returns from isotropic light. Where the air is optically thick that share is taken from the
// neighbourhood lit directly, and the light that diffuses down through hundreds of orders is
// lost: the `thick` preset (50x Rayleigh) kept 17 % of its red and < 0.1 % of its green and blue
// (BENCHMARKS.md, discrepancy 3). The column measures that loss: for each of the LUT's sun
// cosines, the mean radiance J of a plane-parallel atmosphere with the same profiles, its direct
// sunlight attenuated as the LUT's (the transmittance LUT, Earth's shadow included), solved for
// all orders at once and for orders 1 .. K - 1 one by one. The correction
//
//   column(z, mu_s) = (J - J_1 - ... - J_{K-1}) - J_{K-1} f / (1 - f)
//
// is what the column's exact orders past K hold beyond its own series estimate of them, and the
// LUT adds it to its own series, isotropically (ScatteringOrdersSum). In thin air the two agree
// and the correction is small; in the thick preset it is nearly all of the light.
//
// The column follows the LUT's conventions so that the two differ only in geometry and orders:
// radiance order 1 (the LUT's order 2) is the sunlight scattered once, isotropically, with the
// full scattering coefficient, plus the ground's reflection of the direct sun; later orders
// scatter with the aerosols' reduced coefficient (1 - g) sigma_s through the full extinction,
// and f is H20's transfer (no ground) in the same medium. Unlike the LUT's orders, the column's
// include the ground's reflection of the diffuse light (a Lambertian ground of the atmosphere's
// albedo).
//
// Numerics: isotropic scattering in optical depth, J(tau) = 1/2 int S(tau') E1(|tau - tau'|)
// dtau' plus the ground's radiance attenuated by E2 (ScatteringColumn), on `layers` layers
// denser near the ground (boundaries at z = H (e^(4x) - 1) / (e^4 - 1)). One LU factorisation
// per channel serves every sun cosine (Eigen's partial-pivoting LU).
#pragma once

#include <Eigen/Dense>
#include <glm/glm.hpp>
#include <vector>

#include "reference/shared_math.h"
#include "zenith/sky/atmosphere.h"
#include "zenith/sky/lut.h"

namespace zenith::sky {

// A plane-parallel column over a Lambertian ground, scattering isotropically: the mean radiance
// J (1/4pi int L dw) at its nodes, order by order or all orders at once. The nodes are the
// layers' boundaries, listed from the ground (node 0) to the top (node layers); sources are per
// unit optical depth and steradian (S = emission / sigma_t), given at the nodes and linear in
// optical depth between them, with the kernel integrated exactly against them (E2 .. E4), so the
// collocation is second order in the layers' optical depth.
class ScatteringColumn {
  public:
    // optical_depths: each layer's, from the ground up; albedos: the single-scattering albedo at
    // each node (one more than the layers).
    ScatteringColumn(const std::vector<double>& optical_depths, const std::vector<double>& albedos,
                     double ground_albedo);

    int nodes() const { return static_cast<int>(tau_.size()); }
    // J of the light scattered once from `source` and of the radiance `ground_radiance` leaving
    // the ground (with the ground's reflection of the source's own light).
    std::vector<double> FromSource(const std::vector<double>& source, double ground_radiance) const;
    // The next order's J from this order's (each node scatters its albedo of it).
    std::vector<double> NextOrder(const std::vector<double>& j) const;
    // The sum of all orders from the first: (I - NextOrder)^-1 first.
    std::vector<double> AllOrders(std::vector<double> first) const;
    // H20's transfer f_ms at each node: J there of an isotropic unit J everywhere scattered once,
    // without the ground.
    const std::vector<double>& Transfer() const { return transfer_; }
    // The flux a source sends out through the top (x) and down onto the ground (y).
    glm::dvec2 EscapingFlux(const std::vector<double>& source) const;

  private:
    std::vector<double> tau_;  // optical depth from the top at each node
    std::vector<double> ground_, flux_to_ground_, flux_to_top_, transfer_;
    Eigen::MatrixXd kernel_, next_;
    Eigen::PartialPivLU<Eigen::MatrixXd> all_orders_;  // I - next_, factorised
};

// The correction (RGB, per unit light illuminance, like Psi_ms) at each texel centre of one tile
// of the multiple-scattering LUT (settings.multiple_scattering_size), for its last order
// settings.multiple_scattering_orders. All zero when settings.multiple_scattering_column_layers
// is 0 (H20's series alone).
LutImage MultipleScatteringColumnCorrection(const Atmosphere& atmosphere,
                                            const ref::Texture2D& transmittance,
                                            const LutSettings& settings);

}  // namespace zenith::sky
