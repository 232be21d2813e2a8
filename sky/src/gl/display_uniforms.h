// The C++ side of the display pass's GL interface (zenith/sky/display.h): the DisplayStorage
// block of display/storage.glsl (std430) and the explicit locations of the passes' plain
// uniforms. tests/sky/gl_bindings_gl_test.cpp checks both against the linked programs.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

#include "bindings.h"
#include "gl/shader.h"

namespace zenith::sky::gl {

// DisplayStorage (display/storage.glsl), std430: the exposure, the meter's target and average,
// whether a metered frame has run, then the histogram.
struct DisplayStorage {
    float ev100;
    float target_ev100;
    float log2_average;
    std::uint32_t valid;
    std::uint32_t histogram[kDisplayHistogramBins];
};
static_assert(offsetof(DisplayStorage, histogram) == 16);
static_assert(sizeof(DisplayStorage) == 16 + 4 * kDisplayHistogramBins);

// Uniform locations (layout(location = N) in the pass files).
// display/histogram.comp
constexpr int kDisplaySizeLocation = 0;  // ivec2 display_size
// display/meter.comp
constexpr int kDisplayDtOverTauLocation = 0;     // float display_dt_over_tau
constexpr int kDisplayMeterNightLocation = 1;    // int display_night
constexpr int kDisplayCompensationLocation = 2;  // float display_compensation_ev
// display/display.frag
constexpr int kDisplayOriginLocation = 0;     // ivec2 display_origin
constexpr int kDisplayNightLocation = 1;      // int display_night
constexpr int kDisplayDepthModeLocation = 2;  // int display_depth_mode

// The pass's programs, in this order: histogram, meter, display. DisplayPass builds its own with
// this function; renderer_programs.h lists them for the GL contract tests.
enum DisplayProgram : std::size_t {
    kDisplayHistogramProgram,
    kDisplayMeterProgram,
    kDisplayDisplayProgram,
    kDisplayProgramCount
};
std::vector<Program> BuildDisplayPrograms();

}  // namespace zenith::sky::gl
