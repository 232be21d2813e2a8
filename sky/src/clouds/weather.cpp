// Weather presets (JSON), validation, procedural weather maps and weather map images
// (format and rules in weather.h).
#include "zenith/sky/clouds/weather.h"

#include <ImfChannelList.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <span>
#include <sstream>

#include "data_files.h"
#include "reference/cloud_functions.h"
#include "zenith/sky/atmosphere.h"
#include "zenith/sky/clouds/noise.h"
#include "zenith/sky/image_io.h"

namespace zenith::sky::clouds {
namespace {

using data_files::Quote;

using Json = nlohmann::json;

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kMaxTopAltitude = 20000.0;  // m: the troposphere, with room for anvils
constexpr double kMinThickness = 50.0;       // m
constexpr double kMaxWindSpeed = 150.0;      // m/s
constexpr double kMaxShear = 100000.0;       // m: an anvil's reach downwind
constexpr double kMinMapPeriod = 1e3;        // m
constexpr double kMaxMapPeriod = 1e7;        // m
constexpr int kMinMapSize = 16;
constexpr int kStreakAspect = 6;  // streaks: features this many times longer than wide

// Smoothstep of x clamped to [0, 1].
double SmoothUnit(double x) {
    const double c = std::clamp(x, 0.0, 1.0);
    return c * c * (3.0 - 2.0 * c);
}
constexpr int kMaxMapSize = 4096;

struct NamedType {
    const char* name;
    double value;
};
constexpr std::array<NamedType, 5> kCloudTypes = {{{"stratus", 0.0},
                                                   {"stratocumulus", 0.25},
                                                   {"cumulus", 0.5},
                                                   {"congestus", 0.75},
                                                   {"cumulonimbus", 1.0}}};

std::string FormatNumber(double x) {
    if (std::isnan(x)) return "nan";
    if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
    char buffer[64];
    const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, x);
    return ec == std::errc() ? std::string(buffer, end) : std::to_string(x);
}

bool IsPowerOfTwo(long long n) { return n > 0 && (n & (n - 1)) == 0; }

// --- validation -------------------------------------------------------------------------------

// Reports in the file's terms (key names, file units) or in the struct's (members, SI).
class Checker {
  public:
    Checker(std::string source, bool file_terms)
        : source_(std::move(source)), file_terms_(file_terms) {}

    [[noreturn]] void Fail(std::size_t layer, const std::string& layer_name, const char* key,
                           const char* member, const std::string& value,
                           const std::string& expected) const {
        std::string where = source_ + ": layers[" + std::to_string(layer) + "]";
        if (!layer_name.empty()) where += " (" + Quote(layer_name) + ")";
        throw WeatherError(where + "." + (file_terms_ ? key : member) + " = " + value +
                           ": expected " + expected);
    }
    bool file_terms() const { return file_terms_; }

  private:
    std::string source_;
    bool file_terms_;
};

void Check(const Weather& weather, const Checker& check) {
    for (std::size_t i = 0; i < weather.layers.size(); ++i) {
        const CloudLayer& l = weather.layers[i];
        const bool file = check.file_terms();
        // Altitudes: metres in both terms.
        const auto metres = [](double m) { return FormatNumber(m) + " m"; };
        const auto unit = [](double v) { return FormatNumber(v) + " (dimensionless)"; };
        if (!(l.base_altitude >= 0.0 && l.base_altitude <= kMaxTopAltitude - kMinThickness)) {
            check.Fail(i, l.name, "base_altitude_m", "base_altitude", metres(l.base_altitude),
                       "0 <= value <= " + metres(kMaxTopAltitude - kMinThickness));
        }
        if (!(l.top_altitude >= l.base_altitude + kMinThickness &&
              l.top_altitude <= kMaxTopAltitude)) {
            check.Fail(i, l.name, "top_altitude_m", "top_altitude", metres(l.top_altitude),
                       "base + " + metres(kMinThickness) + " <= value <= " +
                           metres(kMaxTopAltitude) + ", with base = " + metres(l.base_altitude) +
                           " (a thinner layer is below the ray march's resolution)");
        }
        if (i > 0 && !(l.base_altitude >= weather.layers[i - 1].top_altitude)) {
            check.Fail(i, l.name, "base_altitude_m", "base_altitude", metres(l.base_altitude),
                       ">= the top of layers[" + std::to_string(i - 1) + "], " +
                           metres(weather.layers[i - 1].top_altitude) +
                           " (layers are listed bottom to top and do not overlap)");
        }
        const auto unit_interval = [&](double v, const char* key, const char* member) {
            if (!(v >= 0.0 && v <= 1.0))
                check.Fail(i, l.name, key, member, unit(v), "0 <= value <= 1");
        };
        unit_interval(l.coverage, "coverage", "coverage");
        unit_interval(l.cloud_type, "cloud_type", "cloud_type");
        unit_interval(l.precipitation, "precipitation", "precipitation");
        if (!(l.wind_speed >= 0.0 && l.wind_speed <= kMaxWindSpeed)) {
            check.Fail(i, l.name, "wind_speed_m_s", "wind_speed",
                       FormatNumber(l.wind_speed) + " m/s",
                       "0 <= value <= " + FormatNumber(kMaxWindSpeed) +
                           " m/s (twice the strongest jet stream)");
        }
        if (!(l.shear >= 0.0 && l.shear <= kMaxShear)) {
            check.Fail(i, l.name, "shear_m", "shear", metres(l.shear),
                       "0 <= value <= " + FormatNumber(kMaxShear / 1000.0) +
                           " km (an anvil's reach downwind)");
        }
        if (!(l.extinction_scale > 0.0 && l.extinction_scale <= kMaxExtinctionScale)) {
            check.Fail(i, l.name, "extinction_scale", "extinction_scale", unit(l.extinction_scale),
                       "0 < value <= " + FormatNumber(kMaxExtinctionScale) +
                           " (of the cloud material's extinction: 1 for water droplets, ~0.02 "
                           "for cirrus' ice, up to 4 for the densest fog)");
        }
        if (!std::isfinite(l.wind_from)) {
            check.Fail(
                i, l.name, "wind_from_deg", "wind_from",
                FormatNumber(file ? l.wind_from / kDeg : l.wind_from) + (file ? " deg" : " rad"),
                "a finite direction");
        }
        if (!(l.map_period >= kMinMapPeriod && l.map_period <= kMaxMapPeriod)) {
            check.Fail(i, l.name, "map_period_m", "map_period", metres(l.map_period),
                       metres(kMinMapPeriod) + " <= value <= " + metres(kMaxMapPeriod));
        }
        const WeatherMapSource& m = l.map;
        if (m.kind == WeatherMapSource::Kind::kFile) {
            if (m.file.empty()) check.Fail(i, l.name, "map.file", "map.file", "''", "a file path");
            continue;
        }
        if (!(IsPowerOfTwo(m.size) && m.size >= kMinMapSize && m.size <= kMaxMapSize)) {
            check.Fail(i, l.name, "map.size", "map.size", std::to_string(m.size),
                       "a power of two in [" + std::to_string(kMinMapSize) + ", " +
                           std::to_string(kMaxMapSize) + "] texels");
        }
        if (!(m.cells_per_tile >= 1 && m.cells_per_tile <= m.size / 2)) {
            check.Fail(i, l.name, "map.cells_per_tile", "map.cells_per_tile",
                       std::to_string(m.cells_per_tile),
                       "1 <= value <= map.size / 2 = " + std::to_string(m.size / 2) +
                           " (a whole number of features per tile keeps the map tiling)");
        }
        if (m.kind == WeatherMapSource::Kind::kStreaks &&
            !(4 * kStreakAspect * m.cells_per_tile <= m.size)) {
            check.Fail(i, l.name, "map.cells_per_tile", "map.cells_per_tile",
                       std::to_string(m.cells_per_tile),
                       "<= map.size / " + std::to_string(4 * kStreakAspect) + " = " +
                           std::to_string(m.size / (4 * kStreakAspect)) +
                           " for streaks (their fine fibres need two texels across)");
        }
        if (!(m.variation >= 0.0 && m.variation <= 1.0)) {
            check.Fail(i, l.name, "map.variation", "map.variation", unit(m.variation),
                       "0 <= value <= 1");
        }
    }
}

// --- reading ----------------------------------------------------------------------------------

class Reader : public data_files::JsonReader<WeatherError> {
  public:
    using JsonReader::JsonReader;

    double Number(const Json& value, const std::string& path) const {
        if (!value.is_number()) Fail(path, "expected a number, got " + DescribeJsonValue(value));
        return value.get<double>();
    }
    double Number(const Json& object, const std::string& prefix, const char* key) const {
        return Number(Required(object, prefix, key), prefix + key);
    }
    double Number(const Json& object, const std::string& prefix, const char* key,
                  double fallback) const {
        const auto it = object.find(key);
        return it == object.end() ? fallback : Number(*it, prefix + key);
    }
    int Integer(const Json& object, const std::string& prefix, const char* key,
                int fallback) const {
        const auto it = object.find(key);
        if (it == object.end()) return fallback;
        if (!it->is_number_integer() || it->get<long long>() < 0 ||
            it->get<long long>() > 1'000'000'000) {
            Fail(prefix + key, "expected a non-negative integer, got " + DescribeJsonValue(*it));
        }
        return static_cast<int>(it->get<long long>());
    }
    std::string String(const Json& value, const std::string& path) const {
        if (!value.is_string()) Fail(path, "expected a string, got " + DescribeJsonValue(value));
        return value.get<std::string>();
    }
};

constexpr const char* kTopKeys[] = {"name", "description", "layers"};
constexpr const char* kLayerKeys[] = {"name",           "base_altitude_m", "top_altitude_m",
                                      "coverage",       "cloud_type",      "precipitation",
                                      "wind_speed_m_s", "wind_from_deg",   "extinction_scale",
                                      "ground_fog",     "map_period_m",    "map",
                                      "shear_m"};
constexpr const char* kProceduralKeys[] = {"procedural", "seed", "cells_per_tile", "variation",
                                           "size"};
constexpr const char* kFileKeys[] = {"file"};

WeatherMapSource ReadMap(const Reader& read, const Json& map, const std::string& prefix,
                         const std::filesystem::path& base_directory) {
    if (!map.is_object()) read.Fail(prefix, "expected an object, got " + DescribeJsonValue(map));
    WeatherMapSource source;
    if (map.contains("file")) {
        read.RejectUnknownKeys(map, prefix + ".", kFileKeys);
        source.kind = WeatherMapSource::Kind::kFile;
        const std::filesystem::path file = read.String(map["file"], prefix + ".file");
        source.file = file.is_absolute() ? file : base_directory / file;
        return source;
    }
    read.RejectUnknownKeys(map, prefix + ".", kProceduralKeys);
    const std::string kind =
        read.String(read.Required(map, prefix + ".", "procedural"), prefix + ".procedural");
    if (kind == "uniform") {
        source.kind = WeatherMapSource::Kind::kUniform;
    } else if (kind == "patches") {
        source.kind = WeatherMapSource::Kind::kPatches;
    } else if (kind == "cells") {
        source.kind = WeatherMapSource::Kind::kCells;
    } else if (kind == "streaks") {
        source.kind = WeatherMapSource::Kind::kStreaks;
    } else {
        read.Fail(prefix + ".procedural",
                  Quote(kind) +
                      " is not a procedural map; expected uniform, patches, cells or streaks "
                      "(or give \"file\" instead)");
    }
    const int seed = read.Integer(map, prefix + ".", "seed", 1);
    source.seed = static_cast<std::uint32_t>(seed);
    source.cells_per_tile = read.Integer(map, prefix + ".", "cells_per_tile", 8);
    source.variation = read.Number(map, prefix + ".", "variation", 0.5);
    source.size = read.Integer(map, prefix + ".", "size", 256);
    return source;
}

double ReadCloudType(const Reader& read, const Json& value, const std::string& path) {
    if (value.is_string()) {
        const std::string name = value.get<std::string>();
        for (const NamedType& type : kCloudTypes) {
            if (name == type.name) return type.value;
        }
        std::string names;
        for (const NamedType& type : kCloudTypes) {
            names += (names.empty() ? "" : ", ") + std::string(type.name);
        }
        read.Fail(path, Quote(name) + " is not a cloud type; expected one of " + names +
                            " or a number in [0, 1]");
    }
    return read.Number(value, path);
}

}  // namespace

void Validate(const Weather& weather) {
    Check(weather, Checker("weather " + Quote(weather.name), false));
}

namespace {

Weather ParseWeatherDocument(std::string_view json_text, const std::string& source) {
    const Reader read(source);
    data_files::CheckJsonDepth<WeatherError>(source, json_text);
    Json root;
    try {
        root = Json::parse(json_text);
    } catch (const Json::parse_error& e) {
        throw WeatherError(data_files::JsonSyntaxMessage(source, json_text, e.byte, e.what()));
    }
    if (!root.is_object())
        read.Fail("(top level)", "expected an object, got " + DescribeJsonValue(root));
    read.RejectUnknownKeys(root, "", kTopKeys);

    Weather weather;
    weather.name = std::filesystem::path(source).stem().string();
    if (const auto it = root.find("name"); it != root.end()) {
        weather.name = read.String(*it, "name");
        if (weather.name.empty()) read.Fail("name", "expected a non-empty string");
    }
    if (const auto it = root.find("description"); it != root.end()) {
        weather.description = read.String(*it, "description");
    }
    const Json& layers = read.Required(root, "", "layers");
    if (!layers.is_array())
        read.Fail("layers", "expected an array, got " + DescribeJsonValue(layers));
    const std::filesystem::path base_directory = std::filesystem::path(source).parent_path();
    for (std::size_t i = 0; i < layers.size(); ++i) {
        const std::string prefix = "layers[" + std::to_string(i) + "].";
        const Json& l = layers[i];
        if (!l.is_object()) read.Fail(prefix, "expected an object, got " + DescribeJsonValue(l));
        read.RejectUnknownKeys(l, prefix, kLayerKeys);
        CloudLayer layer;
        if (const auto it = l.find("name"); it != l.end())
            layer.name = read.String(*it, prefix + "name");
        layer.base_altitude = read.Number(l, prefix, "base_altitude_m");
        layer.top_altitude = read.Number(l, prefix, "top_altitude_m");
        layer.coverage = read.Number(l, prefix, "coverage");
        layer.cloud_type =
            ReadCloudType(read, read.Required(l, prefix, "cloud_type"), prefix + "cloud_type");
        layer.precipitation = read.Number(l, prefix, "precipitation");
        layer.wind_speed = read.Number(l, prefix, "wind_speed_m_s", 0.0);
        layer.wind_from = read.Number(l, prefix, "wind_from_deg", 0.0) * kDeg;
        layer.shear = read.Number(l, prefix, "shear_m", 0.0);
        layer.extinction_scale = read.Number(l, prefix, "extinction_scale", 1.0);
        if (const auto it = l.find("ground_fog"); it != l.end()) {
            if (!it->is_boolean()) {
                read.Fail(prefix + "ground_fog",
                          "expected true or false, got " + DescribeJsonValue(*it));
            }
            layer.ground_fog = it->get<bool>();
        }
        layer.map_period = read.Number(l, prefix, "map_period_m");
        layer.map = ReadMap(read, read.Required(l, prefix, "map"), prefix + "map", base_directory);
        weather.layers.push_back(std::move(layer));
    }
    Check(weather, Checker(source, true));
    return weather;
}

}  // namespace

Weather ParseWeatherJson(std::string_view json_text, std::string_view source_name) {
    const std::string source(source_name);
    try {
        return ParseWeatherDocument(json_text, source);
    } catch (const Json::exception& e) {
        // What the reader's own checks cannot see first: "1e309" overflows while parsing.
        throw WeatherError(data_files::JsonExceptionMessage(source, e.what()));
    }
}

std::filesystem::path WeatherDirectory() {
    // Presets and weather share a data directory: PresetDirectory() is <data>/presets.
    return PresetDirectory().parent_path() / "weather";
}

Weather LoadWeather(std::string_view name_or_path) {
    data_files::NamedFile file;
    std::string error;
    if (!data_files::ReadNamedJsonFile(name_or_path, WeatherDirectory(), "weather", "", file,
                                       error)) {
        throw WeatherError(error);
    }
    return ParseWeatherJson(file.text, file.path.string());
}

// --- maps -------------------------------------------------------------------------------------

WeatherMap BuildWeatherMap(const CloudLayer& layer) {
    const WeatherMapSource& source = layer.map;
    if (source.kind == WeatherMapSource::Kind::kFile) return LoadWeatherMapImage(source.file);
    Weather one;
    one.name = layer.name.empty() ? "layer" : layer.name;
    one.layers = {layer};
    Validate(one);

    WeatherMap map;
    map.size = source.size;
    map.texels.assign(static_cast<std::size_t>(map.size) * static_cast<std::size_t>(map.size),
                      glm::vec4(0.0f));
    const int n = source.cells_per_tile;
    // Periodic with the tile: whole features per tile, z held on one lattice plane.
    const glm::ivec3 cells(n, n, 1);
    const glm::ivec3 fine(2 * n, 2 * n, 1);
    const std::uint32_t seed = source.seed;
    for (int y = 0; y < map.size; ++y) {
        for (int x = 0; x < map.size; ++x) {
            const glm::dvec2 u((x + 0.5) / map.size, (y + 0.5) / map.size);
            double coverage = layer.coverage, precipitation = layer.precipitation;
            double type = layer.cloud_type, height = 1.0;
            switch (source.kind) {
                case WeatherMapSource::Kind::kUniform:
                    break;
                case WeatherMapSource::Kind::kPatches: {
                    // Two Perlin octaves: soft patches of more and less cloud around the
                    // layer's coverage, and varied cloud heights.
                    const glm::dvec3 p(u.x * n, u.y * n, 0.0);
                    const double patch = TileablePerlin(p, cells, seed) +
                                         0.5 * TileablePerlin(2.0 * p, fine, seed + 1U);
                    // Multiplicative, so a layer with coverage 0 stays exactly clear.
                    coverage = layer.coverage * (1.0 + 2.0 * source.variation * patch);
                    const double tall =
                        TileablePerlin(p + glm::dvec3(0.5, 0.5, 0.0), cells, seed + 2U);
                    height = 0.7 + 0.6 * tall;
                    precipitation = layer.precipitation * std::clamp(coverage, 0.0, 1.0);
                    break;
                }
                case WeatherMapSource::Kind::kCells: {
                    // Isolated cells (Worley F1): full cover, full height and the rain in their
                    // cores; cumulus-type cloud at the layer's reduced coverage between them.
                    // Cells differ in size (a Perlin factor 0.7-1.3 on their radius, so no two
                    // neighbours look alike), and keep their type 1.7x as far out as their
                    // cover: a cumulonimbus' anvil spreads over that rim (functions.glsl
                    // CloudAnvilSignal), and the cumulus around it grow toward congestus.
                    const double f1 =
                        TileableWorley(glm::dvec3(u.x * n, u.y * n, 0.5), cells, seed);
                    const double size = std::clamp(
                        1.0 + 0.3 * TileablePerlin(glm::dvec3(2.0 * u.x * n, 2.0 * u.y * n, 0.0),
                                                   fine, seed + 3U),
                        0.7, 1.3);
                    const double w = SmoothUnit(1.0 - f1 / (0.45 * size));
                    const double rim = SmoothUnit(1.0 - f1 / (0.75 * size));
                    coverage = layer.coverage > 0.0
                                   ? layer.coverage * (1.0 - source.variation) +
                                         w * (1.0 - layer.coverage * (1.0 - source.variation))
                                   : 0.0;
                    precipitation = layer.precipitation * w;
                    // Cumulonimbus keep a convective type (above 0.75) over the whole rim,
                    // falling to congestus at its edge; other types fall with the cover.
                    const double between = std::min(layer.cloud_type, 0.5);
                    type = layer.cloud_type > 0.75
                               ? between + (0.75 + (layer.cloud_type - 0.75) * rim - between) *
                                               SmoothUnit(8.0 * rim)
                               : layer.cloud_type + (between - layer.cloud_type) * (1.0 - w);
                    height = (0.5 + 0.5 * SmoothUnit(2.0 * w)) * (0.85 + 0.15 * size);
                    break;
                }
                case WeatherMapSource::Kind::kStreaks: {
                    // Cirrus' fibres: Perlin noise stretched kStreakAspect times along the map's
                    // x (east at the weather's origin; high-level winds are mostly westerly),
                    // two octaves, with a sharper fine one across; the texel's height varies
                    // little (a thin layer).
                    const glm::ivec3 along(n, kStreakAspect * n, 1);
                    const glm::ivec3 along_fine(2 * n, 2 * kStreakAspect * n, 1);
                    const glm::dvec3 p(u.x * n, u.y * kStreakAspect * n, 0.0);
                    const double fibre = TileablePerlin(p, along, seed) +
                                         0.5 * TileablePerlin(glm::dvec3(2.0 * p.x, 2.0 * p.y, 0.0),
                                                              along_fine, seed + 1U);
                    coverage = layer.coverage * (1.0 + 2.0 * source.variation * fibre);
                    height =
                        0.8 + 0.4 * TileablePerlin(p + glm::dvec3(0.5, 0.5, 0.0), along, seed + 2U);
                    break;
                }
                case WeatherMapSource::Kind::kFile:
                    break;
            }
            map.at(x, y) = glm::vec4(glm::clamp(glm::dvec4(coverage, precipitation, type, height),
                                                glm::dvec4(0.0), glm::dvec4(1.0)));
        }
    }
    return map;
}

double CloudTopFraction(const WeatherMap& map) {
    // Bilinear filtering keeps each channel within the four texels it mixes, and the height
    // grows with both the type and A: a cell's largest type profile times its largest A bounds
    // every cloud height h read inside it (GL_REPEAT: the cells wrap). And with shape <= 1, the
    // coverage remap leaves density only where the height signal (u the share of h above the
    // base) exceeds 1 - coverage.
    double top = 0.0;
    for (int y = 0; y < map.size; ++y) {
        for (int x = 0; x < map.size; ++x) {
            double coverage = 0.0, type = 0.0, height = 0.0;
            for (const glm::ivec2 d :
                 {glm::ivec2(0, 0), glm::ivec2(1, 0), glm::ivec2(0, 1), glm::ivec2(1, 1)}) {
                const glm::vec4& t = map.at((x + d.x) % map.size, (y + d.y) % map.size);
                coverage = std::max(coverage, double(t.r));
                type = std::max(type, double(t.b));
                height = std::max(height, double(t.a));
            }
            if (coverage > 0.0) {
                // A tower's signal k 4u(1 - u) (k = 1 + 2 convection) exceeds 1 - coverage
                // below u = (1 + sqrt(1 - (1 - coverage) / k)) / 2; an anvil reaches its top.
                const double convection = ref::CloudConvection(type);
                const double k = 1.0 + 2.0 * convection;
                const double u = 0.5 * (1.0 + std::sqrt(1.0 - (1.0 - std::min(coverage, 1.0)) / k));
                top = std::max(top,
                               ref::CloudTypeHeightFraction(type) * ref::CloudSaturate(height) * u);
                if (convection > 0.0) top = std::max(top, ref::kCloudAnvilTop);
            }
        }
    }
    return top;
}

double LayerTopFraction(const CloudLayer& layer, const WeatherMap& map) {
    if (!layer.ground_fog && !layer.precipitation_shaft) return CloudTopFraction(map);
    for (const glm::vec4& t : map.texels) {
        if ((layer.ground_fog ? t.r : t.g) > 0.0f) return 1.0;
    }
    return 0.0;
}

double HeavyPrecipitationExtinction(bool snow) {
    constexpr double kHeavySnow = 3.0 / 350.0;  // 1/m: MOR 350 m
    // Marshall-Palmer: pi N0 / Lambda^3 = 3.647e-4 R^0.63 /m at R = 16 mm/h.
    const double heavy_rain = 3.647e-4 * std::pow(16.0, 0.63);
    return snow ? kHeavySnow : heavy_rain;
}

Weather WithPrecipitationShafts(const Weather& weather) {
    const std::vector<CloudLayer>& layers = weather.layers;
    if (layers.size() >= kMaxDrawnLayers) return weather;
    const auto raining = std::find_if(layers.begin(), layers.end(), [](const CloudLayer& l) {
        return l.precipitation > 0.0 && !l.ground_fog && !l.precipitation_shaft;
    });
    if (raining == layers.end()) return weather;
    const double base = raining == layers.begin() ? 0.0 : std::prev(raining)->top_altitude;
    if (raining->base_altitude - base < 50.0) return weather;
    CloudLayer shaft = *raining;
    shaft.name = raining->name + " (precipitation)";
    shaft.base_altitude = base;
    shaft.top_altitude = raining->base_altitude;
    shaft.precipitation_shaft = true;
    shaft.shear = 0.0;  // it falls from the cloud's base, where the cloud does not lean
    Weather out = weather;
    out.layers.insert(out.layers.begin() + (raining - layers.begin()), shaft);
    return out;
}

double PrecipitationExtinction(double p, bool snow) {
    // ref::CloudPrecipitationShare is the shape, 1 at p = 0.9 (heavy).
    return HeavyPrecipitationExtinction(snow) * ref::CloudPrecipitationShare(p);
}

namespace {

[[noreturn]] void FailMap(const std::filesystem::path& path, const std::string& problem,
                          const std::string& expected) {
    throw WeatherError("weather map " + Quote(path.string()) + ": " + problem + "; expected " +
                       expected);
}

void CheckMapSize(const std::filesystem::path& path, long long width, long long height) {
    const std::string expected = "a square image whose side is a power of two in [" +
                                 std::to_string(kMinMapSize) + ", " + std::to_string(kMaxMapSize) +
                                 "] pixels (e.g. 256x256)";
    const std::string size = std::to_string(width) + "x" + std::to_string(height) + " pixels";
    if (width != height) FailMap(path, "not square: " + size, expected);
    if (!IsPowerOfTwo(width)) FailMap(path, "side not a power of two: " + size, expected);
    if (width < kMinMapSize || width > kMaxMapSize) FailMap(path, "size " + size, expected);
}

const char* kChannelNames[] = {"R (coverage)", "G (precipitation)", "B (cloud type)", "A (height)"};

void CheckValues(const std::filesystem::path& path, const WeatherMap& map) {
    for (int y = 0; y < map.size; ++y) {
        for (int x = 0; x < map.size; ++x) {
            for (int c = 0; c < 4; ++c) {
                const float v = map.at(x, y)[c];
                if (!(v >= 0.0f && v <= 1.0f)) {
                    FailMap(
                        path,
                        std::string(std::isfinite(v) ? "value out of range" : "non-finite value") +
                            ": pixel (" + std::to_string(x) + ", " + std::to_string(y) +
                            ") channel " + kChannelNames[c] + " = " + FormatNumber(v),
                        "every channel finite and in [0, 1]");
                }
            }
        }
    }
}

WeatherMap ReadPngMap(const std::filesystem::path& path) {
    // The PNG header (signature, IHDR) says the channels before libpng converts them.
    std::ifstream in(path, std::ios::binary);
    if (!in)
        FailMap(path, "cannot open (" + std::generic_category().message(errno) + ")",
                "a readable PNG");
    std::array<unsigned char, 26> head{};
    in.read(reinterpret_cast<char*>(head.data()), head.size());
    static constexpr unsigned char kSignature[8] = {137, 'P', 'N', 'G', '\r', '\n', 26, '\n'};
    if (!in || std::memcmp(head.data(), kSignature, 8) != 0 ||
        std::memcmp(head.data() + 12, "IHDR", 4) != 0) {
        FailMap(path, "not a PNG file", "a PNG (8-bit RGB) or an OpenEXR file");
    }
    const auto be32 = [&](std::size_t at) {
        return (static_cast<long long>(head[at]) << 24) | (head[at + 1] << 16) |
               (head[at + 2] << 8) | head[at + 3];
    };
    const long long width = be32(16), height = be32(20);
    const int bit_depth = head[24], colour_type = head[25];
    const std::string expected_channels =
        "8-bit RGB (3 channels: R coverage, G precipitation, B cloud type); for a 4th, height, "
        "channel use an OpenEXR file with R, G, B, A";
    switch (colour_type) {
        case 2:
            break;
        case 0:
            FailMap(path, "1 channel (grey)", expected_channels);
        case 4:
            FailMap(path, "2 channels (grey + alpha)", expected_channels);
        case 3:
            FailMap(path, "a palette image", expected_channels);
        case 6:
            FailMap(path, "4 channels (RGBA)", expected_channels);
        default:
            FailMap(path, "unknown PNG colour type " + std::to_string(colour_type),
                    expected_channels);
    }
    if (bit_depth != 8) {
        // libpng's simplified reader takes 16-bit data as linear and re-encodes it as sRGB.
        FailMap(path, std::to_string(bit_depth) + "-bit channels", expected_channels);
    }
    CheckMapSize(path, width, height);
    Srgb8Image image;
    try {
        image = ReadPng(path);
    } catch (const ImageError& e) {
        throw WeatherError(std::string("weather map: ") + e.what());
    }
    WeatherMap map;
    map.size = image.width;
    map.texels.resize(static_cast<std::size_t>(image.width) *
                      static_cast<std::size_t>(image.height));
    for (std::size_t i = 0; i < map.texels.size(); ++i) {
        map.texels[i] = glm::vec4(image.rgb[3 * i] / 255.0f, image.rgb[3 * i + 1] / 255.0f,
                                  image.rgb[3 * i + 2] / 255.0f, 1.0f);
    }
    return map;
}

WeatherMap ReadExrMap(const std::filesystem::path& path) {
    std::vector<std::string> channels;
    long long width = 0, height = 0;
    try {
        CheckExrHeader(path, kMaxMapSize);
        Imf::InputFile file(path.c_str());
        const Imath::Box2i window = file.header().dataWindow();
        width = static_cast<long long>(window.max.x) - window.min.x + 1;
        height = static_cast<long long>(window.max.y) - window.min.y + 1;
        for (auto it = file.header().channels().begin(); it != file.header().channels().end();
             ++it) {
            channels.emplace_back(it.name());
        }
    } catch (const std::exception& e) {
        FailMap(path, std::string("cannot read as OpenEXR (") + e.what() + ")",
                "an OpenEXR file with channels R, G, B and optionally A");
    }
    const auto has = [&](const char* name) {
        return std::find(channels.begin(), channels.end(), name) != channels.end();
    };
    if (!has("R") || !has("G") || !has("B")) {
        std::string list;
        for (const std::string& name : channels) list += (list.empty() ? "" : ", ") + name;
        FailMap(path,
                std::to_string(channels.size()) + " channel" + (channels.size() == 1 ? "" : "s") +
                    " (" + (list.empty() ? "none" : list) + ")",
                "channels R (coverage), G (precipitation), B (cloud type) and optionally A "
                "(height)");
    }
    CheckMapSize(path, width, height);
    Image image;
    try {
        image = ReadExr(path, kMaxMapSize);
    } catch (const ImageError& e) {
        throw WeatherError(std::string("weather map: ") + e.what());
    }
    WeatherMap map;
    map.size = image.width;
    map.texels = std::move(image.pixels);
    return map;
}

}  // namespace

WeatherMap LoadWeatherMapImage(const std::filesystem::path& path) {
    std::string extension = path.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    WeatherMap map;
    if (extension == ".png") {
        map = ReadPngMap(path);
    } else if (extension == ".exr") {
        map = ReadExrMap(path);
    } else {
        FailMap(path,
                extension.empty() ? std::string("no extension")
                                  : "unknown extension " + Quote(path.extension().string()),
                "a .png or .exr file");
    }
    CheckValues(path, map);
    return map;
}

glm::dvec2 WindDisplacement(const CloudLayer& layer, double seconds) {
    // Downwind is opposite to where the wind comes from.
    const double distance = layer.wind_speed * seconds;
    return {-distance * std::sin(layer.wind_from), -distance * std::cos(layer.wind_from)};
}

}  // namespace zenith::sky::clouds
