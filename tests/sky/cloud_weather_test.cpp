// Weather presets and maps (clouds/weather.h): the shipped presets load and validate, bad files
// are refused with a message that names the file, the problem and what is expected, procedural
// maps are deterministic, tile, keep coverage 0 exactly clear, and images load from PNG and EXR.
#include <gtest/gtest.h>
#include <png.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>
#include <vector>

#include "cloud_test_support.h"
#include "zenith/sky/clouds/weather.h"
#include "zenith/sky/image_io.h"

namespace zenith::sky::clouds {
namespace {

// The message of the WeatherError `f` throws, or "" (and a failure) if it does not throw.
template <class F>
std::string ErrorOf(F&& f) {
    try {
        f();
    } catch (const WeatherError& e) {
        return e.what();
    }
    ADD_FAILURE() << "no WeatherError";
    return "";
}

void ExpectMentions(const std::string& message, std::initializer_list<const char*> parts) {
    for (const char* part : parts) {
        EXPECT_NE(message.find(part), std::string::npos) << "'" << part << "' not in: " << message;
    }
}

// One layer of JSON with `field` replaced.
std::string LayerJson(const std::string& extra = "", const std::string& coverage = "0.4") {
    return R"({"name": "t", "layers": [{"base_altitude_m": 1500, "top_altitude_m": 4000,
        "coverage": )" +
           coverage + R"(, "cloud_type": "cumulus", "precipitation": 0,
        "map_period_m": 60000, "map": {"procedural": "uniform"})" +
           extra + "}]}";
}

TEST(CloudWeatherPresets, EveryPresetLoadsAndValidates) {
    for (const char* name :
         {"clear", "scattered_cumulus", "broken", "overcast_stratus", "cumulonimbus", "cirrus"}) {
        SCOPED_TRACE(name);
        const Weather weather = LoadWeather(name);
        EXPECT_EQ(weather.name, name);
        EXPECT_FALSE(weather.description.empty());
        EXPECT_NO_THROW(Validate(weather));
        for (const CloudLayer& layer : weather.layers) {
            const WeatherMap map = BuildWeatherMap(layer);
            EXPECT_EQ(map.size, layer.map.size);
        }
    }
    EXPECT_TRUE(LoadWeather("clear").layers.empty());
    const Weather cb = LoadWeather("cumulonimbus");
    ASSERT_EQ(cb.layers.size(), 1u);
    EXPECT_EQ(cb.layers[0].cloud_type, 1.0);
    EXPECT_EQ(cb.layers[0].top_altitude, 12000.0);
    const Weather broken = LoadWeather("broken");
    ASSERT_EQ(broken.layers.size(), 2u);  // several layers at different altitudes
    EXPECT_LE(broken.layers[0].top_altitude, broken.layers[1].base_altitude);
    const Weather scattered = LoadWeather("scattered_cumulus");
    const CloudLayer& cu = scattered.layers[0];
    EXPECT_EQ(cu.wind_speed, 8.0);
    EXPECT_NEAR(cu.wind_from, 1.5 * std::numbers::pi, 1e-15);
    EXPECT_EQ(cu.extinction_scale, 1.0);  // the default: water droplets
    const Weather ci = LoadWeather("cirrus");
    ASSERT_EQ(ci.layers.size(), 1u);
    EXPECT_EQ(ci.layers[0].extinction_scale, 0.04);
    EXPECT_EQ(ci.layers[0].map.kind, WeatherMapSource::Kind::kStreaks);
    EXPECT_GE(ci.layers[0].base_altitude, 6000.0);  // a high cloud
}

TEST(CloudWeatherPresets, UnknownPresetListsTheShippedOnes) {
    ExpectMentions(ErrorOf([] { LoadWeather("drizzle"); }),
                   {"drizzle.json", "scattered_cumulus", "overcast_stratus"});
}

TEST(CloudWeatherPresets, BadFieldsAreNamedWithValueAndRange) {
    ExpectMentions(ErrorOf([] { ParseWeatherJson(LayerJson("", "1.5"), "w.json"); }),
                   {"w.json", "layers[0].coverage", "1.5", "0 <= value <= 1"});
    ExpectMentions(ErrorOf([] { ParseWeatherJson(LayerJson(", \"colour\": 1"), "w.json"); }),
                   {"layers[0].colour", "unknown key", "coverage"});
    ExpectMentions(
        ErrorOf([] { ParseWeatherJson(LayerJson(", \"wind_speed_m_s\": 400"), "w.json"); }),
        {"wind_speed_m_s = 400 m/s", "150 m/s"});
    ExpectMentions(ErrorOf([] { ParseWeatherJson(LayerJson(", \"shear_m\": -5"), "w.json"); }),
                   {"layers[0].shear_m = -5 m", "0 <= value <= 100 km"});
    EXPECT_EQ(ParseWeatherJson(LayerJson(", \"shear_m\": 12000"), "w.json").layers[0].shear,
              12000.0);
    for (const char* scale : {"0", "4.5", "-0.1"}) {
        ExpectMentions(ErrorOf([&] {
                           ParseWeatherJson(
                               LayerJson(std::string(", \"extinction_scale\": ") + scale),
                               "w.json");
                       }),
                       {"w.json", "layers[0].extinction_scale", scale, "0 < value <= 4"});
    }
    ExpectMentions(ErrorOf([] {
                       ParseWeatherJson(R"({"layers": [{"base_altitude_m": 9000,
                           "top_altitude_m": 11000, "coverage": 0.4, "cloud_type": 0,
                           "precipitation": 0, "map_period_m": 60000,
                           "map": {"procedural": "streaks", "cells_per_tile": 30,
                                   "size": 256}}]})",
                                        "w.json");
                   }),
                   {"map.cells_per_tile", "30", "<= map.size / 24 = 10", "streaks"});
    ExpectMentions(ErrorOf([] {
                       ParseWeatherJson(R"({"layers": [{"base_altitude_m": 1500,
                           "top_altitude_m": 4000, "coverage": 0.4, "cloud_type": "nimbus",
                           "precipitation": 0, "map_period_m": 60000,
                           "map": {"procedural": "uniform"}}]})",
                                        "w.json");
                   }),
                   {"cloud_type", "'nimbus'", "cumulonimbus"});
    ExpectMentions(ErrorOf([] {
                       ParseWeatherJson(R"({"layers": [{"base_altitude_m": 3000,
                           "top_altitude_m": 2000, "coverage": 0.4, "cloud_type": 0.5,
                           "precipitation": 0, "map_period_m": 60000,
                           "map": {"procedural": "uniform"}}]})",
                                        "w.json");
                   }),
                   {"top_altitude_m = 2000 m", "base = 3000 m"});
    ExpectMentions(ErrorOf([] { ParseWeatherJson(R"({"layers": [)", "w.json"); }),
                   {"w.json", "JSON syntax"});
    ExpectMentions(ErrorOf([] { ParseWeatherJson(R"({"layers": [{}]})", "w.json"); }),
                   {"layers[0].base_altitude_m", "missing"});
    // Overlapping layers.
    Weather two = ParseWeatherJson(LayerJson(), "w.json");
    two.layers.push_back(two.layers[0]);
    ExpectMentions(ErrorOf([&] { Validate(two); }),
                   {"layers[1]", "base_altitude = 1500 m", "do not overlap"});
    // Procedural map parameters.
    ExpectMentions(ErrorOf([] {
                       ParseWeatherJson(R"({"layers": [{"base_altitude_m": 1500,
                           "top_altitude_m": 4000, "coverage": 0.4, "cloud_type": 0.5,
                           "precipitation": 0, "map_period_m": 60000,
                           "map": {"procedural": "patches", "size": 300}}]})",
                                        "w.json");
                   }),
                   {"map.size = 300", "power of two"});
}

TEST(CloudWeatherPresets, JsonSyntaxErrorsGiveFileLineAndColumn) {
    // The same file:line:column as atmosphere presets (sky/src/data_files.h).
    ExpectMentions(ErrorOf([] { ParseWeatherJson("{\n  \"name\": \"x\",\n  oops\n}", "w.json"); }),
                   {"w.json:3:", "JSON syntax"});
}

TEST(CloudWeatherPresets, HostileJsonIsAWeatherErrorNamingTheFile) {
    // 100,000 nested arrays overflowed the stack (exit 139) before any check.
    const std::string deep = std::string(100000, '[') + std::string(100000, ']');
    ExpectMentions(ErrorOf([&] { ParseWeatherJson(deep, "d.json"); }),
                   {"d.json:1:33: JSON nested deeper than 32 levels"});
    // A value nested deep inside a valid layout is refused the same way, not dumped.
    ExpectMentions(ErrorOf([] {
                       ParseWeatherJson(R"({"layers": [{"name": )" + std::string(40, '[') +
                                            std::string(40, ']') + "}]}",
                                        "n.json");
                   }),
                   {"n.json:1:", "nested deeper"});
    // A number beyond double escaped as nlohmann's out_of_range (171 fuzz crashes, one bug).
    ExpectMentions(
        ErrorOf([] { ParseWeatherJson(R"({"layers": [{"base_altitude_m": 1e309}]})", "o.json"); }),
        {"o.json: ", "1e309"});
}

TEST(CloudWeatherMaps, ProceduralMapsAreDeterministicInRangeAndTile) {
    for (const char* name :
         {"scattered_cumulus", "broken", "overcast_stratus", "cumulonimbus", "cirrus"}) {
        for (const CloudLayer& layer : LoadWeather(name).layers) {
            SCOPED_TRACE(std::string(name) + " " + layer.name);
            const WeatherMap map = BuildWeatherMap(layer);
            EXPECT_EQ(map.texels, BuildWeatherMap(layer).texels);
            double coverage = 0.0;
            // |change| summed over each column boundary (x to x + 1) and row boundary.
            std::vector<double> columns(static_cast<std::size_t>(map.size), 0.0);
            std::vector<double> rows(static_cast<std::size_t>(map.size), 0.0);
            const int n = map.size;
            for (int y = 0; y < n; ++y) {
                for (int x = 0; x < n; ++x) {
                    const glm::vec4 t = map.at(x, y);
                    for (int c = 0; c < 4; ++c) {
                        ASSERT_TRUE(t[c] >= 0.0f && t[c] <= 1.0f) << x << "," << y << " " << c;
                    }
                    coverage += t.x;
                    const double dx = std::abs(map.at((x + 1) % n, y).x - t.x);
                    const double dy = std::abs(map.at(x, (y + 1) % n).x - t.x);
                    columns[static_cast<std::size_t>(x)] += dx;
                    rows[static_cast<std::size_t>(y)] += dy;
                }
            }
            coverage /= n * n;
            // The map's mean coverage is the layer's (cells add full-cover cores on top).
            EXPECT_NEAR(coverage, layer.coverage,
                        layer.map.kind == WeatherMapSource::Kind::kCells ? 0.3 : 0.12);
            // Tiling: the seam (the last boundary, back to the first texel) changes no more than
            // the largest other column or row boundary, in each direction (a map that did not
            // tile would jump there by as much as two unrelated texels differ).
            for (const std::vector<double>* boundaries : {&columns, &rows}) {
                const double seam = boundaries->back();
                const double largest =
                    *std::max_element(boundaries->begin(), boundaries->end() - 1);
                EXPECT_LE(seam, largest + 1e-6) << (boundaries == &columns ? "x" : "y");
            }
        }
    }
}

TEST(CloudWeatherMaps, CoverageZeroIsExactlyClearForEveryProceduralKind) {
    CloudLayer layer;
    layer.coverage = 0.0;
    layer.precipitation = 0.5;
    for (auto kind : {WeatherMapSource::Kind::kUniform, WeatherMapSource::Kind::kPatches,
                      WeatherMapSource::Kind::kCells, WeatherMapSource::Kind::kStreaks}) {
        layer.map.kind = kind;
        layer.map.variation = 1.0;
        const WeatherMap map = BuildWeatherMap(layer);
        for (const glm::vec4& t : map.texels) ASSERT_EQ(t.x, 0.0f);
    }
}

// Streaks are fibres along the map's x: the coverage changes several times less from texel to
// texel along x than across, where patches change alike both ways.
TEST(CloudWeatherMaps, StreaksAreLongAlongXAndThinAcross) {
    CloudLayer layer;
    layer.coverage = 0.5;
    layer.map.size = 256;
    layer.map.cells_per_tile = 6;
    layer.map.variation = 0.7;
    const auto gradients = [&](WeatherMapSource::Kind kind) {
        layer.map.kind = kind;
        const WeatherMap map = BuildWeatherMap(layer);
        double along = 0.0, across = 0.0;
        for (int y = 0; y < map.size; ++y) {
            for (int x = 0; x < map.size; ++x) {
                along += std::abs(map.at((x + 1) % map.size, y).x - map.at(x, y).x);
                across += std::abs(map.at(x, (y + 1) % map.size).x - map.at(x, y).x);
            }
        }
        return across / along;
    };
    const double streaks = gradients(WeatherMapSource::Kind::kStreaks);
    const double patches = gradients(WeatherMapSource::Kind::kPatches);
    std::printf("coverage change across / along x: streaks %.2f, patches %.2f\n", streaks, patches);
    EXPECT_GT(streaks, 3.0);
    EXPECT_NEAR(patches, 1.0, 0.3);
}

TEST(CloudWeatherMaps, WindCarriesTheWeatherDownwind) {
    CloudLayer layer;
    layer.wind_speed = 10.0;
    layer.wind_from = 1.5 * std::numbers::pi;  // a west wind blows toward the east
    const glm::dvec2 d = WindDisplacement(layer, 60.0);
    EXPECT_NEAR(d.x, 600.0, 1e-9);
    EXPECT_NEAR(d.y, 0.0, 1e-9);
    layer.wind_from = 0.0;  // from the north, toward the south
    EXPECT_NEAR(WindDisplacement(layer, 1.0).y, -10.0, 1e-12);
}

// --- images -----------------------------------------------------------------------------------

void WritePngRaw(const std::filesystem::path& path, int width, int height, png_uint_32 format,
                 unsigned char value = 128) {
    png_image image{};
    image.version = PNG_IMAGE_VERSION;
    image.width = static_cast<png_uint_32>(width);
    image.height = static_cast<png_uint_32>(height);
    image.format = format;
    std::vector<unsigned char> pixels(PNG_IMAGE_SIZE(image), value);
    ASSERT_TRUE(png_image_write_to_file(&image, path.c_str(), 0, pixels.data(), 0, nullptr));
}

TEST(CloudWeatherImages, LoadsPngAndExr) {
    const std::filesystem::path dir = test::TempDir("weather-images");
    WritePngRaw(dir / "ok.png", 64, 64, PNG_FORMAT_RGB, 51);
    const WeatherMap png = LoadWeatherMapImage(dir / "ok.png");
    EXPECT_EQ(png.size, 64);
    EXPECT_EQ(png.at(10, 20), glm::vec4(0.2f, 0.2f, 0.2f, 1.0f));

    Image exr(32, 32, glm::vec4(0.25f, 0.0f, 0.5f, 0.75f));
    exr.at(3, 4) = glm::vec4(1.0f, 1.0f, 0.0f, 0.0f);
    WriteExr(dir / "ok.exr", exr);
    const WeatherMap map = LoadWeatherMapImage(dir / "ok.exr");
    EXPECT_EQ(map.size, 32);
    EXPECT_EQ(map.at(0, 0), glm::vec4(0.25f, 0.0f, 0.5f, 0.75f));
    EXPECT_EQ(map.at(3, 4), glm::vec4(1.0f, 1.0f, 0.0f, 0.0f));

    // A preset naming a map file relative to itself.
    std::ofstream(dir / "front.json")
        << R"({"layers": [{"base_altitude_m": 1000, "top_altitude_m": 3000, "coverage": 0.5,
              "cloud_type": "stratus", "precipitation": 0.1, "map_period_m": 20000,
              "map": {"file": "ok.exr"}}]})";
    const Weather weather = LoadWeather((dir / "front.json").string());
    EXPECT_EQ(weather.layers[0].map.file, dir / "ok.exr");
    EXPECT_EQ(BuildWeatherMap(weather.layers[0]).texels, map.texels);
    std::filesystem::remove_all(dir);
}

TEST(CloudWeatherImages, BadImagesAreRefusedWithFileProblemAndExpectation) {
    const std::filesystem::path dir = test::TempDir("weather-bad");
    const auto error = [&](const std::string& file) {
        return ErrorOf([&] { LoadWeatherMapImage(dir / file); });
    };
    WritePngRaw(dir / "wide.png", 64, 32, PNG_FORMAT_RGB);
    ExpectMentions(error("wide.png"), {"wide.png", "not square: 64x32", "power of two"});
    WritePngRaw(dir / "odd.png", 100, 100, PNG_FORMAT_RGB);
    ExpectMentions(error("odd.png"), {"odd.png", "not a power of two: 100x100", "e.g. 256x256"});
    WritePngRaw(dir / "tiny.png", 8, 8, PNG_FORMAT_RGB);
    ExpectMentions(error("tiny.png"), {"tiny.png", "8x8", "[16, 4096]"});
    WritePngRaw(dir / "grey.png", 64, 64, PNG_FORMAT_GRAY);
    ExpectMentions(error("grey.png"), {"grey.png", "1 channel", "8-bit RGB (3 channels"});
    WritePngRaw(dir / "rgba.png", 64, 64, PNG_FORMAT_RGBA);
    ExpectMentions(error("rgba.png"), {"rgba.png", "4 channels (RGBA)", "OpenEXR"});
    std::ofstream(dir / "fake.png") << "this is not a png";
    ExpectMentions(error("fake.png"), {"fake.png", "not a PNG"});
    // Found by the fuzzer (tests/fuzz/corpus/weather_map/regression_huge_exr_attribute, its
    // first byte picks the extension): a 611-byte EXR whose attribute declares gigabytes, which
    // OpenEXR allocated (and zeroed) before reading; and a data window of 2^31 lines.
    {
        std::ifstream in(std::filesystem::path(ZENITH_SOURCE_DIR) /
                             "tests/fuzz/corpus/weather_map/regression_huge_exr_attribute",
                         std::ios::binary);
        in.get();
        std::ofstream(dir / "huge.exr", std::ios::binary) << in.rdbuf();
    }
    ExpectMentions(error("huge.exr"), {"huge.exr", "declares", "more than the header holds"});
    Image small(16, 16, glm::vec4(0.5f));
    WriteExr(dir / "tall.exr", small);
    {
        // Rewrite the dataWindow's yMax (box2i: xMin yMin xMax yMax) to 2^31 - 1.
        std::ifstream in(dir / "tall.exr", std::ios::binary);
        std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        const std::string name("dataWindow\0box2i\0", 17);
        const std::size_t value = bytes.find(name) + name.size() + 4;
        bytes.replace(value + 12, 4, std::string("\xff\xff\xff\x7f", 4));
        std::ofstream(dir / "tall.exr", std::ios::binary | std::ios::trunc) << bytes;
    }
    ExpectMentions(error("tall.exr"), {"tall.exr", "data window 16x2147483648", "4096"});
    std::ofstream(dir / "map.tif") << "x";
    ExpectMentions(error("map.tif"), {"map.tif", "unknown extension '.tif'", ".png or .exr"});

    Image nan(16, 16, glm::vec4(0.5f));
    nan.at(5, 7).y = std::numeric_limits<float>::quiet_NaN();
    WriteExr(dir / "nan.exr", nan);
    ExpectMentions(error("nan.exr"),
                   {"nan.exr", "non-finite", "pixel (5, 7)", "G (precipitation)", "[0, 1]"});
    Image high(16, 16, glm::vec4(0.5f));
    high.at(15, 0).x = 1.5f;
    WriteExr(dir / "high.exr", high);
    ExpectMentions(error("high.exr"),
                   {"high.exr", "out of range", "pixel (15, 0)", "R (coverage) = 1.5"});
    Image wide(32, 16, glm::vec4(0.5f));
    WriteExr(dir / "wide.exr", wide);
    ExpectMentions(error("wide.exr"), {"wide.exr", "not square: 32x16"});
    std::ofstream(dir / "fake.exr") << "nope";
    ExpectMentions(error("fake.exr"), {"fake.exr", "cannot read as OpenEXR"});
    std::filesystem::remove_all(dir);
}

// The precipitation's extinction against its sources: Marshall-Palmer's drop spectrum
// integrated here by quadrature (extinction efficiency 2 for drops far larger than the
// wavelength), at the rates that sit inside FMH-1's light, moderate and heavy rain; snow's
// meteorological optical range (3 / sigma) inside FMH-1's bands for its intensities.
TEST(Precipitation, ExtinctionMatchesMarshallPalmerAndFmh1) {
    for (const auto& [p, rate] : {std::pair{0.3, 1.587}, {0.6, 5.04}, {0.9, 16.0}}) {
        const double lambda = 4.1 * std::pow(rate, -0.21);  // 1/mm
        double sum = 0.0;                                   // m^2 per m^3
        constexpr double kStep = 0.001;                     // mm
        for (double d = 0.5 * kStep; d < 20.0; d += kStep) {
            const double area = 0.25 * std::numbers::pi * d * d * 1e-6;  // m^2
            sum += 2.0 * area * 8000.0 * std::exp(-lambda * d) * kStep;
        }
        EXPECT_NEAR(PrecipitationExtinction(p, false) / sum, 1.0, 0.005) << p;
    }
    EXPECT_EQ(PrecipitationExtinction(0.0, false), 0.0);
    EXPECT_EQ(PrecipitationExtinction(0.0, true), 0.0);
    EXPECT_GT(3.0 / PrecipitationExtinction(0.3, true), 1000.0);  // light snow: > 1 km
    EXPECT_GT(3.0 / PrecipitationExtinction(0.6, true), 500.0);   // moderate: 0.5-1 km
    EXPECT_LT(3.0 / PrecipitationExtinction(0.6, true), 1000.0);
    EXPECT_LT(3.0 / PrecipitationExtinction(0.9, true), 500.0);  // heavy: < 0.5 km
    EXPECT_DOUBLE_EQ(PrecipitationExtinction(0.9, true), HeavyPrecipitationExtinction(true));
}

// The shaft goes under the lowest raining layer, from the top of the layer below (or the
// ground) to its base, as a copy of it; nothing else changes.
TEST(Precipitation, ShaftsFallFromTheLowestRainingLayer) {
    Weather weather;
    CloudLayer low;
    low.name = "low";
    low.base_altitude = 500.0;
    low.top_altitude = 900.0;
    CloudLayer raining;
    raining.name = "raining";
    raining.base_altitude = 1500.0;
    raining.top_altitude = 4000.0;
    raining.precipitation = 0.6;
    raining.snow = true;
    weather.layers = {low, raining};
    const Weather drawn = WithPrecipitationShafts(weather);
    ASSERT_EQ(drawn.layers.size(), 3u);
    EXPECT_EQ(drawn.layers[0], low);
    const CloudLayer& shaft = drawn.layers[1];
    EXPECT_TRUE(shaft.precipitation_shaft);
    EXPECT_TRUE(shaft.snow);
    EXPECT_EQ(shaft.base_altitude, 900.0);
    EXPECT_EQ(shaft.top_altitude, 1500.0);
    EXPECT_EQ(shaft.map, raining.map);
    EXPECT_EQ(shaft.precipitation, raining.precipitation);
    EXPECT_EQ(drawn.layers[2], raining);
    EXPECT_NO_THROW(Validate(drawn));

    // The lowest layer raining: from the ground.
    weather.layers = {raining};
    EXPECT_EQ(WithPrecipitationShafts(weather).layers[0].base_altitude, 0.0);
    // Nothing falls, too little room, or the renderer's layers all taken: unchanged.
    weather.layers = {low};
    EXPECT_EQ(WithPrecipitationShafts(weather), weather);
    CloudLayer touching = raining;
    touching.base_altitude = 930.0;
    weather.layers = {low, touching};
    EXPECT_EQ(WithPrecipitationShafts(weather), weather);
    CloudLayer a = low, b = low, c = low;
    a.base_altitude = 2000.0, a.top_altitude = 2500.0;
    b.base_altitude = 3000.0, b.top_altitude = 3500.0;
    c.base_altitude = 5000.0, c.top_altitude = 6000.0;
    weather.layers = {raining, a, b, c};
    weather.layers[0].top_altitude = 1900.0;
    EXPECT_EQ(WithPrecipitationShafts(weather), weather);
}

}  // namespace
}  // namespace zenith::sky::clouds
