// Laws that the independent CPU reference (deterministic single scattering and the Monte Carlo
// path tracer) must obey: normalised phase functions and exact sampling, the closed-form
// vertical transmittance, agreement of the two methods where they compute the same thing,
// energy conservation, and a physically plausible daytime sky.
#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "luminance.h"
#include "zenith/sky/reference/path_tracer.h"

namespace zenith::sky::reference {
namespace {

using test::Luminance;

constexpr double kPi = std::numbers::pi;

// Sanitizer builds run ~10x slower: fewer paths there, with tolerances in standard errors.
#if defined(__SANITIZE_ADDRESS__)
constexpr std::int64_t kPathScale = 4;
#else
constexpr std::int64_t kPathScale = 1;
#endif

glm::dvec3 SunAt(double elevation) { return {std::cos(elevation), std::sin(elevation), 0.0}; }

glm::dvec3 ViewAt(double elevation, double azimuth) {
    return {std::cos(elevation) * std::cos(azimuth), std::sin(elevation),
            std::cos(elevation) * std::sin(azimuth)};
}

// Composite Simpson on [a, b] with n (even) intervals.
template <class F>
double Simpson(const F& f, double a, double b, int n) {
    const double h = (b - a) / n;
    double sum = f(a) + f(b);
    for (int i = 1; i < n; ++i) sum += (i % 2 ? 4.0 : 2.0) * f(a + i * h);
    return sum * h / 3.0;
}

// ∫_{-1}^{1} f(μ) dμ for a phase lobe that may peak sharply at μ = ±1 (g = 0.95: width ~0.05
// in μ): Simpson, refined near both ends.
template <class F>
double IntegrateCosine(const F& f) {
    double sum = 0.0;
    const std::array<double, 6> edges{-1.0, -0.99, -0.9, 0.9, 0.99, 1.0};
    for (std::size_t i = 0; i + 1 < edges.size(); ++i) {
        sum += Simpson(f, edges[i], edges[i + 1], 20000);
    }
    return sum;
}

TEST(ReferencePhase, IntegratesToOneOverTheSphere) {
    const double rayleigh =
        2.0 * kPi * IntegrateCosine([](double mu) { return RayleighPhase(mu); });
    EXPECT_NEAR(rayleigh, 1.0, 1e-12);
    for (const double g : {-0.7, -0.2, 0.0, 0.3, 0.8, 0.95}) {
        const double norm =
            2.0 * kPi * IntegrateCosine([g](double mu) { return CornetteShanksPhase(mu, g); });
        const double mean =
            2.0 * kPi * IntegrateCosine([g](double mu) { return mu * CornetteShanksPhase(mu, g); });
        EXPECT_NEAR(norm, 1.0, 1e-9) << "g = " << g;
        EXPECT_NEAR(mean, CornetteShanksMeanCosine(g), 1e-9) << "g = " << g;
    }
}

// Pearson chi-square of sampled cosines against the pdf integrated over equal-width bins.
template <class Pdf, class Sampler>
double ChiSquare(const Pdf& pdf, const Sampler& sample, int samples, int bins, double& mean) {
    std::vector<double> counts(static_cast<std::size_t>(bins), 0.0);
    mean = 0.0;
    for (int i = 0; i < samples; ++i) {
        const double mu = sample();
        mean += mu;
        const int bin = std::min(bins - 1, static_cast<int>((mu + 1.0) * 0.5 * bins));
        counts[static_cast<std::size_t>(bin)] += 1.0;
    }
    mean /= samples;
    double chi2 = 0.0;
    for (int b = 0; b < bins; ++b) {
        const double lo = -1.0 + 2.0 * b / bins;
        const double hi = lo + 2.0 / bins;
        const double expected = samples * 2.0 * kPi * Simpson(pdf, lo, hi, 2000);
        const double diff = counts[static_cast<std::size_t>(b)] - expected;
        chi2 += diff * diff / expected;
    }
    return chi2;
}

TEST(ReferencePhase, SamplingMatchesTheDistribution) {
    constexpr int kSamples = 200000;
    constexpr int kBins = 20;
    // 99.99th percentile of chi-square with 19 degrees of freedom.
    constexpr double kChi2Limit = 51.0;
    Rng rng(7);
    double mean = 0.0;
    const double chi2_rayleigh =
        ChiSquare([](double mu) { return RayleighPhase(mu); },
                  [&] { return SampleRayleighCosine(rng.Uniform()); }, kSamples, kBins, mean);
    EXPECT_LT(chi2_rayleigh, kChi2Limit);
    // Rayleigh: E[μ] = 0, sd(μ) = sqrt(2/5).
    EXPECT_NEAR(mean, 0.0, 4.0 * std::sqrt(0.4 / kSamples));
    for (const double g : {-0.3, 0.0, 0.5, 0.8, 0.95}) {
        const double chi2 =
            ChiSquare([g](double mu) { return CornetteShanksPhase(mu, g); },
                      [&] { return SampleCornetteShanksCosine(g, rng); }, kSamples, kBins, mean);
        EXPECT_LT(chi2, kChi2Limit) << "g = " << g;
        // |μ| <= 1, so sd <= 1: 4 sigma of the mean is below 4/sqrt(N).
        EXPECT_NEAR(mean, CornetteShanksMeanCosine(g), 4.0 / std::sqrt(kSamples)) << "g = " << g;
    }
}

// ∫_{h0}^{h1} max(0, 1 - |h - c| / w) dh, the tent's antiderivative differenced.
double TentIntegral(double c, double w, double h0, double h1) {
    const auto antiderivative = [c, w](double h) {
        if (h <= c - w) return 0.0;
        if (h <= c) return (h - (c - w)) * (h - (c - w)) / (2.0 * w);
        if (h <= c + w) return w - (c + w - h) * (c + w - h) / (2.0 * w);
        return w;
    };
    return antiderivative(h1) - antiderivative(h0);
}

TEST(ReferenceTransmittance, VerticalRayMatchesClosedForm) {
    const Atmosphere atmosphere;
    const glm::dvec3 up{0.0, 0.0, 1.0};
    for (const auto& [h0, h1] : {std::pair{0.0, 100e3}, std::pair{3000.0, 100e3},
                                 std::pair{12e3, 31e3}, std::pair{27e3, 45e3}}) {
        const glm::dvec3 origin = (atmosphere.bottom_radius + h0) * up;
        const glm::dvec3 depth = OpticalDepth(atmosphere, origin, up, h1 - h0);
        const auto layer = [&](double scale_height) {
            return scale_height * (std::exp(-h0 / scale_height) - std::exp(-h1 / scale_height));
        };
        const glm::dvec3 expected =
            atmosphere.rayleigh_scattering * layer(atmosphere.rayleigh_scale_height) +
            atmosphere.MieExtinction() * layer(atmosphere.mie_scale_height) +
            atmosphere.absorption_extinction * TentIntegral(atmosphere.absorption_center,
                                                            0.5 * atmosphere.absorption_width, h0,
                                                            h1);
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(depth[c], expected[c], 1e-9 * expected[c])
                << "h0 = " << h0 << " m, h1 = " << h1 << " m, channel " << c;
        }
        if (h1 == 100e3) {
            const glm::dvec3 t = SunTransmittance(atmosphere, origin, up);
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(t[c], std::exp(-expected[c]), 1e-12);
        }
    }
}

TEST(ReferenceTransmittance, GrazingIntersectionsAndShadow) {
    const Atmosphere atmosphere;
    const double r = atmosphere.bottom_radius + 1.0;
    // A horizontal ray 1 m above the ground: the half chord to the top is sqrt(top² - r²).
    const auto hits = IntersectSphere({0.0, r, 0.0}, {1.0, 0.0, 0.0}, atmosphere.top_radius);
    ASSERT_TRUE(hits.has_value());
    const double expected = std::sqrt(atmosphere.top_radius * atmosphere.top_radius - r * r);
    EXPECT_NEAR(hits->t_far, expected, 1e-6);
    EXPECT_NEAR(hits->t_near, -expected, 1e-6);
    EXPECT_FALSE(IntersectSphere({0.0, r, 0.0}, {1.0, 0.0, 0.0}, atmosphere.bottom_radius));
    // A point behind the planet, in its shadow, gets no sun; just above the cylinder it does.
    const glm::dvec3 sun{1.0, 0.0, 0.0};
    const glm::dvec3 in_shadow{-7000e3, atmosphere.bottom_radius - 1.0, 0.0};
    const glm::dvec3 lit{-7000e3, atmosphere.bottom_radius + 30e3, 0.0};
    EXPECT_EQ(SunTransmittance(atmosphere, in_shadow, sun), glm::dvec3(0.0));
    EXPECT_GT(SunTransmittance(atmosphere, lit, sun).r, 0.0);
}

struct ViewCase {
    const char* name;
    glm::dvec3 position;
    glm::dvec3 direction;
    glm::dvec3 sun;
};

std::vector<ViewCase> ViewCases(const Atmosphere& atmosphere) {
    const double r = atmosphere.bottom_radius;
    const double deg = kPi / 180.0;
    const glm::dvec3 ground{0.0, r + 1.0, 0.0};
    return {
        {"zenith, sun 45 deg", ground, {0.0, 1.0, 0.0}, SunAt(45.0 * deg)},
        {"horizon toward sun at 2 deg", ground, ViewAt(3.0 * deg, 0.3), SunAt(2.0 * deg)},
        {"away from sun at 20 deg", ground, ViewAt(10.0 * deg, 2.5), SunAt(20.0 * deg)},
        {"down at the ground from 5 km",
         {0.0, r + 5e3, 0.0},
         ViewAt(-30.0 * deg, 1.0),
         SunAt(30.0 * deg)},
        // Both cross the boundary of the planet's shadow (the integrand jumps there).
        {"sun 6 deg below, toward it from 10 km",
         {0.0, r + 10e3, 0.0},
         ViewAt(5.0 * deg, 0.0),
         SunAt(-6.0 * deg)},
        {"sun 4 deg below, Earth's shadow overhead", ground, ViewAt(20.0 * deg, kPi),
         SunAt(-4.0 * deg)},
        {"space view of the limb",
         {0.0, 0.0, 3.0 * r},
         glm::normalize(glm::dvec3{0.0, r + 20e3, -3.0 * r}),
         SunAt(10.0 * deg)},
    };
}

TEST(ReferencePathTracer, SingleBounceModeMatchesSingleScattering) {
    const Atmosphere atmosphere;
    PathTraceOptions options;
    options.max_bounces = 1;
    options.samples = 8192 / kPathScale;
    options.threads = 2;
    for (const ViewCase& view : ViewCases(atmosphere)) {
        for (const bool ratio_tracking : {false, true}) {
            options.ratio_tracking_shadows = ratio_tracking;
            const glm::dvec3 expected =
                SingleScattering(atmosphere, view.position, view.direction, view.sun);
            const PathTraceResult result =
                PathTrace(atmosphere, view.position, view.direction, view.sun, options);
            for (int c = 0; c < 3; ++c) {
                EXPECT_NEAR(result.luminance[c], expected[c],
                            3.0 * result.standard_error[c] + 0.005 * expected[c])
                    << view.name << ", channel " << c << ", ratio tracking " << ratio_tracking;
            }
            std::printf(
                "%-46s %s SS (%.5g, %.5g, %.5g) PT (%.5g, %.5g, %.5g) +- (%.2g, %.2g, "
                "%.2g)\n",
                view.name, ratio_tracking ? "ratio" : "quad ", expected.r, expected.g, expected.b,
                result.luminance.r, result.luminance.g, result.luminance.b, result.standard_error.r,
                result.standard_error.g, result.standard_error.b);
        }
    }
}

Atmosphere Scaled(Atmosphere atmosphere, double factor) {
    atmosphere.rayleigh_scattering *= factor;
    atmosphere.mie_scattering *= factor;
    atmosphere.mie_absorption *= factor;
    atmosphere.absorption_extinction *= factor;
    return atmosphere;
}

// In an optically thin atmosphere every higher order is O(τ) smaller, so the full path tracer
// (unbounded, Russian roulette) reduces to single scattering. The ground is black: light
// reflected by the ground and scattered once in the air is also first order in τ.
TEST(ReferencePathTracer, ThinLimitEqualsSingleScattering) {
    Atmosphere atmosphere = Scaled(Atmosphere{}, 1e-4);
    atmosphere.ground_albedo = glm::dvec3(0.0);
    PathTraceOptions options;
    options.samples = 16384 / kPathScale;
    options.threads = 2;
    for (const ViewCase& view : ViewCases(atmosphere)) {
        const glm::dvec3 expected =
            SingleScattering(atmosphere, view.position, view.direction, view.sun);
        const PathTraceResult result =
            PathTrace(atmosphere, view.position, view.direction, view.sun, options);
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(result.luminance[c], expected[c],
                        3.0 * result.standard_error[c] + 1e-3 * expected[c])
                << view.name << ", channel " << c;
        }
        std::printf(
            "thin: %-46s (PT - SS) / SS = (%+.4f, %+.4f, %+.4f), SE/SS = (%.4f, %.4f, "
            "%.4f)\n",
            view.name, result.luminance.r / expected.r - 1.0, result.luminance.g / expected.g - 1.0,
            result.luminance.b / expected.b - 1.0, result.standard_error.r / expected.r,
            result.standard_error.g / expected.g, result.standard_error.b / expected.b);
    }
}

// With absorption only, the camera sees exactly the sun-lit ground through the atmosphere:
// T(c, p) ρ/π E cosθ T(p, sun), from the closed-form pieces here.
TEST(ReferencePathTracer, AbsorptionOnlyGivesTheTransmittedGround) {
    Atmosphere atmosphere;
    atmosphere.rayleigh_scattering = glm::dvec3(0.0);
    atmosphere.mie_scattering = glm::dvec3(0.0);
    atmosphere.mie_absorption = glm::dvec3(20e-6, 25e-6, 30e-6);
    const glm::dvec3 position{0.0, atmosphere.bottom_radius + 3e3, 0.0};
    const glm::dvec3 direction = ViewAt(-40.0 * kPi / 180.0, 0.0);
    const glm::dvec3 sun = glm::normalize(glm::dvec3{0.3, 0.8, 0.2});
    const auto ground = IntersectSphere(position, direction, atmosphere.bottom_radius);
    ASSERT_TRUE(ground.has_value());
    const glm::dvec3 p = position + ground->t_near * direction;
    const double cos_sun = glm::dot(glm::normalize(p), sun);
    const glm::dvec3 expected =
        glm::exp(-OpticalDepth(atmosphere, position, direction, ground->t_near)) *
        atmosphere.ground_albedo / kPi * cos_sun * SunTransmittance(atmosphere, p, sun) *
        atmosphere.solar_illuminance;
    const glm::dvec3 single = SingleScattering(atmosphere, position, direction, sun);
    PathTraceOptions options;
    options.samples = 4096 / kPathScale;
    const PathTraceResult traced = PathTrace(atmosphere, position, direction, sun, options);
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(single[c], expected[c], 1e-7 * expected[c]) << "channel " << c;
        EXPECT_NEAR(traced.luminance[c], expected[c], 3.0 * traced.standard_error[c] + 1e-9)
            << "channel " << c;
    }
    // Ratio tracking (the null-collision weights) is the only noise left.
    EXPECT_LT(traced.standard_error.g, 0.02 * expected.g);
}

// White furnace: with no absorption anywhere and a white ground, everything the sun puts into
// the atmosphere (E π R_top²) must leave through its top, as scattered light (every camera
// ray from the top sphere looking in, cosine-weighted) plus the unscattered beam.
TEST(ReferencePathTracer, WhiteFurnaceConservesEnergy) {
    Atmosphere atmosphere;
    atmosphere.mie_absorption = glm::dvec3(0.0);
    atmosphere.absorption_extinction = glm::dvec3(0.0);
    atmosphere.ground_albedo = glm::dvec3(1.0);
    atmosphere.rayleigh_scattering *= 3.0;  // more orders of scattering
    const glm::dvec3 sun{0.0, 0.0, 1.0};
    const double top = atmosphere.top_radius;
    const double bottom = atmosphere.bottom_radius;

    // Scattered flux: 4π R_top² (area) × π (cosine-weighted directions) × E[L].
    const int samples = static_cast<int>(60000 / kPathScale);
    Rng rng(2024);
    PathTraceOptions options;
    options.samples = 1;
    glm::dvec3 sum{0.0}, sum_squares{0.0};
    for (int i = 0; i < samples; ++i) {
        const double z = 2.0 * rng.Uniform() - 1.0;
        const double phi = 2.0 * kPi * rng.Uniform();
        const double s = std::sqrt(1.0 - z * z);
        const glm::dvec3 normal{s * std::cos(phi), s * std::sin(phi), z};
        const double u = rng.Uniform();
        const double cos_theta = std::sqrt(1.0 - u);
        const double sin_theta = std::sqrt(u);
        const double psi = 2.0 * kPi * rng.Uniform();
        const glm::dvec3 a = std::abs(normal.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
        const glm::dvec3 t1 = glm::normalize(glm::cross(normal, a));
        const glm::dvec3 t2 = glm::cross(normal, t1);
        const glm::dvec3 direction =
            -cos_theta * normal + sin_theta * (std::cos(psi) * t1 + std::sin(psi) * t2);
        options.seed = static_cast<std::uint64_t>(i) + 1;
        const glm::dvec3 value =
            4.0 * kPi * top * top * kPi *
            PathTrace(atmosphere, top * normal, direction, sun, options).luminance;
        sum += value;
        sum_squares += value * value;
    }
    const double n = samples;
    const glm::dvec3 scattered = sum / n;
    const glm::dvec3 scattered_error =
        glm::sqrt((sum_squares / n - scattered * scattered) / (n - 1.0));

    // Unscattered beam: E ∫ T(b) 2π b db over impact parameters b that miss the ground.
    const auto transmitted = [&](int c) {
        return Simpson(
            [&](double b) {
                const glm::dvec3 entry{b, 0.0, -std::sqrt(top * top - b * b)};
                const double chord = 2.0 * std::sqrt(top * top - b * b);
                return 2.0 * kPi * b * std::exp(-OpticalDepth(atmosphere, entry, sun, chord)[c]);
            },
            bottom, top, 400);
    };
    const double incident = kPi * top * top;
    for (int c = 0; c < 3; ++c) {
        const double out = scattered[c] / atmosphere.solar_illuminance[c] + transmitted(c);
        const double error = scattered_error[c] / atmosphere.solar_illuminance[c];
        EXPECT_NEAR(out / incident, 1.0, 3.0 * error / incident) << "channel " << c;
        std::printf("white furnace channel %d: out / in = %.4f +- %.4f\n", c, out / incident,
                    error / incident);
    }
}

TEST(ReferencePathTracer, EarthZenithDaylightIsAboutTwoThousandNits) {
    const Atmosphere atmosphere;
    const glm::dvec3 position{0.0, atmosphere.bottom_radius + 1.0, 0.0};
    const glm::dvec3 zenith{0.0, 1.0, 0.0};
    const glm::dvec3 sun = SunAt(kPi / 4.0);
    PathTraceOptions options;
    options.samples = 16384 / kPathScale;
    options.threads = 2;
    const auto start = std::chrono::steady_clock::now();
    const PathTraceResult result = PathTrace(atmosphere, position, zenith, sun, options);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const glm::dvec3 single = SingleScattering(atmosphere, position, zenith, sun);
    const double y = Luminance(result.luminance);
    std::printf(
        "zenith, sun 45 deg: Y = %.1f +- %.1f cd/m^2 (single scattering %.1f), RGB (%.1f, "
        "%.1f, %.1f); %.2f ms per 1000 paths on 2 threads\n",
        y, Luminance(result.standard_error), Luminance(single), result.luminance.r,
        result.luminance.g, result.luminance.b,
        1e3 * seconds / static_cast<double>(options.samples) * 1000.0);
    EXPECT_GT(y, 1000.0);
    EXPECT_LT(y, 5000.0);
    EXPECT_GT(result.luminance.b, result.luminance.r);  // blue sky
    EXPECT_GT(y, Luminance(single));                    // multiple scattering adds light
}

TEST(ReferencePathTracer, DeterministicForASeedWhateverTheThreads) {
    const Atmosphere atmosphere;
    const glm::dvec3 position{0.0, atmosphere.bottom_radius + 100.0, 0.0};
    PathTraceOptions options;
    options.samples = 300;
    options.seed = 99;
    options.threads = 1;
    const PathTraceResult one =
        PathTrace(atmosphere, position, ViewAt(0.2, 0.4), SunAt(0.3), options);
    options.threads = 2;
    const PathTraceResult two =
        PathTrace(atmosphere, position, ViewAt(0.2, 0.4), SunAt(0.3), options);
    EXPECT_EQ(one.luminance, two.luminance);
    EXPECT_EQ(one.standard_error, two.standard_error);
}

TEST(ReferenceCamera, RendersBothMethods) {
    const Atmosphere atmosphere;
    Camera camera;
    camera.width = 6;
    camera.height = 4;
    camera.vertical_fov = 0.8;
    camera.position = {0.0, atmosphere.bottom_radius + 200.0, 0.0};
    camera.forward = {1.0, 0.05, 0.0};
    camera.up = {0.0, 1.0, 0.0};
    const glm::dvec3 sun = SunAt(0.2);
    // Pixel centres straddle the optical axis symmetrically.
    const glm::dvec3 left = CameraRayDirection(camera, 2, 1);
    const glm::dvec3 right = CameraRayDirection(camera, 3, 2);
    EXPECT_NEAR(glm::dot(glm::normalize(left + right), glm::normalize(camera.forward)), 1.0, 1e-12);
    EXPECT_GT(CameraRayDirection(camera, 0, 0).y, CameraRayDirection(camera, 0, 3).y);

    const Image single = RenderSingleScattering(atmosphere, camera, sun, {}, 2);
    PathTraceOptions options;
    options.samples = 32;
    Image error;
    const Image traced = RenderPathTraced(atmosphere, camera, sun, options, 2, &error);
    ASSERT_EQ(single.rgb.size(), 3u * 6u * 4u);
    ASSERT_EQ(traced.rgb.size(), single.rgb.size());
    ASSERT_EQ(error.rgb.size(), single.rgb.size());
    for (std::size_t i = 0; i < single.rgb.size(); ++i) {
        EXPECT_TRUE(single.rgb[i] > 0.0f && std::isfinite(single.rgb[i])) << i;
        EXPECT_TRUE(traced.rgb[i] > 0.0f && std::isfinite(traced.rgb[i])) << i;
        EXPECT_TRUE(traced.rgb[i] >= single.rgb[i] - 4.0f * error.rgb[i]) << i;
    }
    EXPECT_EQ(traced.At(5, 3).r, traced.rgb[3 * (3 * 6 + 5)]);
}

}  // namespace
}  // namespace zenith::sky::reference
