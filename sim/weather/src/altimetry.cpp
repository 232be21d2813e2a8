#include "zenith/weather/altimetry.h"

#include <algorithm>
#include <cmath>

#include "zenith/base/error.h"
#include "zenith/weather/metar.h"

namespace zenith::weather {
namespace {

constexpr double kGasOverGravity = kDryAirGasConstant / kStandardGravity;  // m/K
// Exponent of the troposphere's pressure law, g0 / (R L) = 5.2559.
constexpr double kTroposphereExponent = kStandardGravity / (kDryAirGasConstant * kIsaLapseRate);
constexpr double kTropopauseTemperature = kIsaTemperatureK - kIsaLapseRate * kIsaTropopause;

double TropopausePressure() {
    return kIsaPressureHpa *
           std::pow(kTropopauseTemperature / kIsaTemperatureK, kTroposphereExponent);
}

}  // namespace

double IsaPressure(double h) {
    if (h <= kIsaTropopause) {
        return kIsaPressureHpa *
               std::pow(1.0 - kIsaLapseRate * h / kIsaTemperatureK, kTroposphereExponent);
    }
    return TropopausePressure() *
           std::exp(-(h - kIsaTropopause) / (kGasOverGravity * kTropopauseTemperature));
}

double IsaPressureAltitude(double pressure_hpa) {
    const double p11 = TropopausePressure();
    if (pressure_hpa >= p11) {
        return kIsaTemperatureK / kIsaLapseRate *
               (1.0 - std::pow(pressure_hpa / kIsaPressureHpa, 1.0 / kTroposphereExponent));
    }
    return kIsaTropopause + kGasOverGravity * kTropopauseTemperature * std::log(p11 / pressure_hpa);
}

double HeightFromPressureAltitude(double pressure_altitude_m, const StationAir& air) {
    Require("pressure_altitude", pressure_altitude_m, "m", Range::Closed(-1000.0, 20000.0));
    Require("qnh", air.qnh_hpa, "hPa", Range::Closed(850.0, 1100.0));
    Require("station_elevation", air.elevation_m, "m", Range::Closed(-500.0, 9000.0));
    const double pressure = IsaPressure(pressure_altitude_m);
    // The altimeter set to QNH: ISA with QNH at mean sea level.
    const double altimeter = IsaPressureAltitude(pressure * kIsaPressureHpa / air.qnh_hpa);
    if (!air.temperature_c) return altimeter;
    Require("temperature", *air.temperature_c, "deg C", Range::Closed(-90.0, 60.0));
    // The station's pressure (on the altimeter's atmosphere, by QNH's definition) and the
    // deviation from that atmosphere's temperature there, carried up the pressure levels.
    const double station_pressure =
        air.qnh_hpa *
        std::pow(1.0 - kIsaLapseRate * air.elevation_m / kIsaTemperatureK, kTroposphereExponent);
    const double deviation =
        *air.temperature_c + 273.15 - (kIsaTemperatureK - kIsaLapseRate * air.elevation_m);
    return altimeter + deviation * kGasOverGravity * std::log(station_pressure / pressure);
}

geo::RefractionAir RefractionAirOf(const StationAir& air) {
    geo::RefractionAir out;
    out.sea_level_pressure_hpa = air.qnh_hpa;
    if (air.temperature_c) {
        out.sea_level_temperature_c =
            std::clamp(*air.temperature_c + kIsaLapseRate * air.elevation_m, -90.0, 60.0);
    }
    return out;
}

StationAir StationAirOf(const Metar& report, double elevation_m) {
    StationAir air;
    if (report.qnh_hpa) air.qnh_hpa = *report.qnh_hpa;
    air.temperature_c = report.temperature_c;
    air.elevation_m = elevation_m;
    return air;
}

}  // namespace zenith::weather
