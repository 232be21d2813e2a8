// Files compiled into the library by cmake/EmbedFiles.cmake (the generated embedded_shaders.cpp
// defines EmbeddedFiles()).
#pragma once

#include <span>
#include <string_view>

namespace zenith::sky::shaders {

struct EmbeddedFile {
    std::string_view name;  // path relative to sky/shaders, e.g. "atmosphere/functions.glsl"
    std::string_view text;
};

std::span<const EmbeddedFile> EmbeddedFiles();

}  // namespace zenith::sky::shaders
