// A host's colour target for the GL tests: a 2-D texture of one format attached to a framebuffer
// of its own, as an external host makes one. A GL context must be current.
#pragma once

#include <glad/gl.h>

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

namespace zenith::test {

class ColourTarget {
  public:
    ColourTarget(GLenum format, int width, int height) : width_(width), height_(height) {
        glCreateTextures(GL_TEXTURE_2D, 1, &texture_);
        glTextureStorage2D(texture_, 1, format, width, height);
        glCreateFramebuffers(1, &framebuffer_);
        glNamedFramebufferTexture(framebuffer_, GL_COLOR_ATTACHMENT0, texture_, 0);
    }
    ~ColourTarget() {
        glDeleteFramebuffers(1, &framebuffer_);
        glDeleteTextures(1, &texture_);
    }
    ColourTarget(const ColourTarget&) = delete;
    ColourTarget& operator=(const ColourTarget&) = delete;

    GLuint texture() const { return texture_; }
    GLuint framebuffer() const { return framebuffer_; }

    // What is stored, RGBA per pixel, rows bottom-up (no sRGB decoding): as floats, or as bytes.
    std::vector<glm::vec4> ReadFloat() const {
        std::vector<glm::vec4> pixels(Count());
        glGetTextureImage(texture_, 0, GL_RGBA, GL_FLOAT,
                          static_cast<GLsizei>(pixels.size() * sizeof(glm::vec4)), pixels.data());
        return pixels;
    }
    std::vector<std::uint8_t> ReadBytes() const {
        std::vector<std::uint8_t> rgba(4u * Count());
        glGetTextureImage(texture_, 0, GL_RGBA, GL_UNSIGNED_BYTE, static_cast<GLsizei>(rgba.size()),
                          rgba.data());
        return rgba;
    }

  private:
    std::size_t Count() const {
        return static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_);
    }
    int width_, height_;
    GLuint texture_ = 0, framebuffer_ = 0;
};

}  // namespace zenith::test
