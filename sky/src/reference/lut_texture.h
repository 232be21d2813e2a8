// Conversions between the float LUT images the GPU stores (LutImage) and the double textures the
// shared functions sample on the CPU (ref::Texture2D), so CPU sampling of a GPU LUT matches GPU
// sampling of it.
#pragma once

#include "reference/shared_math.h"
#include "zenith/sky/lut.h"

namespace zenith::sky::ref {

inline LutImage ToImage(const Texture2D& texture) {
    LutImage image(texture.width(), texture.height());
    for (int y = 0; y < texture.height(); ++y) {
        for (int x = 0; x < texture.width(); ++x) image.at(x, y) = glm::vec4(texture.at(x, y));
    }
    return image;
}

// Slice `z` of the image (0 for a 2D LUT). wrap_u: GL_REPEAT along u (the Sky-View azimuth),
// else GL_CLAMP_TO_EDGE.
inline Texture2D FromImage(const LutImage& image, bool wrap_u = false, int z = 0) {
    Texture2D texture(image.size.x, image.size.y, wrap_u);
    for (int y = 0; y < image.size.y; ++y) {
        for (int x = 0; x < image.size.x; ++x) texture.at(x, y) = glm::dvec4(image.at(x, y, z));
    }
    return texture;
}

}  // namespace zenith::sky::ref
