// A host's render target for the SkySystem GL tests: an RGBA32F colour texture and a 32-bit
// float depth texture on the host's own framebuffer, as an external host attaches them. A GL
// context must be current (SkySystem::CreateHeadless makes one).
#pragma once

#include <glad/gl.h>

#include <glm/glm.hpp>
#include <vector>

#include "zenith/sim/sky_system.h"

namespace zenith::sim::test {

class HostFrame {
  public:
    HostFrame(int width, int height) : width_(width), height_(height) {
        glCreateTextures(GL_TEXTURE_2D, 1, &colour_);
        glTextureStorage2D(colour_, 1, GL_RGBA32F, width, height);
        glCreateTextures(GL_TEXTURE_2D, 1, &depth_);
        glTextureStorage2D(depth_, 1, GL_DEPTH_COMPONENT32F, width, height);
        glCreateFramebuffers(1, &framebuffer_);
        glNamedFramebufferTexture(framebuffer_, GL_COLOR_ATTACHMENT0, colour_, 0);
    }
    ~HostFrame() {
        glDeleteFramebuffers(1, &framebuffer_);
        glDeleteTextures(1, &colour_);
        glDeleteTextures(1, &depth_);
    }
    HostFrame(const HostFrame&) = delete;
    HostFrame& operator=(const HostFrame&) = delete;

    // The host's frame after `sky` renders over it: the colour cleared to (c, c, c, 1), the
    // depth texture filled with `depth` (window values, width x height, row 0 at the bottom)
    // and handed to SetSceneDepth with near_m, far_m and `reversed`; rows bottom-up.
    std::vector<glm::vec4> Render(SkySystem& sky, const std::vector<float>& depth, float colour,
                                  double near_m, double far_m, bool reversed = false) {
        glTextureSubImage2D(depth_, 0, 0, 0, width_, height_, GL_DEPTH_COMPONENT, GL_FLOAT,
                            depth.data());
        const float host_colour[4] = {colour, colour, colour, 1.0f};
        glClearNamedFramebufferfv(framebuffer_, GL_COLOR, 0, host_colour);
        sky.SetSceneDepth(depth_, near_m, far_m, reversed);
        sky.Render(framebuffer_, {0, 0, width_, height_});
        sky.ClearSceneDepth();
        std::vector<glm::vec4> pixels(static_cast<std::size_t>(width_ * height_));
        glGetTextureImage(colour_, 0, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(pixels.size() * 16),
                          pixels.data());
        return pixels;
    }

  private:
    int width_, height_;
    GLuint colour_ = 0, depth_ = 0, framebuffer_ = 0;
};

}  // namespace zenith::sim::test
