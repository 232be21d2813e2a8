// sky/shaders/bindings.glsl (the GL contract: texture units, block bindings, image units,
// work-group sizes, shared limits) as C++ constants in namespace zenith::sky, seen from
// zenith::sky::gl and zenith::sky::ref alike. The same text is the first part of every program.
#pragma once

namespace zenith::sky {
#include "bindings.glsl"

// What GLSL cannot check itself: the weather maps' units do not run into the next sampler's.
static_assert(kWeatherMapsUnit + kCloudMaxLayers <= kCloudTraceUnit);
}  // namespace zenith::sky
