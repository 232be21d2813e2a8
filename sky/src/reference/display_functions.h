// sky/shaders/common/display.glsl compiled as C++ (double precision) in namespace
// zenith::sky::ref: the display transform of the GPU display pass, for the CPU (PNG output in
// image_io.cpp) and tests. Internal linkage, like atmosphere_functions.h.
#pragma once

#include "reference/shared_math.h"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
namespace zenith::sky::ref {
namespace {
using glm::exp2;
using glm::isinf;
using glm::isnan;
using glm::log2;
#include "common/display.glsl"
}  // namespace
}  // namespace zenith::sky::ref
#pragma GCC diagnostic pop
