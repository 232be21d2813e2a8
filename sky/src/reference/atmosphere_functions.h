// sky/shaders/atmosphere/functions.glsl compiled as C++ (double precision) in namespace
// zenith::sky::ref. Internal linkage, like a shader: every translation unit that includes this
// compiles its own copy, so tests can call the functions directly next to the library's copy.
// Functions a given unit does not call would trip -Wunused-function; that is expected here.
#pragma once

#include "reference/shared_math.h"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
namespace zenith::sky::ref {
namespace {
#include "atmosphere/functions.glsl"
}  // namespace
}  // namespace zenith::sky::ref
#pragma GCC diagnostic pop
