// Twilight against measurements of the real sky (issue 18 §2): how fast the sky's light falls as
// the Sun sinks below the horizon, from the ground. The rate depends on the geometry of the
// Earth's shadow and on the air's vertical profile, little on the amount of aerosol (which sets
// the level: the Earth preset's air is cleaner than the measured skies; BENCHMARKS.md, "Twilight
// against measurements"), so it is what is tested here. The path tracer checks the transport
// (accuracy_report --grid illuminance, --grid twilight); these check the whole model.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "luminance.h"
#include "zenith/sky/lighting.h"
#include "zenith/sky/reference/atmosphere_reference.h"

namespace zenith::sky {
namespace {

using zenith::test::Luminance;

constexpr double kDeg = std::numbers::pi / 180.0;

// Least-squares slope of y against x.
double Slope(const std::vector<double>& x, const std::vector<double>& y) {
    double mx = 0.0, my = 0.0;
    for (std::size_t i = 0; i < x.size(); ++i) mx += x[i], my += y[i];
    mx /= static_cast<double>(x.size());
    my /= static_cast<double>(y.size());
    double sxy = 0.0, sxx = 0.0;
    for (std::size_t i = 0; i < x.size(); ++i) {
        sxy += (x[i] - mx) * (y[i] - my);
        sxx += (x[i] - mx) * (x[i] - mx);
    }
    return sxy / sxx;
}

// The sun `elevation` (rad) above the horizon of an observer on the +y axis, toward +x.
glm::dvec3 SunAt(double elevation) { return {std::cos(elevation), std::sin(elevation), 0.0}; }

TEST(TwilightMeasurements, GroundIlluminanceFallsAsBrown1952) {
    // Brown (1952), "Natural Illumination Charts" (U.S. Navy Bureau of Ships report 374-1), as
    // fitted in USNO Circular 171 (Janiczek & DeYoung 1987): horizontal illuminance under an
    // average clear sky, lux, at sun altitudes -2 to -8 deg.
    const double altitudes[] = {-2.0, -3.0, -4.0, -5.0, -6.0, -7.0, -8.0};
    const double measured[] = {192.0, 81.0, 30.7, 10.7, 3.47, 1.14, 0.357};
    const Atmosphere earth;
    const reference::AtmosphereReference renderer(earth);
    std::vector<double> x, log_measured, log_renderer;
    for (std::size_t i = 0; i < std::size(altitudes); ++i) {
        const double mu = std::sin(altitudes[i] * kDeg);
        const double lux = Luminance(SampleGroundIrradiance(renderer.ground_irradiance(), mu) *
                                     earth.solar_illuminance);
        std::printf("sun %+.0f deg: renderer %.3g lux, measured %.3g lux (ratio %.2f)\n",
                    altitudes[i], lux, measured[i], lux / measured[i]);
        x.push_back(altitudes[i]);
        log_measured.push_back(std::log10(measured[i]));
        log_renderer.push_back(std::log10(lux));
    }
    const double slope_measured = Slope(x, log_measured);
    const double slope_renderer = Slope(x, log_renderer);
    std::printf("fall rate -2..-8 deg: renderer %.3f, measured %.3f dex per degree\n",
                slope_renderer, slope_measured);
    // 0.455 dex per degree measured: within 10 %.
    EXPECT_NEAR(slope_renderer / slope_measured, 1.0, 0.10);
}

TEST(TwilightMeasurements, ZenithLuminanceFallsAsMeasuredAtLaPalma) {
    // Isaac Newton Group, "Twilight sky brightness" (INT Wide Field Camera, La Palma, 2010-2011,
    // measured by M. Karami): for 10 to 35 min after sunset the sky's brightness falls as
    // log10 B = A - 0.103 T (T in minutes) in U, B, g, V, r, i and Z alike. At La Palma
    // (28.76 deg N) the Sun sinks 0.19 to 0.22 deg per minute at that time of day through the
    // year (15 deg/h cos(lat) cos(dec) sin(H)), so 10-35 min after sunset (the upper limb at
    // -0.83 deg) spans sun altitudes of about -3 to -8.5 deg, and the measured rate is
    // 0.103 / (0.19..0.22) = 0.47..0.55 dex per degree. The renderer's zenith luminance from the
    // ground (the Sky-View LUT as render.frag reads it) over those altitudes.
    const Atmosphere earth;
    const reference::AtmosphereReference renderer(earth);
    const glm::dvec3 camera(0.0, earth.bottom_radius + 1.0, 0.0);
    std::vector<double> x, log_zenith;
    for (double altitude = -3.0; altitude >= -8.5; altitude -= 0.5) {
        Lights lights;
        lights.sun_direction = SunAt(altitude * kDeg);
        lights.sun_illuminance = earth.solar_illuminance;
        const LutImage sky_view = renderer.SkyView(camera, lights);
        const double zenith = Luminance(renderer.SampleSkyView(
            sky_view, camera, lights.sun_direction, glm::dvec3(0.0, 1.0, 0.0)));
        x.push_back(altitude);
        log_zenith.push_back(std::log10(zenith));
    }
    const double slope = Slope(x, log_zenith);
    std::printf(
        "zenith luminance %.3g cd/m2 at -3 deg, %.3g at -8.5 deg: %.3f dex per degree "
        "(measured 0.47..0.55)\n",
        std::pow(10.0, log_zenith.front()), std::pow(10.0, log_zenith.back()), slope);
    EXPECT_GE(slope, 0.47 * 0.95);
    EXPECT_LE(slope, 0.55 * 1.05);
}

}  // namespace
}  // namespace zenith::sky
