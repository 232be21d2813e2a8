// Golden frames (filament renderdiff style): small headless renders of the whole pipeline, from
// geo's Sun/Moon/stars to the composite, compared with reviewed EXRs in tests/golden under a
// tolerance that is data. On failure the actual frame and a difference image are written next to
// the test binary and their paths printed. Goldens change only through the explicit target
// `cmake --build build --target update_goldens` (ZENITH_UPDATE_GOLDENS=1), then review.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <glm/gtc/constants.hpp>
#include <memory>
#include <optional>
#include <ostream>
#include <string>

#include "luminance.h"
#include "zenith/geo/ephemeris.h"
#include "zenith/sky/atmosphere_renderer.h"
#include "zenith/sky/gl/context.h"
#include "zenith/sky/image_io.h"
#include "zenith/sky/inspection.h"
#include "zenith/sky/sky_state.h"

namespace zenith::sky {
namespace {

using test::Luminance;

namespace fs = std::filesystem;

// Tolerance as data: luminance within kPixelTolerance (relative, with a floor of 1e-3 of the
// frame's mean) on at least kPassFraction of the pixels, and never more than kMaxTolerance.
constexpr double kPixelTolerance = 0.01;
constexpr double kPassFraction = 0.99;
constexpr double kMaxTolerance = 0.10;
constexpr glm::ivec2 kSize{64, 36};

struct Scene {
    const char* name;
    const char* utc;
    double height_m;  // < 0: inside the weather's first layer, at its middle
    double pitch_deg;
    bool toward_sun;  // heading: the Sun's azimuth (plus sun_offset_deg), else north
    const char* weather = "clear";
    double sun_offset_deg = 0.0;
};

constexpr double kInsideTheLayer = -1.0;
constexpr const char* kCloudUtc = "2024-06-21T15:00:00Z";

// Over Lake Geneva (46.45 N, 6.6 E) on 2024-06-21: noon, sunset and astronomical night.
constexpr Scene kScenes[] = {
    {"ground_noon", "2024-06-21T11:30:00Z", 2.0, 15.0, true},
    {"ground_sunset", "2024-06-21T19:25:00Z", 2.0, 5.0, true},
    {"ground_night", "2024-06-21T23:30:00Z", 2.0, 40.0, false},
    {"10km_noon", "2024-06-21T11:30:00Z", 10000.0, 0.0, true},
    {"10km_sunset", "2024-06-21T19:25:00Z", 10000.0, 0.0, true},
    {"10km_night", "2024-06-21T23:30:00Z", 10000.0, 20.0, false},
    {"100km_noon", "2024-06-21T11:30:00Z", 100000.0, -10.0, true},
    {"100km_sunset", "2024-06-21T19:25:00Z", 100000.0, -5.0, true},
    {"100km_night", "2024-06-21T23:30:00Z", 100000.0, 0.0, false},
    {"1000km_noon", "2024-06-21T11:30:00Z", 1000000.0, -45.0, true},
    {"1000km_sunset", "2024-06-21T19:25:00Z", 1000000.0, -30.0, true},
    {"1000km_night", "2024-06-21T23:30:00Z", 1000000.0, -20.0, false},
    // Each cloudy weather preset from the ground, inside its first layer and from above it, in
    // the afternoon, looking 60 deg right of the Sun (lit sides and shadows both in view).
    {"scattered_cumulus_ground", kCloudUtc, 2.0, 20.0, true, "scattered_cumulus", 60.0},
    {"scattered_cumulus_inside", kCloudUtc, kInsideTheLayer, 0.0, true, "scattered_cumulus", 60.0},
    {"scattered_cumulus_above", kCloudUtc, 12000.0, -25.0, true, "scattered_cumulus", 60.0},
    {"broken_ground", kCloudUtc, 2.0, 20.0, true, "broken", 60.0},
    {"broken_inside", kCloudUtc, kInsideTheLayer, 0.0, true, "broken", 60.0},
    {"broken_above", kCloudUtc, 12000.0, -25.0, true, "broken", 60.0},
    {"overcast_stratus_ground", kCloudUtc, 2.0, 20.0, true, "overcast_stratus", 60.0},
    {"overcast_stratus_inside", kCloudUtc, kInsideTheLayer, 0.0, true, "overcast_stratus", 60.0},
    {"overcast_stratus_above", kCloudUtc, 12000.0, -25.0, true, "overcast_stratus", 60.0},
    {"cumulonimbus_ground", kCloudUtc, 2.0, 20.0, true, "cumulonimbus", 60.0},
    {"cumulonimbus_inside", kCloudUtc, kInsideTheLayer, 0.0, true, "cumulonimbus", 60.0},
    {"cumulonimbus_above", kCloudUtc, 14000.0, -25.0, true, "cumulonimbus", 60.0},
    {"cirrus_ground", kCloudUtc, 2.0, 35.0, true, "cirrus", 60.0},
    {"cirrus_inside", kCloudUtc, kInsideTheLayer, 0.0, true, "cirrus", 60.0},
    {"cirrus_above", kCloudUtc, 12000.0, -25.0, true, "cirrus", 60.0},
};

// gtest prints the parameter in test names and failures.
void PrintTo(const Scene& scene, std::ostream* os) { *os << scene.name; }

fs::path GoldenPath(const Scene& s) {
    return fs::path(ZENITH_SOURCE_DIR) / "tests" / "golden" / (std::string(s.name) + ".exr");
}

class GoldenFrames : public ::testing::TestWithParam<Scene> {
  protected:
    static void SetUpTestSuite() {
        context_ = gl::CreateHeadlessContextFromEnvironment().release();
        renderer_ = new AtmosphereRenderer(Atmosphere{});
        try {
            catalog_ = new geo::StarCatalog(geo::StarCatalog::Load(6.5));
        } catch (const geo::CatalogError& e) {
            std::printf("golden frames without stars: %s\n", e.what());
        }
    }
    static void TearDownTestSuite() {
        delete catalog_;
        delete renderer_;
        delete context_;
    }
    static gl::HeadlessContext* context_;
    static AtmosphereRenderer* renderer_;
    static geo::StarCatalog* catalog_;
};
gl::HeadlessContext* GoldenFrames::context_ = nullptr;
AtmosphereRenderer* GoldenFrames::renderer_ = nullptr;
geo::StarCatalog* GoldenFrames::catalog_ = nullptr;

Image Render(const Scene& scene, AtmosphereRenderer& renderer, const geo::StarCatalog* catalog) {
    // Clouds: every pixel traced (a golden is one frame, without history).
    const clouds::Weather weather = clouds::LoadWeather(scene.weather);
    CloudSettings cloud_settings;
    cloud_settings.block = 1;
    cloud_settings.shadow_map_size = 16;
    cloud_settings.noise_cache_directory = fs::path(ZENITH_BINARY_DIR) / "cloud-noise-cache";
    renderer.SetWeather(weather, cloud_settings);
    const double height =
        scene.height_m == kInsideTheLayer
            ? 0.5 * (weather.layers[0].base_altitude + weather.layers[0].top_altitude)
            : scene.height_m;
    FrameSetup setup;
    setup.time = geo::TimeFromIso8601(scene.utc);
    setup.observer = geo::Observer(46.45, 6.6, height);
    const geo::Ephemeris calculator(catalog);
    if (scene.toward_sun) {
        const geo::SkyEphemeris e = calculator.Compute(setup.time, setup.observer);
        setup.attitude.heading_rad =
            e.sun.topocentric.horizontal.azimuth + glm::radians(scene.sun_offset_deg);
    }
    setup.attitude.pitch_rad = glm::radians(scene.pitch_deg);
    setup.vertical_fov = glm::radians(90.0);
    setup.aspect = double(kSize.x) / kSize.y;
    SkyFrame frame = BuildSkyFrame(calculator, setup, renderer.atmosphere());
    // The night sky's diffuse light, with the catalogue's stars past the drawn V = 6.5 (to its
    // V = 8 end) in the integrated starlight when it is installed.
    static const std::shared_ptr<const StarlightMap> starlight = [] {
        try {
            return std::make_shared<const StarlightMap>(
                StarlightMap::FromCatalog(geo::StarCatalog::Load(8.0), 6.5));
        } catch (const geo::CatalogError&) {
            return std::make_shared<const StarlightMap>(StarlightMap::ModelOnly());
        }
    }();
    frame.scene.night_sky.starlight = starlight;
    renderer.Update(frame.scene, frame.view);
    renderer.Render(RenderTarget::Offscreen(kSize));
    return ImageFromFrame(Inspect(renderer).ReadFrame());
}

TEST_P(GoldenFrames, MatchesTheReviewedFrame) {
    const Scene& scene = GetParam();
    const Image actual = Render(scene, *renderer_, catalog_);
    const fs::path golden_path = GoldenPath(scene);
    if (std::getenv("ZENITH_UPDATE_GOLDENS") != nullptr) {
        WriteExr(golden_path, actual, ExrPixelType::kFloat);
        std::printf("updated %s\n", golden_path.c_str());
        return;
    }
    if (catalog_ == nullptr && std::string(scene.name).find("night") != std::string::npos) {
        GTEST_SKIP() << "star catalogue not installed (apt-get install kstars-data)";
    }
    ASSERT_TRUE(fs::exists(golden_path))
        << "no golden " << golden_path << "; create it with the update_goldens target";
    const Image golden = ReadExr(golden_path);
    ASSERT_EQ(golden.width, actual.width);
    ASSERT_EQ(golden.height, actual.height);

    double mean = 0.0;
    for (const glm::vec4& p : golden.pixels) mean += Luminance(p);
    mean /= static_cast<double>(golden.pixels.size());
    const double floor = std::max(1e-3 * mean, 1e-9);
    std::size_t within = 0;
    double worst = 0.0;
    Image diff(golden.width, golden.height);
    for (std::size_t i = 0; i < golden.pixels.size(); ++i) {
        const double g = Luminance(golden.pixels[i]), a = Luminance(actual.pixels[i]);
        const double relative = std::abs(a - g) / std::max(std::abs(g), floor);
        worst = std::max(worst, relative);
        if (relative <= kPixelTolerance) ++within;
        diff.pixels[i] = glm::vec4(static_cast<float>(relative));
    }
    const double fraction = static_cast<double>(within) / static_cast<double>(golden.pixels.size());
    if (fraction < kPassFraction || worst > kMaxTolerance) {
        const fs::path out = fs::path(ZENITH_BINARY_DIR) / "golden_failures";
        fs::create_directories(out);
        WriteExr(out / (std::string(scene.name) + "_actual.exr"), actual, ExrPixelType::kFloat);
        WriteExr(out / (std::string(scene.name) + "_diff.exr"), diff, ExrPixelType::kFloat);
        ADD_FAILURE() << scene.name << ": " << 100.0 * fraction << " % of pixels within "
                      << 100.0 * kPixelTolerance << " % (need " << 100.0 * kPassFraction
                      << " %), worst " << 100.0 * worst << " %; wrote " << out.string() << "/"
                      << scene.name << "_{actual,diff}.exr";
    }
}

INSTANTIATE_TEST_SUITE_P(Views, GoldenFrames, ::testing::ValuesIn(kScenes),
                         [](const ::testing::TestParamInfo<Scene>& param) {
                             return std::string(param.param.name);
                         });

}  // namespace
}  // namespace zenith::sky
