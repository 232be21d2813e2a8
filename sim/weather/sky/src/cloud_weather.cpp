// METAR -> zenith weather; the mapping table is in cloud_weather.h.
#include "zenith/weather/cloud_weather.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "zenith/base/units.h"

namespace zenith::weather {

namespace {

using sky::clouds::CloudLayer;
using sky::clouds::WeatherMapSource;

constexpr double kLowEtageTop = 2000.0;    // m above the station (WMO cloud atlas, temperate)
constexpr double kHighEtageBase = 6000.0;  // m
// Cirrus' ice against the water clouds' extinction (the `cirrus` preset; weather.h).
constexpr double kIceExtinctionScale = 0.04;
constexpr double kCbTopAboveStation = 10000.0;
constexpr double kMaxTop = 20000.0;  // sky::clouds::Validate's troposphere
constexpr double kMinThickness = 50.0;
constexpr double kFogDepth = 100.0;
constexpr double kShallowFogDepth = 50.0;
constexpr double kFogPatchVisibility = 500.0;  // m: in fog reported with 1 km or more

// Cloud types of the weather map's B channel (weather.h).
constexpr double kStratus = 0.0;
constexpr double kStratocumulus = 0.25;
constexpr double kCumulus = 0.5;
constexpr double kCongestus = 0.75;
constexpr double kCumulonimbus = 1.0;

struct CoverEntry {
    Cover cover;
    double coverage;
};
constexpr CoverEntry kCoverage[] = {
    {Cover::kFew, 0.38},     {Cover::kScattered, 0.48}, {Cover::kBroken, 0.75},
    {Cover::kOvercast, 1.0}, {Cover::kUnknown, 0.48},
};

double Coverage(Cover cover) {
    for (const auto& e : kCoverage) {
        if (e.cover == cover) return e.coverage;
    }
    return 0.5;
}

struct IntensityEntry {
    Intensity intensity;
    double precipitation;
};
constexpr IntensityEntry kPrecipitation[] = {
    {Intensity::kLight, 0.3},
    {Intensity::kModerate, 0.6},
    {Intensity::kHeavy, 0.9},
    {Intensity::kVicinity, 0.0},
};

double PrecipitationAmount(Intensity intensity) {
    for (const auto& e : kPrecipitation) {
        if (e.intensity == intensity) return e.precipitation;
    }
    return 0.0;
}

bool IsSolid(Phenomenon p) {
    return p == Phenomenon::kSnow || p == Phenomenon::kSnowGrains || p == Phenomenon::kIcePellets ||
           p == Phenomenon::kHail || p == Phenomenon::kSmallHail || p == Phenomenon::kIceCrystals;
}

bool IsHaze(Phenomenon p) {
    return p == Phenomenon::kHaze || p == Phenomenon::kMist || p == Phenomenon::kSmoke ||
           p == Phenomenon::kDust || p == Phenomenon::kSand || p == Phenomenon::kVolcanicAsh;
}

// FNV-1a of the station and the layer index: the same report gives the same maps.
std::uint32_t Seed(const std::string& station, std::size_t index) {
    std::uint32_t h = 2166136261u;
    for (const char c : station) {
        h ^= static_cast<unsigned char>(c);
        h *= 16777619u;
    }
    h ^= static_cast<std::uint32_t>(index);
    h *= 16777619u;
    return h == 0 ? 1u : h;
}

WeatherMapSource Map(WeatherMapSource::Kind kind, std::uint32_t seed, int cells, double variation) {
    WeatherMapSource map;
    map.kind = kind;
    map.seed = seed;
    map.cells_per_tile = cells;
    map.variation = variation;
    map.size = 256;
    return map;
}

struct Built {
    CloudLayer layer;
    bool convective = false;     // CB/TCU: where showers and thunderstorms rain from
    bool can_rain = false;       // BKN/OVC
    double reported_base = 0.0;  // m, before the base is lowered to where its clouds start
};

}  // namespace

double ExtinctionForVisibility(double visibility_m) {
    Require("visibility", visibility_m, "m", Range::LeftOpen(0.0, 1e9));
    return std::log(20.0) / visibility_m;
}

MetarWeather CloudWeatherFromMetar(const Metar& metar, double station_elevation_m,
                                   double cloud_extinction_per_m) {
    Require("station_elevation", station_elevation_m, "m", Range::Closed(-500.0, 9000.0));
    Require("cloud_extinction", cloud_extinction_per_m, "1/m", Range::LeftOpen(0.0, 10.0));
    MetarWeather out;
    out.clouds.name = "metar " + metar.station;
    out.clouds.description = "from the METAR of " + metar.station;
    const double ground = std::max(0.0, station_elevation_m);
    if (station_elevation_m < 0.0) {
        out.notes.push_back(fmt::format(
            "station {:.0f} m below the sphere: layers are placed from 0 m", station_elevation_m));
    }
    const double wind_speed =
        metar.wind && metar.wind->speed_m_s ? std::min(*metar.wind->speed_m_s, 150.0) : 0.0;
    const double wind_from =
        metar.wind && metar.wind->direction_deg ? Radians(*metar.wind->direction_deg) : 0.0;

    // Present weather at the station (not in the vicinity).
    Intensity rain_intensity = Intensity::kVicinity;
    bool showers = false;
    bool fog = false;
    Descriptor fog_descriptor = Descriptor::kNone;
    for (const PresentWeather& w : metar.weather) {
        if (w.intensity == Intensity::kVicinity) continue;
        if (w.HasPrecipitation()) {
            out.precipitation = std::max(out.precipitation, PrecipitationAmount(w.intensity));
            rain_intensity = w.intensity;
            out.snow = out.snow || std::any_of(w.phenomena.begin(), w.phenomena.end(), IsSolid);
            showers = showers || w.descriptor == Descriptor::kShowers ||
                      w.descriptor == Descriptor::kThunderstorm;
        }
        if (w.Has(Phenomenon::kFog)) {
            fog = true;
            fog_descriptor = w.descriptor;
        }
        if (std::any_of(w.phenomena.begin(), w.phenomena.end(), IsHaze)) out.haze = true;
    }

    std::vector<Built> layers;
    // A fog layer at the ground: the vertical visibility, or FG's depth.
    if (metar.vertical_visibility_reported || fog) {
        out.fog = true;
        double depth = kFogDepth;
        if (metar.vertical_visibility_ft) {
            depth = std::max(kMinThickness, *metar.vertical_visibility_ft * kMetresPerFoot);
        } else if (fog_descriptor == Descriptor::kShallow) {
            depth = kShallowFogDepth;
        } else if (metar.vertical_visibility_reported) {
            out.notes.push_back("VV///: fog 100 m deep assumed");
        }
        const bool patchy =
            fog_descriptor == Descriptor::kPatches || fog_descriptor == Descriptor::kPartial;
        Built b;
        b.layer.name = "fog";
        b.layer.base_altitude = ground;
        b.layer.top_altitude = ground + depth;
        b.layer.coverage = patchy ? 0.5 : 1.0;
        b.layer.cloud_type = kStratus;
        // Homogeneous, with the extinction that makes the reported visibility in it: ln 20 / V
        // less the air's, which AtmosphereForVisibility sets for kFogAerosolVisibility (below
        // 1 km). Fog reported with 1 km or more (shallow or patchy: MIFG, BCFG, PRFG) or
        // without a visibility is given kFogPatchVisibility inside it. Patchy fog is that
        // dense in its patches.
        b.layer.ground_fog = true;
        const std::optional<double> v = metar.visibility && metar.visibility->visibility_m > 0.0
                                            ? std::optional<double>(metar.visibility->visibility_m)
                                            : std::nullopt;
        const double fog_visibility = v && *v < kFogAerosolVisibility ? *v : kFogPatchVisibility;
        const double fog_extinction = ExtinctionForVisibility(fog_visibility) -
                                      ExtinctionForVisibility(kFogAerosolVisibility);
        const double scale = fog_extinction / (b.layer.coverage * cloud_extinction_per_m);
        using sky::clouds::kMaxExtinctionScale;
        b.layer.extinction_scale = std::clamp(scale, 1e-3, kMaxExtinctionScale);
        if (scale > kMaxExtinctionScale) {
            out.notes.push_back(fmt::format(
                "fog of {:.0f} m visibility is denser than the densest fog drawn ({:.0f} m)",
                fog_visibility, std::log(20.0) / (kMaxExtinctionScale * cloud_extinction_per_m)));
        }
        b.layer.map = patchy
                          ? Map(WeatherMapSource::Kind::kPatches, Seed(metar.station, 99), 8, 0.6)
                          : Map(WeatherMapSource::Kind::kUniform, 1, 8, 0.0);
        b.layer.map_period = 20000.0;
        layers.push_back(b);
    }

    if (!metar.cavok) {
        const double surface_c = metar.temperature_c.value_or(15.0);
        for (std::size_t i = 0; i < metar.sky.size(); ++i) {
            const SkyLayer& s = metar.sky[i];
            if (!s.base_ft) {
                out.notes.push_back(fmt::format("layer {} ({}///) has no base: left out", i + 1,
                                                CoverCode(s.cover)));
                continue;
            }
            if (s.cover == Cover::kUnknown) {
                out.notes.push_back(
                    fmt::format("layer {}: amount not observed, 4 oktas assumed", i + 1));
            }
            const double height = *s.base_m();
            Built b;
            CloudLayer& l = b.layer;
            l.coverage = Coverage(s.cover);
            l.base_altitude = ground + height;
            b.reported_base = l.base_altitude;
            const bool overcast = s.cover == Cover::kOvercast;
            const bool cumuliform = s.cover == Cover::kFew || s.cover == Cover::kScattered ||
                                    s.cover == Cover::kUnknown;
            double depth = 0.0;
            if (s.convective == ConvectiveCloud::kCumulonimbus) {
                l.name = "cumulonimbus";
                l.cloud_type = kCumulonimbus;
                depth = std::max(3000.0, kCbTopAboveStation - height);
                l.map = Map(WeatherMapSource::Kind::kCells, Seed(metar.station, i), 4, 0.5);
                l.map_period = 80000.0;
                b.convective = true;
            } else if (s.convective == ConvectiveCloud::kToweringCumulus) {
                l.name = "towering cumulus";
                l.cloud_type = kCongestus;
                depth = 4000.0;
                l.map = Map(WeatherMapSource::Kind::kPatches, Seed(metar.station, i), 12, 0.6);
                l.map_period = 60000.0;
                b.convective = true;
            } else if (height < kLowEtageTop) {
                if (cumuliform) {
                    l.name = "cumulus";
                    l.cloud_type = kCumulus;
                    // Fair-weather cumulus deepen with the warmth of the ground.
                    depth = std::clamp(1000.0 + 50.0 * (surface_c - 15.0), 500.0, 2000.0);
                } else if (overcast) {
                    l.name = out.precipitation > 0.0 ? "nimbostratus" : "stratus";
                    l.cloud_type = kStratus;
                    depth = out.precipitation > 0.0 ? 2000.0 : 400.0;
                } else {
                    l.name = "stratocumulus";
                    l.cloud_type = kStratocumulus;
                    depth = 600.0;
                }
            } else if (height < kHighEtageBase) {
                l.name = overcast ? "altostratus" : "altocumulus";
                l.cloud_type = overcast ? kStratus : kStratocumulus;
                depth = 800.0;
            } else {
                // Ice: cirrus fibres, or an overcast veil of cirrostratus (the `cirrus` preset's
                // material and map).
                l.name = overcast ? "cirrostratus" : "cirrus";
                l.cloud_type = kStratus;
                l.extinction_scale = kIceExtinctionScale;
                depth = 500.0;
            }
            if (b.convective) {
                // set above
            } else if (height >= kHighEtageBase && !overcast) {
                l.map = Map(WeatherMapSource::Kind::kStreaks, Seed(metar.station, i), 6, 0.7);
                l.map_period = 80000.0;
            } else if (overcast) {
                l.map = Map(WeatherMapSource::Kind::kUniform, 1, 8, 0.0);
                l.map_period = 50000.0;
            } else if (s.cover == Cover::kBroken) {
                l.map = Map(WeatherMapSource::Kind::kPatches, Seed(metar.station, i), 8, 0.4);
                l.map_period = 50000.0;
            } else {
                l.map = Map(WeatherMapSource::Kind::kPatches, Seed(metar.station, i), 12, 0.6);
                l.map_period = 60000.0;
            }
            if (!overcast && !b.convective) {
                // The density model starts a cloud at the layer's base only where the coverage
                // is 1: with coverage c the noise must exceed 1 - c, which the base's parabola
                // reaches a share x = (1 - sqrt(c)) / 2 of the cloud's height up (H16 Eq. 5.1).
                // Half of that for the tallest clouds of the type is the lowest base measured
                // over six stations' maps (tests/weather_sky/metar_sky_cover_test.cpp); the
                // layer starts that much lower so that the base seen is the report's.
                const double type_height = l.cloud_type < 0.5
                                               ? 0.25 + (0.6 - 0.25) * 2.0 * l.cloud_type
                                               : 0.6 + (1.0 - 0.6) * (2.0 * l.cloud_type - 1.0);
                const double lift = 0.5 * 0.5 * (1.0 - std::sqrt(l.coverage)) * depth * type_height;
                l.base_altitude = std::max(ground, l.base_altitude - lift);
            }
            l.top_altitude = std::min(kMaxTop, l.base_altitude + depth);
            if (l.top_altitude - l.base_altitude < kMinThickness) {
                out.notes.push_back(
                    fmt::format("layer {} above {:.0f} m: left out", i + 1, kMaxTop));
                continue;
            }
            b.can_rain = s.cover == Cover::kBroken || overcast;
            layers.push_back(b);
        }
    }

    // The layer that rains.
    if (out.precipitation > 0.0 && !layers.empty()) {
        auto it = layers.end();
        if (showers) {
            it = std::find_if(layers.begin(), layers.end(),
                              [](const Built& b) { return b.convective; });
        }
        if (it == layers.end()) {
            it = std::find_if(layers.begin(), layers.end(),
                              [](const Built& b) { return b.can_rain; });
        }
        if (it == layers.end()) {
            it = std::find_if(layers.begin(), layers.end(),
                              [](const Built& b) { return b.layer.name != "fog"; });
        }
        if (it != layers.end()) {
            it->layer.precipitation = PrecipitationAmount(rain_intensity);
            it->layer.snow = out.snow;
        }
    }

    // Bottom to top without overlap (sky::clouds::Validate).
    std::stable_sort(layers.begin(), layers.end(), [](const Built& a, const Built& b) {
        return a.layer.base_altitude < b.layer.base_altitude;
    });
    std::vector<CloudLayer> result;
    for (std::size_t i = 0; i < layers.size(); ++i) {
        CloudLayer l = layers[i].layer;
        if (i + 1 < layers.size()) {
            CloudLayer& next = layers[i + 1].layer;
            if (l.top_altitude > next.base_altitude) l.top_altitude = next.base_altitude;
            // Two reports of (nearly) one base are one layer, whatever their lowered bases.
            if (l.top_altitude - l.base_altitude < kMinThickness ||
                (layers[i].reported_base > 0.0 &&
                 layers[i + 1].reported_base - layers[i].reported_base < kMinThickness)) {
                out.notes.push_back(
                    fmt::format("{} merged into the {} above it", l.name, next.name));
                next.base_altitude = l.base_altitude;
                next.coverage = std::max(next.coverage, l.coverage);
                next.cloud_type = std::max(next.cloud_type, l.cloud_type);
                next.precipitation = std::max(next.precipitation, l.precipitation);
                if (next.top_altitude - next.base_altitude < kMinThickness) {
                    next.top_altitude = next.base_altitude + kMinThickness;
                }
                continue;
            }
        }
        l.wind_speed = wind_speed;
        l.wind_from = wind_from;
        result.push_back(std::move(l));
    }
    out.clouds.layers = std::move(result);

    // A bound from above (P6SM) says only that the air is clearer than that.
    if (metar.visibility && metar.visibility->bound != Bound::kMoreThan &&
        metar.visibility->visibility_m < 10000.0 && metar.visibility->visibility_m > 0.0) {
        out.visibility_m = metar.visibility->visibility_m;
        out.ground_extinction_per_m = ExtinctionForVisibility(*out.visibility_m);
    }
    sky::clouds::Validate(out.clouds);
    return out;
}

double GroundExtinctionGreen(const sky::Atmosphere& atmosphere) {
    // The absorbing layer is a tent of full width absorption_width around absorption_center.
    const double half_width = 0.5 * atmosphere.absorption_width;
    const double tent = std::max(0.0, 1.0 - std::abs(atmosphere.absorption_center) / half_width);
    return atmosphere.rayleigh_scattering.y + atmosphere.MieExtinction().y +
           tent * atmosphere.absorption_extinction.y;
}

sky::Atmosphere AtmosphereForVisibility(const sky::Atmosphere& base, double visibility_m, bool fog,
                                        std::vector<std::string>* notes) {
    Require("visibility", visibility_m, "m", Range::LeftOpen(0.0, 1e6));
    double target_visibility = visibility_m;
    if (fog && visibility_m < kFogAerosolVisibility) {
        target_visibility = kFogAerosolVisibility;
        if (notes != nullptr) {
            notes->push_back(fmt::format(
                "visibility {:.0f} m is the fog layer's; the air above and around it is set to "
                "{:.0f} m",
                visibility_m, kFogAerosolVisibility));
        }
    }
    const double target = ExtinctionForVisibility(target_visibility);
    sky::Atmosphere air = base;
    const double mie = base.MieExtinction().y;
    const double clean = GroundExtinctionGreen(base) - mie;
    double factor = 0.0;
    if (target > clean && mie > 0.0) {
        factor = (target - clean) / mie;
    } else if (notes != nullptr) {
        notes->push_back(fmt::format(
            "visibility {:.0f} m is beyond what the clean air of '{}' allows ({:.0f} m): no "
            "aerosols",
            target_visibility, base.name, std::log(20.0) / clean));
    }
    air.mie_scattering = base.mie_scattering * factor;
    air.mie_absorption = base.mie_absorption * factor;
    air.name = base.name + fmt::format(" (visibility {:.0f} m)", target_visibility);
    sky::Validate(air);
    return air;
}

}  // namespace zenith::weather
