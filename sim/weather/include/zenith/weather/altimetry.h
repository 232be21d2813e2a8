// Altimetry: the height of an aircraft from its pressure altitude, in the air a METAR reports.
//
// A pressure altitude (an IGC file's, a transponder's) is the ISA height of the static pressure
// p with the 1013.25 hPa datum (ICAO Doc 7488, the International Standard Atmosphere), a
// geopotential height. The real air differs in two ways, and a report gives both:
//   - the pressure: an altimeter set to QNH reads the height of p in ISA with QNH at mean sea
//     level, H_qnh(p) = H_isa(p 1013.25 / QNH) (ICAO Annex 3: QNH is the station's pressure
//     reduced to mean sea level through ISA, so it reads the station's elevation z_s there);
//   - the temperature: the station's T_s deviates by dT = T_s - (T0 - L z_s) from that
//     atmosphere, and dT is taken as constant on every pressure level above (the assumption of
//     ICAO Doc 8168's cold-temperature corrections); the hypsometric equation
//     dz = -(R T / g0) dp / p then adds dT (R / g0) ln(p_s / p) to the altimeter's height.
// So z = H_qnh(p) + dT (R / g0) ln(p_s / p), p = P_isa(H_p), p_s = QNH (1 - L z_s / T0)^(g0/RL).
// Without a temperature z = H_qnh(p), and with QNH = 1013.25 hPa as well, z = H_p. The
// station's elevation only places dT's reference (T0 - L z_s) and p_s: 0 when it is not known.
#pragma once

#include <optional>

#include "zenith/geo/refraction.h"
#include "zenith/geo/standard_atmosphere.h"
#include "zenith/weather/metar.h"

namespace zenith::weather {

// ISA (zenith/geo/standard_atmosphere.h): sea-level pressure and temperature, the
// troposphere's lapse rate and its top, standard gravity and the gas constant of dry air.
using geo::kDryAirGasConstant;
using geo::kIsaLapseRate;
using geo::kIsaPressureHpa;
using geo::kIsaTemperatureK;
using geo::kIsaTropopause;
using geo::kStandardGravity;

// ISA pressure (hPa) at geopotential height `h` (m; -5 km to 20 km), and its inverse.
double IsaPressure(double h);
double IsaPressureAltitude(double pressure_hpa);

// What a report says about the air for altimetry.
struct StationAir {
    double qnh_hpa = kIsaPressureHpa;
    std::optional<double> temperature_c;  // at the station; none: ISA's there
    double elevation_m = 0.0;             // of the station above mean sea level
};

// Geopotential height above mean sea level (m) of an aircraft at pressure altitude
// `pressure_altitude_m` in `air` (see the file comment). Throws zenith::ArgumentError for a
// QNH outside 850..1100 hPa, a temperature outside -90..60 deg C or a pressure altitude outside
// -1 km..20 km.
double HeightFromPressureAltitude(double pressure_altitude_m, const StationAir& air);

// A report's QNH (ISA's 1013.25 hPa when it has none) and temperature, at a station of that
// elevation.
StationAir StationAirOf(const Metar& report, double elevation_m);

// The air refraction is traced through (zenith/geo/refraction.h) from what a station reports:
// QNH as the sea-level pressure, the station's temperature carried down ISA's lapse rate to sea
// level (ISA's 15 deg C without one; within -90..60 deg C).
geo::RefractionAir RefractionAirOf(const StationAir& air);

}  // namespace zenith::weather
