// sky/shaders/clouds/march.glsl compiled as C++ (double precision) in namespace zenith::sky::ref,
// after the atmosphere and cloud functions it builds on. Internal linkage, like a shader (see
// atmosphere_functions.h).
#pragma once

#include "reference/atmosphere_functions.h"
#include "reference/cloud_functions.h"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
namespace zenith::sky::ref {
namespace {
#include "clouds/march.glsl"
}  // namespace
}  // namespace zenith::sky::ref
#pragma GCC diagnostic pop
