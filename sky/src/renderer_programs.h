// Every GL program the renderer builds, for tests of the GL contract between C++ and GLSL
// (tests/sky/gl_bindings_gl_test.cpp): AtmosphereRenderer's LUT passes and composites, the
// composites with clouds, CloudPasses' programs, DisplayPass's and EnvironmentPasses'
// (gl/display_uniforms.h). The renderer builds its own from the same functions, so a new program is
// checked as soon as it is built. A context must be current.
#pragma once

#include <vector>

#include "gl/shader.h"

namespace zenith::sky {

std::vector<gl::Program> BuildRendererPrograms();

}  // namespace zenith::sky
