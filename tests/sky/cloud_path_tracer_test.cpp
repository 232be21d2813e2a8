// The cloud path tracer (reference/cloud_path_tracer.h) against closed forms and published
// plane-parallel results, never against the renderer. Every Monte Carlo assertion allows 4
// standard errors computed from the paths themselves (a false alarm about once in 16,000 runs
// per assertion, and runs are deterministic: fixed seeds), plus a stated model error where the
// closed form is itself an approximation.
#include "zenith/sky/reference/cloud_path_tracer.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include "cloud_test_support.h"
#include "h_function.h"
#include "zenith/sky/reference/path_tracer.h"

namespace zenith::sky::reference {
namespace {

using test::HFunction;

constexpr double kPi = std::numbers::pi;
constexpr double kSigmas = 4.0;

CloudPathTraceOptions Paths(std::int64_t samples, std::uint64_t seed = 1) {
    CloudPathTraceOptions options;
    options.samples = samples;
    options.seed = seed;
    options.threads = 2;
    return options;
}

// --- Phase functions --------------------------------------------------------------------------

TEST(CloudPathTracerPhase, DualLobeIsNormalisedAndSampledExactly) {
    const CloudPhase phase{0.8, -0.3, 0.3};
    // ∫ p dΩ = 2π ∫ p dμ = 1 (composite Simpson; the forward peak is resolved at 2e5 panels).
    constexpr int kPanels = 200000;
    double integral = 0.0;
    for (int i = 0; i <= kPanels; ++i) {
        const double mu = -1.0 + 2.0 * i / kPanels;
        const double w = (i == 0 || i == kPanels) ? 1.0 : (i % 2 ? 4.0 : 2.0);
        integral += w * CloudPhaseValue(phase, mu);
    }
    integral *= 2.0 * kPi * (2.0 / kPanels) / 3.0;
    EXPECT_NEAR(integral, 1.0, 1e-6);
    // The sampled mean cosine is the analytic one, (1 - w) g0 + w g1.
    Rng rng(7);
    constexpr int kSamples = 400000;
    double sum = 0.0, sum_squares = 0.0;
    for (int i = 0; i < kSamples; ++i) {
        const double mu = SampleCloudPhaseCosine(phase, rng.Uniform(), rng.Uniform());
        sum += mu;
        sum_squares += mu * mu;
    }
    const double mean = sum / kSamples;
    const double error = std::sqrt((sum_squares / kSamples - mean * mean) / kSamples);
    EXPECT_NEAR(mean, 0.7 * 0.8 + 0.3 * -0.3, kSigmas * error);
}

// --- Slab: energy -----------------------------------------------------------------------------

// A non-absorbing slab over a black ground reflects or transmits everything: R + T = 1.
// Photons (light paths) are counted where they leave, so R + T = 1 holds per photon unless the
// tracking loses or duplicates one (a leak, a NaN direction, a path cut short): asserted to
// 1e-12, far inside the 0.5 % the issue asks for. Camera paths (the estimator that gives cloud
// radiance) estimate R and T from independent path sets by integrating radiance over the
// hemisphere; their sum is held to 1 within 4 sigma, with sigma ~1 % at this cost (the
// forward-peaked g = 0.85 radiance field is a poor match for cosine-weighted directions), and
// R agrees with the photons'.
TEST(CloudPathTracerSlab, NonAbsorbingSlabConservesEnergy) {
    for (const double tau : {1.0, 10.0, 30.0}) {
        SCOPED_TRACE(::testing::Message() << "tau = " << tau);
        SlabProblem problem;
        problem.optical_depth = tau;
        problem.phase = CloudPhase{0.85, 0.0, 0.0};
        problem.mu0 = 0.6;
        problem.majorant_factor = 1.5;  // null collisions too

        const SlabFluxes photons = SlabFluxesFromPhotons(problem, Paths(200000, 11));
        EXPECT_NEAR(photons.reflectance + photons.transmittance, 1.0, 1e-12);
        EXPECT_GT(photons.reflectance, 0.0);
        EXPECT_GT(photons.transmittance, photons.direct_transmittance);

        const SlabFluxes camera = SlabFluxesFromRadiance(problem, Paths(40000, 12));
        const double sum = camera.reflectance + camera.transmittance;
        const double sigma = std::hypot(camera.reflectance_error, camera.transmittance_error);
        EXPECT_LE(sigma, 0.02);
        EXPECT_NEAR(sum, 1.0, kSigmas * sigma);
        EXPECT_NEAR(camera.reflectance, photons.reflectance,
                    kSigmas * std::hypot(camera.reflectance_error, photons.reflectance_error));
    }
}

// --- Slab: single scattering ------------------------------------------------------------------

// Reflected radiance of single scattering from a homogeneous slab (e.g. Liou 2002, Eq. 6.3.6;
// van de Hulst 1980 §3.2), per unit E0 (beam irradiance):
//   L1(mu, phi) / E0 = omega p(Theta) mu0 / (mu0 + mu) (1 - exp(-tau (1/mu + 1/mu0)))
// with p normalised to 1 over the sphere. As tau -> 0 it is omega tau p / mu, and with van de
// Hulst's phase normalisation (4 pi p) the reflection function pi L / (mu0 E0) is
// omega tau P(Theta) / (4 mu mu0).
double SingleScatteringReflection(const SlabProblem& p, double mu, double phi) {
    const double sin0 = std::sqrt(1.0 - p.mu0 * p.mu0);
    const double sin1 = std::sqrt(1.0 - mu * mu);
    // Incoming propagation (-sin0, 0, -mu0), outgoing (sin1 cos phi, sin1 sin phi, mu).
    const double cos_theta = -sin0 * sin1 * std::cos(phi) - p.mu0 * mu;
    return p.single_scattering_albedo * CloudPhaseValue(p.phase, cos_theta) * p.mu0 / (p.mu0 + mu) *
           (1.0 - std::exp(-p.optical_depth * (1.0 / mu + 1.0 / p.mu0)));
}

TEST(CloudPathTracerSlab, FirstOrderIsTheSingleScatteringClosedForm) {
    SlabProblem problem;
    problem.optical_depth = 1.0;
    problem.phase = CloudPhase{0.8, -0.3, 0.3};
    problem.single_scattering_albedo = 0.9;
    problem.mu0 = 0.7;
    problem.majorant_factor = 2.0;
    CloudPathTraceOptions options = Paths(100000, 21);
    options.max_bounces = 1;
    for (const auto& [mu, phi] : {std::pair{0.5, 0.3}, std::pair{0.9, 2.5}, std::pair{0.3, 0.0}}) {
        SCOPED_TRACE(::testing::Message() << "mu = " << mu << ", phi = " << phi);
        const SlabRadianceResult l = SlabRadiance(problem, mu, phi, options);
        const double expected = SingleScatteringReflection(problem, mu, phi);
        EXPECT_LE(l.standard_error, 0.02 * expected);
        EXPECT_NEAR(l.value, expected, kSigmas * l.standard_error);
    }
}

TEST(CloudPathTracerSlab, ThinSlabIsSingleScattering) {
    // tau = 0.01, every order: higher orders add O(tau) relative (double scattering is at most
    // tau (1/mu + 1/mu0) ~ 3 % of single here), so they get that allowance on top of 4 sigma.
    SlabProblem problem;
    problem.optical_depth = 0.01;
    problem.phase = CloudPhase{0.8, -0.3, 0.3};
    problem.mu0 = 0.7;
    for (const auto& [mu, phi] : {std::pair{0.5, 0.3}, std::pair{0.9, 2.5}}) {
        SCOPED_TRACE(::testing::Message() << "mu = " << mu << ", phi = " << phi);
        const SlabRadianceResult l = SlabRadiance(problem, mu, phi, Paths(1000000, 31));
        const double expected = SingleScatteringReflection(problem, mu, phi);
        const double higher_orders = problem.optical_depth * (1.0 / mu + 1.0 / problem.mu0);
        EXPECT_LE(l.standard_error, 0.02 * expected);
        EXPECT_GE(l.value, expected - kSigmas * l.standard_error);
        EXPECT_LE(l.value, expected * (1.0 + higher_orders) + kSigmas * l.standard_error);
        // τ P / (4 μ μ0) form of the same limit (van de Hulst's normalisation).
        const double r = kPi * l.value / problem.mu0;
        const double sin0 = std::sqrt(1.0 - problem.mu0 * problem.mu0);
        const double cos_theta =
            -sin0 * std::sqrt(1.0 - mu * mu) * std::cos(phi) - problem.mu0 * mu;
        const double thin = problem.optical_depth * 4.0 * kPi *
                            CloudPhaseValue(problem.phase, cos_theta) / (4.0 * mu * problem.mu0);
        EXPECT_NEAR(r, thin, thin * higher_orders + kSigmas * kPi * l.standard_error / problem.mu0);
    }
}

// --- Slab: published tables -------------------------------------------------------------------

// van de Hulst 1980, "Multiple Light Scattering", Table 37 (Henyey-Greenstein g = 0.75,
// omega = 1, mu0 = 1, black ground), as reproduced by DISORT's test problem 3 (disotest.f,
// "Compare To Ref. VH2, Table 37"; Stamnes et al. 1988), whose correct answers are for an
// incident flux mu0 FBEAM = pi:
//   tau = 1: diffuse up at the top 0.247374, diffuse down at the bottom 1.73849,
//            intensity up at the top for mu = 0.5: 0.101103, mu = 1: 0.0395460
//   tau = 8: diffuse up 1.59096, diffuse down 1.54958,
//            intensity up for mu = 0.5: 0.519598, mu = 1: 0.493302
// Divided by pi: R and diffuse T per incident flux, and L / E0 (E0 = FBEAM = pi).
struct PublishedCase {
    double tau;
    double up_flux;
    double down_flux;
    double intensity_mu05;
    double intensity_mu1;
};

TEST(CloudPathTracerSlab, MatchesVanDeHulstTable37) {
    for (const PublishedCase& c : {PublishedCase{1.0, 0.247374, 1.73849, 0.101103, 0.0395460},
                                   PublishedCase{8.0, 1.59096, 1.54958, 0.519598, 0.493302}}) {
        SCOPED_TRACE(::testing::Message() << "tau = " << c.tau);
        SlabProblem problem;
        problem.optical_depth = c.tau;
        problem.phase = CloudPhase{0.75, 0.0, 0.0};
        problem.mu0 = 1.0;
        // Table values carry 6 digits; DISORT's own agreement with them is ~1e-4 relative.
        const double table_tolerance = 2e-4;
        const double r = c.up_flux / kPi;
        const double t = c.down_flux / kPi + std::exp(-c.tau);

        const SlabFluxes photons = SlabFluxesFromPhotons(problem, Paths(200000, 41));
        EXPECT_NEAR(photons.reflectance, r, kSigmas * photons.reflectance_error + table_tolerance);
        EXPECT_NEAR(photons.transmittance, t,
                    kSigmas * photons.transmittance_error + table_tolerance);

        const SlabFluxes camera = SlabFluxesFromRadiance(problem, Paths(40000, 42));
        EXPECT_NEAR(camera.reflectance, r, kSigmas * camera.reflectance_error + table_tolerance);
        EXPECT_NEAR(camera.transmittance, t,
                    kSigmas * camera.transmittance_error + table_tolerance);

        for (const auto& [mu, intensity] :
             {std::pair{0.5, c.intensity_mu05}, std::pair{1.0, c.intensity_mu1}}) {
            SCOPED_TRACE(::testing::Message() << "mu = " << mu);
            const SlabRadianceResult l = SlabRadiance(problem, mu, 0.0, Paths(40000, 43));
            EXPECT_LE(l.standard_error, 0.03 * intensity / kPi);
            EXPECT_NEAR(l.value, intensity / kPi,
                        kSigmas * l.standard_error + table_tolerance * intensity / kPi);
        }
    }
}

TEST(CloudPathTracerSlab, SemiInfiniteIsotropicAlbedoIsChandrasekhars) {
    // Plane albedo of a semi-infinite isotropic medium: A(mu0) = 1 - H(mu0) sqrt(1 - omega)
    // (Chandrasekhar 1950; van de Hulst 1980 §6). tau = 40 is semi-infinite here: the light
    // decays as exp(-k tau) with k > 0.5 for omega <= 0.9, so the missing depth is < 1e-8.
    for (const double omega : {0.5, 0.9}) {
        const HFunction h(omega);
        EXPECT_GT(h(1.0), 1.0);
        for (const double mu0 : {1.0, 0.4}) {
            SCOPED_TRACE(::testing::Message() << "omega = " << omega << ", mu0 = " << mu0);
            SlabProblem problem;
            problem.optical_depth = 40.0;
            problem.phase = CloudPhase{0.0, 0.0, 0.0};
            problem.single_scattering_albedo = omega;
            problem.mu0 = mu0;
            const double expected = 1.0 - h(mu0) * std::sqrt(1.0 - omega);
            const SlabFluxes photons = SlabFluxesFromPhotons(problem, Paths(200000, 51));
            EXPECT_NEAR(photons.reflectance, expected, kSigmas * photons.reflectance_error);
            const SlabFluxes camera = SlabFluxesFromRadiance(problem, Paths(50000, 52));
            EXPECT_LE(camera.reflectance_error, 0.01 * expected);
            EXPECT_NEAR(camera.reflectance, expected, kSigmas * camera.reflectance_error);
        }
    }
}

TEST(CloudPathTracerSlab, HFunctionMeetsItsMomentIdentity) {
    // The test's own H-function: its zeroth moment is exactly (2 / omega)(1 - sqrt(1 - omega))
    // (Chandrasekhar 1950, Ch. V), here by 400-point midpoint quadrature.
    for (const double omega : {0.5, 0.9}) {
        const HFunction h(omega);
        double moment = 0.0;
        for (int i = 0; i < 400; ++i) moment += h((i + 0.5) / 400.0) / 400.0;
        EXPECT_NEAR(moment, 2.0 / omega * (1.0 - std::sqrt(1.0 - omega)), 1e-5);
    }
}

// --- Determinism ------------------------------------------------------------------------------

TEST(CloudPathTracerSlab, ResultsDependOnTheSeedOnlyNotOnThreads) {
    SlabProblem problem;
    problem.optical_depth = 5.0;
    CloudPathTraceOptions one = Paths(5000, 3);
    one.threads = 1;
    CloudPathTraceOptions two = Paths(5000, 3);
    const SlabRadianceResult a = SlabRadiance(problem, 0.6, 0.2, one);
    const SlabRadianceResult b = SlabRadiance(problem, 0.6, 0.2, two);
    EXPECT_EQ(a.value, b.value);
    EXPECT_EQ(a.standard_error, b.standard_error);
    const SlabRadianceResult c = SlabRadiance(problem, 0.6, 0.2, Paths(5000, 4));
    EXPECT_NE(a.value, c.value);
}

// --- Clouds in the atmosphere -----------------------------------------------------------------

// Without clouds the scene is the atmosphere path tracer's (path_tracer.h): a second, separately
// written transport over the same air must give the same sky. 80 000 paths: with the aerosols'
// albedo 0.9 (issue 18) 60 000 left the red channel's standard error at 3.04 % of its radiance.
TEST(CloudPathTracerScene, ClearSkyAgreesWithTheAtmospherePathTracer) {
    CloudScene scene;
    scene.atmosphere = Atmosphere{};
    scene.sun_direction = glm::normalize(glm::dvec3(0.0, 0.6, 0.8));
    const glm::dvec3 camera(0.0, 0.0, scene.atmosphere.bottom_radius + 1000.0);
    const glm::dvec3 view = glm::normalize(glm::dvec3(0.3, -0.4, 0.5));
    const CloudPathTraceResult ours = CloudPathTrace(scene, camera, view, Paths(80000, 61));
    PathTraceOptions options;
    options.samples = 4000;
    options.threads = 2;
    const PathTraceResult theirs =
        PathTrace(scene.atmosphere, camera, view, scene.sun_direction, options);
    for (int c = 0; c < 3; ++c) {
        SCOPED_TRACE(::testing::Message() << "channel " << c);
        EXPECT_NEAR(ours.radiance[c], theirs.luminance[c],
                    kSigmas * std::hypot(ours.standard_error[c], theirs.standard_error[c]));
        EXPECT_LE(ours.standard_error[c], 0.03 * ours.radiance[c]);
    }
}

// Delta and ratio tracking are unbiased only if the majorant bounds the extinction everywhere:
// check the overcast preset's shells at random points, and that the deck is there.
TEST(CloudPathTracerScene, CloudMajorantBoundsTheExtinction) {
    const clouds::Weather weather = clouds::LoadWeather("overcast_stratus");
    const CloudField field(weather, CloudSettings{}, clouds::test::CachedNoise(), 6360e3);
    ASSERT_EQ(field.shells().size(), 1u);
    const CloudField::Shell& shell = field.shells()[0];
    Rng rng(9);
    double largest = 0.0;
    for (int i = 0; i < 200000; ++i) {
        const double r =
            shell.inner_radius + rng.Uniform() * (shell.outer_radius - shell.inner_radius);
        const double x = (rng.Uniform() - 0.5) * 80000.0;
        const double y = (rng.Uniform() - 0.5) * 80000.0;
        const glm::dvec3 p = glm::normalize(glm::dvec3(x, y, 6360e3)) * r;
        largest = std::max(largest, field.Extinction(p));
    }
    EXPECT_GT(largest, 0.0);
    EXPECT_LE(largest, shell.majorant);
    // Nothing outside the shell.
    EXPECT_EQ(field.Extinction(glm::dvec3(0.0, 0.0, shell.outer_radius + 1.0)), 0.0);
    EXPECT_EQ(field.Extinction(glm::dvec3(0.0, 0.0, shell.inner_radius - 1.0)), 0.0);
    EXPECT_GT(field.MeanVerticalOpticalDepth(8, 128), 1.0);
}

}  // namespace
}  // namespace zenith::sky::reference
