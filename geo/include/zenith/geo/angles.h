// Angle constants and the two small angle helpers every part of geo/ needs.
#pragma once

#include <cmath>
#include <glm/glm.hpp>
#include <numbers>

namespace zenith::geo {

inline constexpr double kTwoPi = 2.0 * std::numbers::pi;
inline constexpr double kArcsecToRad = std::numbers::pi / 648000.0;

// a reduced to [0, 2pi).
inline double WrapTwoPi(double a) {
    const double w = std::fmod(a, kTwoPi);
    return w < 0.0 ? w + kTwoPi : w;
}

// Angle between two vectors; atan2 of |a x b| and a.b keeps full precision near 0 and pi,
// where acos of the dot product loses half the digits.
inline double AngleBetween(const glm::dvec3& a, const glm::dvec3& b) {
    return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

}  // namespace zenith::geo
