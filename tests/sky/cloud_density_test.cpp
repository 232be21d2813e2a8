// Laws of the cloud density (sky/shaders/clouds/functions.glsl compiled as C++): coverage 0 is
// exactly the clear sky, nothing outside the layer, the height signal of H16 Eq. 5.1, erosion
// that only removes, density monotonic in coverage, tiling with the weather map's period, and
// the dome projection that keeps the shell at a constant altitude over the curved planet.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <random>

#include "cloud_test_support.h"
#include "reference/cloud_functions.h"
#include "reference/cloud_march.h"

namespace zenith::sky::ref {
namespace {

using clouds::CloudLayer;
using clouds::WeatherMapSource;

const Texture3D& Shape() {
    static const Texture3D t = ToTexture(clouds::test::CachedNoise().shape);
    return t;
}
const Texture3D& Detail() {
    static const Texture3D t = ToTexture(clouds::test::CachedNoise().detail);
    return t;
}

CloudLayerParameters Layer() { return clouds::test::CumulusLayer(); }

RepeatTexture2D WeatherFor(double coverage, WeatherMapSource::Kind kind, double type = 0.5,
                           double precipitation = 0.0) {
    CloudLayer layer;
    layer.coverage = coverage;
    layer.cloud_type = type;
    layer.precipitation = precipitation;
    layer.map.kind = kind;
    layer.map.size = 64;
    // Streaks' fine fibres need 4 x 6 x cells texels across.
    layer.map.cells_per_tile = kind == WeatherMapSource::Kind::kStreaks ? 2 : 6;
    layer.map.variation = 0.8;
    return ToTexture(clouds::BuildWeatherMap(layer));
}

struct Point {
    vec2 ground;
    double altitude;
};

std::vector<Point> RandomPoints(int n, double altitude_lo, double altitude_hi, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> g(-100.0, 100.0), a(altitude_lo, altitude_hi);
    std::vector<Point> points;
    for (int i = 0; i < n; ++i) points.push_back({vec2(g(rng), g(rng)), a(rng)});
    return points;
}

double Density(const CloudLayerParameters& layer, const RepeatTexture2D& weather, const Point& p) {
    return SampleCloudDensityAt(layer, weather, Shape(), Detail(), p.ground, p.altitude).density;
}

TEST(CloudDensity, CoverageZeroIsExactlyTheClearSky) {
    for (auto kind : {WeatherMapSource::Kind::kUniform, WeatherMapSource::Kind::kPatches,
                      WeatherMapSource::Kind::kCells, WeatherMapSource::Kind::kStreaks}) {
        const RepeatTexture2D weather = WeatherFor(0.0, kind, 1.0, 1.0);
        for (const Point& p : RandomPoints(20000, 0.0, 6.0, 1)) {
            ASSERT_EQ(Density(Layer(), weather, p), 0.0);
        }
    }
    // And clouds do appear with coverage, on the same points.
    const RepeatTexture2D weather = WeatherFor(0.6, WeatherMapSource::Kind::kUniform);
    int cloudy = 0;
    for (const Point& p : RandomPoints(20000, 1.5, 4.0, 1))
        cloudy += Density(Layer(), weather, p) > 0.0;
    EXPECT_GT(cloudy, 500);
}

TEST(CloudDensity, NothingBelowTheBaseOrAboveTheTop) {
    const RepeatTexture2D weather = WeatherFor(1.0, WeatherMapSource::Kind::kUniform, 1.0);
    for (const Point& p : RandomPoints(5000, -1.0, 1.5, 2))
        ASSERT_EQ(Density(Layer(), weather, p), 0.0);
    for (const Point& p : RandomPoints(5000, 4.0, 20.0, 3))
        ASSERT_EQ(Density(Layer(), weather, p), 0.0);
    double largest = 0.0;
    for (const Point& p : RandomPoints(5000, 1.5, 4.0, 4)) {
        const double d = Density(Layer(), weather, p);
        ASSERT_GE(d, 0.0);
        ASSERT_LE(d, 1.0);
        largest = std::max(largest, d);
    }
    EXPECT_GT(largest, 0.3);
}

TEST(CloudDensity, HeightSignalIsTheParabolaOfEquation51) {
    for (const double h : {0.2, 1.0, 2.0, 7.5}) {
        const double a = 1.0;
        EXPECT_EQ(CloudHeightSignal(a, a, h), 0.0);
        EXPECT_NEAR(CloudHeightSignal(a + h, a, h), 0.0, 1e-14);
        EXPECT_NEAR(CloudHeightSignal(a + 0.5 * h, a, h), 1.0, 1e-15);  // the maximum, 1
        EXPECT_NEAR(CloudHeightSignal(a + 0.25 * h, a, h), 0.75, 1e-15);
        EXPECT_EQ(CloudHeightSignal(a - 0.1, a, h), 0.0);
        EXPECT_EQ(CloudHeightSignal(a + h + 0.1, a, h), 0.0);
        for (int i = 0; i <= 100; ++i) {
            const double x = a + h * i / 100.0;
            EXPECT_NEAR(CloudHeightSignal(x, a, h), (x - a) * (x - a - h) * -4.0 / (h * h), 1e-14);
            EXPECT_LE(CloudHeightSignal(x, a, h), 1.0);
            EXPECT_NEAR(CloudHeightSignal(x, a, h), CloudHeightSignal(2.0 * a + h - x, a, h),
                        1e-14);
        }
    }
    EXPECT_EQ(CloudHeightSignal(1.0, 1.0, 0.0), 0.0);
    // H16 Fig. 5.2: a_s = 1, h = 2, density above 0 between altitudes 1 and 3.
    EXPECT_GT(CloudHeightSignal(1.01, 1.0, 2.0), 0.0);
    EXPECT_GT(CloudHeightSignal(2.99, 1.0, 2.0), 0.0);
}

TEST(CloudDensity, ErosionOnlyRemovesDensity) {
    const RepeatTexture2D weather = WeatherFor(0.7, WeatherMapSource::Kind::kPatches);
    CloudLayerParameters smooth = Layer(), eroded = Layer();
    smooth.erosion_strength = 0.0;
    eroded.erosion_strength = 0.7;
    int removed = 0;
    for (const Point& p : RandomPoints(20000, 1.5, 4.0, 5)) {
        const double d0 = Density(smooth, weather, p), d1 = Density(eroded, weather, p);
        ASSERT_LE(d1, d0) << p.ground.x << " " << p.ground.y << " " << p.altitude;
        removed += d1 < d0;
    }
    EXPECT_GT(removed, 100);
    for (int i = 0; i <= 100; ++i) {
        for (int j = 0; j <= 10; ++j) {
            const double d = i / 100.0, e = j / 10.0;
            EXPECT_LE(CloudErode(d, e), d);
            EXPECT_GE(CloudErode(d, e), 0.0);
        }
    }
    EXPECT_EQ(CloudErode(1.0, 0.6), 1.0);
}

TEST(CloudDensity, MoreCoverageNeverMeansLessCloud) {
    const RepeatTexture2D thin = WeatherFor(0.3, WeatherMapSource::Kind::kUniform);
    const RepeatTexture2D thick = WeatherFor(0.8, WeatherMapSource::Kind::kUniform);
    double sum_thin = 0.0, sum_thick = 0.0;
    for (const Point& p : RandomPoints(10000, 1.5, 4.0, 6)) {
        const double a = Density(Layer(), thin, p), b = Density(Layer(), thick, p);
        ASSERT_LE(a, b + 1e-15);
        sum_thin += a, sum_thick += b;
    }
    EXPECT_GT(sum_thick, 2.0 * sum_thin);
}

TEST(CloudDensity, TilesWithTheWeatherPeriodAlsoInWind) {
    const RepeatTexture2D weather = WeatherFor(0.6, WeatherMapSource::Kind::kPatches);
    CloudLayerParameters layer = Layer();
    layer.wind_offset_x = 3.7;
    layer.wind_offset_y = -12.1;
    int cloudy = 0;
    for (const Point& p : RandomPoints(5000, 1.5, 4.0, 7)) {
        const double d = Density(layer, weather, p);
        cloudy += d > 0.0;
        for (const vec2 shift : {vec2(40.0, 0.0), vec2(0.0, -40.0), vec2(80.0, 120.0)}) {
            ASSERT_NEAR(Density(layer, weather, {p.ground + shift, p.altitude}), d, 1e-9);
        }
    }
    EXPECT_GT(cloudy, 200);
    // Wind moves the whole field: the density at g with offset w is the still density at g + w.
    const CloudLayerParameters still = Layer();
    for (const Point& p : RandomPoints(2000, 1.5, 4.0, 8)) {
        ASSERT_NEAR(Density(layer, weather, p),
                    Density(still, weather, {p.ground + vec2(3.7, -12.1), p.altitude}), 1e-9);
    }
}

TEST(CloudDensity, DomeProjectionKeepsTheShellAtConstantAltitude) {
    const CloudLayerParameters layer = Layer();
    const RepeatTexture2D weather = WeatherFor(0.8, WeatherMapSource::Kind::kUniform, 1.0);
    const double r = layer.bottom_radius;
    for (const double arc : {0.0, 0.001, 5.0, 100.0, 300.0, 1000.0}) {
        const double theta = arc / r;
        for (const double azimuth : {0.0, 1.0, 2.5}) {
            const vec3 up(std::sin(theta) * std::cos(azimuth), std::sin(theta) * std::sin(azimuth),
                          std::cos(theta));
            const vec2 ground = CloudGroundCoordinates(layer, (r + 2.7) * up);
            // Arc length along the ground, whatever the altitude of the point.
            EXPECT_NEAR(glm::length(ground), arc, 1e-9 * (1.0 + arc));
            EXPECT_NEAR(glm::length(CloudGroundCoordinates(layer, (r + 9.0) * up) - ground), 0.0,
                        1e-9 * (1.0 + arc));
            const CloudSample s =
                SampleCloudDensity(layer, weather, Shape(), Detail(), (r + 2.7) * up);
            EXPECT_NEAR(s.density, Density(layer, weather, {ground, 2.7}), 1e-9);
            EXPECT_NEAR(s.height_fraction, 1.2 / 2.5, 1e-9);
        }
    }
    // 300 km away the flat plane y = R + 2.7 km is ~7 km above the sphere, over the layer; the
    // shell still holds cloud there.
    const vec3 flat(300.0, r + 2.7, 0.0);
    EXPECT_GT(CloudAltitude(layer, flat), 4.0);
    EXPECT_EQ(SampleCloudDensity(layer, weather, Shape(), Detail(), flat).density, 0.0);
}

TEST(CloudDensity, TypeSetsHowHighCloudsReach) {
    // Uniform full coverage: the highest altitude with density is the type's share of the layer.
    const CloudLayerParameters layer = Layer();
    for (const double type : {0.0, 0.5, 1.0}) {
        const RepeatTexture2D weather = WeatherFor(1.0, WeatherMapSource::Kind::kUniform, type);
        double highest = 0.0;
        for (const Point& p : RandomPoints(20000, 1.5, 4.0, 9)) {
            if (Density(layer, weather, p) > 0.0) highest = std::max(highest, p.altitude);
        }
        const double top = 1.5 + 2.5 * CloudTypeHeightFraction(type);
        EXPECT_LE(highest, top);
        EXPECT_GT(highest, 1.5 + 0.6 * (top - 1.5)) << "type " << type;
    }
    EXPECT_EQ(CloudTypeHeightFraction(1.0), 1.0);
    EXPECT_LT(CloudTypeHeightFraction(0.0), CloudTypeHeightFraction(0.5));
}

// The march ends at the clouds' top (CloudTopFraction): it must never cut off a cloud, and be
// tight enough to matter. Every built-in preset's maps, and a uniform map of each type.
TEST(CloudDensity, NothingAboveTheMapsCloudTopWhichIsTight) {
    std::vector<clouds::CloudLayer> layers;
    for (const char* preset : {"scattered_cumulus", "broken", "overcast_stratus", "cumulonimbus"}) {
        for (const CloudLayer& l : clouds::LoadWeather(preset).layers) layers.push_back(l);
    }
    for (const double type : {0.0, 0.5, 1.0}) {
        CloudLayer l;
        l.coverage = 1.0;
        l.cloud_type = type;
        l.map.kind = WeatherMapSource::Kind::kUniform;
        l.map.size = 16;
        layers.push_back(l);
    }
    for (const CloudLayer& l : layers) {
        const clouds::WeatherMap map = clouds::BuildWeatherMap(l);
        const double fraction = clouds::CloudTopFraction(map);
        CloudLayerParameters layer = Layer();
        layer.weather_period = 20.0;  // the whole map within the random points' 200 km
        const double top =
            layer.base_altitude + (layer.top_altitude - layer.base_altitude) * fraction;
        const RepeatTexture2D weather = ToTexture(map);
        double highest = layer.base_altitude;
        for (const Point& p : RandomPoints(40000, 1.5, 4.0, 13)) {
            if (Density(layer, weather, p) > 0.0) highest = std::max(highest, p.altitude);
        }
        SCOPED_TRACE(l.name + " type " + std::to_string(l.cloud_type));
        std::printf(
            "%-14s type %.2f: clouds reach %.3f of the layer, the highest found %.0f %% of it\n",
            l.name.c_str(), l.cloud_type, fraction,
            100.0 * (highest - layer.base_altitude) / (top - layer.base_altitude));
        EXPECT_LE(highest, top);
        // 40,000 random points find a cloud within a quarter of the bound below it.
        EXPECT_GT(highest, layer.base_altitude + 0.75 * (top - layer.base_altitude));
        EXPECT_GT(fraction, 0.2);
        EXPECT_LE(fraction, 1.0);
    }
    CloudLayer clear;
    clear.coverage = 0.0;
    EXPECT_EQ(clouds::CloudTopFraction(clouds::BuildWeatherMap(clear)), 0.0);
}

// The cumulonimbus preset's layer, its shear left out, and its map.
struct Cumulonimbus {
    CloudLayerParameters layer = Layer();
    RepeatTexture2D weather;
};
Cumulonimbus CumulonimbusPreset() {
    const CloudLayer cb = clouds::LoadWeather("cumulonimbus").layers.at(0);
    Cumulonimbus c{Layer(), ToTexture(clouds::BuildWeatherMap(cb))};
    c.layer.base_altitude = cb.base_altitude / 1000.0;
    c.layer.top_altitude = cb.top_altitude / 1000.0;
    c.layer.weather_period = cb.map_period / 1000.0;
    return c;
}

// A cumulonimbus spreads an anvil under the layer's top (the tropopause), wider than its tower:
// over the cumulonimbus preset's map, more columns hold cloud at 90 % of the layer than at 50 %.
// Congestus, the type below, has none: a uniform congestus layer keeps below its type's height.
TEST(CloudDensity, CumulonimbusSpreadsAnAnvilWiderThanItsTower) {
    const Cumulonimbus cb = CumulonimbusPreset();
    const CloudLayerParameters& layer = cb.layer;
    const RepeatTexture2D& weather = cb.weather;
    const auto covered = [&](double height_fraction) {
        const double altitude =
            layer.base_altitude + height_fraction * (layer.top_altitude - layer.base_altitude);
        int n = 0;
        const int side = 120;
        for (int y = 0; y < side; ++y) {
            for (int x = 0; x < side; ++x) {
                const vec2 ground((x + 0.5) / side * layer.weather_period,
                                  (y + 0.5) / side * layer.weather_period);
                if (Density(layer, weather, {ground, altitude}) > 0.0) ++n;
            }
        }
        return double(n) / (side * side);
    };
    const double tower = covered(0.5), anvil = covered(0.9);
    std::printf(
        "cumulonimbus: cloud over %.1f %% of the ground at half the layer, %.1f %% at 0.9\n",
        100.0 * tower, 100.0 * anvil);
    EXPECT_GT(tower, 0.02);
    EXPECT_GT(anvil, 1.5 * tower);

    CloudLayerParameters uniform = Layer();
    const RepeatTexture2D congestus = WeatherFor(1.0, WeatherMapSource::Kind::kUniform, 0.75);
    const double top = uniform.base_altitude + (uniform.top_altitude - uniform.base_altitude) *
                                                   CloudTypeHeightFraction(0.75);
    for (const Point& p : RandomPoints(20000, top, uniform.top_altitude, 5)) {
        ASSERT_EQ(Density(uniform, congestus, p), 0.0) << p.altitude;
    }
}

// The wind's shear leans the clouds downwind by the square of the height's share h of the layer:
// with a shear of 10 km east over the cumulonimbus preset's tile, the clouds' envelope (the
// weather's, without the noise) at h is the unsheared one moved h^2 x 10 km east, exactly, at
// 20,000 random points; the cloud cover at each height is kept (the noise stays in place); and
// the anvil's centroid (circular: the tile repeats) at 0.95 of the layer moves 9.0 km east.
TEST(CloudDensity, ShearLeansTheCloudsDownwind) {
    const Cumulonimbus cb = CumulonimbusPreset();
    const CloudLayerParameters& layer = cb.layer;
    const RepeatTexture2D& weather = cb.weather;
    CloudLayerParameters sheared = layer;
    sheared.shear_x = 10.0;  // km, east
    const auto fraction = [&](double altitude) {
        return (altitude - layer.base_altitude) / (layer.top_altitude - layer.base_altitude);
    };
    for (const Point& p : RandomPoints(20000, layer.base_altitude, layer.top_altitude, 7)) {
        const double lean = fraction(p.altitude) * fraction(p.altitude) * 10.0;
        ASSERT_EQ(CloudEnvelope(sheared, weather, p.ground, p.altitude),
                  CloudEnvelope(layer, weather, p.ground - vec2(lean, 0.0), p.altitude));
    }
    struct Centroid {
        double east_km;
        double cover;
    };
    const auto centroid = [&](const CloudLayerParameters& l, double height_fraction) {
        const double altitude =
            l.base_altitude + height_fraction * (l.top_altitude - l.base_altitude);
        const double period = l.weather_period;
        double c = 0.0, s = 0.0;
        int n = 0;
        const int side = 160;
        for (int y = 0; y < side; ++y) {
            for (int x = 0; x < side; ++x) {
                const vec2 ground((x + 0.5) / side * period, (y + 0.5) / side * period);
                const double d = Density(l, weather, {ground, altitude});
                c += d * std::cos(2.0 * kPi * ground.x / period);
                s += d * std::sin(2.0 * kPi * ground.x / period);
                if (d > 0.0) ++n;
            }
        }
        return Centroid{std::atan2(s, c) / (2.0 * kPi) * period, double(n) / (side * side)};
    };
    for (const double h : {0.3, 0.6, 0.95}) {
        const Centroid plain = centroid(layer, h), leaning = centroid(sheared, h);
        double moved = leaning.east_km - plain.east_km;
        moved -= layer.weather_period * std::round(moved / layer.weather_period);
        std::printf(
            "at %.2f of the layer: cover %.3f -> %.3f, centroid moved %.2f km east "
            "(h^2 x 10 km = %.2f)\n",
            h, plain.cover, leaning.cover, moved, h * h * 10.0);
        EXPECT_NEAR(leaning.cover, plain.cover, 0.02 * plain.cover) << h;
        // The anvil is the weather's: there the noise hardly moves the centroid.
        if (h > 0.9) {
            EXPECT_NEAR(moved, h * h * 10.0, 0.05 * h * h * 10.0);
        }
    }
}

// A rain or snow shaft is as dense at every height of its layer as the weather map's
// precipitation says (the layer's extinction_scale times CloudPrecipitationShare: 1 for heavy,
// 0.9, and 0 without), whatever the map's coverage and the noise, and 0 outside its layer.
TEST(CloudDensity, AShaftIsAsDenseAsItsPrecipitationAtEveryHeight) {
    CloudLayerParameters shaft = Layer();
    shaft.precipitation_shaft = 1.0;
    shaft.extinction_scale = 0.5;
    EXPECT_EQ(CloudPrecipitationShare(0.0), 0.0);
    EXPECT_NEAR(CloudPrecipitationShare(0.9), 1.0, 1e-12);
    for (const double precipitation : {0.0, 0.2, 0.6, 0.9}) {
        const double coverage = precipitation > 0.5 ? 1.0 : 0.3;
        const RepeatTexture2D weather =
            WeatherFor(coverage, WeatherMapSource::Kind::kUniform, 0.5, precipitation);
        const double expected = 0.5 * CloudPrecipitationShare(precipitation);
        for (const Point& p : RandomPoints(50, 1.5, 4.0, 7)) {
            EXPECT_NEAR(Density(shaft, weather, p), expected, 1e-6 + 1e-5 * expected)
                << precipitation << " at " << p.altitude << " km";
        }
        for (const Point& p : RandomPoints(20, 0.0, 1.5, 8)) {
            EXPECT_EQ(Density(shaft, weather, p), 0.0) << p.altitude << " km";
        }
        for (const Point& p : RandomPoints(20, 4.0, 6.0, 9)) {
            EXPECT_EQ(Density(shaft, weather, p), 0.0) << p.altitude << " km";
        }
    }
}

}  // namespace
}  // namespace zenith::sky::ref
