#include "zenith/sky/reference/accuracy.h"

#include <chrono>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "zenith/base/error.h"
#include "zenith/sky/reference/atmosphere_reference.h"

namespace zenith::sky::reference {

glm::dvec3 LocalDirection(double elevation, double azimuth) {
    return {std::cos(elevation) * std::cos(azimuth), std::sin(elevation),
            std::cos(elevation) * std::sin(azimuth)};
}

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
// Camera height of the ground views: above the ground so the horizon is a sharp edge, low enough
// to be "on the ground" (the paper's demo starts there too).
constexpr double kGroundCameraHeight = 500.0;  // m
// Space views look at the planet's centre from this many planet radii, with this field of view:
// the whole disk with its limb fits in a 3:2 frame.
constexpr double kSpaceDistanceInRadii = 2.5;
constexpr double kSpaceFov = 60.0 * kDeg;

Atmosphere BlackGround(Atmosphere atmosphere) {
    atmosphere.ground_albedo = glm::dvec3(0.0);
    return atmosphere;
}

AccuracyScenario GroundView(std::string name, std::string description, const Atmosphere& atmosphere,
                            double view_elevation, double vertical_fov, double sun_elevation,
                            double sun_azimuth) {
    AccuracyScenario s;
    s.name = std::move(name);
    s.description = std::move(description);
    s.atmosphere = BlackGround(atmosphere);
    s.camera_position = {0.0, atmosphere.bottom_radius + kGroundCameraHeight, 0.0};
    s.forward = LocalDirection(view_elevation, 0.0);
    s.up = {0.0, 1.0, 0.0};
    s.vertical_fov = vertical_fov;
    s.sun_direction = LocalDirection(sun_elevation, sun_azimuth);
    return s;
}

AccuracyScenario SpaceView(std::string name, std::string description,
                           const Atmosphere& atmosphere) {
    AccuracyScenario s;
    s.name = std::move(name);
    s.description = std::move(description);
    s.atmosphere = BlackGround(atmosphere);
    s.camera_position = {0.0, 0.0, kSpaceDistanceInRadii * atmosphere.bottom_radius};
    s.forward = {0.0, 0.0, -1.0};
    s.up = {0.0, 1.0, 0.0};
    s.vertical_fov = kSpaceFov;
    // 70 deg from the camera, to its right: a gibbous planet with the terminator, the twilight
    // band and the sunlit limb in view.
    s.sun_direction = {std::sin(70.0 * kDeg), 0.0, std::cos(70.0 * kDeg)};
    return s;
}

double Sum(const glm::dvec3& v) { return v.x + v.y + v.z; }

}  // namespace

std::vector<AccuracyScenario> PaperScenarios() {
    const Atmosphere earth = LoadAtmosphere("earth");
    const Atmosphere mars = LoadAtmosphere("mars");
    const Atmosphere thick = LoadAtmosphere("thick");
    // 66.6 deg: the vertical field of view of the paper's demo (Game.cpp,
    // XMMatrixPerspectiveFovLH).
    const double fov = 66.6 * kDeg;
    std::vector<AccuracyScenario> scenarios;
    scenarios.push_back(GroundView(
        "earth_daytime",
        "Fig. 9 daytime: 500 m up, looking 10 deg above the horizon; sun 45 deg high, 60 deg to "
        "the right (its Mie aureole at the frame's edge)",
        earth, 10.0 * kDeg, fov, 45.0 * kDeg, 60.0 * kDeg));
    scenarios.back().paper_rmse = glm::dvec3(0.94e-3, 1.74e-3, 5.07e-3);
    scenarios.push_back(GroundView(
        "earth_sunset",
        "Fig. 9 sunset: 500 m up, looking 5 deg above the horizon toward a sun 2 deg high and 20 "
        "deg to the right (in the frame, no disk)",
        earth, 5.0 * kDeg, fov, 2.0 * kDeg, 20.0 * kDeg));
    scenarios.push_back(GroundView(
        "earth_shadow",
        "Fig. 9 bottom: 500 m up, sun 4 deg below the horizon behind the camera; a 150 deg view "
        "centred 40 deg above the anti-solar horizon shows the Earth's shadow",
        earth, 40.0 * kDeg, 150.0 * kDeg, -4.0 * kDeg, 180.0 * kDeg));
    scenarios.push_back(SpaceView(
        "earth_space",
        "Fig. 10 Earth: from 2.5 planet radii, the whole disk; sun 70 deg off the line of sight",
        earth));
    scenarios.back().paper_rmse = glm::dvec3(0.95e-3, 0.85e-3, 1.23e-3);
    scenarios.push_back(
        SpaceView("mars_space",
                  "Fig. 10 Mars: as earth_space with the mars preset (not the paper's Mars-like "
                  "parameters)",
                  mars));
    scenarios.back().paper_rmse = glm::dvec3(1.99e-3, 0.91e-3, 0.56e-3);
    scenarios.push_back(GroundView(
        "thick_daytime",
        "Fig. 11 left: earth_daytime's view in the 50x denser Rayleigh atmosphere (scale height "
        "20 km), where multiple scattering dominates",
        thick, 10.0 * kDeg, fov, 45.0 * kDeg, 60.0 * kDeg));
    return scenarios;
}

Camera ScenarioCamera(const AccuracyScenario& scenario, int width, int height) {
    Camera camera;
    camera.width = width;
    camera.height = height;
    camera.vertical_fov = scenario.vertical_fov;
    camera.position = scenario.camera_position;
    camera.forward = scenario.forward;
    camera.up = scenario.up;
    return camera;
}

glm::dvec3 AccuracyResult::RelativeRmseNoiseCorrected() const {
    const glm::dvec3 bias_squared = glm::max(rmse * rmse - noise * noise, glm::dvec3(0.0));
    return glm::sqrt(bias_squared) / reference_mean;
}

glm::dvec3 AccuracyResult::MeanBiasError() const {
    // The mean of N independent pixels has standard error sqrt(mean SE²) / sqrt(N); the ratio's
    // relative error is that of the reference mean (the renderer is deterministic).
    const double pixels = static_cast<double>(reference.width) * reference.height;
    return noise / std::sqrt(pixels) * renderer_mean / (reference_mean * reference_mean);
}

AccuracyResult MeasureAccuracy(const AccuracyScenario& scenario, const AccuracyOptions& options) {
    if (!(options.width > 0 && options.height > 0 && options.width <= 4096 &&
          options.height <= 4096)) {
        throw ArgumentError("accuracy image size " + std::to_string(options.width) + "x" +
                            std::to_string(options.height) +
                            " is out of range (expected 1..4096 per axis)");
    }
    if (!(options.samples >= 2)) {
        throw ArgumentError("accuracy samples " + std::to_string(options.samples) +
                            " is out of range (expected >= 2, for a standard error)");
    }
    using Clock = std::chrono::steady_clock;
    const Atmosphere& atmosphere = scenario.atmosphere;
    const Camera camera = ScenarioCamera(scenario, options.width, options.height);
    AccuracyResult result;
    result.solar_illuminance = atmosphere.solar_illuminance;

    // The renderer: render.frag's choice of path, on the same pixel rays as the reference.
    auto start = Clock::now();
    const AtmosphereReference renderer(atmosphere, options.lut_settings);
    Lights lights;
    lights.sun_direction = glm::normalize(scenario.sun_direction);
    lights.sun_illuminance = atmosphere.solar_illuminance;
    result.ray_marched = glm::length(camera.position) >= atmosphere.top_radius;
    const LutImage sky_view =
        result.ray_marched ? LutImage() : renderer.SkyView(camera.position, lights);
    result.renderer.width = options.width;
    result.renderer.height = options.height;
    result.renderer.rgb.resize(3 * static_cast<std::size_t>(options.width) *
                               static_cast<std::size_t>(options.height));
    for (int y = 0; y < options.height; ++y) {
        for (int x = 0; x < options.width; ++x) {
            const glm::dvec3 direction = CameraRayDirection(camera, x, y);
            const glm::dvec3 value =
                result.ray_marched
                    ? renderer.RayMarch(camera.position, direction, lights, options.ray_march_steps)
                    : renderer.SampleSkyView(sky_view, camera.position, lights.sun_direction,
                                             direction);
            const std::size_t i =
                3 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(options.width) +
                     static_cast<std::size_t>(x));
            for (int c = 0; c < 3; ++c) {
                result.renderer.rgb[i + static_cast<std::size_t>(c)] = static_cast<float>(value[c]);
            }
        }
    }
    result.renderer_seconds = std::chrono::duration<double>(Clock::now() - start).count();

    // The reference: black ground (albedo 0 already), unbounded scattering orders.
    start = Clock::now();
    PathTraceOptions trace;
    trace.samples = options.samples;
    trace.seed = options.seed;
    trace.ground = false;
    result.reference = RenderPathTraced(atmosphere, camera, lights.sun_direction, trace,
                                        options.threads, &result.standard_error);
    result.reference_seconds = std::chrono::duration<double>(Clock::now() - start).count();

    const double pixels = static_cast<double>(options.width) * options.height;
    glm::dvec3 squared_error(0.0), variance(0.0);
    for (int y = 0; y < options.height; ++y) {
        for (int x = 0; x < options.width; ++x) {
            const glm::dvec3 ours = result.renderer.At(x, y);
            const glm::dvec3 truth = result.reference.At(x, y);
            const glm::dvec3 error = result.standard_error.At(x, y);
            result.renderer_mean += ours / pixels;
            result.reference_mean += truth / pixels;
            squared_error += (ours - truth) * (ours - truth) / pixels;
            variance += error * error / pixels;
        }
    }
    result.rmse = glm::sqrt(squared_error);
    result.noise = glm::sqrt(variance);
    if (!(Sum(result.reference_mean) > 0.0)) {
        throw Error("scenario " + scenario.name + ": the reference image is black (mean " +
                    std::to_string(Sum(result.reference_mean)) + " cd/m^2)");
    }
    return result;
}

}  // namespace zenith::sky::reference
