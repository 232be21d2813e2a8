// Compute programs assembled from the shader files embedded in the library (sky/shaders).
#pragma once

#include <span>
#include <string>
#include <string_view>

#include "gl/shader.h"

namespace zenith::sky::gl {

// Text of an embedded file such as "atmosphere/functions.glsl"; throws GlError if absent.
std::string_view EmbeddedShaderFile(std::string_view name);

// "#version 450 core", bindings.glsl (the GL contract), the shared definitions and atmosphere
// functions, the pass interface, then `pass_file`. Each part starts with "#line 1 N"; a compile
// error's "N:line" is translated back to the file name in the thrown ShaderError.
// `defines` (e.g. "#define X 1\n") go right after the #version line; `extra_parts` (e.g. the
// cloud files) follow the prelude, before the pass file.
std::string ComposeShader(std::string_view pass_file, std::string_view defines = {},
                          std::span<const std::string_view> extra_parts = {});
Program ComputeProgram(std::string_view pass_file,
                       std::span<const std::string_view> extra_parts = {},
                       std::string_view defines = {});
// The same prelude for a fragment pass; the vertex shader is common/fullscreen.vert.
Program FullscreenProgram(std::string_view fragment_file, std::string_view defines = {},
                          std::span<const std::string_view> extra_parts = {});

}  // namespace zenith::sky::gl
