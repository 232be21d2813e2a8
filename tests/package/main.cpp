// Uses each installed library from a separate project: geo (ephemeris), sky (presets), sim
// (the batch record) and weather (a METAR report as cloud layers). No GL context is needed.
#include <zenith/geo/ephemeris.h>
#include <zenith/sim/ephemeris_report.h>
#include <zenith/sky/atmosphere.h>
#include <zenith/weather/cloud_weather.h>

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

int main() {
    const zenith::geo::Time t = zenith::geo::TimeFromIso8601("2000-01-01T12:00:00Z");
    const zenith::geo::Observer greenwich(51.4769, 0.0, 46.0);
    const auto e = zenith::geo::Ephemeris().Compute(t, greenwich);
    const double elevation_deg = zenith::sim::EphemerisRecord(e)["sun_el_deg"].get<double>();
    const zenith::sky::Atmosphere earth;
    zenith::sky::Validate(earth);
    std::printf("sun elevation %.3f deg, Rayleigh %.3e /m\n", elevation_deg,
                earth.rayleigh_scattering.b);
    const auto weather = zenith::weather::CloudWeatherFromMetar(
        zenith::weather::DecodeMetar("EGLL 211750Z 24012KT 9999 FEW035 SCT250 18/09 Q1018"), 25.0);
    if (weather.clouds.layers.size() != 2) return 1;
    return std::abs(elevation_deg - 15.5) < 1.0 ? 0 : 1;  // winter noon sun at 51.5 N
}
