// Laws of the cloud light transport (sky/shaders/clouds/functions.glsl compiled as C++): phase
// functions integrate to 1, the delta-Eddington diffuse field meets its boundary conditions and
// conserves flux, the sun's and the sky's scattering have their thin and thick limits, and the
// energy-conserving analytic integration (F16 §5.6.3) converges with ~20 samples through the
// real heterogeneous cloud field where the naive sum does not.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <random>

#include "cloud_test_support.h"
#include "reference/cloud_functions.h"

namespace zenith::sky::ref {
namespace {

// ∫ f(μ) 2π dμ over [-1, 1]: Simpson, refined toward μ = ±1 where the lobes peak.
template <class F>
double IntegrateSphere(const F& f) {
    const double edges[] = {-1.0, -0.999, -0.99, -0.9, 0.0, 0.9, 0.99, 0.999, 1.0};
    double sum = 0.0;
    for (int e = 0; e + 1 < 9; ++e) {
        const int n = 4000;
        const double a = edges[e], h = (edges[e + 1] - a) / n;
        double s = f(a) + f(edges[e + 1]);
        for (int i = 1; i < n; ++i) s += (i % 2 ? 4.0 : 2.0) * f(a + i * h);
        sum += s * h / 3.0;
    }
    return 2.0 * kPi * sum;
}

TEST(CloudPhase, HenyeyGreensteinAndDualLobeIntegrateToOne) {
    for (const double g : {-0.7, -0.2, 0.0, 0.3, 0.8, 0.95}) {
        EXPECT_NEAR(IntegrateSphere([&](double nu) { return CloudHenyeyGreensteinPhase(g, nu); }),
                    1.0, 1e-6)
            << "g = " << g;
        // Its mean cosine is g.
        EXPECT_NEAR(
            IntegrateSphere([&](double nu) { return nu * CloudHenyeyGreensteinPhase(g, nu); }), g,
            1e-6);
    }
    for (const double w : {0.0, 0.3, 0.5, 1.0}) {
        EXPECT_NEAR(
            IntegrateSphere([&](double nu) { return CloudDualLobePhase(0.8, -0.5, w, nu); }), 1.0,
            1e-6);
        EXPECT_NEAR(
            IntegrateSphere([&](double nu) { return nu * CloudDualLobePhase(0.8, -0.5, w, nu); }),
            (1.0 - w) * 0.8 + w * -0.5, 1e-6);
    }
    // Silver lining: forward scattering dominates, and the back lobe lifts the back side.
    EXPECT_GT(CloudDualLobePhase(0.8, -0.5, 0.2, 1.0),
              10.0 * CloudDualLobePhase(0.8, -0.5, 0.2, 0.0));
    EXPECT_GT(CloudDualLobePhase(0.8, -0.5, 0.2, -1.0), CloudHenyeyGreensteinPhase(0.8, -1.0));
}

CloudScatteringParameters Scattering(double multiple_scattering = 1.0, double g0 = 0.8,
                                     double g1 = -0.5, double w = 0.2) {
    CloudScatteringParameters p{};
    p.forward_g = g0;
    p.backward_g = g1;
    p.lobe_weight = w;
    p.albedo = 1.0;
    p.multiple_scattering = multiple_scattering;
    p.ground_albedo = 0.0;
    return p;
}

// The delta-Eddington slab (JWW76) from its own radiance: the Marshak conditions at both faces,
// the fluxes that give R and T, a net flux that stays constant through a non-absorbing slab, and
// R from the closed form worked out by hand for g = 0.85, tau = 10, mu0 = 1. All of it for
// JWW76's beam (m = mu0) and for the exact slab's at a grazing Sun (CloudBeamCosine: m down to
// -0.1 at mu0 = 0.05).
TEST(CloudDiffuseField, DeltaEddingtonSlabMeetsItsBoundaryConditionsAndConservesFlux) {
    // f: one Henyey-Greenstein lobe's g^2, and the most CloudDeltaFraction gives, g.
    for (const double g : {0.0, 0.47, 0.85}) {
        for (const double f : {g * g, g}) {
            for (const double tau_total : {0.5, 5.0, 10.0, 50.0}) {
                for (const auto& [mu0, m] :
                     {std::pair{1.0, 1.0}, std::pair{0.5, 0.5}, std::pair{0.15, 0.15},
                      std::pair{1.0, 1.04}, std::pair{0.15, 0.03}, std::pair{0.05, -0.1}}) {
                    const auto direct = [&](double tau) {  // scaled beam, horizontal flux per E
                        return mu0 * std::exp(-(1.0 - f) * tau / mu0);
                    };
                    const vec2 top = CloudDiffuseRadiance(g, f, 0.0, tau_total, mu0, m, 0.0);
                    const vec2 bottom =
                        CloudDiffuseRadiance(g, f, tau_total, tau_total, mu0, m, 0.0);
                    EXPECT_NEAR(top.x + 2.0 / 3.0 * top.y, 0.0, 1e-12);
                    EXPECT_NEAR(bottom.x - 2.0 / 3.0 * bottom.y, 0.0, 1e-12);
                    const vec2 rt = CloudSlabReflectanceTransmittance(g, f, tau_total, mu0, m);
                    // Upward flux pi (I0 - 2/3 I1) at the top, downward pi (I0 + 2/3 I1) plus the
                    // beam at the base.
                    EXPECT_NEAR(kPi * (top.x - 2.0 / 3.0 * top.y), rt.x * mu0, 1e-12);
                    EXPECT_NEAR(kPi * (bottom.x + 2.0 / 3.0 * bottom.y) + direct(tau_total),
                                rt.y * mu0, 1e-12);
                    for (const double x : {0.0, 0.3, 0.7, 1.0}) {
                        const vec2 i =
                            CloudDiffuseRadiance(g, f, x * tau_total, tau_total, mu0, m, 0.0);
                        // Net downward flux 4 pi / 3 I1 plus the beam: constant, (1 - R) mu0.
                        EXPECT_NEAR(4.0 * kPi / 3.0 * i.y + direct(x * tau_total),
                                    (1.0 - rt.x) * mu0, 1e-12);
                        EXPECT_GE(i.x, 0.0);
                    }
                    EXPECT_GT(rt.x, 0.0);
                    EXPECT_LT(rt.x, 1.0);
                }
            }
        }
    }
    // A white ground returns all the light: nothing flows down through the slab, R = 1.
    for (const double tau_total : {0.1, 3.0, 30.0}) {
        const vec2 top = CloudDiffuseRadiance(0.47, 0.47 * 0.47, 0.0, tau_total, 0.6, 0.6, 1.0);
        EXPECT_NEAR(kPi * (top.x - 2.0 / 3.0 * top.y), 0.6, 1e-12);
        // A grey one returns less, and more than a black one.
        const vec2 grey = CloudDiffuseRadiance(0.47, 0.47 * 0.47, 0.0, tau_total, 0.6, 0.6, 0.3);
        EXPECT_GT(grey.x, CloudDiffuseRadiance(0.47, 0.47 * 0.47, 0.0, tau_total, 0.6, 0.6, 0.0).x);
        EXPECT_LT(grey.x, top.x);
    }
    EXPECT_NEAR(CloudSlabReflectanceTransmittance(0.85, 0.85 * 0.85, 10.0, 1.0, 1.0).x,
                (1.5 - (1.0 / 3.0) * (1.0 - std::exp(-2.775))) / (4.0 / 3.0 + 1.5), 1e-12);
    // Thin clouds keep no diffuse light; thick ones reflect nearly all.
    EXPECT_LT(CloudSlabReflectanceTransmittance(0.85, 0.85 * 0.85, 1e-4, 1.0, 1.0).x, 1e-4);
    EXPECT_GT(CloudSlabReflectanceTransmittance(0.85, 0.85 * 0.85, 1e5, 1.0, 1.0).x, 0.9998);
}

// The slab whose diffuse light leaks out sideways (a transverse buckling B): its own boundary
// conditions at both faces over a black and a grey ground, the diffusion length 1 / B deep
// inside a thick slab (the mean radiance falls as exp(-B tau) per unit of unscaled optical
// depth, whatever the phase), less light out of both faces the more it leaks, and the
// non-leaking slab as B -> 0.
TEST(CloudDiffuseField, LeakingSlabMeetsItsBoundaryConditionsAndDiffusionLength) {
    for (const double g : {0.0, 0.47, 0.85}) {
        for (const double f : {g * g, g}) {
            for (const double mu0 : {1.0, 0.5, 0.15}) {
                for (const double a : {0.0, 0.3}) {
                    for (const double tau_total : {0.5, 5.0, 50.0}) {
                        const vec2 top =
                            CloudLeakingDiffuseRadiance(g, f, 0.0, tau_total, mu0, mu0, a, 0.1);
                        const vec2 bottom = CloudLeakingDiffuseRadiance(g, f, tau_total, tau_total,
                                                                        mu0, mu0, a, 0.1);
                        EXPECT_NEAR(top.x + 2.0 / 3.0 * top.y, 0.0, 1e-12);
                        const double beam = mu0 * std::exp(-(1.0 - f) * tau_total / mu0);
                        EXPECT_NEAR((1.0 - a) * bottom.x - 2.0 / 3.0 * (1.0 + a) * bottom.y,
                                    a * beam / kPi, 1e-12);
                    }
                }
                // Deep inside a slab of scaled optical depth 400 (1 - f) tau the beam is gone
                // and the mode growing toward the base is exp(-2 B 290) < 1e-5 of the other: I0
                // falls by exp(-B d) over d. (Where B / (1 - f) passes the solution's bound, 0.5
                // at mu0 = 1, the slab leaks at the bound instead.)
                const double scale = 1.0 / (1.0 - f);
                for (const double leakage : {0.02, 0.05, 0.1}) {
                    if (leakage * scale > 0.5) continue;
                    const double d = 10.0;
                    const vec2 near = CloudLeakingDiffuseRadiance(
                        g, f, 100.0 * scale, 400.0 * scale, mu0, mu0, 0.0, leakage);
                    const vec2 far = CloudLeakingDiffuseRadiance(
                        g, f, 100.0 * scale + d, 400.0 * scale, mu0, mu0, 0.0, leakage);
                    EXPECT_NEAR(far.x / near.x, std::exp(-leakage * d), 1e-5)
                        << "g " << g << " mu0 " << mu0 << " B " << leakage;
                }
                // Upward flux at the top and downward flux (with the beam) at the base: less light
                // leaves through the faces the more leaks out; with none they sum to the light in.
                for (const double tau_total : {2.0, 20.0}) {
                    double previous_r = 2.0, previous_t = 2.0;
                    for (const double leakage : {0.0, 0.01, 0.05, 0.2}) {
                        const vec2 top = CloudLeakingDiffuseRadiance(g, f, 0.0, tau_total, mu0, mu0,
                                                                     0.0, leakage);
                        const vec2 bottom = CloudLeakingDiffuseRadiance(g, f, tau_total, tau_total,
                                                                        mu0, mu0, 0.0, leakage);
                        const double r = kPi * (top.x - 2.0 / 3.0 * top.y) / mu0;
                        const double t = (kPi * (bottom.x + 2.0 / 3.0 * bottom.y) +
                                          mu0 * std::exp(-(1.0 - f) * tau_total / mu0)) /
                                         mu0;
                        if (leakage == 0.0) {
                            EXPECT_NEAR(r + t, 1.0, 1e-12);
                        }
                        EXPECT_LT(r, previous_r);
                        EXPECT_LE(t, previous_t);
                        previous_r = r;
                        previous_t = t;
                    }
                }
                // Finite and non-negative over the whole range the renderer can ask for (a cloud
                // of no height leaks at pi / (1.42 / (1 - g)), the light grazing at mu0 0.05).
                for (const double mu : {0.05, 0.2, 0.7}) {
                    for (const double tau_total : {0.01, 1.0, 30.0, 3000.0}) {
                        for (const double leakage : {1e-3, 0.3, 2.2, 1e3}) {
                            for (const double x : {0.0, 0.01, 0.5, 1.0}) {
                                const vec2 i = CloudLeakingDiffuseRadiance(
                                    g, f, x * tau_total, tau_total, mu, mu, 0.3, leakage);
                                EXPECT_TRUE(std::isfinite(i.x) && std::isfinite(i.y));
                                EXPECT_GE(i.x, -1e-12)
                                    << "g " << g << " mu0 " << mu << " tau " << tau_total << " B "
                                    << leakage << " x " << x;
                            }
                        }
                    }
                }
                // B -> 0: the non-leaking slab, within O(B tau) on both sides of the switch at
                // B tau = 1e-3, for JWW76's beam and one that sends more of its light up.
                for (const double m : {mu0, 0.8 * mu0 - 0.1}) {
                    for (const double x : {0.0, 0.5, 1.0}) {
                        const vec2 tight = CloudDiffuseRadiance(g, f, x * 10.0, 10.0, mu0, m, 0.3);
                        const vec2 leaking =
                            CloudLeakingDiffuseRadiance(g, f, x * 10.0, 10.0, mu0, m, 0.3, 2e-4);
                        EXPECT_NEAR(leaking.x, tight.x, 5e-3 * tight.x) << "m " << m;
                        EXPECT_NEAR(leaking.y, tight.y, 5e-3 * std::abs(tight.y) + 1e-6)
                            << "m " << m;
                    }
                }
            }
        }
    }
}

TEST(CloudSunScattering, FirstOrderAloneInThinCloudsAndTheDiffuseLightInThickOnes) {
    const CloudScatteringParameters full = Scattering(1.0);
    const CloudScatteringParameters single = Scattering(0.0);
    for (const double nu : {-1.0, -0.3, 0.4, 0.99}) {
        // Single scattering: the dual lobe in the shadow.
        EXPECT_NEAR(CloudSunScattering(single, 2.0, 3.0, 0.8, nu, 0.5, 0.0),
                    CloudDualLobePhase(0.8, -0.5, 0.2, nu) * std::exp(-2.0), 1e-15);
        // The thin limit: at the top of a slab of no depth the diffuse field is nothing.
        EXPECT_NEAR(CloudSunScattering(full, 0.0, 0.0, 0.8, nu, -nu, 0.0),
                    CloudSunScattering(single, 0.0, 0.0, 0.8, nu, -nu, 0.0), 1e-12);
        // Deep inside a thick cloud the first order is gone and the diffuse light remains.
        EXPECT_GT(CloudSunScattering(full, 20.0, 20.0, 0.8, nu, -nu, 0.0),
                  1e3 * CloudSunScattering(single, 20.0, 20.0, 0.8, nu, -nu, 0.0));
    }
    // Silver lining kept: looking toward the sun at the sunlit edge, forward scattering wins.
    EXPECT_GT(CloudSunScattering(full, 0.2, 10.0, 0.8, 0.99, 0.8, 0.0),
              3.0 * CloudSunScattering(full, 0.2, 10.0, 0.8, -0.3, 0.8, 0.0));
    // The base of a thick cloud is darker than its top.
    EXPECT_LT(CloudSunScattering(full, 40.0, 0.1, 1.0, 0.0, 1.0, 0.0),
              0.3 * CloudSunScattering(full, 0.1, 40.0, 1.0, 0.0, -1.0, 0.0));
}

// However deep in a cloud, the light is a number: no exponential may overflow where the
// sunlight's has gone to 0 (a rain shaft lit through a cumulonimbus' core, optical depth 2,500
// toward a Sun 17 deg up, drew NaN: the light passed on along the view, its integral alone, is
// exp(sun_optical_depth (1 - mu0 / |mu_view|)) seen more steeply than the Sun). Past about 700
// a double overflows; a float past 88.
TEST(CloudSunScattering, FiniteAndNotNegativeAtAnyDepth) {
    const CloudScatteringParameters full = Scattering(1.0);
    for (const double depth : {50.0, 100.0, 1e3, 1e4, 1e6}) {
        for (const double below : {0.0, 0.5, 50.0}) {
            for (const double mu0 : {0.05, 0.3, 1.0}) {
                for (const double mu_view : {-1.0, -0.3, 0.02, 0.3, 1.0}) {
                    for (const double leakage : {0.0, 0.05}) {
                        const double light =
                            CloudSunScattering(full, depth, below, mu0, 0.5, mu_view, leakage);
                        EXPECT_TRUE(std::isfinite(light) && light >= 0.0)
                            << "depth " << depth << ", below " << below << ", mu0 " << mu0
                            << ", mu_view " << mu_view << ", leakage " << leakage << ": " << light;
                    }
                }
            }
        }
    }
}

TEST(CloudSkyScattering, HalfTheSkyInThinCloudsAllOfItOverWhiteGroundDarkBasesInThickOnes) {
    CloudScatteringParameters p = Scattering();
    // A wisp sees the sky above and nothing below: the mean radiance is half the sky's.
    EXPECT_NEAR(CloudSkyScattering(p, 0.0, 0.0, 0.0), 0.5, 1e-12);
    // Its top reflects pi (I0 - 2/3 I1) = R of the sky's pi L: nothing for a wisp, most of it
    // for a thick deck (R = (1 - g) tau / (4/3 + (1 - g) tau) for diffuse light).
    const double g = CloudAsymmetry(p);
    for (const double tau : {0.0, 2.0, 20.0, 200.0}) {
        const double i0 = CloudSkyScattering(p, 0.0, tau, 0.0);
        const double i1 = (CloudSkyScattering(p, 0.0, tau, 1.0) - i0) / g;
        EXPECT_NEAR(i0 - 2.0 / 3.0 * i1, (1.0 - g) * tau / (4.0 / 3.0 + (1.0 - g) * tau), 1e-12);
    }
    EXPECT_LT(CloudSkyScattering(p, 40.0, 40.0, 1.0), 0.1 * CloudSkyScattering(p, 0.0, 40.0, -1.0));
    p.ground_albedo = 1.0;  // nothing leaves: the field is the sky's radiance everywhere
    for (const double tau : {0.0, 5.0, 50.0}) {
        EXPECT_NEAR(CloudSkyScattering(p, 0.5 * tau, tau, 0.7), 1.0, 1e-12);
    }
}

// --- integration ------------------------------------------------------------------------------

struct Scene {
    CloudLayerParameters layer;
    RepeatTexture2D weather;
    Texture3D shape, detail;
    CloudScatteringParameters scattering = Scattering();
    double sigma_t = 0.0;  // 1/km at density 1
    vec3 sun;

    Scene() {
        // The test cumulus layer, 1-3 km.
        layer = clouds::test::CumulusLayer();
        layer.base_altitude = 1.0;
        layer.top_altitude = 3.0;
        layer.cloud_top_altitude = layer.top_altitude;
        clouds::CloudLayer weather_layer;
        weather_layer.coverage = 0.7;
        weather_layer.cloud_type = 0.5;
        weather_layer.map.kind = clouds::WeatherMapSource::Kind::kPatches;
        weather_layer.map.size = 64;
        weather_layer.map.cells_per_tile = 4;
        weather = ToTexture(clouds::BuildWeatherMap(weather_layer));
        shape = ToTexture(clouds::test::CachedNoise().shape);
        detail = ToTexture(clouds::test::CachedNoise().detail);
        sun = glm::normalize(vec3(0.4, 0.8, 0.2));
    }

    double Extinction(const vec3& p) const {
        return sigma_t *
               SampleCloudDensityAt(layer, weather, shape, detail, vec2(p.x, p.z), p.y).density;
    }

    // Luminance scattered at p toward -view, per unit sun illuminance and per unit σ_s: the
    // octave sum with the optical depth toward the sun from a fixed march (6 steps growing
    // geometrically, F16 §5.5.2), so it is a function of p alone, the same for every estimate.
    double InScattered(const vec3& p, double nu) const {
        double depth = 0.0, s = 0.0, step = 0.05;
        for (int i = 0; i < 6; ++i) {
            depth += Extinction(p + (s + 0.5 * step) * sun) * step;
            s += step;
            step *= 2.0;
        }
        // The cloud below p plays no part here: a fixed slab of depth 10 under it.
        return CloudSunScattering(scattering, depth, 10.0, sun.y, nu, 0.0, 0.0);
    }

    // Scattered luminance along a ray through the layer (altitudes as flat y: the shell's
    // curvature plays no part in the integration).
    double March(const vec3& origin, const vec3& direction, double length, int steps,
                 bool analytic) const {
        const double nu = glm::dot(direction, sun);
        const double dt = length / steps;
        vec3 luminance(0.0);
        double transmittance = 1.0;
        for (int i = 0; i < steps; ++i) {
            const vec3 p = origin + (i + 0.5) * dt * direction;
            const double extinction = Extinction(p);
            const double source =
                extinction > 0.0 ? scattering.albedo * extinction * InScattered(p, nu) : 0.0;
            if (analytic) {
                CloudIntegrateStep(vec3(source), extinction, dt, luminance, transmittance);
            } else {
                // F16 Listing 1, (S) then (T): the usual sum.
                luminance += transmittance * source * dt;
                transmittance *= std::exp(-extinction * dt);
            }
        }
        return luminance.x;
    }
};

TEST(CloudIntegration, AnalyticConvergesWithTwentySamplesWhereTheNaiveSumDoesNot) {
    Scene scene;
    // Stratocumulus-like extinction, 20 /km at density 1 (F16 §5.2 reports 40-60 /km for
    // stratus): 20 samples over 4 km take optical depths up to 4 per step.
    scene.sigma_t = 20.0;
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    double reference_sum = 0.0, analytic_sum = 0.0, naive_sum = 0.0;
    double worst_analytic = 0.0;
    int rays = 0;
    std::vector<double> analytic_errors;
    while (rays < 24) {
        // Slanted rays through the layer from below it to above it, 4 km long.
        const double azimuth = 2.0 * kPi * u(rng);
        const double elevation = 0.35 + 0.5 * u(rng);
        const vec3 direction(std::cos(elevation) * std::cos(azimuth), std::sin(elevation),
                             std::cos(elevation) * std::sin(azimuth));
        const vec3 origin(80.0 * u(rng), 0.9, 80.0 * u(rng));
        const double length = 2.2 / std::sin(elevation);
        const double reference = scene.March(origin, direction, length, 1000, true);
        if (reference < 1e-4) continue;  // a clear ray tests nothing
        // The reference has converged: 4000 samples agree to 0.5%.
        if (rays < 3) {
            EXPECT_NEAR(scene.March(origin, direction, length, 4000, true), reference,
                        5e-3 * reference);
        }
        const double analytic = scene.March(origin, direction, length, 20, true);
        const double naive = scene.March(origin, direction, length, 20, false);
        reference_sum += reference, analytic_sum += analytic, naive_sum += naive;
        analytic_errors.push_back(std::abs(analytic / reference - 1.0));
        worst_analytic = std::max(worst_analytic, analytic_errors.back());
        ++rays;
    }
    std::sort(analytic_errors.begin(), analytic_errors.end());
    const double analytic_error = std::abs(analytic_sum / reference_sum - 1.0);
    const double naive_error = std::abs(naive_sum / reference_sum - 1.0);
    std::printf(
        "20 samples vs 1000 over %d rays: analytic %+.1f%% (median ray %.1f%%, worst "
        "%.1f%%), naive %+.1f%%\n",
        rays, 100.0 * (analytic_sum / reference_sum - 1.0),
        100.0 * analytic_errors[analytic_errors.size() / 2], 100.0 * worst_analytic,
        100.0 * (naive_sum / reference_sum - 1.0));
    EXPECT_LT(analytic_error, 0.05);
    EXPECT_LT(analytic_errors[analytic_errors.size() / 2], 0.05);
    EXPECT_GT(naive_error, 0.3);
}

TEST(CloudIntegration, AStepNeverAddsMoreThanItsSourceOverExtinction) {
    // Energy conservation of one slab, whatever its thickness (F16 App. C, Fig. 53).
    for (const double sigma : {1e-9, 1e-3, 0.5, 5.0, 50.0, 5000.0}) {
        for (const double dt : {1e-4, 0.01, 0.2, 3.0}) {
            vec3 luminance(0.0);
            double transmittance = 1.0;
            CloudIntegrateStep(vec3(sigma), sigma, dt, luminance, transmittance);
            // σ_s = σ_t and unit light: the slab returns 1 - T.
            EXPECT_NEAR(luminance.x, 1.0 - std::exp(-sigma * dt), 1e-12);
            EXPECT_LE(luminance.x, 1.0);
            EXPECT_NEAR(transmittance, std::exp(-sigma * dt), 1e-15);
        }
    }
    // Many thin steps equal one thick one in a homogeneous medium.
    vec3 many(0.0), one(0.0);
    double t_many = 1.0, t_one = 1.0;
    for (int i = 0; i < 100; ++i) CloudIntegrateStep(vec3(2.0), 7.0, 0.01, many, t_many);
    CloudIntegrateStep(vec3(2.0), 7.0, 1.0, one, t_one);
    EXPECT_NEAR(many.x, one.x, 1e-12);
    EXPECT_NEAR(t_many, t_one, 1e-12);
}

}  // namespace
}  // namespace zenith::sky::ref
