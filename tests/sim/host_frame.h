// A host's render target for the SkySystem GL tests: an RGBA32F colour target and a 32-bit
// float depth texture beside it, as an external host attaches them. A GL
// context must be current (SkySystem::CreateHeadless makes one).
#pragma once

#include <glad/gl.h>

#include <glm/glm.hpp>
#include <vector>

#include "colour_target.h"
#include "zenith/sim/sky_system.h"

namespace zenith::sim::test {

class HostFrame {
  public:
    HostFrame(int width, int height)
        : width_(width), height_(height), colour_(GL_RGBA32F, width, height) {
        glCreateTextures(GL_TEXTURE_2D, 1, &depth_);
        glTextureStorage2D(depth_, 1, GL_DEPTH_COMPONENT32F, width, height);
    }
    ~HostFrame() { glDeleteTextures(1, &depth_); }
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
        glClearNamedFramebufferfv(colour_.framebuffer(), GL_COLOR, 0, host_colour);
        sky.SetSceneDepth(depth_, near_m, far_m, reversed);
        sky.Render(colour_.framebuffer(), {0, 0, width_, height_});
        sky.ClearSceneDepth();
        return colour_.ReadFloat();
    }

  private:
    int width_, height_;
    zenith::test::ColourTarget colour_;
    GLuint depth_ = 0;
};

}  // namespace zenith::sim::test
