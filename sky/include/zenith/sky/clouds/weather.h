// Weather for the cloud layers (Högfeldt 2016 §4.4, Frostbite 2016 §5.3.1): which clouds are
// where. A Weather is a list of layers at different altitudes; each layer has a world-space
// weather map that tiles over map_period metres and drifts with its wind.
//
// Weather map texels (RGBA, each in [0, 1]; H16 Table 4.2 / F16 §5.3.1):
//   R coverage       0 = clear (exactly: no density anywhere above that texel), 1 = full
//   G precipitation  0 = none; the rain or snow falling from the cloud's base
//                    (WithPrecipitationShafts)
//   B cloud type     0 stratus, 0.25 stratocumulus, 0.5 cumulus, 0.75 congestus, 1 cumulonimbus
//   A height         the local cloud's height as a share of what its type reaches in the layer
//
// Presets are JSON files in data/weather/ (LoadWeather("scattered_cumulus")); the format is
// documented at LoadWeather. Units are SI and in the key names, as for atmosphere presets.
#pragma once

#include <cstdint>
#include <filesystem>
#include <glm/glm.hpp>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "zenith/base/error.h"

namespace zenith::sky::clouds {

// An invalid weather file, layer or map: the message names the file (or layer), the field or
// pixel, the value and what is expected.
class WeatherError : public InputError {
  public:
    using InputError::InputError;
};

// Where a layer's weather map comes from.
struct WeatherMapSource {
    enum class Kind {
        kUniform,  // every texel the layer's values
        kPatches,  // coverage varies in soft patches around the layer's (cumulus, broken decks)
        kCells,    // isolated cells of varied size with raining cores (cumulonimbus); a
                   // cumulonimbus layer keeps its type over a rim 1.7x the cells' cover,
                   // where the anvil spreads under the layer's top
        kStreaks,  // long thin fibres along the map's x (east), 6 times longer than wide
                   // (cirrus); cells_per_tile of them across a tile
        kFile,     // an image: see LoadWeatherMapImage
    };
    Kind kind = Kind::kUniform;
    std::uint32_t seed = 1;      // procedural maps
    int cells_per_tile = 8;      // procedural: features across one tile, >= 1 (keeps it tiling)
    double variation = 0.5;      // procedural: amplitude of the coverage variation, [0, 1]
    int size = 256;              // procedural: texels per side, a power of two in [16, 4096]
    std::filesystem::path file;  // kFile: absolute, or relative to the weather file's directory
    bool operator==(const WeatherMapSource&) const = default;
};

// The largest CloudLayer::extinction_scale: fog of 20 m visibility.
inline constexpr double kMaxExtinctionScale = 4.0;

struct CloudLayer {
    std::string name;
    double base_altitude = 1500.0;  // m above the planet's surface (sphere)
    double top_altitude = 3500.0;   // m
    double coverage = 0.5;          // [0, 1], the mean of the map's R
    double cloud_type = 0.5;        // [0, 1], see the B channel above
    double precipitation = 0.0;     // [0, 1]
    double wind_speed = 0.0;        // m/s
    double wind_from = 0.0;         // rad, meteorological: where the wind blows from, clockwise
                                    // from north (pi / 2: an east wind, clouds move west)
    // m: how far downwind of their bases the clouds reach at the layer's top, the wind's shear
    // over the layer (the upper winds blowing harder): a cumulonimbus' anvil spreads downwind
    // of its cell. The clouds lean by the square of the height's share of the layer.
    double shear = 0.0;
    double map_period = 50000.0;  // m of ground covered by one tile of the weather map
    // The layer's cloud material's extinction relative to CloudSettings::extinction, (0, 4]:
    // 1 for water droplets (cumulus, stratus: 40 /km), ~0.02 for the ice of cirrus (~1 /km:
    // fewer, larger crystals; vertical optical depths 0.03-3, Sassen & Cho 1992).
    double extinction_scale = 1.0;
    // Ground fog (METAR FG, VV): the layer is homogeneous (no noise), as dense as the map's
    // coverage from its base to 80 % of its thickness and thinning to 0 at its top, so that its
    // extinction at the ground, coverage x extinction_scale x CloudSettings::extinction, sets the
    // visibility in it. Its base is the ground.
    bool ground_fog = false;
    // The layer's precipitation falls as snow (METAR SN, SG, PL, GR, GS, IC), not rain: its
    // shaft (below) is denser.
    bool snow = false;
    // A precipitation shaft (WithPrecipitationShafts makes them): the rain or snow below the
    // layer above it, drawn from that layer's own map (this layer is its copy), homogeneous in
    // height, its extinction from the map's G (precipitation) channel alone:
    // PrecipitationExtinction. Its extinction_scale is not used.
    bool precipitation_shaft = false;
    WeatherMapSource map;
    bool operator==(const CloudLayer&) const = default;
};

struct Weather {
    std::string name = "clear";
    std::string description;
    std::vector<CloudLayer> layers;  // bottom to top, not overlapping; empty: clear sky
    bool operator==(const Weather&) const = default;
};

// A square weather map, texels x fastest, row 0 at v = 0 (the image's top row).
struct WeatherMap {
    int size = 0;
    std::vector<glm::vec4> texels;
    glm::vec4& at(int x, int y) { return texels[Index(x, y)]; }
    const glm::vec4& at(int x, int y) const { return texels[Index(x, y)]; }
    std::size_t Index(int x, int y) const {
        return static_cast<std::size_t>(y) * static_cast<std::size_t>(size) +
               static_cast<std::size_t>(x);
    }
};

// Throws WeatherError naming the layer (index and name), the field, the value with its unit and
// the allowed range. Ranges: 0 <= base_altitude < top_altitude <= 20 km with top - base >= 50 m
// (the troposphere; a thinner layer is below the ray march's resolution); coverage, cloud_type,
// precipitation, map.variation in [0, 1]; 0 <= wind_speed <= 150 m/s (twice the strongest jet
// stream); wind_from finite; 0 <= shear <= 100 km; 1 km <= map_period <= 10000 km; map.size a power
// of two in [16, 4096]; 1 <= map.cells_per_tile <= map.size / 2; layers ordered bottom to top
// without overlap; a kFile map names a file.
void Validate(const Weather& weather);

// Reads a preset: a built-in name ("clear", "scattered_cumulus", "broken", "overcast_stratus",
// "cumulonimbus", "cirrus") in WeatherDirectory(), or a path to a JSON file (anything with a '/' or
// ending in ".json"). Unknown keys are errors. The result is validated; map files are checked when
// the map is built (BuildWeatherMap), not here.
//
//   {
//     "name": "scattered_cumulus",          optional, default: the file's stem
//     "description": "...",                 optional
//     "layers": [                           bottom to top; [] is a clear sky
//       {
//         "name": "cumulus",                optional
//         "base_altitude_m": 1500,
//         "top_altitude_m": 4000,
//         "coverage": 0.35,
//         "cloud_type": "cumulus",          or a number in [0, 1]; names: stratus,
//                                           stratocumulus, cumulus, congestus, cumulonimbus
//         "precipitation": 0,
//         "wind_speed_m_s": 8,              optional, default 0
//         "wind_from_deg": 270,             optional, default 0
//         "shear_m": 15000,                 optional, default 0: how far downwind the clouds
//                                           reach at the layer's top (0 <= value <= 100 km)
//         "map_period_m": 60000,
//         "extinction_scale": 1,            optional, default 1 (water); ~0.02 for cirrus' ice
//         "ground_fog": false,              optional: homogeneous fog from the layer's base
//         "map": {"procedural": "patches", "seed": 3, "cells_per_tile": 12, "variation": 0.6,
//                 "size": 256}             or {"procedural": "uniform"} / "cells" / "streaks", or
//                {"file": "maps/front.exr"} (relative to this JSON file)
//       }
//     ]
//   }
Weather LoadWeather(std::string_view name_or_path);
// As LoadWeather, from text; source_name is used in messages, as the default name, and its
// directory resolves relative map files.
Weather ParseWeatherJson(std::string_view json_text, std::string_view source_name);

// $ZENITH_DATA_DIR/weather if set, else the installed data directory's weather/ if it exists,
// else the source tree's data/weather.
std::filesystem::path WeatherDirectory();

// The weather map of a layer: procedural maps from tileable noise (seeded, deterministic), or
// the layer's image file through LoadWeatherMapImage.
WeatherMap BuildWeatherMap(const CloudLayer& layer);

// How high the clouds of `map` reach, as a share of their layer's thickness: a bound from the
// largest height (B's type profile times A) and coverage that the density's bilinear reading of
// the map can give wherever its coverage is above 0. Above it the density is exactly 0, so the
// ray march ends there (CloudLayerParameters.cloud_top_altitude): the scattered cumulus, whose
// clouds reach 53 % of their layer, are not marched through the empty rest above them. 0 for a
// map without cover.
double CloudTopFraction(const WeatherMap& map);
// The same for `layer` built from `map`: ground fog fills its whole layer (1, or 0 without cover)
// and a precipitation shaft too (1, or 0 where nothing falls).
double LayerTopFraction(const CloudLayer& layer, const WeatherMap& map);

// The precipitation the weather's lowest raining layer (precipitation > 0, not fog) drops, as a
// shaft layer (CloudLayer::precipitation_shaft) from the top of the layer below it, or the
// ground, up to its base: what the renderer draws (AtmosphereRenderer::SetWeather). The shaft
// goes in the list right before the raining layer, through which the renderer lights it (the
// next layer up). The weather unchanged when nothing rains, when the shaft would be under 50 m
// deep, or when the weather already holds the kMaxDrawnLayers layers the renderer draws.
inline constexpr std::size_t kMaxDrawnLayers = 4;
Weather WithPrecipitationShafts(const Weather& weather);

// The extinction (1/m) of precipitation of intensity p (the map's G channel: METAR's light 0.3,
// moderate 0.6, heavy 0.9). Rain: a rate R(p) = 0.5 x 32^(p / 0.9) mm/h (1.6, 5 and 16 mm/h,
// inside the FAA's light (< 2.5), moderate (2.6-7.6) and heavy (> 7.6) bands, FMH-1 8.5.2), and
// the optical extinction of its Marshall-Palmer drops (N(D) = 8000 exp(-4.1 R^-0.21 D) /m^3/mm,
// extinction efficiency 2): pi N0 / Lambda^3 = 0.365 R^0.63 /km (MOR 8 km at 1 mm/h, 1.4 km at
// 16 mm/h). Snow: FMH-1 names its intensity by the visibility it leaves (light > 1 km,
// moderate 0.5-1 km, heavy < 0.5 km): the same shape in p scaled to 3 / 0.35 km at p = 0.9
// (1.5 km at 0.3, 0.73 km at 0.6). 0 at p = 0, ramping in over p < 0.1.
double PrecipitationExtinction(double p, bool snow);
// PrecipitationExtinction(0.9, snow): heavy rain's 2.1e-3 /m, heavy snow's 8.6e-3 /m.
double HeavyPrecipitationExtinction(bool snow);

// Reads a weather map image: PNG (8- or 16-bit RGB: R coverage, G precipitation, B cloud type;
// A = 1) or OpenEXR (channels R, G, B and optionally A, half or float). Throws WeatherError
// naming the file, the problem and what is expected, for: an unknown extension; a size that is
// not square or not a power of two in [16, 4096]; a PNG that is not RGB (grey, palette or with
// alpha) or an EXR without R, G and B; any NaN or infinite value; any value outside [0, 1]
// (with the pixel and channel of the first one).
WeatherMap LoadWeatherMapImage(const std::filesystem::path& path);

// How far the weather has drifted after `seconds`: metres (east, north), downwind.
glm::dvec2 WindDisplacement(const CloudLayer& layer, double seconds);

}  // namespace zenith::sky::clouds
