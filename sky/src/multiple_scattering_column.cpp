#include "multiple_scattering_column.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>
#include <vector>

#include "reference/atmosphere_functions.h"
#include "shader_parameters.h"

namespace zenith::sky {
namespace {

constexpr double kPi = std::numbers::pi;

// The exponential integrals E_m(x) = int_1^inf e^(-x t) / t^m dt for x >= 0, m = 1 .. 4, by
// E_(m+1) = (e^-x - x E_m) / m from E1 (std::expint is Ei: E1(x) = -Ei(-x)); E_m(0) = 1 / (m - 1).
struct ExpIntegrals {
    double e[5];  // e[m] = E_m(x), e[0] unused
    explicit ExpIntegrals(double x) : e{} {
        if (x > 0.0) {
            const double decay = std::exp(-x);
            e[1] = -std::expint(-x);
            for (int m = 1; m < 4; ++m) e[m + 1] = (decay - x * e[m]) / m;
        } else {
            e[1] = 0.0;  // infinite; never read (E1 enters only through E2 .. E4)
            e[2] = 1.0;
            e[3] = 0.5;
            e[4] = 1.0 / 3.0;
        }
    }
};

// The integrals of E_m(|t - tau|) against the two linear pieces of an interval [a, b] of optical
// depth that does not contain t (t at or beyond either end), given E at |t - a| and |t - b|:
// against (tau - a) / (b - a) (rising to 1 at b) and (b - tau) / (b - a) (falling from 1 at a).
// With x = |t - tau| running from x1 (the near end) to x2 (the far end): int E_m = E_(m+1)(x1) -
// E_(m+1)(x2) and int x E_m = [x E_(m+1) + E_(m+2)] from x2 to x1.
glm::dvec2 LinearPieces(int m, double t, double a, double b, const ExpIntegrals& at_a,
                        const ExpIntegrals& at_b) {
    const double length = b - a;
    if (!(length > 0.0)) return glm::dvec2(0.0);
    const bool above = t <= a;  // t before the interval: x grows with tau
    const double x1 = above ? a - t : t - b;
    const double x2 = above ? b - t : t - a;
    const ExpIntegrals& near = above ? at_a : at_b;
    const ExpIntegrals& far = above ? at_b : at_a;
    const double zeroth = near.e[m + 1] - far.e[m + 1];
    const double first = (x1 * near.e[m + 1] + near.e[m + 2]) - (x2 * far.e[m + 1] + far.e[m + 2]);
    // int (tau - t) E_m over the interval: +first when t is before it, -first when after.
    const double moment = above ? first : -first;
    const double rising = (moment + (t - a) * zeroth) / length;
    return {rising, zeroth - rising};
}

std::size_t Index(int i) { return static_cast<std::size_t>(i); }

Eigen::Map<const Eigen::VectorXd> AsVector(const std::vector<double>& v) {
    return {v.data(), static_cast<Eigen::Index>(v.size())};
}

std::vector<double> ToStd(const Eigen::VectorXd& v) { return {v.begin(), v.end()}; }

}  // namespace

ScatteringColumn::ScatteringColumn(const std::vector<double>& optical_depths,
                                   const std::vector<double>& albedos, double ground_albedo) {
    const std::size_t layers = optical_depths.size();
    const int n = static_cast<int>(layers) + 1;  // nodes
    const std::size_t un = layers + 1;
    tau_.assign(un, 0.0);  // node k is the lower boundary of layer k; tau_[n - 1] = 0 at the top
    for (std::size_t k = layers; k-- > 0;) tau_[k] = tau_[k + 1] + optical_depths[k];
    const double tau_ground = tau_[0];

    // J at node i of a source linear between nodes with unit value at node j, 1/2 int E1, and
    // the flux it sends to the ground (2 pi int E2) and up through the top (2 pi int E2): each
    // node's hat is the rising piece of the layer below it and the falling piece of the one
    // above it (in optical depth from the top, the layer above comes first).
    const auto hats = [&](int m, double t) {
        std::vector<ExpIntegrals> at_nodes;  // E at |t - tau| of each node, shared by two layers
        at_nodes.reserve(un);
        for (std::size_t k = 0; k < un; ++k) at_nodes.emplace_back(std::abs(t - tau_[k]));
        std::vector<double> weights(un, 0.0);
        for (std::size_t k = 0; k < layers; ++k) {
            // Layer k runs from tau_[k + 1] (its top, node k + 1) to tau_[k] (node k).
            const glm::dvec2 pieces =
                LinearPieces(m, t, tau_[k + 1], tau_[k], at_nodes[k + 1], at_nodes[k]);
            weights[k] += pieces.x;      // rising to node k at the layer's bottom
            weights[k + 1] += pieces.y;  // falling from node k + 1 at its top
        }
        return weights;
    };
    flux_to_ground_ = hats(2, tau_ground);
    flux_to_top_ = hats(2, 0.0);
    for (std::size_t j = 0; j < un; ++j) {
        flux_to_ground_[j] *= 2.0 * kPi;
        flux_to_top_[j] *= 2.0 * kPi;
    }
    ground_.resize(un);
    for (std::size_t i = 0; i < un; ++i) ground_[i] = 0.5 * ExpIntegrals(tau_ground - tau_[i]).e[2];
    kernel_.resize(n, n);
    transfer_.assign(un, 0.0);
    for (int i = 0; i < n; ++i) {
        const std::vector<double> air = hats(1, tau_[Index(i)]);
        for (int j = 0; j < n; ++j) {
            const std::size_t uj = Index(j);
            transfer_[Index(i)] += 0.5 * air[uj] * albedos[uj];
            kernel_(i, j) =
                0.5 * air[uj] + ground_albedo / kPi * ground_[Index(i)] * flux_to_ground_[uj];
        }
    }
    // NextOrder's operator (each node scatters its albedo), and I minus it factorised.
    next_ = kernel_ * AsVector(albedos).asDiagonal();
    all_orders_.compute(Eigen::MatrixXd::Identity(n, n) - next_);
}

std::vector<double> ScatteringColumn::FromSource(const std::vector<double>& source,
                                                 double ground_radiance) const {
    return ToStd(kernel_ * AsVector(source) + ground_radiance * AsVector(ground_));
}

std::vector<double> ScatteringColumn::NextOrder(const std::vector<double>& j) const {
    return ToStd(next_ * AsVector(j));
}

std::vector<double> ScatteringColumn::AllOrders(std::vector<double> first) const {
    return ToStd(all_orders_.solve(AsVector(first)));
}

glm::dvec2 ScatteringColumn::EscapingFlux(const std::vector<double>& source) const {
    glm::dvec2 flux(0.0);
    for (std::size_t j = 0; j < source.size(); ++j) {
        flux.x += source[j] * flux_to_top_[j];
        flux.y += source[j] * flux_to_ground_[j];
    }
    return flux;
}

LutImage MultipleScatteringColumnCorrection(const Atmosphere& air,
                                            const ref::Texture2D& transmittance,
                                            const LutSettings& settings) {
    const auto atmosphere = MakeShaderParameters<ref::AtmosphereParameters>(air);
    const glm::ivec2 size = settings.multiple_scattering_size;
    LutImage correction(size.x, size.y);
    const int layers = settings.multiple_scattering_column_layers;
    if (layers == 0) return correction;
    const auto un = static_cast<std::size_t>(layers) + 1;  // nodes
    const int last_order = settings.multiple_scattering_orders;
    const double height = atmosphere.top_radius - atmosphere.bottom_radius;  // km

    // The nodes' altitudes, from the ground (z[0] = 0) to the top, denser near the ground.
    constexpr double kStretch = 4.0;
    std::vector<double> z(un);
    for (std::size_t k = 0; k < un; ++k) {
        z[k] =
            height * std::expm1(kStretch * static_cast<double>(k) / layers) / std::expm1(kStretch);
    }

    // The LUT's sun cosines (texel columns) and altitudes (texel rows), as
    // ComputeScatteringOrderTexel places them.
    std::vector<double> sun_cosines(static_cast<std::size_t>(size.x));
    for (int x = 0; x < size.x; ++x) {
        sun_cosines[static_cast<std::size_t>(x)] = ref::SunCosineFromUnitRange(
            ref::GetUnitRangeFromTextureCoord((x + 0.5) / size.x, size.x));
    }
    // Each row's altitude lies between the nodes above - 1 and above, at weight w of the latter.
    struct RowNodes {
        std::size_t above;
        double w;
    };
    std::vector<RowNodes> row_nodes(static_cast<std::size_t>(size.y));
    for (int y = 0; y < size.y; ++y) {
        const double x_h = ref::GetUnitRangeFromTextureCoord((y + 0.5) / size.y, size.y);
        const double altitude = std::clamp(x_h, 0.0, 1.0) * height;
        const auto above = std::clamp<std::size_t>(
            static_cast<std::size_t>(std::upper_bound(z.begin(), z.end(), altitude) - z.begin()), 1,
            un - 1);
        const double w =
            std::clamp((altitude - z[above - 1]) / (z[above] - z[above - 1]), 0.0, 1.0);
        row_nodes[static_cast<std::size_t>(y)] = {above, w};
    }

    // The direct sunlight at each node (as the LUT's order 2 has it, Earth's shadow included)
    // and the flux it brings to the ground, per sun cosine.
    std::vector<std::vector<ref::vec3>> sunlight(sun_cosines.size());
    std::vector<ref::vec3> ground_sunlight(sun_cosines.size());
    for (std::size_t u = 0; u < sun_cosines.size(); ++u) {
        sunlight[u].resize(un);
        for (std::size_t k = 0; k < un; ++k) {
            const double r =
                std::clamp(atmosphere.bottom_radius + z[k], atmosphere.bottom_radius + 1e-4,
                           atmosphere.top_radius - 1e-4);
            sunlight[u][k] =
                ref::GetTransmittanceToSun(atmosphere, transmittance, r, sun_cosines[u]);
        }
        ground_sunlight[u] = sunlight[u][0] * std::max(sun_cosines[u], 0.0);
    }

    // The medium at the nodes, and each layer's optical depth by the midpoint rule in 8 parts.
    std::vector<ref::MediumSample> at_nodes(un);
    for (std::size_t k = 0; k < un; ++k) at_nodes[k] = ref::SampleMedium(atmosphere, z[k]);
    std::vector<ref::vec3> depth(un - 1, ref::vec3(0.0));
    for (std::size_t k = 0; k + 1 < un; ++k) {
        constexpr int kParts = 8;
        for (int part = 0; part < kParts; ++part) {
            depth[k] +=
                ref::SampleMedium(atmosphere, z[k] + (part + 0.5) / kParts * (z[k + 1] - z[k]))
                    .extinction;
        }
        depth[k] *= (z[k + 1] - z[k]) / kParts;
    }

    for (int c = 0; c < 3; ++c) {
        // Albedos: orders >= 2 with the aerosols' reduced scattering, order 1 with the full.
        std::vector<double> depths(un - 1), albedo(un), first_albedo(un);
        for (std::size_t k = 0; k + 1 < un; ++k) depths[k] = depth[k][c];
        for (std::size_t k = 0; k < un; ++k) {
            const ref::MediumSample& s = at_nodes[k];
            const double extinction = s.extinction[c];
            albedo[k] =
                extinction > 0.0
                    ? (s.scattering[c] - atmosphere.mie_g * s.mie_scattering[c]) / extinction
                    : 0.0;
            first_albedo[k] = extinction > 0.0 ? s.scattering[c] / extinction : 0.0;
        }
        const double ground_albedo = atmosphere.ground_albedo[c];
        const ScatteringColumn column(depths, albedo, ground_albedo);
        const std::vector<double>& transfer = column.Transfer();

        for (std::size_t u = 0; u < sun_cosines.size(); ++u) {
            // Order 1: the sunlight scattered once, and the ground's reflection of it.
            std::vector<double> source(un);
            for (std::size_t k = 0; k < un; ++k) {
                source[k] = first_albedo[k] * sunlight[u][k][c] / (4.0 * kPi);
            }
            std::vector<double> order =
                column.FromSource(source, ground_albedo / kPi * ground_sunlight[u][c]);
            std::vector<double> past = column.AllOrders(order);
            // Orders 1 .. K - 1 (the LUT's 2 .. K) out; `order` ends at K - 1.
            for (int k = 1; k < last_order; ++k) {
                if (k > 1) order = column.NextOrder(order);
                for (std::size_t i = 0; i < un; ++i) past[i] -= order[i];
            }
            std::vector<double> value(un);
            for (std::size_t i = 0; i < un; ++i) {
                const double f = std::min(transfer[i], 0.999);
                value[i] = past[i] - order[i] * f / (1.0 - f);
            }
            // To the LUT's rows, linearly between nodes.
            for (int y = 0; y < size.y; ++y) {
                const auto [above, w] = row_nodes[static_cast<std::size_t>(y)];
                correction.at(static_cast<int>(u), y)[c] =
                    static_cast<float>((1.0 - w) * value[above - 1] + w * value[above]);
            }
        }
    }
    return correction;
}

}  // namespace zenith::sky
