// A decoded METAR as zenith weather: cloud layers for the renderer (sky::clouds::Weather) and the
// near-ground extinction that makes the meteorological optical range equal the report.
//
// A separate target (zenith::weather_sky) from the METAR reader, because it needs zenith::sky's
// weather types and checks; the reader (zenith::weather) stays free of GL.
//
// The mapping (values chosen to look right and to meet the measured criteria, not
// measured; "base" is the report's height above the station plus the station's elevation, i.e.
// metres above the planet's sphere like every CloudLayer altitude):
//
//   report                  layer coverage      cloud type                  depth (top - base)
//   ----------------------  ------------------  --------------------------  --------------------
//   FEW (1-2 oktas)         0.38                low: cumulus (0.5)          low cumulus:
//   SCT (3-4 oktas)         0.48                low: cumulus (0.5)            1000 m + 50 m/degC
//   BKN (5-7 oktas)         0.75                low: stratocumulus (0.25)     above 15 degC,
//   OVC (8 oktas)           1                   low: stratus (0)              [500, 2000] m
//   /// (amount unknown)    0.48                as SCT                      stratocumulus 600 m
//   ...CB                   as its amount       cumulonimbus (1)            stratus 400 m (2000 m
//   ...TCU                  as its amount       congestus (0.75)              with precipitation:
//   middle (base >= 2 km)   as its amount       stratocumulus (0.25);         nimbostratus)
//                                               OVC: stratus (0)            middle 800 m
//   high (base >= 6 km)     as its amount       cirrus (OVC: cirrostratus): high 500 m
//                                               ice, extinction_scale 0.04,
//                                               stratus (0) profile
//                                                                           TCU 4000 m
//                                                                           CB to 10 km above
//                                                                             the station
//   VVhhh                   fog layer at the ground, coverage 1, stratus, top = hhh (>= 50 m)
//   FG (no VV), FZFG        fog layer at the ground, 100 m deep; MIFG 50 m; BCFG/PRFG 0.5
//                           Fog is homogeneous ground fog (CloudLayer::ground_fog) whose
//                           extinction plus the air's (set for 1 km) is ln 20 / V for a
//                           reported V below 1 km, or that of 500 m in its patches else
//   CAVOK, SKC/CLR/NSC/NCD  no layer (a clear sky: the same Weather as the "clear" preset)
//   ///hhh or XXX///        a layer without a base is left out, with a note
//
// Coverage is the density model's parameter, not the share of sky: its remap keeps only noise
// above 1 - c, so 1.5/8 drew no sky below a transmittance of 0.5. The values are those whose
// drawn share of the sky above 10 deg, seen from the station, is mid-range (FEW 1.5, SCT 3.5,
// BKN 6 oktas on average over six stations' maps; measured in
// tests/weather_sky/metar_sky_cover_test.cpp). A FEW/SCT/BKN layer's base is lowered by
// (1 - sqrt(c)) / 4 of its clouds' tallest height, where its density starts, so the lowest base
// seen is the report's (within 3 %); two layers reported less than 50 m apart are one.
//
// Map: FEW/SCT and TCU layers "patches" (12 cells per tile, variation 0.6), BKN "patches"
// (8, 0.4), OVC and fog "uniform", CB "cells", high non-OVC "streaks" (6, 0.7; cirrus' fibres);
// seeds from the station and the layer's index, so the same report gives the same sky. Each
// layer drifts with the reported surface wind.
// Precipitation (-: 0.3, moderate: 0.6, +: 0.9) goes to the layer that rains: a CB or TCU layer
// for showers and thunderstorms, else the lowest BKN/OVC layer, else the lowest layer; solid
// precipitation marks it CloudLayer::snow. The renderer draws what it drops as a shaft below it
// (sky::clouds::WithPrecipitationShafts: Marshall-Palmer rain, FMH-1's snow visibilities).
// Layers that overlap are cut at the next layer's base; one left thinner than 50 m is merged
// into the next (largest coverage, type and precipitation).
//
// Visibility: the meteorological optical range V is the distance at which a black target's
// contrast against the horizon sky falls to 5 % (WMO No. 8, Part I, ch. 9); with Koschmieder's
// law C = exp(-sigma x) that gives sigma = ln 20 / V. A report of 10 km or more (9999, CAVOK,
// 10SM and beyond), or one given as a lower bound (P6SM), sets no extinction: the atmosphere
// preset's own aerosols apply. A report below a bound (M1/4SM, 0000) uses the bound. Turning
// sigma into the atmosphere's aerosol density near the ground is AtmosphereForVisibility.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "zenith/sky/atmosphere.h"
#include "zenith/sky/atmosphere_renderer.h"
#include "zenith/sky/clouds/weather.h"
#include "zenith/weather/metar.h"

namespace zenith::weather {

struct MetarWeather {
    sky::clouds::Weather clouds;  // validated (sky::clouds::Validate)
    // The reported visibility and the extinction coefficient near the ground that gives it,
    // both absent when the report has no visibility or one of 10 km or more.
    std::optional<double> visibility_m;
    std::optional<double> ground_extinction_per_m;
    bool fog = false;                // VV, or FG (not in the vicinity)
    bool haze = false;               // HZ, BR, FU, DU, SA, VA at the station
    double precipitation = 0.0;      // [0, 1] at the station, from the present weather's intensity
    bool snow = false;               // the precipitation is solid (SN, SG, PL, GR, GS, IC)
    std::vector<std::string> notes;  // choices the mapping made that the report did not say
};

// sigma = ln 20 / V (see the file comment). Throws ArgumentError unless V > 0.
double ExtinctionForVisibility(double visibility_m);

// See the table above. station_elevation_m: the station's height above the planet's sphere
// (mean sea level), [-500, 9000] m; throws ArgumentError outside.
// cloud_extinction_per_m: the renderer's cloud material (sky::CloudSettings::extinction), which
// the fog layer's extinction_scale is relative to.
MetarWeather CloudWeatherFromMetar(const Metar& metar, double station_elevation_m,
                                   double cloud_extinction_per_m = sky::CloudSettings{}.extinction);

// The extinction coefficient of `atmosphere` at its ground in the green channel, 1/m: Rayleigh,
// aerosol extinction and the absorbing layer's share there. The meteorological optical range is
// photopic (WMO No. 8 defines it for a colour temperature of 2700 K, through the eye's response);
// the renderer's green channel is the middle of that response.
double GroundExtinctionGreen(const sky::Atmosphere& atmosphere);

// `base` with its aerosols (Mie scattering and absorption, one factor for both, so their albedo,
// phase and profile stay) scaled so that GroundExtinctionGreen is ln 20 / V: the air of the
// report. Fog is the fog layer's (CloudWeatherFromMetar), so with `fog` the aerosols are set for
// at least kFogAerosolVisibility: aerosols with a 1.2 km scale height that alone made 200 m would
// block the Sun far above the fog's top. A V the clean air alone cannot reach (Rayleigh and
// ozone at the ground exceed ln 20 / V: ~200 km on Earth) leaves no aerosol. Each such choice is
// added to `notes`. Throws ArgumentError unless 0 < V <= 1000 km.
inline constexpr double kFogAerosolVisibility = 1000.0;  // m
sky::Atmosphere AtmosphereForVisibility(const sky::Atmosphere& base, double visibility_m, bool fog,
                                        std::vector<std::string>* notes);

}  // namespace zenith::weather
