// Rec.709 luminance of linear RGB, Y = 0.2126 R + 0.7152 G + 0.0722 B: the renderer's cd/m^2 or
// lux per channel to one photometric figure (sky/include/zenith/sky/atmosphere.h).
#pragma once

#include <glm/glm.hpp>

namespace zenith::test {

inline double Luminance(const glm::dvec3& c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }
inline double Luminance(const glm::vec3& c) { return Luminance(glm::dvec3(c)); }
inline double Luminance(const glm::vec4& c) { return Luminance(glm::dvec3(c.r, c.g, c.b)); }

}  // namespace zenith::test
