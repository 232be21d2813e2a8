// The International Standard Atmosphere (ICAO Doc 7488; the 1976 US Standard Atmosphere below
// 86 km): its sea-level state, constants and temperature layers, for the altimetry of pressure
// altitudes (zenith/weather/altimetry.h) and the air refraction is traced through
// (refraction.h).
#pragma once

#include <array>

namespace zenith::geo {

inline constexpr double kIsaPressureHpa = 1013.25;
inline constexpr double kIsaTemperatureK = 288.15;
inline constexpr double kIsaLapseRate = 0.0065;          // K/m, the troposphere's
inline constexpr double kIsaTropopause = 11000.0;        // m, geopotential
inline constexpr double kStandardGravity = 9.80665;      // m/s^2
inline constexpr double kDryAirGasConstant = 287.05287;  // J/(kg K)

// The layers: base geopotential height (m) and temperature gradient (K/m) up to the next base;
// the last entry is the top (84.852 km).
struct IsaLayer {
    double base_m;
    double gradient;
};
inline constexpr std::array<IsaLayer, 8> kIsaLayers = {{{0.0, -0.0065},
                                                        {11000.0, 0.0},
                                                        {20000.0, 0.001},
                                                        {32000.0, 0.0028},
                                                        {47000.0, 0.0},
                                                        {51000.0, -0.0028},
                                                        {71000.0, -0.002},
                                                        {84852.0, 0.0}}};

}  // namespace zenith::geo
