#include "zenith/sim/ephemeris_report.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

namespace zenith::sim {
namespace {

std::vector<nlohmann::json> Lines(const std::string& text) {
    std::vector<nlohmann::json> out;
    std::istringstream in(text);
    std::string line;
    while (std::getline(in, line)) out.push_back(nlohmann::json::parse(line));
    return out;
}

TEST(EphemerisBatch, HostileLinesCostLittleAndAreReportedInPlace) {
    const std::string good =
        R"({"utc": "2024-04-08T18:18:00Z", "lat_deg": 31.0, "lon_deg": -104.0, "height_m": 1000})";
    std::istringstream in(good + "\n" + std::string(40, '[') + std::string(40, ']') + "\n" +
                          "{\"utc\": \"" + std::string(200000, 'x') + "\"}\n" + good);
    std::ostringstream out;
    const BatchSummary summary = RunEphemerisBatch(in, out);
    EXPECT_EQ(summary.lines, 4u);
    EXPECT_EQ(summary.failed, 2u);
    const auto lines = Lines(out.str());
    ASSERT_EQ(lines.size(), 4u);
    EXPECT_EQ(lines[1]["error"], "JSON nested deeper than 8 levels at byte 9");
    EXPECT_EQ(lines[2]["error"], "line of 200011 bytes (at most 65536)");
    EXPECT_TRUE(lines[3].contains("sun_az_deg"));
}

TEST(EphemerisBatch, KeepsOrderAndReportsBadLinesInPlace) {
    std::istringstream in(
        R"({"utc": "2024-04-08T18:18:00Z", "lat_deg": 31.0, "lon_deg": -104.0, "height_m": 1000, "note": "ignored"})"
        "\n"
        R"({"utc": "2024-02-30T00:00:00Z", "lat_deg": 31.0, "lon_deg": -104.0, "height_m": 0})"
        "\n"
        "this is not json\n"
        R"({"utc": "2024-04-08T18:18:00Z", "lat_deg": 95.0, "lon_deg": 0, "height_m": 0})"
        "\n"
        R"({"utc": "2024-04-08T18:18:00Z", "lon_deg": 0, "height_m": 0})"
        "\n"
        R"({"utc": "2024-04-08T18:18:00Z", "lat_deg": "north", "lon_deg": 0, "height_m": 0})"
        "\n"
        R"({"utc": "2003-10-17T12:30:30-07:00", "lat_deg": 39.742476, "lon_deg": -105.1786, "height_m": 1830.14, "delta_t_s": 67})"
        "\n");
    std::ostringstream out;
    const BatchSummary summary = RunEphemerisBatch(in, out);
    EXPECT_EQ(summary.lines, 7u);
    EXPECT_EQ(summary.failed, 5u);
    EXPECT_NE(summary.first_error.find("line 2"), std::string::npos) << summary.first_error;

    const auto lines = Lines(out.str());
    ASSERT_EQ(lines.size(), 7u);
    for (const char* key :
         {"sun_az_deg", "sun_el_deg", "sun_dist_km", "sun_diameter_deg", "moon_az_deg",
          "moon_el_deg", "moon_dist_km", "moon_diameter_deg", "moon_illum_fraction",
          "moon_phase_angle_deg", "moon_bright_limb_deg"}) {
        EXPECT_TRUE(lines[0].contains(key)) << key;
        EXPECT_TRUE(lines[6].contains(key)) << key;
    }
    auto error_of = [&](std::size_t i) {
        EXPECT_EQ(lines[i]["line"], i + 1);
        return lines[i]["error"].get<std::string>();
    };
    EXPECT_NE(error_of(1).find("day"), std::string::npos) << error_of(1);
    EXPECT_NE(error_of(2).find("JSON"), std::string::npos) << error_of(2);
    EXPECT_NE(error_of(3).find("lat_deg = 95"), std::string::npos) << error_of(3);
    EXPECT_NE(error_of(4).find("lat_deg"), std::string::npos) << error_of(4);
    EXPECT_NE(error_of(5).find("\"north\""), std::string::npos) << error_of(5);
    // The SPA line: geometric topocentric elevation e0 = 39.872046 deg.
    EXPECT_NEAR(lines[6]["sun_el_deg"].get<double>(), 39.872046, 1.0 / 3600.0);
    EXPECT_NEAR(lines[6]["sun_az_deg"].get<double>(), 194.34024, 1.0 / 3600.0);
}

// Batch records and the table carry the planets (Venus at greatest brilliancy, 2020-04-28).
TEST(EphemerisReport, PlanetsAreReported) {
    std::istringstream in(
        R"({"utc": "2020-04-28T19:45:00Z", "lat_deg": 45, "lon_deg": 7, "height_m": 500})"
        "\n");
    std::ostringstream out;
    RunEphemerisBatch(in, out);
    const nlohmann::json record = nlohmann::json::parse(out.str());
    for (const char* planet :
         {"mercury", "venus", "mars", "jupiter", "saturn", "uranus", "neptune"}) {
        for (const char* field : {"_az_deg", "_el_deg", "_dist_au", "_mag", "_illum_fraction"}) {
            EXPECT_TRUE(record.contains(std::string(planet) + field)) << planet << field;
        }
    }
    EXPECT_NEAR(record["venus_mag"].get<double>(), -4.75, 0.05);
    EXPECT_NEAR(record["venus_el_deg"].get<double>(), 23.3, 0.1);
    EXPECT_NEAR(record["venus_illum_fraction"].get<double>(), 0.27, 0.01);
}

// Eclipses in the batch records and the table: 2024-04-08 at Chicago's maximum (timeanddate:
// 93.9 % of the Sun covered) and in Dallas's totality; the 2022-11-08 lunar eclipse's greatest
// (tests/geo/eclipse_test.cpp has the sources).
TEST(EphemerisReport, EclipsesAreReported) {
    std::istringstream in(
        R"({"utc": "2024-04-08T19:07:41Z", "lat_deg": 41.8781, "lon_deg": -87.6298, "height_m": 180})"
        "\n"
        R"({"utc": "2024-04-08T18:42:00Z", "lat_deg": 32.7767, "lon_deg": -96.797, "height_m": 140})"
        "\n"
        R"({"utc": "2024-04-08T12:00:00Z", "lat_deg": 41.8781, "lon_deg": -87.6298, "height_m": 180})"
        "\n"
        R"({"utc": "2022-11-08T10:59:08Z", "lat_deg": 21.3, "lon_deg": -157.86, "height_m": 10})"
        "\n");
    std::ostringstream out;
    RunEphemerisBatch(in, out);
    const auto lines = Lines(out.str());
    ASSERT_EQ(lines.size(), 4u);
    EXPECT_NEAR(lines[0]["sun_obscuration"].get<double>(), 0.939, 0.002);
    EXPECT_LT(lines[0]["sun_uncovered_flux"].get<double>(), 1.0 - 0.939);
    EXPECT_GT(lines[0]["sun_uncovered_flux"].get<double>(), 0.02);
    EXPECT_NEAR(lines[0]["sun_eclipse_magnitude"].get<double>(), 0.942, 0.003);
    EXPECT_EQ(lines[1]["sun_obscuration"].get<double>(), 1.0);
    EXPECT_EQ(lines[1]["sun_uncovered_flux"].get<double>(), 0.0);
    EXPECT_GT(lines[1]["sun_eclipse_magnitude"].get<double>(), 1.0);
    EXPECT_EQ(lines[2]["sun_obscuration"].get<double>(), 0.0);  // before it began
    EXPECT_EQ(lines[2]["sun_uncovered_flux"].get<double>(), 1.0);
    EXPECT_EQ(lines[3]["moon_direct_sunlight"].get<double>(), 0.0);
    EXPECT_NEAR(lines[3]["moon_umbral_magnitude"].get<double>(), 1.339, 0.005);
    EXPECT_EQ(lines[0]["moon_direct_sunlight"].get<double>(), 1.0);
}

}  // namespace
}  // namespace zenith::sim
