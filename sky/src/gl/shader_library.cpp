#include "gl/shader_library.h"

#include <array>
#include <string>

#include "gl/embedded_files.h"
#include "zenith/sky/gl/error.h"

namespace zenith::sky::gl {
namespace {

// Parts every atmosphere compute pass is made of, before the pass's own file.
// bindings.glsl comes first: the structs and blocks that follow are sized and bound by it.
constexpr std::array<std::string_view, 4> kPrelude = {"bindings.glsl", "common/definitions.glsl",
                                                      "atmosphere/functions.glsl",
                                                      "atmosphere/interface.glsl"};

}  // namespace

std::string_view EmbeddedShaderFile(std::string_view name) {
    for (const shaders::EmbeddedFile& file : shaders::EmbeddedFiles()) {
        if (file.name == name) return file.text;
    }
    throw GlError("shader file '" + std::string(name) + "' is not embedded in the library");
}

std::string ComposeShader(std::string_view pass_file, std::string_view defines,
                          std::span<const std::string_view> extra_parts) {
    std::string source = "#version 450 core\n" + std::string(defines);
    int index = 1;
    for (std::string_view part : kPrelude) {
        source += "#line 1 " + std::to_string(index++) + "\n";
        source += EmbeddedShaderFile(part);
        source += "\n";
    }
    for (std::string_view part : extra_parts) {
        source += "#line 1 " + std::to_string(index++) + "\n";
        source += EmbeddedShaderFile(part);
        source += "\n";
    }
    source += "#line 1 " + std::to_string(index) + "\n";
    source += EmbeddedShaderFile(pass_file);
    return source;
}

namespace {

// Rethrows a shader error with the legend of the #line source numbers.
[[noreturn]] void RethrowWithLegend(const ShaderError& e, std::string_view pass_file,
                                    std::span<const std::string_view> extra_parts) {
    std::string legend = "\nsource numbers in the log: ";
    int index = 1;
    for (std::string_view part : kPrelude) {
        legend += std::to_string(index++) + " = " + std::string(part) + ", ";
    }
    for (std::string_view part : extra_parts) {
        legend += std::to_string(index++) + " = " + std::string(part) + ", ";
    }
    legend += std::to_string(index) + " = " + std::string(pass_file);
    throw ShaderError(e.what() + legend);
}

}  // namespace

Program FullscreenProgram(std::string_view fragment_file, std::string_view defines,
                          std::span<const std::string_view> extra_parts) {
    const std::string vertex =
        "#version 450 core\n" + std::string(EmbeddedShaderFile("common/fullscreen.vert"));
    try {
        return Program::Graphics(vertex, ComposeShader(fragment_file, defines, extra_parts),
                                 fragment_file);
    } catch (const ShaderError& e) {
        RethrowWithLegend(e, fragment_file, extra_parts);
    }
}

Program ComputeProgram(std::string_view pass_file, std::span<const std::string_view> extra_parts,
                       std::string_view defines) {
    try {
        return Program::Compute(ComposeShader(pass_file, defines, extra_parts), pass_file);
    } catch (const ShaderError& e) {
        RethrowWithLegend(e, pass_file, extra_parts);
    }
}

}  // namespace zenith::sky::gl
