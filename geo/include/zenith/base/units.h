// Unit constants. SI everywhere in C++ (metres, seconds, radians); other units are in names
// (lat_deg, altitude_ft). Shaders work in kilometres, converted once with kMetresPerKm.
#pragma once

#include <numbers>

namespace zenith {

inline constexpr double kPi = std::numbers::pi;
inline constexpr double kRadiansPerDegree = std::numbers::pi / 180.0;
inline constexpr double kDegreesPerRadian = 180.0 / std::numbers::pi;
inline constexpr double kMetresPerKm = 1000.0;
inline constexpr double kMetresPerFoot = 0.3048;           // international foot (exact)
inline constexpr double kMetresPerStatuteMile = 1609.344;  // exact
inline constexpr double kMetresPerNauticalMile = 1852.0;   // exact
inline constexpr double kSecondsPerDay = 86400.0;

constexpr double Radians(double degrees) { return degrees * kRadiansPerDegree; }
constexpr double Degrees(double radians) { return radians * kDegreesPerRadian; }

}  // namespace zenith
