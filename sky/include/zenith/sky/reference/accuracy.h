// Accuracy of the LUT renderer against the independent path tracer, per RGB channel, in the
// scenarios of Hillaire 2020 §6: the measurement behind tests/sky/accuracy_test.cpp and
// tests/bench/accuracy_report.cpp.
//
// The renderer side is AtmosphereReference, the renderer's own GLSL compiled as C++ (equal to the
// GPU within 1e-4), used as sky/shaders/atmosphere/render.frag uses it: the Sky-View LUT when the
// camera is inside the atmosphere, per-pixel ray marching above it. The reference side is
// RenderPathTraced (path_tracer.h: no LUT, unbounded scattering orders). Both see the same pixel
// rays, a black ground and no sun disk, as in the paper ("a planet with a terrain using a
// pure-black albedo, and without sun disk, so as not to influence the RMSE measure").
//
// Two normalisations of the per-channel RMSE between the two images:
//   relative: RMSE / (mean of the reference image in that channel). Dimensionless and independent
//     of the sun's illuminance and of units; what the test bounds.
//   absolute: RMSE / solar illuminance, in 1/sr: the luminance the images would have under a
//     white sun of illuminance 1. The paper does not state its normalisation; its demo
//     (github.com/sebh/UnrealEngineSkyAtmosphere, both the LUT and the path-traced modes) renders
//     with gSunIlluminance = 1 (white) by default and saves linear HDR frames, so this is our best
//     reading of "RMSE (0.94, 1.74, 5.07)·10⁻³". It remains an inference, and absolute RMSE also
//     depends on framing (e.g. the fraction of black space in a space view), which the paper gives
//     only as figures: compare orders of magnitude, not digits.
//
// The reference is a Monte Carlo estimate: its per-pixel standard error adds in quadrature to the
// renderer's true error, E[RMSE²] = bias² + noise², with noise² the mean over pixels of the
// squared standard error. An RMSE near `noise` says nothing about the renderer; the noise-corrected
// RMSE sqrt(max(0, RMSE² - noise²)) estimates its own part.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "zenith/base/error.h"
#include "zenith/sky/atmosphere.h"
#include "zenith/sky/lut.h"
#include "zenith/sky/reference/path_tracer.h"

namespace zenith::sky::reference {

struct AccuracyScenario {
    std::string name;         // short identifier, e.g. "earth_daytime"
    std::string description;  // camera, sun and what the scene shows, with the paper's figure
    Atmosphere atmosphere;    // a preset with ground_albedo = 0 (the paper's black terrain)
    glm::dvec3 camera_position{0.0};  // m, planet-centred
    glm::dvec3 forward{0.0, 0.0, -1.0};
    glm::dvec3 up{0.0, 1.0, 0.0};
    double vertical_fov = 1.0;                // rad; the aspect is the image's width / height
    glm::dvec3 sun_direction{0.0, 1.0, 0.0};  // unit, toward the sun
    // The paper's RMSE of its model (O) for this scenario, per channel, if it gives one (§6);
    // zero otherwise.
    glm::dvec3 paper_rmse{0.0};
};

// A direction (radians) in the frame of the ground views: +y up, azimuth 0 along +x, +90 deg
// along +z (the camera's right when it looks along +x with +y up).
glm::dvec3 LocalDirection(double elevation, double azimuth);

// The six scenarios, in this order: earth_daytime, earth_sunset, earth_shadow (sun 4 deg below
// the horizon, 150 deg field of view), earth_space, mars_space, thick_daytime (50x Rayleigh,
// scale height 20 km). Loads the presets (LoadAtmosphere), so it throws AtmosphereError if they
// cannot be read.
std::vector<AccuracyScenario> PaperScenarios();

struct AccuracyOptions {
    int width = 24;
    int height = 16;
    std::int64_t samples = 256;  // paths per pixel of the reference
    std::uint64_t seed = 1;
    int threads = 2;  // for the path tracer; results do not depend on it
    // render.frag's SkyView::ray_march_steps default, for views from space.
    int ray_march_steps = 32;
    LutSettings lut_settings = LutSettings::Pc();
};

struct AccuracyResult {
    Image renderer;            // the LUT renderer's image (CPU twin of the GPU), cd/m²
    Image reference;           // path traced, cd/m²
    Image standard_error;      // of each reference pixel, cd/m²
    bool ray_marched = false;  // true: camera above the atmosphere, per-pixel ray marching

    glm::dvec3 reference_mean{0.0};  // mean over pixels, cd/m² per channel
    glm::dvec3 renderer_mean{0.0};
    glm::dvec3 rmse{0.0};   // cd/m²
    glm::dvec3 noise{0.0};  // sqrt(mean of squared standard errors), cd/m²

    // Normalisations (see the top of this file).
    glm::dvec3 RelativeRmse() const { return rmse / reference_mean; }
    glm::dvec3 RelativeNoise() const { return noise / reference_mean; }
    // RMSE with the reference's own noise removed in quadrature, relative.
    glm::dvec3 RelativeRmseNoiseCorrected() const;
    // renderer_mean / reference_mean - 1: the renderer's overall gain error per channel, with
    // standard error MeanBiasError() (the pixels' errors are independent).
    glm::dvec3 MeanBias() const { return renderer_mean / reference_mean - 1.0; }
    glm::dvec3 MeanBiasError() const;
    glm::dvec3 AbsoluteRmse() const { return rmse / solar_illuminance; }    // 1/sr
    glm::dvec3 AbsoluteNoise() const { return noise / solar_illuminance; }  // 1/sr

    glm::dvec3 solar_illuminance{1.0};  // lux, of the scenario's atmosphere
    double renderer_seconds = 0.0;
    double reference_seconds = 0.0;
};

// The pinhole camera of a scenario at a resolution (path_tracer.h's Camera).
Camera ScenarioCamera(const AccuracyScenario& scenario, int width, int height);

// Renders both images of the scenario and compares them. Throws zenith::ArgumentError for a
// size or sample count out of range.
AccuracyResult MeasureAccuracy(const AccuracyScenario& scenario, const AccuracyOptions& options);

}  // namespace zenith::sky::reference
