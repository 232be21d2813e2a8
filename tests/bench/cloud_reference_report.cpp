// The cloud path tracer (reference/cloud_path_tracer.h) as markdown tables: not a Google
// Benchmark, a plain main built by tests/bench/CMakeLists.txt's glob.
//
//   cloud_reference_report --part energy   [--samples N] [--threads T] [--seed S]
//   cloud_reference_report --part overcast [--samples N] [--threads T] [--seed S] [--utc T]
//   cloud_reference_report --part cumulus  [--samples N] [--threads T] [--seed S] [--maps]
//                                          [--single-scattering]
//                                          [--max-steps N] [--min-step M]
//   cloud_reference_report --part formal
//   cloud_reference_report --part grazing  [--samples N] [--threads T] [--seed S]
//   cloud_reference_report --part decks    [--samples N] [--threads T] [--seed S]
//   cloud_reference_report --part thin     [--samples N] [--threads T] [--seed S]
//                                          [--view-elevation DEG]
// (--no-lit-face: overcast, cumulus, formal, decks and thin with CloudSettings::lit_face_source =
// false; --no-column-steps: overcast, cumulus, decks and thin with CloudSettings::column_steps =
// false; --max-steps, --min-step, --shadow-steps, --thick-step-refinement: overcast, cumulus,
// decks and thin with those march steps, samples toward the light and thick steps' shadow
// refinement.)
//
// energy: a non-absorbing HG slab (g = 0.85, mu0 = 0.6) over a black ground, R and T by photons
//   and by camera paths, R + T, and the time per path, over optical depths 1-128.
// overcast: the overcast_stratus preset at 2024-06-21T11:00:00Z (or --utc), 47.45 N 8.56 E (sun
//   from the ephemeris), camera at 8000 m looking straight down (pitch -89.9 deg) and on the ground
//   looking up: reference luminance L, the horizontal illuminance E on the cloud top and at the
//   ground, and the effective albedo / transmittance pi L / E; beside it the renderer's cloud pass
//   for the same ray, evaluated on the CPU (reference/cloud_trace.h, the shared GLSL compiled as
//   C++, over CPU-built LUTs from AtmosphereReference): its cloud luminance and transmittance.
// cumulus: an isolated cumulus on a small image, sun behind, beside and in front (CumulusPart),
//   N paths per pixel; --maps prints each case's reference image (% of its peak) and the
//   renderer / reference ratio over the pixels the median counts.
// formal: the renderer's source per unit sigma_s (CloudSunScattering, the shared GLSL) through a
//   homogeneous non-absorbing slab over a black ground, integrated along every exit direction by
//   a fine deterministic quadrature instead of the march (FormalPart): R and T against the
//   delta-Eddington closed form, up to a semi-infinite slab.
// grazing: the renderer's slab (its source by quadrature, as formal) and the adding-doubling
//   solution it is fitted to (ConservativeSlabTransfer) against the path tracer's photons (the
//   same dual lobe, black ground) as the sun goes down to 3 deg, optical depths 2-20
//   (GrazingPart), and the share of the scaled beam's scattering the two-stream closed form
//   would have to send up to give the path tracer's R.
// decks: where the march's fluxes through decks of optical depth 8-128 part from the path
//   tracer's (DecksPart): R and T of the path tracer (photons), of the renderer's source by
//   quadrature (formal), and of the march (the slab test's parabolic deck) at its default steps,
//   with fine primary steps, and with fine primary and shadow steps.
// thin: where the light scattered more than once goes in thin and moderate decks (ThinPart):
//   a homogeneous slab of optical depth 0.06-4 seen from below and above at 55 deg (or
//   --view-elevation) with the sun 40 deg up behind, beside and ahead of the camera, the
//   renderer's march with and without its diffuse field against the path tracer's slab with all
//   orders and with one scattering.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

#include "zenith/geo/ephemeris.h"
#include "zenith/geo/observer.h"
#include "zenith/geo/time.h"
#include "zenith/sky/atmosphere.h"
#include "zenith/sky/reference/atmosphere_reference.h"
#include "zenith/sky/reference/cloud_path_tracer.h"
#include "zenith/sky/sky_state.h"
// The renderer's cloud pass on the CPU (private headers; this target sees sky/src).
#include "cloud_march_support.h"
#include "clouds/slab_transfer.h"
#include "reference/cloud_trace.h"
#include "zenith/sky/image_io.h"

namespace {

using namespace zenith::sky;
using namespace zenith::sky::reference;

constexpr double kPi = std::numbers::pi;

// The path tracer's homogeneous slab with the renderer's dual lobe (settings' phase).
SlabProblem RendererPhaseSlab(const CloudSettings& settings, double tau, double mu0) {
    SlabProblem problem;
    problem.optical_depth = tau;
    problem.phase = CloudPhase{settings.forward_g, settings.backward_g, settings.lobe_weight};
    problem.mu0 = mu0;
    return problem;
}

CloudPathTraceOptions TraceOptions(std::int64_t samples, int threads, std::uint64_t seed) {
    CloudPathTraceOptions options;
    options.threads = threads;
    options.seed = seed;
    options.samples = samples;
    return options;
}

void EnergyPart(std::int64_t samples, int threads, std::uint64_t seed) {
    std::printf(
        "Non-absorbing Henyey-Greenstein slab, g = 0.85, mu0 = 0.6, black ground; photons: %lld "
        "light paths, camera: %lld camera paths for each of R and T (threads %d).\n\n",
        static_cast<long long>(samples * 5), static_cast<long long>(samples), threads);
    std::printf(
        "| tau | R (photons) | T (photons) | R + T (photons) | R (camera) | T (camera) | "
        "R + T (camera) | us/photon | us/camera path |\n");
    std::printf("|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    for (const double tau : {1.0, 2.0, 4.0, 8.0, 16.0, 32.0, 64.0, 128.0}) {
        SlabProblem problem;
        problem.optical_depth = tau;
        problem.phase = CloudPhase{0.85, 0.0, 0.0};
        problem.mu0 = 0.6;
        CloudPathTraceOptions options = TraceOptions(samples * 5, threads, seed);
        const SlabFluxes photons = SlabFluxesFromPhotons(problem, options);
        options.samples = samples;
        const SlabFluxes camera = SlabFluxesFromRadiance(problem, options);
        std::printf(
            "| %g | %.4f ± %.4f | %.4f ± %.4f | %.6f | %.4f ± %.4f | %.4f ± %.4f | %.4f ± %.4f "
            "| %.2f | %.1f |\n",
            tau, photons.reflectance, photons.reflectance_error, photons.transmittance,
            photons.transmittance_error, photons.reflectance + photons.transmittance,
            camera.reflectance, camera.reflectance_error, camera.transmittance,
            camera.transmittance_error, camera.reflectance + camera.transmittance,
            std::hypot(camera.reflectance_error, camera.transmittance_error),
            1e6 * photons.seconds * threads / static_cast<double>(photons.samples),
            1e6 * camera.seconds * threads / (2.0 * static_cast<double>(camera.samples)));
        std::fflush(stdout);
    }
    std::printf("\n(± one standard error; times are thread-seconds per path.)\n");
}

void FormalPart(const CloudSettings& settings) {
    const ref::CloudScatteringParameters p = ref::DefaultScattering(0.0, settings);
    ref::CloudScatteringParameters single_only = p;
    single_only.multiple_scattering = 0.0;
    const double g = ref::CloudAsymmetry(p);
    const double f = ref::CloudDeltaFraction(p);
    std::printf(
        "The renderer's source (CloudSunScattering, default CloudSettings, g = %.2f) through a "
        "homogeneous non-absorbing slab over a black ground, by quadrature: R and T (T with the "
        "direct beam) against the delta-Eddington closed form; and the light scattered more than "
        "once that leaves the slab, the renderer's against all that the direct beam and the "
        "first order leave (1 - direct - first order's R and T: the slab absorbs nothing).\n\n",
        g);
    std::printf(
        "| tau | mu0 | R | R closed | T | T closed | R + T | orders >= 2: renderer / all |\n");
    std::printf("|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    for (const double tau : {0.5, 1.0, 2.0, 5.0, 10.0, 20.0, 50.0, 200.0}) {
        for (const double mu0 : {1.0, 0.5, 0.25}) {
            const double direct = std::exp(-tau / mu0);
            const double r = ref::FormalSlabFlux(p, tau, mu0, true, 4000, 48);
            const double t = ref::FormalSlabFlux(p, tau, mu0, false, 4000, 48) + direct;
            const double first = ref::FormalSlabFlux(single_only, tau, mu0, true, 4000, 48) +
                                 ref::FormalSlabFlux(single_only, tau, mu0, false, 4000, 48);
            const ref::vec2 closed = ref::CloudSlabReflectanceTransmittance(
                g, f, tau, mu0, ref::CloudBeamCosine(p, tau, mu0));
            std::printf("| %g | %.2f | %.4f | %.4f | %.4f | %.4f | %.4f | %.3f |\n", tau, mu0, r,
                        closed.x, t, closed.y, r + t,
                        (r + t - direct - first) / (1.0 - direct - first));
        }
    }
}

void GrazingPart(const CloudSettings& settings, std::int64_t samples, int threads,
                 std::uint64_t seed) {
    const ref::CloudScatteringParameters p = ref::DefaultScattering(0.0, settings);
    const double g = ref::CloudAsymmetry(p);
    const double f = ref::CloudDeltaFraction(p);
    std::printf(
        "A homogeneous non-absorbing slab over a black ground lit at cosine mu0: the path "
        "tracer's photons (%lld, the renderer's dual lobe) against the adding-doubling "
        "solution (ConservativeSlabTransfer) and the renderer's source through the slab by "
        "quadrature (formal); T with the direct beam. m: the beam's cosine in the renderer's "
        "diffuse field (CloudBeamCosine; delta-Eddington's is mu0). gamma3: the share of the "
        "delta-scaled beam's scattering that the two-stream closed form R = (g1 t + (gamma3 - g1 "
        "mu0)(1 - exp(-t / mu0))) / (1 + g1 t), g1 = 3/4, t = (1 - f) tau, would send up to give "
        "the path tracer's R (delta-Eddington: 1/2 here, g' = %.2f).\n\n",
        static_cast<long long>(samples), (g - f) / (1.0 - f));
    std::printf(
        "| tau | mu0 | path tracer R | path tracer T | adding-doubling R | renderer R | renderer T "
        "| renderer / path tracer, T | R + T | m | gamma3 |\n");
    std::printf("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    for (const double tau : {2.0, 5.0, 10.0, 20.0}) {
        const std::vector<double> cosines = {1.0, 0.5, 0.29, 0.17, 0.1, 0.05};
        const std::vector<SlabTransfer> exact = ConservativeSlabTransfer(
            settings.forward_g, settings.backward_g, settings.lobe_weight, tau, cosines);
        for (std::size_t k = 0; k < cosines.size(); ++k) {
            const double mu0 = cosines[k];
            const SlabFluxes photons = SlabFluxesFromPhotons(RendererPhaseSlab(settings, tau, mu0),
                                                             TraceOptions(samples, threads, seed));
            const double direct = std::exp(-tau / mu0);
            const double r = ref::FormalSlabFlux(p, tau, mu0, true, 4000, 48);
            const double t = ref::FormalSlabFlux(p, tau, mu0, false, 4000, 48) + direct;
            const double scaled = (1.0 - f) * tau;
            const double gamma3 = (photons.reflectance * (1.0 + 0.75 * scaled) - 0.75 * scaled) /
                                      (1.0 - std::exp(-scaled / mu0)) +
                                  0.75 * mu0;
            std::printf(
                "| %g | %.2f | %.4f ± %.4f | %.4f ± %.4f "
                "| %.4f | %.4f | %.4f | %.3f | %.4f | %.3f | %.3f |\n",
                tau, mu0, photons.reflectance, photons.reflectance_error, photons.transmittance,
                photons.transmittance_error, exact[k].reflectance, r, t, t / photons.transmittance,
                r + t, ref::CloudBeamCosine(p, tau, mu0), gamma3);
            std::fflush(stdout);
        }
    }
    std::printf("\n(± one standard error.)\n");
}

// The march's R and T (direct beam included) through the slab test's deck, with its primary
// step at most `step_km` (0: the default) and, if fine_shadow, a shadow march of 100 samples
// 15 m apart (1.5 km: through the deck at the sun's 60 deg).
std::pair<double, double> MarchedSlabFluxes(const CloudSettings& settings, double tau, double mu0,
                                            double step_km, bool fine_shadow) {
    ref::Slab slab(tau, settings);
    if (step_km > 0.0) {
        slab.march.min_step = step_km;
        slab.march.max_steps = 1024.0;
    }
    if (fine_shadow) {
        slab.march.shadow_steps = 100.0;
        slab.march.shadow_first_step = 0.015;
        slab.march.shadow_growth = 1.0;
    }
    const ref::Sunlight sun(mu0);
    return {slab.Flux(sun, mu0, true), slab.Flux(sun, mu0, false) + std::exp(-tau / mu0)};
}

void ThinPart(const CloudSettings& settings, std::int64_t samples, int threads, std::uint64_t seed,
              double view_elevation_deg) {
    constexpr double kSunElevation = 40.0 * kPi / 180.0;
    const double view_elevation = view_elevation_deg * kPi / 180.0;
    const double mu0 = std::sin(kSunElevation);
    CloudSettings first_order = settings;
    first_order.multiple_scattering = 0.0;
    const char* names[] = {"behind the camera", "beside", "ahead"};
    const double azimuths[] = {0.0, 0.5 * kPi, kPi};
    // The direction the light leaves the slab in (azimuth from the sunlight's own; the camera
    // looks against it), and its scattering angle from the sunlight's way, in degrees.
    const auto leaving = [&](bool above, int k) {
        const double sine = std::cos(view_elevation);
        return ref::vec3(sine * std::cos(azimuths[k]), sine * std::sin(azimuths[k]),
                         above ? std::sin(view_elevation) : -std::sin(view_elevation));
    };
    const auto angle = [&](bool above, int k) {
        const ref::vec3 sunlight(-std::cos(kSunElevation), 0.0, -std::sin(kSunElevation));
        return std::acos(std::clamp(dot(sunlight, leaving(above, k)), -1.0, 1.0)) * 180.0 / kPi;
    };
    std::printf(
        "Homogeneous non-absorbing decks (default dual lobe) over a black ground, the sun %.0f "
        "deg up, seen %.0f deg off the horizon from below (transmitted) and above (reflected) with "
        "the sun behind the camera, beside it and ahead of it (%.0f, %.0f and %.0f deg from the "
        "light's way below, %.0f, %.0f and %.0f deg above): L / E0 of the renderer's march (%d m "
        "steps at most %d, 16 sample offsets) against "
        "the path tracer's slab (%lld paths; all orders, and paths of one scattering). Ratios "
        "renderer / path tracer; 'more than once' is all minus one scattering on each side, ± "
        "the path tracer's standard error of it.\n\n",
        kSunElevation * 180.0 / kPi, view_elevation_deg, angle(false, 0), angle(false, 1),
        angle(false, 2), angle(true, 0), angle(true, 1), angle(true, 2),
        static_cast<int>(settings.min_step), settings.max_steps, static_cast<long long>(samples));
    std::printf(
        "| tau | side | sun | path tracer L / E0 | all | one scattering | more than once |\n");
    std::printf("|---:|---|---|---:|---:|---:|---:|\n");
    SlabProblem problem = RendererPhaseSlab(settings, 0.0, mu0);
    const CloudPathTraceOptions options = TraceOptions(samples, threads, seed);
    CloudPathTraceOptions single = options;
    single.max_bounces = 1;
    const ref::Sunlight sun(mu0);
    for (const double tau : {0.06, 0.25, 1.0, 4.0}) {
        const ref::Slab slab(tau, settings);
        problem.optical_depth = tau;
        for (const bool above : {false, true}) {
            for (int k = 0; k < 3; ++k) {
                const ref::vec3 out = leaving(above, k);
                const ref::vec3 camera(0.0, 0.0, ref::kR + (above ? 5.0 : 0.5));
                const auto march = [&](const CloudSettings& s) {
                    return ref::CloudLuminance(sun, slab.layer, slab.weather, slab.shape,
                                               slab.detail, ref::DefaultScattering(0.0, s),
                                               slab.march, camera, -out, 16);
                };
                const double all = march(settings), once = march(first_order);
                const SlabRadianceResult traced =
                    SlabRadiance(problem, out.z, azimuths[k], options);
                const SlabRadianceResult traced_once =
                    SlabRadiance(problem, out.z, azimuths[k], single);
                const double more = traced.value - traced_once.value;
                std::printf("| %g | %s | %s | %.5f | %.3f | %.3f | %.2f ± %.2f |\n", tau,
                            above ? "reflected" : "transmitted", names[k], traced.value,
                            all / traced.value, once / traced_once.value, (all - once) / more,
                            std::hypot(traced.standard_error, traced_once.standard_error) *
                                (all - once) / (more * more));
                std::fflush(stdout);
            }
        }
    }
}

void DecksPart(const CloudSettings& settings, std::int64_t samples, int threads,
               std::uint64_t seed) {
    const ref::CloudScatteringParameters p = ref::DefaultScattering(0.0, settings);
    std::printf(
        "Non-absorbing decks (default dual lobe) over a black ground: R and T (T with the direct "
        "beam) of the path tracer (%lld photons, ± one standard error), of the renderer's source "
        "by quadrature (formal) and of its march through the parabolic deck: default steps "
        "(%.0f m primary, %d shadow samples from %.0f m), primary steps of 8 m, and 8 m with 100 "
        "shadow samples 15 m apart.\n\n",
        static_cast<long long>(samples), settings.min_step, settings.shadow_steps,
        settings.shadow_first_step);
    std::printf(
        "| tau | mu0 | path tracer R | T | formal R | T | march R | T | 8 m steps R | T | 8 m "
        "steps, fine shadow R | T |\n");
    std::printf("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    for (const double tau : {8.0, 32.0, 128.0}) {
        for (const double mu0 : {1.0, 0.5}) {
            const SlabFluxes traced = SlabFluxesFromPhotons(RendererPhaseSlab(settings, tau, mu0),
                                                            TraceOptions(samples, threads, seed));
            const double direct = std::exp(-tau / mu0);
            const auto coarse = MarchedSlabFluxes(settings, tau, mu0, 0.0, false);
            const auto fine = MarchedSlabFluxes(settings, tau, mu0, 0.008, false);
            const auto finest = MarchedSlabFluxes(settings, tau, mu0, 0.008, true);
            std::printf(
                "| %g | %.1f | %.4f ± %.4f | %.4f ± %.4f | %.4f | %.4f | %.4f | %.4f | %.4f | "
                "%.4f | %.4f | %.4f |\n",
                tau, mu0, traced.reflectance, traced.reflectance_error, traced.transmittance,
                traced.transmittance_error, ref::FormalSlabFlux(p, tau, mu0, true, 4000, 48),
                ref::FormalSlabFlux(p, tau, mu0, false, 4000, 48) + direct, coarse.first,
                coarse.second, fine.first, fine.second, finest.first, finest.second);
            std::fflush(stdout);
        }
    }
}

void OvercastPart(const CloudSettings& settings, std::int64_t samples, int threads,
                  std::uint64_t seed, const std::string& utc) {
    const double lat = 47.45, lon = 8.56;
    const zenith::geo::Time time = zenith::geo::TimeFromIso8601(utc);
    const Atmosphere earth = LoadAtmosphere("earth");
    const clouds::Weather weather = clouds::LoadWeather("overcast_stratus");
    const clouds::CloudNoiseLoad noise = clouds::LoadOrGenerateCloudNoise(settings.noise);
    const CloudField field(weather, settings, noise.noise, earth.bottom_radius);

    // The sun from the ephemeris, as `zenith render` places it (ENU frame at the observer = the
    // weather frame when the weather's origin is the observer).
    const zenith::geo::Observer observer(lat, lon, 0.0);
    const zenith::geo::SkyEphemeris ephemeris = zenith::geo::Ephemeris().Compute(time, observer);
    const SkyState state =
        MakeSkyState(ephemeris, observer, earth,
                     zenith::geo::Attitude::FromDegrees(0.0, -89.9, 0.0), 20.0 * kPi / 180.0, 1.0);
    CloudScene scene;
    scene.atmosphere = earth;
    scene.atmosphere.solar_illuminance = state.scene.lights.sun_illuminance;  // at today's distance
    scene.clouds = &field;
    scene.sun_direction = glm::normalize(state.scene.lights.sun_direction);

    const CloudField::Shell& shell = field.shells().front();
    const double r = earth.bottom_radius;
    std::printf(
        "overcast_stratus at %s, %.2f N %.2f E: sun elevation %.2f deg, "
        "E_sun(TOA) Y = %.0f lux; deck %.0f-%.0f m (clouds' top), mean vertical optical depth "
        "%.2f; ground albedo %.2f; %lld paths per number (threads %d).\n\n",
        utc.c_str(), lat, lon, std::asin(scene.sun_direction.z) * 180.0 / kPi,
        0.2126 * scene.atmosphere.solar_illuminance.x +
            0.7152 * scene.atmosphere.solar_illuminance.y +
            0.0722 * scene.atmosphere.solar_illuminance.z,
        shell.inner_radius - r, shell.outer_radius - r, field.MeanVerticalOpticalDepth(32, 256),
        earth.ground_albedo.x, static_cast<long long>(samples), threads);

    const CloudPathTraceOptions options = TraceOptions(samples, threads, seed);
    const double pitch = 89.9 * kPi / 180.0;
    const glm::dvec3 down(0.0, std::cos(pitch), -std::sin(pitch));
    const glm::dvec3 up(0.0, std::cos(pitch), std::sin(pitch));
    const glm::dvec3 high(0.0, 0.0, r + 8000.0);
    const glm::dvec3 low(0.0, 0.0, r + 2.0);

    const CloudPathTraceResult l_above = CloudPathTrace(scene, high, down, options);
    const CloudPathTraceResult l_below = CloudPathTrace(scene, low, up, options);
    const CloudPathTraceResult e_top =
        CloudHorizontalIlluminance(scene, glm::dvec3(0.0, 0.0, shell.outer_radius), options);
    const CloudPathTraceResult e_ground =
        CloudHorizontalIlluminance(scene, glm::dvec3(0.0, 0.0, r), options);

    const auto ratio_error = [](double a, double da, double b, double db) {
        return a / b * std::hypot(da / a, db / b);
    };
    std::printf("| view | L (Y, cd/m²) | E (Y, lux) | pi L / E | vertices/path | us/path |\n");
    std::printf("|---|---:|---:|---:|---:|---:|\n");
    const auto row = [&](const char* name, const CloudPathTraceResult& l, const char* e_name,
                         const CloudPathTraceResult& e) {
        const double albedo = kPi * l.luminance / e.luminance;
        std::printf(
            "| %s | %.0f ± %.0f | %s %.0f ± %.0f | %.3f ± %.3f | %.1f | %.0f |\n", name,
            l.luminance, l.luminance_error, e_name, e.luminance, e.luminance_error, albedo,
            ratio_error(kPi * l.luminance, kPi * l.luminance_error, e.luminance, e.luminance_error),
            l.mean_vertices, 1e6 * l.seconds * threads / static_cast<double>(l.samples));
    };
    row("8000 m, down", l_above, "cloud top", e_top);
    row("ground, up", l_below, "ground", e_ground);
    row("ground, up", l_below, "cloud top", e_top);
    std::printf("\nRGB (cd/m²): from 8000 m %.0f %.0f %.0f; from the ground %.0f %.0f %.0f.\n",
                l_above.radiance.x, l_above.radiance.y, l_above.radiance.z, l_below.radiance.x,
                l_below.radiance.y, l_below.radiance.z);
    std::printf("(± one standard error; times are thread-seconds per path.)\n");

    // The renderer's cloud pass for the same rays (its CPU twin; block = 1).
    const AtmosphereReference luts(earth);
    Lights lights = state.scene.lights;
    const auto renderer = [&](const glm::dvec3& position, const glm::dvec3& view) {
        Camera camera = state.view.camera;
        camera.position = position;
        const ref::CloudScene cloud_scene = ref::MakeCloudScene(
            earth, luts.transmittance(), luts.multiple_scattering(), luts.ground_irradiance(),
            weather, settings, noise.noise, camera, lights, CloudView{});
        // The mean over the sample offsets the renderer's reprojection averages over frames.
        constexpr int kJitters = 16;
        glm::dvec4 sum(0.0);
        for (int j = 0; j < kJitters; ++j) {
            sum +=
                ref::TraceClouds(cloud_scene, position / 1000.0,
                                 (glm::length(position) - r) / 1000.0, view, (j + 0.5) / kJitters);
        }
        return sum / double(kJitters);
    };
    const glm::dvec4 above = renderer(high, down);
    const glm::dvec4 below = renderer(low, up);
    const auto y = [](const glm::dvec4& v) { return 0.2126 * v.x + 0.7152 * v.y + 0.0722 * v.z; };
    std::printf(
        "\nRenderer (cloud pass, CPU twin), same rays: from 8000 m L_clouds = %.0f cd/m², "
        "T = %.4f, pi L / E(cloud top, reference) = %.3f; from the ground L_clouds = %.0f cd/m², "
        "T = %.4f, pi L / E(ground, reference) = %.3f, pi L / E(cloud top, reference) = %.3f. "
        "(The frame adds T times what lies behind the clouds.)\n",
        y(above), above.w, kPi * y(above) / e_top.luminance, y(below), below.w,
        kPi * y(below) / e_ground.luminance, kPi * y(below) / e_top.luminance);
}

// The isolated cumulus of cloud_march_support.h against the path tracer, N paths per pixel.
// The reference in % of its peak beside renderer / reference wherever the reference has over
// 1 % of its peak, '*' where the median counts the pixel (over a fifth of the peak), '.'
// elsewhere; the top row first. Then the share of the image's light in the pixels the median
// leaves out, and the renderer's over the reference's there.
void PrintCumulusMaps(const ref::IsolatedCumulusCase& c) {
    const std::vector<double>& traced = c.reference_pixels;
    const double peak = *std::max_element(traced.begin(), traced.end());
    const std::size_t width = static_cast<std::size_t>(c.width);
    std::printf("\n%s: the reference, %% of its peak | renderer / reference\n", c.name);
    for (std::size_t row = traced.size() / width; row-- > 0;) {
        for (std::size_t i = row * width; i < (row + 1) * width; ++i) {
            std::printf("%4.0f", 100.0 * traced[i] / peak);
        }
        std::printf("  |");
        for (std::size_t i = row * width; i < (row + 1) * width; ++i) {
            if (traced[i] > 0.01 * peak) {
                const bool counted = traced[i] > ref::kCumulusCloudPixelShare * peak;
                std::printf("%5.2f%c", c.renderer_pixels[i] / traced[i], counted ? '*' : ' ');
            } else {
                std::printf("     .");
            }
        }
        std::printf("\n");
    }
    double dim_reference = 0.0, dim_renderer = 0.0, all_reference = 0.0;
    for (std::size_t i = 0; i < traced.size(); ++i) {
        all_reference += traced[i];
        if (!(traced[i] > ref::kCumulusCloudPixelShare * peak)) {
            dim_reference += traced[i];
            dim_renderer += c.renderer_pixels[i];
        }
    }
    std::printf(
        "pixels the median leaves out: %.1f %% of the reference's light; renderer / "
        "reference there %.3f\n",
        100.0 * dim_reference / all_reference, dim_renderer / dim_reference);
}

// single: the renderer's first order alone (multiple_scattering 0) against the path tracer's
// single scattering.
void CumulusPart(CloudSettings settings, std::int64_t samples, int threads, std::uint64_t seed,
                 bool maps, bool single) {
    const auto start = std::chrono::steady_clock::now();
    if (single) settings.multiple_scattering = 0.0;
    const std::vector<ref::IsolatedCumulusCase> cases = ref::CompareIsolatedCumulus(
        settings, clouds::LoadOrGenerateCloudNoise(settings.noise).noise,
        std::filesystem::temp_directory_path() / ("zenith-cumulus-" + std::to_string(::getpid())),
        samples, threads, seed, single ? 1 : 0);
    for (const ref::IsolatedCumulusCase& c : cases) {
        std::printf(
            "isolated cumulus, %-22s: mean L/E renderer %.5f, reference %.5f +- %.5f (ratio "
            "%.3f); median per-pixel |difference| %.1f %% over %zu cloud pixels (the "
            "reference's noise alone: %.1f %%)\n",
            c.name, c.renderer, c.reference, c.reference_error, c.renderer / c.reference,
            100.0 * c.median_difference, c.cloud_pixels, 100.0 * c.reference_noise);
    }
    std::printf("(%lld paths per pixel, %.1f s)\n", static_cast<long long>(samples),
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    if (maps) {
        for (const ref::IsolatedCumulusCase& c : cases) PrintCumulusMaps(c);
    }
}

}  // namespace

int main(int argc, char** argv) {
    std::string part;
    std::int64_t samples = 0;
    int threads = 2;
    std::uint64_t seed = 1;
    bool maps = false;
    bool single = false;
    CloudSettings settings;
    double view_elevation = 55.0;
    std::string utc = "2024-06-21T11:00:00Z";
    CLI::App app{"The cloud path tracer against closed forms and the renderer (BENCHMARKS.md)"};
    app.add_option("--part", part, "energy, overcast, cumulus, formal, grazing, decks or thin")
        ->required()
        ->check(
            CLI::IsMember({"energy", "overcast", "cumulus", "formal", "grazing", "decks", "thin"}));
    app.add_option(
           "--samples", samples,
           "paths (default: energy, overcast 20000; cumulus 256 per pixel; decks 40000; thin "
           "200000 per direction; grazing 200000 photons)")
        ->check(CLI::Range(std::int64_t{2}, std::int64_t{1} << 32));
    app.add_option("--threads", threads)->check(CLI::Range(1, 1024));
    app.add_option("--seed", seed)->check(CLI::Range(std::uint64_t{0}, std::uint64_t{1} << 62));
    app.add_flag("--maps", maps, "cumulus: print each case's images");
    app.add_flag("--single-scattering", single,
                 "cumulus: single scattering on both sides (the renderer's first order, the path "
                 "tracer's paths of one scattering)");
    app.add_flag(
        "!--no-lit-face", settings.lit_face_source,
        "overcast, cumulus, formal, decks, thin: the renderer without the lit face's source");
    app.add_flag(
        "!--no-column-steps", settings.column_steps,
        "decks, overcast, cumulus, thin: each step's sample for a point (the midpoint rule)");
    app.add_option(
           "--max-steps", settings.max_steps,
           "decks, overcast, cumulus, thin: the march's primary steps per layer crossing at "
           "most (CloudSettings::max_steps, default 64): with --min-step, the march "
           "converged, apart from the default steps' own error")
        ->check(CLI::Range(1, 4096));
    app.add_option("--min-step", settings.min_step,
                   "decks, overcast, cumulus, thin: m, the step of a short crossing (default 120)")
        ->check(CLI::Range(1.0, 10000.0));
    app.add_option("--thick-step-refinement", settings.thick_step_refinement,
                   "decks, overcast, cumulus, thin: halvings of a thick step's first shadow step "
                   "at most (default 3)")
        ->check(CLI::Range(0, 3));
    app.add_option("--shadow-steps", settings.shadow_steps,
                   "decks, overcast, cumulus, thin: samples toward each light (default 7; "
                   "each one twice as long as the one before)")
        ->check(CLI::Range(1, 16));
    CLI::Option* view_elevation_option =
        app.add_option("--view-elevation", view_elevation,
                       "thin: deg, the views' elevation off the deck's plane (default 55)")
            ->check(CLI::Range(5.0, 89.0));
    CLI::Option* utc_option =
        app.add_option("--utc", utc, "overcast: the time, ISO 8601 (default 2024-06-21T11:00:00Z)")
            ->check([](const std::string& text) {
                try {
                    zenith::geo::TimeFromIso8601(text);
                    return std::string();
                } catch (const std::exception& error) {
                    return std::string(error.what());
                }
            });
    CLI11_PARSE(app, argc, argv);
    if ((maps || single) && part != "cumulus") {
        std::fprintf(stderr,
                     "cloud_reference_report: --maps and --single-scattering apply to --part "
                     "cumulus\n");
        return 2;
    }
    if (view_elevation_option->count() > 0 && part != "thin") {
        std::fprintf(stderr, "cloud_reference_report: --view-elevation applies to --part thin\n");
        return 2;
    }
    if (utc_option->count() > 0 && part != "overcast") {
        std::fprintf(stderr, "cloud_reference_report: --utc applies to --part overcast\n");
        return 2;
    }
    if (part == "energy") {
        EnergyPart(samples > 0 ? samples : 20000, threads, seed);
    } else if (part == "overcast") {
        OvercastPart(settings, samples > 0 ? samples : 20000, threads, seed, utc);
    } else if (part == "formal") {
        FormalPart(settings);
    } else if (part == "grazing") {
        GrazingPart(settings, samples > 0 ? samples : 200000, threads, seed);
    } else if (part == "decks") {
        DecksPart(settings, samples > 0 ? samples : 40000, threads, seed);
    } else if (part == "thin") {
        ThinPart(settings, samples > 0 ? samples : 200000, threads, seed, view_elevation);
    } else {
        CumulusPart(settings, samples > 0 ? samples : 256, threads, seed, maps, single);
    }
    return 0;
}
