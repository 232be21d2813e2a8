// Accuracy of the LUT renderer against the independent path tracer in the scenarios of Hillaire
// 2020 §6 (reference/accuracy.h): bounds measured at this test's size and sample count, with
// margin, per channel. The larger table is BENCHMARKS.md, "sky: accuracy against the path
// tracer" (tests/bench/accuracy_report.cpp).
//
// Two measures per scenario:
//   - the mean bias, renderer mean / reference mean - 1, against its Monte Carlo standard error
//     (the reference's pixels are independent): a sensitive detector of a gain or colour error;
//   - the relative RMSE with the reference's noise removed in quadrature (accuracy.h), bounding
//     per-pixel errors (a misplaced aureole, horizon or terminator).
// Mars has errors well beyond the paper's (BENCHMARKS.md has the analysis); its bounds only
// guard against getting worse and say so.
#include "zenith/sky/reference/accuracy.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numbers>
#include <string>

#include "zenith/base/error.h"
#include "zenith/sky/atmosphere.h"
#include "zenith/sky/reference/atmosphere_reference.h"
#include "zenith/sky/reference/path_tracer.h"

namespace zenith::sky::reference {
namespace {

// 256 paths per pixel in every build: the noise-corrected RMSE, sqrt(RMSE^2 - noise^2), is a
// difference of two noisy estimates and meant nothing at 64 paths, where the reference's own
// noise is most of the RMSE (a sanitizer run once read 0.26 against 0.10 at 256 paths). Only the
// 50x atmosphere, whose path tracing is 20x dearer, runs fewer paths in sanitizer builds (~10x
// slower), with its RMSE bound widened to match (ThickDaytime).
constexpr std::int64_t kSamples = 256;
#if defined(__SANITIZE_ADDRESS__)
constexpr std::int64_t kThickSamples = 64;
constexpr std::int64_t kTwilightPaths = 1 << 16;
#else
constexpr std::int64_t kThickSamples = 256;
constexpr std::int64_t kTwilightPaths = 1 << 19;
#endif
// Mean-bias tolerance in standard errors of the reference mean: 4 sigma, a false alarm rate of
// 6e-5 per channel, with fixed seeds anyway.
constexpr double kSigmas = 4.0;

AccuracyOptions TestOptions() {
    AccuracyOptions options;
    options.width = 24;
    options.height = 16;
    options.samples = kSamples;
    options.threads = 2;
    return options;
}

const AccuracyScenario& Scenario(const std::string& name) {
    static const std::vector<AccuracyScenario> scenarios = PaperScenarios();
    for (const AccuracyScenario& s : scenarios) {
        if (s.name == name) return s;
    }
    throw zenith::ArgumentError("no scenario " + name);
}

AccuracyResult Measure(const std::string& name) {
    AccuracyOptions options = TestOptions();
    if (name == "thick_daytime") options.samples = kThickSamples;
    const AccuracyResult r = MeasureAccuracy(Scenario(name), options);
    const glm::dvec3 rel = r.RelativeRmse(), corrected = r.RelativeRmseNoiseCorrected(),
                     noise = r.RelativeNoise(), bias = r.MeanBias(), sigma = r.MeanBiasError();
    std::printf(
        "%s (%s, %lld paths/pixel): relative RMSE (%.4f, %.4f, %.4f), noise (%.4f, %.4f, %.4f), "
        "noise-corrected (%.4f, %.4f, %.4f), mean bias (%+.4f, %+.4f, %+.4f) +- (%.4f, %.4f, "
        "%.4f); %.2f s + %.2f s\n",
        name.c_str(), r.ray_marched ? "ray march" : "Sky-View", static_cast<long long>(kSamples),
        rel.x, rel.y, rel.z, noise.x, noise.y, noise.z, corrected.x, corrected.y, corrected.z,
        bias.x, bias.y, bias.z, sigma.x, sigma.y, sigma.z, r.renderer_seconds, r.reference_seconds);
    return r;
}

// Per channel: |mean bias| <= bias_bound + kSigmas standard errors, and the noise-corrected
// relative RMSE <= rmse_bound. `if (!(x <= bound))` so that NaN fails.
void ExpectWithin(const AccuracyResult& r, const char* name, double bias_bound, double rmse_bound) {
    const glm::dvec3 bias = r.MeanBias(), sigma = r.MeanBiasError(),
                     rmse = r.RelativeRmseNoiseCorrected();
    for (int c = 0; c < 3; ++c) {
        const double allowed = bias_bound + kSigmas * sigma[c];
        if (!(std::abs(bias[c]) <= allowed)) {
            ADD_FAILURE() << name << " channel " << c << ": mean bias " << bias[c] << " exceeds "
                          << bias_bound << " + " << kSigmas << " x " << sigma[c];
        }
        if (!(rmse[c] <= rmse_bound)) {
            ADD_FAILURE() << name << " channel " << c << ": noise-corrected relative RMSE "
                          << rmse[c] << " exceeds " << rmse_bound;
        }
    }
}

// Bounds measured at 256 paths per pixel (BENCHMARKS.md has the 96x64 table); the Earth
// ones are about twice the largest measured value, so noise and a changed seed stay inside.

// Measured (Earth aerosols of albedo 0.9, iterated orders and their moments, issue 18): bias
// -1.1, -1.2, -1.5 % (H20's Psi_ms: -1.3, -1.5, -2.1 %; significant: the renderer is slightly
// dark, within the paper's reported level), noise-corrected RMSE <= 0.035.
constexpr double kDaytimeBias = 0.04;
constexpr double kDaytimeRmse = 0.08;
TEST(Accuracy, EarthDaytime) {
    ExpectWithin(Measure("earth_daytime"), "earth_daytime", kDaytimeBias, kDaytimeRmse);
}

// Measured: bias -2.5, -1.9, -1.1 %, noise-corrected RMSE <= 0.031 (iterated orders and the
// moments of their light, issue 18 §2; with H20's Psi_ms -3.3, -3.7, -5.0 %, <= 0.061: the
// aureole of the low sun, sampled by the Sky-View LUT's 200 x 100 texels).
constexpr double kSunsetBias = 0.07;
constexpr double kSunsetRmse = 0.12;
TEST(Accuracy, EarthSunset) {
    ExpectWithin(Measure("earth_sunset"), "earth_sunset", kSunsetBias, kSunsetRmse);
}

// Measured: bias -0.4, -0.4, -0.9 % (+- 0.6 .. 0.8 %), noise-corrected RMSE <= 0.08 (earlier
// +1.1 .. +2.6 %, <= 0.04; at 96x64 and 1024 paths the bias is +0.2 .. +0.3 % both before and
// after issue 18, so this is noise): ray marching with 32 steps from space is as close as the
// paper's space view.
constexpr double kEarthSpaceBias = 0.05;
constexpr double kEarthSpaceRmse = 0.12;
TEST(Accuracy, EarthSpace) {
    ExpectWithin(Measure("earth_space"), "earth_space", kEarthSpaceBias, kEarthSpaceRmse);
}

// The Earth's shadow, sun 4 deg below the horizon. With the paper's u = 0.5 + 0.5 mu_s the
// 32-texel multiple-scattering LUT has 3.6 deg of sun elevation per texel at the horizon and
// overshot this sky by +27, +53, +55 %; with u = 0.5 + 0.5 sign(mu_s) sqrt|mu_s| (functions.glsl)
// +5, +8, +7 %, noise-corrected RMSE <= 0.11; with 128 texels, iterated orders and the moments
// of their light (issue 18 §2) measured: bias +3.2, +3.2, +1.0 % (+- 1.0 .. 1.7), RMSE <= 0.02.
constexpr double kShadowBias = 0.08;
constexpr double kShadowRmse = 0.12;
TEST(Accuracy, EarthShadow) {
    ExpectWithin(Measure("earth_shadow"), "earth_shadow", kShadowBias, kShadowRmse);
}

// Mars from space: dust with g = 0.65, optical depth 0.5. Hillaire 2020 §5.5 transfers orders
// >= 3 isotropically, which for forward-peaked dust gave 2.2x the path tracer's multiple
// scattering (bias +51..+58 %); with the reduced scattering coefficient (1 - g) sigma_s in that
// transfer (functions.glsl, Eq. 8) measured: bias +14, +16, +20 %, noise-corrected RMSE <= 0.44.
// Still the largest error of the set: the isotropy assumption itself (paper Fig. 12).
constexpr double kMarsBias = 0.30;
constexpr double kMarsRmse = 0.60;
TEST(Accuracy, MarsSpace) {
    ExpectWithin(Measure("mars_space"), "mars_space", kMarsBias, kMarsRmse);
}

// The paper's limit (Fig. 12, "the hue can be lost or even start to drift"): with 50x Rayleigh
// the slant optical depth to a 45 deg sun is 8 (R) to 47 (B), the directly lit neighbourhood
// from which H20 builds Psi_ms (Eq. 7-10) is dark, and its series lost the light that diffuses
// down through hundreds of orders: the renderer kept 17 % of the red and < 0.1 % of the green
// and blue (bias -83, -99.9, -100 %, a whitish sky rendered dark red). The plane-parallel
// column's orders past the LUT's last (multiple_scattering_column.h) put it back: measured
// -3.5, -4.7, -7.6 % (+- 1.5 .. 2.8 %; at 96x64 -1.3, -6.6, -7.8 %), noise-corrected RMSE 0 (the
// reference's noise is 0.3 .. 0.6 of the mean at 256 paths). Bounds: issue 18's 10 % for the
// thick preset. The RMSE bound is the larger with the sanitizers' 64 paths, where the
// reference's noise is 0.6 .. 1.2 of the mean and the noise-corrected RMSE of the same renderer
// read 0.30 in green (0.0 at 256 paths): the difference of two noisy estimates, not an error.
constexpr double kThickBias = 0.10;
#if defined(__SANITIZE_ADDRESS__)
constexpr double kThickRmse = 0.5;
#else
constexpr double kThickRmse = 0.25;
#endif
TEST(Accuracy, ThickDaytime) {
    ExpectWithin(Measure("thick_daytime"), "thick_daytime", kThickBias, kThickRmse);
}

// Twilight past sunset on single view rays (BENCHMARKS.md, "Twilight grid"; issue 18 §2): the
// horizon away from the sun, where almost all the light is multiply scattered and comes from the
// sunward sky. H20's Psi_ms (second order scattered isotropically, the rest a geometric series)
// was 18-25 % low in blue on these rays (-24.7 % at the anti-solar horizon at sunset): the
// renderer now iterates the orders and scatters them through Rayleigh's phase over the incident
// light's second moments (functions.glsl, MultipleScatteringSample). Measured with the shipped
// LUTs: at sunset -2.7 to -4.8 % (+- 0.4), at 95 deg -3.5 to +11.7 % (+- 2.1; the anti-solar
// red), against bounds of 6 and 15 % plus 4 standard errors.
TEST(Accuracy, TwilightHorizonAwayFromTheSun) {
    Atmosphere earth = LoadAtmosphere("earth");
    earth.ground_albedo = glm::dvec3(0.0);
    const AtmosphereReference renderer(earth, LutSettings::Pc());
    constexpr double kDeg = std::numbers::pi / 180.0;
    const struct {
        double sun_zenith_deg, view_azimuth_deg, bound;
    } rays[] = {{90.0, 180.0, 0.06}, {90.0, 90.0, 0.06}, {95.0, 180.0, 0.15}, {95.0, 90.0, 0.15}};
    std::uint64_t seed = 1;
    for (const auto& ray : rays) {
        Lights lights;
        lights.sun_direction = LocalDirection((90.0 - ray.sun_zenith_deg) * kDeg, 0.0);
        lights.sun_illuminance = earth.solar_illuminance;
        const glm::dvec3 camera(0.0, earth.bottom_radius + 1.0, 0.0);  // 1 m above the ground
        const glm::dvec3 direction = LocalDirection(1.0 * kDeg, ray.view_azimuth_deg * kDeg);
        const glm::dvec3 lut = renderer.SampleSkyView(renderer.SkyView(camera, lights), camera,
                                                      lights.sun_direction, direction);
        PathTraceOptions options;
        options.samples = kTwilightPaths;
        options.ground = false;
        options.threads = 2;
        options.seed = seed++;
        const PathTraceResult pt =
            PathTrace(earth, camera, direction, lights.sun_direction, options);
        for (int c = 0; c < 3; ++c) {
            const double error = lut[c] / pt.luminance[c] - 1.0;
            const double se = pt.standard_error[c] / pt.luminance[c];
            std::printf("sun zenith %.0f, view azimuth %.0f, channel %d: %+.1f +- %.1f %%\n",
                        ray.sun_zenith_deg, ray.view_azimuth_deg, c, 100.0 * error, 100.0 * se);
            EXPECT_LE(std::abs(error), ray.bound + kSigmas * se)
                << "sun zenith " << ray.sun_zenith_deg << ", view azimuth " << ray.view_azimuth_deg
                << ", channel " << c;
        }
    }
}

// The reference's noise estimate is what the RMSE floor rests on: it must shrink as 1/sqrt(N).
TEST(Accuracy, ReferenceNoiseFallsAsOneOverSqrtSamples) {
    AccuracyOptions options = TestOptions();
    options.width = 8;
    options.height = 6;
    options.samples = kSamples / 4;
    const AccuracyResult few = MeasureAccuracy(Scenario("earth_daytime"), options);
    options.samples = kSamples;
    const AccuracyResult many = MeasureAccuracy(Scenario("earth_daytime"), options);
    for (int c = 0; c < 3; ++c) {
        // Expected ratio 2; the per-pixel variance estimates themselves scatter by ~10 %.
        const double ratio = few.noise[c] / many.noise[c];
        EXPECT_GT(ratio, 1.6) << "channel " << c;
        EXPECT_LT(ratio, 2.5) << "channel " << c;
    }
    // The LUT image is deterministic.
    EXPECT_EQ(few.renderer.rgb, many.renderer.rgb);
}

TEST(Accuracy, RejectsBadOptions) {
    AccuracyOptions options = TestOptions();
    options.width = 0;
    EXPECT_THROW(MeasureAccuracy(Scenario("earth_daytime"), options), zenith::ArgumentError);
    options = TestOptions();
    options.samples = 1;
    EXPECT_THROW(MeasureAccuracy(Scenario("earth_daytime"), options), zenith::ArgumentError);
}

}  // namespace
}  // namespace zenith::sky::reference
