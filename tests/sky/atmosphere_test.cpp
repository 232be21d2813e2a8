// Atmosphere parameters: presets load and validate, JSON round-trips exactly, and every invalid
// input is reported with its field, value and the expected range.
#include "zenith/sky/atmosphere.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include "zenith/sky/reference/path_tracer.h"

namespace zenith::sky {
namespace {

const std::filesystem::path kSourcePresets =
    std::filesystem::path(ZENITH_SOURCE_DIR) / "data" / "presets";

Atmosphere LoadSourcePreset(const std::string& name) {
    return LoadAtmosphere((kSourcePresets / (name + ".json")).string());
}

// The message of the AtmosphereError thrown by f, or a test failure if none is thrown.
template <typename F>
std::string ErrorOf(F&& f) {
    try {
        f();
    } catch (const AtmosphereError& error) {
        return error.what();
    }
    ADD_FAILURE() << "no AtmosphereError thrown";
    return {};
}

std::string ParseError(const std::string& json) {
    return ErrorOf([&] { ParseAtmosphereJson(json, "test.json"); });
}

// Earth's file text with one substring replaced (the replaced text must be there).
std::string EarthWith(const std::string& from, const std::string& to) {
    std::ifstream file(kSourcePresets / "earth.json");
    std::string text((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
    const std::size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
    return text;
}

TEST(AtmospherePresets, EachLoadsAndValidates) {
    for (const char* name : {"earth", "mars", "thick"}) {
        SCOPED_TRACE(name);
        Atmosphere a;
        ASSERT_NO_THROW(a = LoadSourcePreset(name));
        EXPECT_EQ(a.name, name);
        EXPECT_NO_THROW(Validate(a));
    }
}

TEST(AtmospherePresets, BuiltInNamesResolveThroughThePresetDirectory) {
    // The test's environment may not set ZENITH_DATA_DIR; point it at the source tree so the
    // name lookup is what is tested, then restore it.
    const char* old = std::getenv("ZENITH_DATA_DIR");
    const std::string saved = old != nullptr ? old : "";
    setenv("ZENITH_DATA_DIR", (std::filesystem::path(ZENITH_SOURCE_DIR) / "data").c_str(), 1);
    EXPECT_EQ(PresetDirectory(), kSourcePresets);
    EXPECT_EQ(LoadAtmosphere("earth"), LoadSourcePreset("earth"));
    EXPECT_EQ(LoadAtmosphere("mars").name, "mars");
    const std::string message = ErrorOf([] { LoadAtmosphere("venus"); });
    EXPECT_NE(message.find("venus.json"), std::string::npos) << message;
    EXPECT_NE(message.find("earth"), std::string::npos) << message;  // lists what there is
    if (old != nullptr) {
        setenv("ZENITH_DATA_DIR", saved.c_str(), 1);
    } else {
        unsetenv("ZENITH_DATA_DIR");
    }
}

// Hillaire 2020, Table 1 (x 1e-6 /m) and Sec. 4: Rayleigh 8 km, Mie 1.2 km, g = 0.8; ozone tent
// of width 30 km centred at 25 km (after Bruneton); radii as in Bruneton's reference. Mie
// absorption is the demos' 0.444, not the table's misprinted 4.40 (data/presets/README.md).
TEST(AtmospherePresets, EarthIsHillaire2020Table1WithTheDemosMieAbsorption) {
    const Atmosphere a = LoadSourcePreset("earth");
    EXPECT_EQ(a.bottom_radius, 6360e3);
    EXPECT_EQ(a.top_radius, 6460e3);
    EXPECT_EQ(a.rayleigh_scattering, glm::dvec3(5.802e-6, 13.558e-6, 33.1e-6));
    EXPECT_EQ(a.rayleigh_scale_height, 8000.0);
    EXPECT_EQ(a.mie_scattering, glm::dvec3(3.996e-6));
    EXPECT_EQ(a.mie_absorption, glm::dvec3(0.444e-6));
    EXPECT_EQ(a.mie_scale_height, 1200.0);
    EXPECT_EQ(a.mie_g, 0.8);
    EXPECT_EQ(a.absorption_extinction, glm::dvec3(0.650e-6, 1.881e-6, 0.085e-6));
    EXPECT_EQ(a.absorption_center, 25e3);
    EXPECT_EQ(a.absorption_width, 30e3);
    EXPECT_EQ(a.ground_albedo, glm::dvec3(0.3));
    EXPECT_EQ(a.solar_illuminance, glm::dvec3(127000.0));
    // Everything the struct's defaults hold is the same preset, except the sun's size: the
    // default keeps Bruneton's 0.004675 rad, the preset the almanac's 959.63 arcsec.
    Atmosphere defaults;
    defaults.sun_angular_radius = a.sun_angular_radius;
    EXPECT_EQ(a, defaults);
    EXPECT_NEAR(a.sun_angular_radius, 959.63 / 3600.0 * M_PI / 180.0, 1e-8);  // 6 digits
}

TEST(AtmospherePresets, ThickIsHillaire2020Figure7) {
    const Atmosphere earth = LoadSourcePreset("earth");
    const Atmosphere thick = LoadSourcePreset("thick");
    for (int i = 0; i < 3; ++i) {
        EXPECT_DOUBLE_EQ(thick.rayleigh_scattering[i], 50.0 * earth.rayleigh_scattering[i]);
    }
    EXPECT_EQ(thick.rayleigh_scale_height, 20e3);
    Atmosphere rest = thick;  // all else is Earth's
    rest.name = earth.name;
    rest.rayleigh_scattering = earth.rayleigh_scattering;
    rest.rayleigh_scale_height = earth.rayleigh_scale_height;
    EXPECT_EQ(rest, earth);
}

// The Earth preset's aerosols as physics rather than digits (issue 18): Hillaire's and Bruneton's
// demos give them a single-scattering albedo of 0.9 (extinction 4.44e-6 /m = 3.996e-6 / 0.9);
// Table 1's misprinted absorption 4.40e-6 made it 0.48. Measured through the independent path
// tracer's medium and optical-depth quadrature, not the renderer's GLSL.
TEST(AtmospherePresets, EarthAerosolAlbedoAndHorizontalOpticalDepth) {
    const Atmosphere earth = LoadSourcePreset("earth");
    Atmosphere aerosols = earth;  // aerosols alone: no Rayleigh, no ozone
    aerosols.rayleigh_scattering = glm::dvec3(0.0);
    aerosols.absorption_extinction = glm::dvec3(0.0);

    // Single-scattering albedo at the ground, sigma_s / sigma_t of the aerosols, every channel.
    const reference::Medium ground = reference::EvaluateMedium(aerosols, 0.0);
    for (int i = 0; i < 3; ++i) {
        SCOPED_TRACE(i);
        EXPECT_NEAR(ground.mie_scattering[i] / ground.extinction[i], 0.9, 0.001);
        EXPECT_NEAR(earth.mie_scattering[i] / earth.MieExtinction()[i], 0.9, 0.001);
    }

    // Horizontal optical depth of 1 km of air at 1 km altitude. Closed form of the preset's
    // profile at constant altitude: tau = sigma_t,M exp(-h / H_M) L. The straight ray below is
    // tangent to the 1 km sphere at its middle, so it rises L^2 / (24 r) = 6.5 mm on average,
    // which lowers the density by 5.5e-6 of itself: tolerance 2e-5, relative.
    constexpr double kAltitude = 1000.0;  // m
    constexpr double kLength = 1000.0;    // m
    const double r = earth.bottom_radius + kAltitude;
    const glm::dvec3 origin(-0.5 * kLength, r, 0.0);
    const glm::dvec3 direction(1.0, 0.0, 0.0);
    const glm::dvec3 tau = reference::OpticalDepth(aerosols, origin, direction, kLength);
    const glm::dvec3 closed_form =
        earth.MieExtinction() * std::exp(-kAltitude / earth.mie_scale_height) * kLength;
    for (int i = 0; i < 3; ++i) {
        SCOPED_TRACE(i);
        EXPECT_NEAR(tau[i], closed_form[i], 2e-5 * closed_form[i]);
        // The published extinction, 4.44e-3 /km, through the same profile: 1.9296e-3.
        EXPECT_NEAR(closed_form[i], 4.44e-3 * std::exp(-1.0 / 1.2), 1e-12);
    }
    // For the record: the whole air (Rayleigh, ozone) along the same ray, green channel.
    const glm::dvec3 tau_air = reference::OpticalDepth(earth, origin, direction, kLength);
    std::printf(
        "aerosol albedo %.6f; horizontal 1 km at 1 km: aerosol tau %.6e (closed form "
        "%.6e), all air tau (G) %.6e\n",
        ground.mie_scattering.y / ground.extinction.y, tau.y, closed_form.y, tau_air.y);
}

TEST(AtmospherePresets, MarsIsPlausible) {
    const Atmosphere mars = LoadSourcePreset("mars");
    EXPECT_EQ(mars.bottom_radius, 3389.5e3);
    // Inverse square law at 1.5237 au, within the rounding to 100 lux.
    EXPECT_NEAR(mars.solar_illuminance.y, 127000.0 / (1.5237 * 1.5237), 50.0);
    EXPECT_EQ(mars.absorption_extinction, glm::dvec3(0.0));
    // Dust dominates: vertical optical depth ~0.5 of dust against ~0.003 of gas (green).
    const double dust_tau = mars.MieExtinction().y * mars.mie_scale_height;
    const double gas_tau = mars.rayleigh_scattering.y * mars.rayleigh_scale_height;
    EXPECT_NEAR(dust_tau, 0.5, 0.01);
    EXPECT_NEAR(gas_tau, 0.0032, 0.0002);
    // Dust absorbs blue more than red (the butterscotch daytime sky).
    EXPECT_GT(mars.mie_absorption.b, mars.mie_absorption.r);
}

TEST(AtmosphereJson, RoundTripIsExact) {
    for (const char* name : {"earth", "mars", "thick"}) {
        SCOPED_TRACE(name);
        const Atmosphere first = LoadSourcePreset(name);
        const std::string json = AtmosphereToJson(first);
        const Atmosphere second = ParseAtmosphereJson(json, "round_trip.json");
        EXPECT_EQ(second, first) << json;
        EXPECT_EQ(AtmosphereToJson(second), json);
    }
}

TEST(AtmosphereJson, RoundTripIsExactForAwkwardValues) {
    Atmosphere a;
    a.name = "odd \"quoted\" name";
    a.bottom_radius = 1234567.891;
    a.top_radius = a.bottom_radius + 98765.4321;
    a.rayleigh_scattering = {1.0 / 3.0 * 1e-5, 2.0 / 7.0 * 1e-5, M_PI * 1e-6};
    a.mie_g = -0.123456789012345;
    a.sun_angular_radius = 0.1;  // 5.729... deg, not a short decimal
    a.solar_illuminance = {1.0 / 3.0, 2.0, 3.0};
    for (int i = 0; i < 200; ++i) {  // many angles: the degree conversion must always invert
        a.sun_angular_radius = 1e-4 + i * 3.3e-4;
        a.rayleigh_scale_height = 7000.0 + i * 13.37;
        ASSERT_EQ(ParseAtmosphereJson(AtmosphereToJson(a), "x.json"), a) << AtmosphereToJson(a);
    }
}

TEST(AtmosphereJson, ScalarAndArrayFormsAreEquivalent) {
    const Atmosphere array = ParseAtmosphereJson(
        EarthWith("\"ground_albedo\": 0.3", "\"ground_albedo\": [0.3, 0.3, 0.3]"), "a.json");
    EXPECT_EQ(array.ground_albedo, glm::dvec3(0.3));
}

TEST(AtmosphereJson, AbsorptionGroupIsOptional) {
    const std::string text = EarthWith(
        "    \"absorption\": {\n"
        "        \"extinction_per_km\": [0.00065, 0.001881, 0.000085],\n"
        "        \"center_km\": 25,\n"
        "        \"width_km\": 30\n"
        "    },\n",
        "");
    EXPECT_EQ(ParseAtmosphereJson(text, "a.json").absorption_extinction, glm::dvec3(0.0));
}

TEST(AtmosphereJson, NameDefaultsToTheFileStem) {
    const std::string text = EarthWith("\"name\": \"earth\",", "");
    EXPECT_EQ(ParseAtmosphereJson(text, "/some/where/my_planet.json").name, "my_planet");
}

// Each field, made invalid in the file: the message names the file, the key path, the value as
// written (in the file's unit) and what was expected.
TEST(AtmosphereJson, InvalidFieldsNameFieldValueAndRange) {
    struct Case {
        const char* from;
        const char* to;
        const char* field;
        const char* value;
    };
    const Case cases[] = {
        {"\"bottom_radius_km\": 6360", "\"bottom_radius_km\": -1", "bottom_radius_km", "-1 km"},
        {"\"top_radius_km\": 6460", "\"top_radius_km\": 6300", "top_radius_km", "6300 km"},
        {"\"top_radius_km\": 6460", "\"top_radius_km\": 7500", "top_radius_km", "7500 km"},
        {"[0.005802, 0.013558, 0.0331]", "[0.005802, -0.013558, 0.0331]",
         "rayleigh.scattering_per_km[1]", "-0.013558 1/km"},
        {"[0.005802, 0.013558, 0.0331]", "[0.005802, 0.013558, 33100]",
         "rayleigh.scattering_per_km[2]", "33100 1/km"},
        {"\"scale_height_km\": 8", "\"scale_height_km\": 0", "rayleigh.scale_height_km", "0 km"},
        {"\"scattering_per_km\": 0.003996", "\"scattering_per_km\": -0.003996",
         "mie.scattering_per_km[0]", "-0.003996 1/km"},
        {"\"absorption_per_km\": 0.000444", "\"absorption_per_km\": -1e-9",
         "mie.absorption_per_km[0]", "-1e-09 1/km"},
        {"\"scale_height_km\": 1.2", "\"scale_height_km\": -1.2", "mie.scale_height_km", "-1.2 km"},
        {"\"g\": 0.8", "\"g\": 1", "mie.g", "1 (dimensionless)"},
        {"\"g\": 0.8", "\"g\": -1.5", "mie.g", "-1.5 (dimensionless)"},
        {"[0.00065, 0.001881, 0.000085]", "[0.00065, 0.001881, -0.000085]",
         "absorption.extinction_per_km[2]", "-8.5e-05 1/km"},
        {"\"center_km\": 25", "\"center_km\": 250", "absorption.center_km", "250 km"},
        {"\"width_km\": 30", "\"width_km\": 0", "absorption.width_km", "0 km"},
        {"\"ground_albedo\": 0.3", "\"ground_albedo\": [0.3, 1.5, 0.3]", "ground_albedo[1]", "1.5"},
        {"\"solar_illuminance_lux\": 127000", "\"solar_illuminance_lux\": 0",
         "solar_illuminance_lux[0]", "0 lux"},
        {"\"sun_angular_radius_deg\": 0.266564", "\"sun_angular_radius_deg\": 0",
         "sun_angular_radius_deg", "0 deg"},
        {"\"sun_angular_radius_deg\": 0.266564", "\"sun_angular_radius_deg\": 50",
         "sun_angular_radius_deg", "50 deg"},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.to);
        const std::string message = ParseError(EarthWith(c.from, c.to));
        EXPECT_NE(message.find("test.json"), std::string::npos) << message;
        EXPECT_NE(message.find(std::string(c.field) + " = " + c.value), std::string::npos)
            << message;
        EXPECT_NE(message.find("expected"), std::string::npos) << message;
    }
}

TEST(AtmosphereJson, TopRadiusMessageGivesTheBottomRadius) {
    const std::string message =
        ParseError(EarthWith("\"top_radius_km\": 6460", "\"top_radius_km\": 6000"));
    EXPECT_NE(message.find("bottom_radius_km = 6360 km"), std::string::npos) << message;
}

TEST(AtmosphereJson, SyntaxErrorGivesLineAndColumn) {
    // The missing comma after 6360 is noticed at the end of the next token, "top_radius_km"
    // (line 4, columns 5 to 19); nlohmann reports where it stopped reading.
    const std::string text =
        "{\n    \"name\": \"x\",\n    \"bottom_radius_km\": 6360\n"
        "    \"top_radius_km\": 6460\n}\n";
    const std::string message = ParseError(text);
    EXPECT_NE(message.find("test.json:4:19:"), std::string::npos) << message;
    EXPECT_NE(message.find("JSON syntax"), std::string::npos) << message;

    const std::string first_column = ParseError("x");
    EXPECT_NE(first_column.find("test.json:1:1:"), std::string::npos) << first_column;
    const std::string truncated = ParseError("{\n  \"name\": \"x\",\n");
    EXPECT_NE(truncated.find("test.json:3:1:"), std::string::npos) << truncated;
    // A number beyond double is a syntax error of the file, not an infinity.
    const std::string overflow = ParseError(
        EarthWith("\"solar_illuminance_lux\": 127000", "\"solar_illuminance_lux\": 1e999"));
    EXPECT_NE(overflow.find("test.json:22:"), std::string::npos) << overflow;
    EXPECT_NE(overflow.find("1e999"), std::string::npos) << overflow;
}

TEST(AtmosphereJson, DeepNestingIsRefusedBeforeParsing) {
    const std::string message =
        ParseError("{\n  \"name\": " + std::string(100000, '[') + std::string(100000, ']') + "}");
    EXPECT_NE(message.find("test.json:2:42: JSON nested deeper than 32 levels"), std::string::npos)
        << message;
    // Brackets inside strings are text, not nesting.
    EXPECT_NO_THROW(ParseAtmosphereJson(
        EarthWith("\"name\": \"earth\"", "\"name\": \"" + std::string(100, '[') + "\""), "a.json"));
}

TEST(AtmosphereJson, UnknownKeyIsRejected) {
    const std::string top = ParseError(EarthWith("\"ground_albedo\"", "\"ground_albedeo\""));
    EXPECT_NE(top.find("ground_albedeo"), std::string::npos) << top;
    EXPECT_NE(top.find("unknown key"), std::string::npos) << top;
    EXPECT_NE(top.find("expected one of"), std::string::npos) << top;
    const std::string nested = ParseError(EarthWith("\"g\": 0.8", "\"g\": 0.8, \"G\": 0.7"));
    EXPECT_NE(nested.find("mie.G"), std::string::npos) << nested;
}

TEST(AtmosphereJson, DuplicateKeyIsRejected) {
    const std::string message = ParseError(EarthWith("\"g\": 0.8", "\"g\": 0.8, \"g\": 0.2"));
    EXPECT_NE(message.find("mie.g: duplicate key"), std::string::npos) << message;
}

TEST(AtmosphereJson, MissingRequiredKeyIsRejected) {
    const std::string message = ParseError(EarthWith("\"g\": 0.8", "\"h\": 0.8"));
    // The unknown "h" is reported first; with it gone, the missing "g" is.
    EXPECT_NE(message.find("mie.h"), std::string::npos) << message;
    const std::string missing =
        ParseError(EarthWith("        \"scale_height_km\": 1.2,\n        \"g\": 0.8\n",
                             "        \"scale_height_km\": 1.2\n"));
    EXPECT_NE(missing.find("mie.g: missing"), std::string::npos) << missing;
    const std::string group = ParseError("{\"bottom_radius_km\": 1, \"top_radius_km\": 2}");
    EXPECT_NE(group.find("rayleigh: missing"), std::string::npos) << group;
}

TEST(AtmosphereJson, WrongTypesAreRejected) {
    const std::string text = ParseError(EarthWith("\"g\": 0.8", "\"g\": \"0.8\""));
    EXPECT_NE(text.find("mie.g: expected a number, got string"), std::string::npos) << text;
    const std::string pair =
        ParseError(EarthWith("\"ground_albedo\": 0.3", "\"ground_albedo\": [0.3, 0.3]"));
    EXPECT_NE(pair.find("ground_albedo: expected a number or an array of 3"), std::string::npos)
        << pair;
    const std::string group = ParseError(
        "{\"bottom_radius_km\": 6360, \"top_radius_km\": 6460, \"mie\": 3,\n"
        "\"rayleigh\": {\"scattering_per_km\": 0.001, \"scale_height_km\": 8}}");
    EXPECT_NE(group.find("mie: expected an object, got number 3"), std::string::npos) << group;
    EXPECT_NE(ParseError("[1, 2]").find("expected an object"), std::string::npos);
}

TEST(AtmosphereLoad, MissingFileNamesThePath) {
    const std::string path = "/nonexistent/zenith/atmosphere.json";
    const std::string message = ErrorOf([&] { LoadAtmosphere(path); });
    EXPECT_NE(message.find(path), std::string::npos) << message;
    EXPECT_NE(message.find("No such file"), std::string::npos) << message;
}

// Validate() on the struct reports members and SI values, since that is what its caller holds.
TEST(AtmosphereValidate, NanAndNegativeCoefficientsAreRejected) {
    Atmosphere a;
    a.mie_scattering.g = std::numeric_limits<double>::quiet_NaN();
    std::string message = ErrorOf([&] { Validate(a); });
    EXPECT_NE(message.find("mie_scattering[1] = nan 1/m"), std::string::npos) << message;
    EXPECT_NE(message.find("expected"), std::string::npos) << message;

    a = Atmosphere{};
    a.rayleigh_scattering.b = -33.1e-6;
    message = ErrorOf([&] { Validate(a); });
    EXPECT_NE(message.find("rayleigh_scattering[2] = -3.31e-05 1/m"), std::string::npos) << message;
}

TEST(AtmosphereValidate, EveryFieldRejectsNan) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const struct {
        const char* member;
        void (*spoil)(Atmosphere&, double);
    } cases[] = {
        {"bottom_radius", [](Atmosphere& a, double x) { a.bottom_radius = x; }},
        {"top_radius", [](Atmosphere& a, double x) { a.top_radius = x; }},
        {"rayleigh_scattering[0]", [](Atmosphere& a, double x) { a.rayleigh_scattering.r = x; }},
        {"rayleigh_scale_height", [](Atmosphere& a, double x) { a.rayleigh_scale_height = x; }},
        {"mie_absorption[2]", [](Atmosphere& a, double x) { a.mie_absorption.b = x; }},
        {"mie_scale_height", [](Atmosphere& a, double x) { a.mie_scale_height = x; }},
        {"mie_g", [](Atmosphere& a, double x) { a.mie_g = x; }},
        {"absorption_extinction[1]",
         [](Atmosphere& a, double x) { a.absorption_extinction.g = x; }},
        {"absorption_center", [](Atmosphere& a, double x) { a.absorption_center = x; }},
        {"absorption_width", [](Atmosphere& a, double x) { a.absorption_width = x; }},
        {"ground_albedo[0]", [](Atmosphere& a, double x) { a.ground_albedo.r = x; }},
        {"solar_illuminance[2]", [](Atmosphere& a, double x) { a.solar_illuminance.b = x; }},
        {"sun_angular_radius", [](Atmosphere& a, double x) { a.sun_angular_radius = x; }},
    };
    for (const auto& c : cases) {
        SCOPED_TRACE(c.member);
        Atmosphere a;
        c.spoil(a, nan);
        const std::string message = ErrorOf([&] { Validate(a); });
        EXPECT_NE(message.find(std::string(c.member) + " = nan"), std::string::npos) << message;
        EXPECT_NE(message.find("expected"), std::string::npos) << message;
    }
}

TEST(AtmosphereValidate, GMustBeStrictlyInsideMinusOneOne) {
    Atmosphere a;
    for (double g : {-0.999999, 0.0, 0.999999}) {
        a.mie_g = g;
        EXPECT_NO_THROW(Validate(a)) << g;
    }
    for (double g : {-1.0, 1.0}) {
        a.mie_g = g;
        EXPECT_THROW(Validate(a), AtmosphereError) << g;
    }
}

TEST(AtmosphereValidate, DefaultsAreValid) { EXPECT_NO_THROW(Validate(Atmosphere{})); }

}  // namespace
}  // namespace zenith::sky
