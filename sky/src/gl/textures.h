// Linear-filtered textures with immutable storage, and reading one back, for the renderer's
// LUTs, render targets and uploaded data.
#pragma once

#include <glad/gl.h>

#include <glm/glm.hpp>

#include "zenith/sky/lut.h"

namespace zenith::sky::gl {

// wrap_s/wrap_t: GL_CLAMP_TO_EDGE, or GL_REPEAT for an axis that wraps (the Sky-View azimuth, a
// tiling weather map).
inline GLuint CreateTexture2D(glm::ivec2 size, GLenum format = GL_RGBA32F,
                              GLenum wrap_s = GL_CLAMP_TO_EDGE, GLenum wrap_t = GL_CLAMP_TO_EDGE) {
    GLuint texture = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &texture);
    glTextureStorage2D(texture, 1, format, size.x, size.y);
    glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(texture, GL_TEXTURE_WRAP_S, static_cast<GLint>(wrap_s));
    glTextureParameteri(texture, GL_TEXTURE_WRAP_T, static_cast<GLint>(wrap_t));
    return texture;
}

// The same wrap on every axis: GL_CLAMP_TO_EDGE, or GL_REPEAT for tiling noise.
inline GLuint CreateTexture3D(glm::ivec3 size, GLenum format = GL_RGBA32F,
                              GLenum wrap = GL_CLAMP_TO_EDGE) {
    GLuint texture = 0;
    glCreateTextures(GL_TEXTURE_3D, 1, &texture);
    glTextureStorage3D(texture, 1, format, size.x, size.y, size.z);
    glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(texture, GL_TEXTURE_WRAP_S, static_cast<GLint>(wrap));
    glTextureParameteri(texture, GL_TEXTURE_WRAP_T, static_cast<GLint>(wrap));
    glTextureParameteri(texture, GL_TEXTURE_WRAP_R, static_cast<GLint>(wrap));
    return texture;
}

// Level 0 as RGBA floats (synchronous).
inline LutImage ReadTexture(GLuint texture, glm::ivec3 size) {
    LutImage image(size.x, size.y, size.z);
    glGetTextureImage(texture, 0, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(image.bytes()),
                      image.texels.data());
    return image;
}

}  // namespace zenith::sky::gl
