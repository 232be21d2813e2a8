// The Moon's geocentric apparent position from the ELP/MPP02 lunar theory (Chapront & Francou
// 2003), constants fitted to DE405, series truncated as documented in data/README.md.
#pragma once

#include <glm/glm.hpp>

#include "zenith/geo/sun.h"

namespace zenith::geo {

inline constexpr double kMoonRadius = 1737400.0;  // m, IAU mean radius

// Geometric geocentric Moon, mean ecliptic and equinox of date, metres.
EclipticPosition MoonGeometricEcliptic(double jd_tt);

// Apparent: light time (geocentric frame) and nutation in longitude; true equinox of date.
EclipticPosition MoonApparentEcliptic(double jd_tt);

// Geocentric apparent position in TOD, metres.
glm::dvec3 MoonApparentTod(double jd_tt);

}  // namespace zenith::geo
