// The display pass: linear luminance (cd/m^2) to what a screen shows, on the GPU. Exposure (an
// EV100 given, or metered from the frame and adapted over time), night (scotopic) adaptation, the
// ACES fitted tone map and sRGB encoding, the same formulas as the PNGs of `zenith render`
// (sky/shaders/common/display.glsl is compiled by both; image_io.h's ToneMapToSrgb8 is the CPU
// side). References and constants are in that file.
#pragma once

#include <glm/glm.hpp>
#include <memory>
#include <optional>

#include "zenith/sky/atmosphere_renderer.h"

namespace zenith::sky {

struct DisplaySettings {
    enum class Output {
        // Linear Rec.709 luminance in cd/m^2 per channel, as computed (0 to ~1.6e9 at the Sun's
        // disk, ~7e7 after a pixel's footprint, ~1e4 for a noon sky, ~1e-3 for a moonlit one): the
        // host exposes and tone maps it itself (an RGBA32F target keeps it all; RGBA16F clips at
        // 65504, an 8-bit target at 1).
        kLinear,
        // Display-referred, sRGB-encoded in [0, 1] for an 8-bit target (RGBA8, or SRGB8_ALPHA8,
        // which gets the same bytes: encoding is done in the shader with GL_FRAMEBUFFER_SRGB off).
        kDisplay,
    };
    Output output = Output::kLinear;
    // A fixed exposure (EV100, [kDisplayMinEV100 = -20, kDisplayMaxEV100 = 30]); nullopt: metered
    // from each frame as image_io's AutoExposureEV100 does (log-average of the 50th-95th
    // percentiles of luminance, EV100 = log2(L_avg S / K), S = 100, K = 12.5), with the night
    // compensation below when night_adaptation.
    std::optional<double> ev100;
    // Metered exposure: time constant of the adaptation, seconds of the host's frame clock:
    // EV += (target - EV) (1 - exp(-dt / tau)), in EV (a log of luminance). 0: the target at once.
    double adaptation_time_s = 1.0;
    // Added to the exposure, in EV (positive: darker), metered or given.
    double compensation_ev = 0.0;
    // Night vision: below 4 cd/m^2 each colour moves toward the rods' blue-grey and its
    // luminance toward the scotopic one (Jensen et al. 2000, §7), and the metered exposure is
    // made darker by up to 3.3 EV (Krawczyk et al. 2005's key), so a moonlit sky looks like night.
    bool night_adaptation = true;
    // Throws zenith::ArgumentError naming the field, its value and the allowed range.
    void Validate() const;
};

// The pass. Needs a current GL 4.5 context; holds a StateGuard in Run (the GL state contract of
// zenith/sim/sky_system.h): it sets what it needs and, with preserve_gl_state, restores it.
class DisplayPass {
  public:
    DisplayPass();
    ~DisplayPass();
    DisplayPass(const DisplayPass&) = delete;
    DisplayPass& operator=(const DisplayPass&) = delete;

    // Displays `input` (a 2-D RGBA float texture of `viewport`'s size, linear cd/m^2) into draw
    // buffer 0 of `framebuffer` over `viewport`; dt_s: seconds since the previous Run (for the
    // adaptation; <= 0 or the first metered run: no adaptation). With `scene_depth`, the pixels
    // nearer than the far plane (the host's geometry) are left as they are.
    void Run(unsigned input, unsigned framebuffer, const glm::ivec4& viewport,
             const DisplaySettings& settings, double dt_s,
             const std::optional<SceneDepth>& scene_depth = std::nullopt);
    // The next metered Run starts from its own target (after a cut).
    void ResetAdaptation();
    // The exposure the last Run applied (EV100). A metered one is read back from the GPU: the
    // call waits for the last Run to finish. nullopt before the first Run.
    std::optional<double> exposure_ev100() const;
    // The last metered run's target (before adaptation) and log2 of its log-average luminance
    // (waits for the GPU); nullopt unless the last Run was metered.
    std::optional<double> metered_target_ev100() const;
    std::optional<double> metered_log2_average() const;

    void set_preserve_gl_state(bool preserve);

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace zenith::sky
