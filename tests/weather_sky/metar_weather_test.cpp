// METAR -> zenith weather (cloud_weather.h): the table's rules, checked as laws where there is
// one (MOR and Koschmieder, okta ranges, heights above the station) and as the table elsewhere.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <utility>

#include "zenith/base/units.h"
#include "zenith/sky/reference/accuracy.h"
#include "zenith/sky/reference/atmosphere_reference.h"
#include "zenith/sky/reference/cloud_path_tracer.h"
#include "zenith/sky/reference/path_tracer.h"
#include "zenith/weather/cloud_weather.h"

namespace zenith::weather {
namespace {

MetarWeather FromText(const std::string& text, double elevation_m = 0.0) {
    return CloudWeatherFromMetar(DecodeMetar(text), elevation_m);
}

// The layer's coverage grows with the report's amount. The coverage parameter is not the share of
// the sky covered (the density model's remap makes a coverage of 0.38 about 1.5 oktas of sky);
// the drawn share is measured in metar_sky_cover_test.cpp.
TEST(CloudWeather, CoverageGrowsWithTheAmount) {
    double previous = 0.0;
    for (const Cover cover : {Cover::kFew, Cover::kScattered, Cover::kBroken, Cover::kOvercast}) {
        const std::string code(CoverCode(cover));
        SCOPED_TRACE(code);
        const MetarWeather w = FromText("EGLL 211750Z 24012KT 9999 " + code + "035 18/09 Q1018");
        ASSERT_EQ(w.clouds.layers.size(), 1u);
        EXPECT_GT(w.clouds.layers[0].coverage, previous);
        previous = w.clouds.layers[0].coverage;
    }
    EXPECT_EQ(previous, 1.0);
}

// Bases are the report's heights above the station, placed on the station's elevation.
TEST(CloudWeather, BaseIsAboveTheStation) {
    const MetarWeather w =
        FromText("LFMY 141200Z 31010KT 9999 FEW045 BKN080 OVC250 29/12 Q1016", 98.0);
    ASSERT_EQ(w.clouds.layers.size(), 3u);
    // Broken and scattered layers start a little lower, where their clouds' density starts
    // (the base seen is measured in metar_sky_cover_test.cpp); overcast ones at the report.
    EXPECT_LT(w.clouds.layers[0].base_altitude, 98.0 + 4500 * kMetresPerFoot);
    EXPECT_GT(w.clouds.layers[0].base_altitude, 98.0 + 0.9 * 4500 * kMetresPerFoot);
    EXPECT_LT(w.clouds.layers[1].base_altitude, 98.0 + 8000 * kMetresPerFoot);
    EXPECT_GT(w.clouds.layers[1].base_altitude, 98.0 + 0.97 * 8000 * kMetresPerFoot);
    EXPECT_DOUBLE_EQ(w.clouds.layers[2].base_altitude, 98.0 + 25000 * kMetresPerFoot);
    EXPECT_EQ(w.clouds.layers[0].name, "cumulus");
    EXPECT_EQ(w.clouds.layers[1].name, "altocumulus");
    EXPECT_EQ(w.clouds.layers[2].name, "cirrostratus");  // ice: OVC250
    EXPECT_EQ(w.clouds.layers[2].extinction_scale, 0.04);
    EXPECT_EQ(w.clouds.layers[1].extinction_scale, 1.0);  // water
    const MetarWeather cirrus = FromText("LFMY 141200Z 31010KT 9999 SCT280 29/12 Q1016", 98.0);
    ASSERT_EQ(cirrus.clouds.layers.size(), 1u);
    EXPECT_EQ(cirrus.clouds.layers[0].name, "cirrus");
    EXPECT_EQ(cirrus.clouds.layers[0].map.kind, sky::clouds::WeatherMapSource::Kind::kStreaks);
    // The cumulus reach the altocumulus' base; alone, on a warm day (29 degC), they are deeper
    // than the 1000 m of a 15 degC day.
    EXPECT_DOUBLE_EQ(w.clouds.layers[0].top_altitude, w.clouds.layers[1].base_altitude);
    const MetarWeather alone = FromText("LFMY 141200Z 31010KT 9999 FEW045 29/12 Q1016", 98.0);
    EXPECT_NEAR(alone.clouds.layers[0].top_altitude - alone.clouds.layers[0].base_altitude, 1700.0,
                1e-9);
    for (const auto& l : w.clouds.layers) {
        EXPECT_NEAR(l.wind_from, Radians(310.0), 1e-12);
        EXPECT_NEAR(l.wind_speed, 10 * kMetresPerSecondPerKnot, 1e-12);
    }
}

// CAVOK and the clear-sky codes give exactly the clear preset's layers (none) and no extinction.
TEST(CloudWeather, ClearReportsAreTheClearSky) {
    const sky::clouds::Weather clear = sky::clouds::LoadWeather("clear");
    for (const char* body : {"CAVOK", "9999 SKC", "10SM CLR", "9999 NSC", "9999 NCD", "P6SM"}) {
        SCOPED_TRACE(body);
        const MetarWeather w =
            FromText(std::string("KXYZ 010000Z 27005KT ") + body + " 10/05 Q1000");
        EXPECT_EQ(w.clouds.layers, clear.layers);
        EXPECT_FALSE(w.ground_extinction_per_m);
        EXPECT_FALSE(w.fog);
        EXPECT_TRUE(w.notes.empty());
    }
}

// MOR: a black target at the reported distance keeps 5 % contrast (Koschmieder).
TEST(CloudWeather, ExtinctionGivesTheReportedVisualRange) {
    for (const double v : {200.0, 800.0, 1609.344, 5000.0, 9000.0}) {
        EXPECT_NEAR(std::exp(-ExtinctionForVisibility(v) * v), 0.05, 1e-12);
    }
    const MetarWeather w = FromText("KXYZ 010000Z 27005KT 1/2SM BR OVC004 10/09 A3000");
    ASSERT_TRUE(w.ground_extinction_per_m);
    EXPECT_NEAR(*w.ground_extinction_per_m * 0.5 * kMetresPerStatuteMile, std::log(20.0), 1e-12);
    EXPECT_TRUE(w.haze);
    EXPECT_THROW(ExtinctionForVisibility(0.0), ArgumentError);
    EXPECT_THROW(ExtinctionForVisibility(std::nan("")), ArgumentError);
}

// The fog's medium, as the renderer and the cloud path tracer define it (CloudField: the shared
// density function over the layer's map and the noise), has at eye height the extinction that,
// with the air's (set for 1 km), makes the reported visibility: ln 20 / V in all, by Koschmieder.
TEST(CloudWeather, FogsExtinctionAtTheGroundGivesTheReportedVisibility) {
    const sky::CloudSettings settings;
    const sky::clouds::CloudNoise noise =
        sky::clouds::LoadOrGenerateCloudNoise(
            settings.noise, std::filesystem::path(ZENITH_BINARY_DIR) / "cloud-noise-cache")
            .noise;
    const sky::Atmosphere earth;
    for (const char* text :
         {"EDDF 010000Z 00000KT 0100 FG VV002 05/05 Q1020",
          "EDDF 010000Z 00000KT 0250 FG 05/05 Q1020", "EDDF 010000Z 00000KT 0600 FG 05/05 Q1020"}) {
        SCOPED_TRACE(text);
        const MetarWeather w = FromText(text, 0.0);
        const double v = *w.visibility_m;
        const sky::Atmosphere air = AtmosphereForVisibility(earth, v, w.fog, nullptr);
        const sky::reference::CloudField field(w.clouds, settings, noise, earth.bottom_radius);
        const double expected = std::log(20.0) / v - GroundExtinctionGreen(air);
        for (const glm::dvec3 p : {glm::dvec3(0.0, 0.0, earth.bottom_radius + 2.0),
                                   glm::dvec3(3000.0, -2000.0, earth.bottom_radius + 20.0)}) {
            // Near the origin, the dome is the plane: the point's height is its altitude.
            EXPECT_NEAR(field.Extinction(p) / expected, 1.0, 1e-3);
        }
        // Above the fog, nothing.
        EXPECT_EQ(field.Extinction(glm::dvec3(0.0, 0.0, earth.bottom_radius + 150.0)), 0.0);
    }
}

TEST(CloudWeather, VerticalVisibilityAndFogAreAFogLayer) {
    const MetarWeather vv = FromText("EDDF 010000Z 00000KT 0100 FG VV002 05/05 Q1020", 111.0);
    ASSERT_EQ(vv.clouds.layers.size(), 1u);
    const auto& fog = vv.clouds.layers[0];
    EXPECT_EQ(fog.name, "fog");
    EXPECT_DOUBLE_EQ(fog.base_altitude, 111.0);
    EXPECT_DOUBLE_EQ(fog.top_altitude, 111.0 + 200 * kMetresPerFoot);
    EXPECT_EQ(fog.coverage, 1.0);
    EXPECT_TRUE(vv.fog);
    EXPECT_NEAR(*vv.ground_extinction_per_m, std::log(20.0) / 100.0, 1e-12);
    const MetarWeather patches = FromText("EDDF 010000Z 00000KT 3000 BCFG FEW005 05/05 Q1020");
    ASSERT_EQ(patches.clouds.layers.size(), 2u);
    EXPECT_EQ(patches.clouds.layers[0].coverage, 0.5);
    EXPECT_TRUE(patches.clouds.layers[0].ground_fog);
    EXPECT_FALSE(patches.clouds.layers[1].ground_fog);
    EXPECT_DOUBLE_EQ(patches.clouds.layers[0].top_altitude, 100.0);
    // Fog in the vicinity is not at the station.
    EXPECT_FALSE(FromText("EDDF 010000Z 00000KT 3000 VCFG FEW005 05/05 Q1020").fog);
}

TEST(CloudWeather, CumulonimbusRainsAndTowers) {
    const MetarWeather w = FromText(
        "KABC 121755Z 21016G24KT 3/4SM +TSRA BR FEW008 BKN020 OVC040CB 18/17 A2970", 150.0);
    ASSERT_EQ(w.clouds.layers.size(), 3u);
    const auto& cb = w.clouds.layers[2];
    EXPECT_EQ(cb.name, "cumulonimbus");
    EXPECT_EQ(cb.cloud_type, 1.0);
    EXPECT_EQ(cb.map.kind, sky::clouds::WeatherMapSource::Kind::kCells);
    EXPECT_DOUBLE_EQ(cb.top_altitude, 150.0 + 10000.0);
    EXPECT_EQ(cb.precipitation, 0.9);  // heavy, from the CB for a thunderstorm
    EXPECT_EQ(w.clouds.layers[1].precipitation, 0.0);
    EXPECT_EQ(w.precipitation, 0.9);
    EXPECT_FALSE(w.snow);
    EXPECT_FALSE(cb.snow);
    // Steady snow from the lowest BKN/OVC layer, a nimbostratus.
    const MetarWeather sn = FromText("KGTF 170322Z 33014KT 1 3/4SM -SN BR OVC005 A2991");
    EXPECT_EQ(sn.clouds.layers[0].name, "nimbostratus");
    EXPECT_EQ(sn.clouds.layers[0].precipitation, 0.3);
    EXPECT_TRUE(sn.snow);
    EXPECT_TRUE(sn.clouds.layers[0].snow);  // its shaft is snow's (clouds::PrecipitationExtinction)
    const MetarWeather tcu = FromText("KXYZ 010000Z 27005KT 10SM SCT040TCU 30/20 A3000");
    EXPECT_EQ(tcu.clouds.layers[0].cloud_type, 0.75);
}

// Overlapping layers are cut at the next base; one too thin to march is merged upwards.
TEST(CloudWeather, LayersDoNotOverlap) {
    const MetarWeather cut = FromText("KXYZ 010000Z 27005KT 10SM FEW020 SCT030 BKN040 20/10 A3000");
    ASSERT_EQ(cut.clouds.layers.size(), 3u);
    EXPECT_DOUBLE_EQ(cut.clouds.layers[0].top_altitude, cut.clouds.layers[1].base_altitude);
    const MetarWeather merged = FromText("KXYZ 010000Z 27005KT 10SM FEW020 BKN020 20/10 A3000");
    ASSERT_EQ(merged.clouds.layers.size(), 1u);
    EXPECT_EQ(merged.clouds.layers[0].coverage, 0.75);
    EXPECT_FALSE(merged.notes.empty());
}

TEST(CloudWeather, EveryReportGivesAValidWeather) {
    const char* reports[] = {
        "METAR KABC 121755Z AUTO 21016G24KT 180V240 1SM R11/P6000FT -RA BR BKN015 OVC025 06/04 "
        "A2990",
        "KABQ 100156Z 32010KT 280V340 10SM TS FEW033 BKN075CB OVC100 19/14 A2999",
        "EDDF 010000Z AUTO 27005KT //// // ////// ///// Q////",
        "EDDF 010000Z AUTO 27005KT 9999 BKN/// ///050 FEW///CB 10/05 Q1000",
        "KXYZ 010000Z 27005KT 1/4SM FG VV/// FEW001 OVC002 OVC002 OVC003 M01/M01 A3000",
        "KXYZ 010000Z 27005KT 10SM FEW600 OVC700 20/10 A3000",
        "KXYZ 010000Z 27005KT 10SM SCT300CB 20/10 A3000",
        "METAR EDDF 010000Z NIL=",
    };
    for (const char* r : reports) {
        for (const double elevation : {-400.0, 0.0, 4000.0, 9000.0}) {
            SCOPED_TRACE(std::string(r) + " at " + std::to_string(elevation));
            EXPECT_NO_THROW(FromText(r, elevation));
        }
    }
    EXPECT_THROW(FromText(reports[0], 9001.0), ArgumentError);
    EXPECT_THROW(FromText(reports[0], std::nan("")), ArgumentError);
}

// Whatever the decoder accepts maps to a valid Weather at any allowed elevation: the fuzz seeds,
// or a whole fuzz corpus given in $ZENITH_METAR_CORPUS.
TEST(CloudWeather, FuzzCorpusMapsToValidWeather) {
    const char* env = std::getenv("ZENITH_METAR_CORPUS");
    const std::filesystem::path dir =
        env ? std::filesystem::path(env)
            : std::filesystem::path(ZENITH_SOURCE_DIR) / "tests/fuzz/corpus/metar";
    int decoded = 0;
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
        std::ifstream in(entry.path(), std::ios::binary);
        std::stringstream text;
        text << in.rdbuf();
        Metar m;
        try {
            m = DecodeMetar(text.str());
        } catch (const MetarError&) {
            continue;
        }
        ++decoded;
        for (const double elevation : {-500.0, 0.0, 9000.0}) {
            EXPECT_NO_THROW(CloudWeatherFromMetar(m, elevation)) << entry.path();
        }
    }
    EXPECT_GT(decoded, 0);
}

}  // namespace
}  // namespace zenith::weather

namespace zenith::weather {
namespace {

// Koschmieder's law on the atmosphere itself: along a horizontal chord from the ground, the
// transmittance over the reported visibility V is 1/20 (a black target's contrast of 5 %). The
// extinction is integrated here from the preset's own profiles (exponential Rayleigh and
// aerosols, the ozone tent) along the curved-Earth chord, independently of how the factor was
// found. MOR is local (a transmissometer's baseline): the chord rises V^2 / 2R, 8 m at 10 km,
// inside the 1 % asked, but 280 m at 60 km, where the aerosols thin, so longer V are not used.
double HorizontalTransmittance(const sky::Atmosphere& a, double distance_m) {
    const int steps = 4000;
    double optical_depth = 0.0;
    for (int i = 0; i < steps; ++i) {
        const double x = (i + 0.5) * distance_m / steps;
        const double h = std::hypot(a.bottom_radius, x) - a.bottom_radius;
        const double tent =
            std::max(0.0, 1.0 - std::abs(h - a.absorption_center) / (0.5 * a.absorption_width));
        const double sigma = a.rayleigh_scattering.y * std::exp(-h / a.rayleigh_scale_height) +
                             a.MieExtinction().y * std::exp(-h / a.mie_scale_height) +
                             tent * a.absorption_extinction.y;
        optical_depth += sigma * distance_m / steps;
    }
    return std::exp(-optical_depth);
}

TEST(Visibility, TheAirTransmitsOneTwentiethOverTheReportedVisibility) {
    const sky::Atmosphere earth = sky::LoadAtmosphere("earth");
    for (const double v : {800.0, 1500.0, 3000.0, 5000.0, 8000.0, 10000.0}) {
        std::vector<std::string> notes;
        const sky::Atmosphere air = AtmosphereForVisibility(earth, v, false, &notes);
        EXPECT_NEAR(HorizontalTransmittance(air, v), 0.05, 0.0005) << "V = " << v << " m";
        EXPECT_TRUE(notes.empty());
        // Only the aerosols' amount changed: their albedo and the rest of the air did not.
        const double albedo = earth.mie_scattering.y / earth.MieExtinction().y;
        EXPECT_NEAR(air.mie_scattering.y / air.MieExtinction().y, albedo, 1e-12);
        EXPECT_EQ(air.rayleigh_scattering, earth.rayleigh_scattering);
        EXPECT_EQ(air.mie_scale_height, earth.mie_scale_height);
    }
}

TEST(Visibility, FogIsTheLayersAndClearAirCannotBeClearerThanRayleigh) {
    const sky::Atmosphere earth = sky::LoadAtmosphere("earth");
    std::vector<std::string> notes;
    const sky::Atmosphere fog = AtmosphereForVisibility(earth, 200.0, true, &notes);
    EXPECT_NEAR(HorizontalTransmittance(fog, kFogAerosolVisibility), 0.05, 0.0005);
    ASSERT_EQ(notes.size(), 1u);
    EXPECT_NE(notes[0].find("fog layer"), std::string::npos) << notes[0];

    notes.clear();
    const sky::Atmosphere clean = AtmosphereForVisibility(earth, 900e3, false, &notes);
    EXPECT_EQ(clean.MieExtinction(), glm::dvec3(0.0));
    ASSERT_EQ(notes.size(), 1u);
    EXPECT_NE(notes[0].find("no aerosols"), std::string::npos) << notes[0];

    EXPECT_THROW(AtmosphereForVisibility(earth, 0.0, false, nullptr), ArgumentError);
    EXPECT_THROW(AtmosphereForVisibility(earth, std::nan(""), false, nullptr), ArgumentError);
}

// The air a visibility sets is the same medium to the renderer and to the path tracer: single
// scattering alone (AtmosphereReference::SingleScattering, the renderer's view march, shared
// GLSL compiled as C++, against the path tracer's one-vertex paths) agrees within 0.5 % at
// 5 and 23 km (BENCHMARKS.md, "Hazy air", whose multiple scattering does not: the error there
// is the multiple-scattering LUT's, not the aerosols' definition).
TEST(Visibility, HazyAirsSingleScatteringMatchesThePathTracer) {
    const sky::Atmosphere earth = sky::LoadAtmosphere("earth");
    const double kDeg = std::numbers::pi / 180.0;
    for (const double v : {5000.0, 23000.0}) {
        const sky::Atmosphere air = AtmosphereForVisibility(earth, v, false, nullptr);
        const sky::LutSettings settings = sky::LutSettings::Pc();
        const sky::reference::AtmosphereReference renderer(air, settings);
        sky::Lights lights;
        lights.sun_direction = sky::reference::LocalDirection(40.0 * kDeg, 0.0);
        lights.sun_illuminance = air.solar_illuminance;
        const glm::dvec3 camera(0.0, air.bottom_radius + 2.0, 0.0);
        std::uint64_t seed = 1;
        // The horizon 90 deg off the sun, 30 deg up away from it, the zenith (deg).
        for (const auto& [elevation, azimuth] :
             {std::pair{1.0, 90.0}, std::pair{30.0, 180.0}, std::pair{90.0, 0.0}}) {
            const glm::dvec3 direction =
                sky::reference::LocalDirection(elevation * kDeg, azimuth * kDeg);
            const glm::dvec3 lut = renderer.SingleScattering(camera, direction, lights, 1000);
            sky::reference::PathTraceOptions options;
            options.samples = 8192;
            options.max_bounces = 1;
            options.threads = 2;
            options.seed = seed++;
            const sky::reference::PathTraceResult pt =
                sky::reference::PathTrace(air, camera, direction, lights.sun_direction, options);
            for (int c = 0; c < 3; ++c) {
                EXPECT_NEAR(lut[c] / pt.luminance[c], 1.0,
                            0.01 + 4.0 * pt.standard_error[c] / pt.luminance[c])
                    << "V = " << v << " m, view elevation " << elevation << " deg, channel " << c;
            }
        }
    }
}

}  // namespace
}  // namespace zenith::weather
