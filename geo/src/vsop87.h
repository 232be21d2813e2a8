// VSOP87B series evaluation, shared by sun.cpp and planets.cpp (private to zenith::geo).
//
// The tables (vsop87b_<body>.inc, made by scripts/gen_vsop87b_table.py) give heliocentric
// spherical coordinates referred to the dynamical ecliptic and equinox of J2000 as Poisson series
// X = sum_i tau^i sum_k A cos(B + C tau), tau in Julian millennia of TT since J2000.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <glm/glm.hpp>
#include <span>

namespace zenith::geo::detail {

struct VsopTerm {
    double a, b, c;  // term = a cos(b + c tau)
};

using VsopSeries = std::span<const std::span<const VsopTerm>>;

inline constexpr double kDaysPerMillennium = 365250.0;

// sum_i tau^i sum_k a cos(b + c tau), by Horner's rule over the powers of tau. With
// max_terms, only the first max_terms of each power (the source lists them by roughly
// decreasing amplitude): a cheap, coarse value.
inline double EvaluateVsop(VsopSeries series, double tau,
                           std::size_t max_terms = static_cast<std::size_t>(-1)) {
    double result = 0.0;
    for (auto power = series.rbegin(); power != series.rend(); ++power) {
        const std::span<const VsopTerm> terms = power->first(std::min(max_terms, power->size()));
        double sum = 0.0;
        // Smallest terms (stored last) first, for rounding.
        for (auto term = terms.rbegin(); term != terms.rend(); ++term) {
            sum += term->a * std::cos(term->b + term->c * tau);
        }
        result = result * tau + sum;
    }
    return result;
}

inline glm::dvec3 FromSpherical(double longitude, double latitude, double distance) {
    const double cb = std::cos(latitude);
    return distance *
           glm::dvec3(cb * std::cos(longitude), cb * std::sin(longitude), std::sin(latitude));
}

// GCRS <- VSOP87 ecliptic and equinox of J2000 (sun.cpp).
const glm::dmat3& GcrsFromEclipticJ2000();

// Heliocentric Earth in the VSOP87B frame (ecliptic and equinox J2000), metres (sun.cpp).
glm::dvec3 EarthHeliocentricEclipticJ2000(double jd_tt);

}  // namespace zenith::geo::detail
