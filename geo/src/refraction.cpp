#include "zenith/geo/refraction.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "zenith/base/error.h"

namespace zenith::geo {
namespace {

constexpr double kHalfPi = 1.5707963267948966;

// ISA's layers with every temperature shifted to the sea-level temperature given, and their
// base pressures by the hydrostatic equation from the sea-level pressure given.
class AirProfile {
  public:
    explicit AirProfile(const RefractionAir& air) {
        const double shift = air.sea_level_temperature_c + 273.15 - kIsaTemperatureK;
        double isa_temperature = kIsaTemperatureK;
        double pressure = air.sea_level_pressure_hpa;
        for (std::size_t i = 0; i + 1 < kIsaLayers.size(); ++i) {
            const IsaLayer& l = kIsaLayers[i];
            layers_[i] = {l.base_m, l.gradient, isa_temperature + shift, pressure};
            const double depth = kIsaLayers[i + 1].base_m - l.base_m;
            pressure = Pressure(layers_[i], depth);
            isa_temperature += l.gradient * depth;
        }
    }

    double top() const { return kIsaLayers.back().base_m; }

    // n - 1, and -(dn/dh) / n (1/m), at geopotential height h (m); 0 above the top, the first
    // layer's law below sea level.
    void At(double h, double* refractivity, double* gradient) const {
        if (h >= top()) {
            *refractivity = 0.0;
            *gradient = 0.0;
            return;
        }
        std::size_t i = 0;
        while (i + 1 < layers_.size() && h >= layers_[i + 1].base) ++i;
        const Layer& l = layers_[i];
        const double temperature = l.temperature + l.gradient * (h - l.base);
        const double n1 = kAirRefractivity * (Pressure(l, h - l.base) / kIsaPressureHpa) *
                          (kIsaTemperatureK / temperature);
        *refractivity = n1;
        // ln(n - 1) = ln p - ln T + const; d ln p / dh = -g / (R T).
        *gradient =
            n1 *
            (kStandardGravity / (kDryAirGasConstant * temperature) + l.gradient / temperature) /
            (1.0 + n1);
    }

    // n r at planet radius `radius` + h.
    double Invariant(double radius, double h) const {
        double n1 = 0.0, gradient = 0.0;
        At(h, &n1, &gradient);
        return (1.0 + n1) * (radius + h);
    }

  private:
    struct Layer {
        double base = 0.0;         // m
        double gradient = 0.0;     // K/m
        double temperature = 0.0;  // K at the base
        double pressure = 0.0;     // hPa at the base
    };
    static double Pressure(const Layer& l, double above_base) {
        const double t = l.temperature + l.gradient * above_base;
        if (l.gradient == 0.0) {
            return l.pressure *
                   std::exp(-kStandardGravity * above_base / (kDryAirGasConstant * l.temperature));
        }
        return l.pressure *
               std::pow(l.temperature / t, kStandardGravity / (kDryAirGasConstant * l.gradient));
    }
    std::array<Layer, kIsaLayers.size() - 1> layers_{};
};

// The bending along the ray of invariant k between radii ra < rb (planet radius `radius`):
// the integral of -(dn/dr / n) k / sqrt(u^2 - k^2), u = n r, with r = origin + x^2
// (dr = 2x dx; origin <= ra, the ray's lowest point, real or where the air's law continued
// down would put it, which makes the integrand smooth in x), each stretch between the layers'
// bases by Gauss-Legendre (8 nodes, kPanels panels).
double Bending(const AirProfile& air, double radius, double k, double origin, double ra,
               double rb) {
    static constexpr double kNodes[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267,
                                         0.9602898564975363};
    static constexpr double kWeights[4] = {0.3626837833783620, 0.3137066458778873,
                                           0.2223810344533745, 0.1012285362903763};
    constexpr int kPanels = 4;
    std::vector<double> breaks = {std::sqrt(ra - origin)};
    for (const IsaLayer& l : kIsaLayers) {
        const double r = radius + l.base_m;
        if (r > ra && r < rb) breaks.push_back(std::sqrt(r - origin));
    }
    breaks.push_back(std::sqrt(rb - origin));
    const auto integrand = [&](double x) {
        const double r = origin + x * x;
        double n1 = 0.0, gradient = 0.0;
        air.At(r - radius, &n1, &gradient);
        const double u = (1.0 + n1) * r;
        const double s = std::sqrt(std::max((u - k) * (u + k), 1e-300));
        return 2.0 * x * gradient * k / s;
    };
    double sum = 0.0;
    for (std::size_t b = 0; b + 1 < breaks.size(); ++b) {
        const double width = (breaks[b + 1] - breaks[b]) / kPanels;
        for (int p = 0; p < kPanels; ++p) {
            const double mid = breaks[b] + (p + 0.5) * width;
            for (int i = 0; i < 4; ++i) {
                const double dx = 0.5 * width * kNodes[i];
                sum += 0.5 * width * kWeights[i] * (integrand(mid - dx) + integrand(mid + dx));
            }
        }
    }
    return sum;
}

// The radius in [lo, hi] where n r = k (n r grows with r), by bisection.
double InvariantRadius(const AirProfile& air, double radius, double k, double lo, double hi) {
    for (int i = 0; i < 100 && hi - lo > 1e-6; ++i) {
        const double mid = 0.5 * (lo + hi);
        (air.Invariant(radius, mid - radius) < k ? lo : hi) = mid;
    }
    return lo;
}

std::optional<double> Trace(const AirProfile& air, double height_m, double e, double radius) {
    const double r0 = radius + height_m;
    const double top = radius + air.top();
    const double k = air.Invariant(radius, height_m) * std::cos(e);
    if (e >= 0.0) {
        if (r0 >= top) return 0.0;
        // The rising ray's lowest point continued below the observer (a shallow ray's integrand
        // is steep there); at most 20 km below, where steeper rays no longer need it.
        const double floor = r0 - 20000.0;
        const double origin = air.Invariant(radius, floor - radius) >= k
                                  ? floor
                                  : InvariantRadius(air, radius, k, floor, r0);
        return Bending(air, radius, k, origin, r0, top);
    }
    // Below the horizontal: down to the lowest point, where n r = k, then up to the top.
    if (air.Invariant(radius, 0.0) >= k) return std::nullopt;  // the ray comes from the ground
    const double lowest = InvariantRadius(air, radius, k, radius, r0);
    if (lowest >= top) return 0.0;
    return Bending(air, radius, k, lowest, lowest, std::min(r0, top)) +
           Bending(air, radius, k, lowest, lowest, top);
}

}  // namespace

void RefractionAir::Validate() const {
    Require("pressure", sea_level_pressure_hpa, "hPa", Range::Closed(850.0, 1100.0));
    Require("temperature", sea_level_temperature_c, "deg C", Range::Closed(-90.0, 60.0));
}

std::optional<double> TraceRefraction(const RefractionAir& air, double height_m,
                                      double apparent_elevation, double planet_radius_m) {
    air.Validate();
    Require("height", height_m, "m", Range::Closed(-12000.0, 1e8));
    Require("apparent_elevation", apparent_elevation, "rad", Range::Closed(-kHalfPi, kHalfPi));
    return Trace(AirProfile(air), std::max(height_m, 0.0), apparent_elevation, planet_radius_m);
}

RefractionTable::RefractionTable(const RefractionAir& air, double height_m, double planet_radius_m)
    : air_(air), height_m_(height_m), planet_radius_m_(planet_radius_m) {
    air.Validate();
    Require("height", height_m, "m", Range::Closed(-12000.0, 1e8));
    const AirProfile profile(air);
    const double h = std::max(height_m, 0.0);
    // The lowest ray that clears the ground grazes it: n r cos(e) = n(0) R.
    const double grazing =
        profile.Invariant(planet_radius_m, 0.0) / profile.Invariant(planet_radius_m, h);
    const double lowest = -std::acos(std::min(grazing, 1.0)) + 1e-9;
    for (int i = 0; i < kSamples; ++i) {
        const double t = static_cast<double>(i) / (kSamples - 1);
        const double e = lowest + (kHalfPi - lowest) * t * t * t;
        apparent_[static_cast<std::size_t>(i)] = e;
        geometric_[static_cast<std::size_t>(i)] =
            e - Trace(profile, h, e, planet_radius_m).value_or(0.0);
    }
}

std::optional<double> RefractionTable::Apparent(double geometric_elevation) const {
    if (geometric_elevation < geometric_.front()) return std::nullopt;
    if (geometric_elevation >= geometric_.back()) return geometric_elevation;
    const auto it = std::upper_bound(geometric_.begin(), geometric_.end(), geometric_elevation);
    const auto i = static_cast<std::size_t>(it - geometric_.begin()) - 1;
    const double u = (geometric_elevation - geometric_[i]) / (geometric_[i + 1] - geometric_[i]);
    return apparent_[i] + u * (apparent_[i + 1] - apparent_[i]);
}

double RefractionTable::VerticalScale(double geometric_elevation) const {
    if (geometric_elevation < geometric_.front() || geometric_elevation >= geometric_.back()) {
        return 1.0;
    }
    const auto it = std::upper_bound(geometric_.begin(), geometric_.end(), geometric_elevation);
    const auto i = static_cast<std::size_t>(it - geometric_.begin()) - 1;
    return (apparent_[i + 1] - apparent_[i]) / (geometric_[i + 1] - geometric_[i]);
}

}  // namespace zenith::geo
