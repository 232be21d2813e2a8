// One full-screen triangle into a framebuffer.
#pragma once

#include <glad/gl.h>

#include <glm/glm.hpp>
#include <optional>

#include "gl/shader.h"

namespace zenith::sky::gl {

enum class Blend {
    kReplace,        // framebuffer = output
    kAdd,            // framebuffer += output
    kPremultiplied,  // framebuffer = output.rgb + output.a * framebuffer (alpha kept)
};

// Makes `target` the draw framebuffer with `viewport`, blending `blend` into draw buffer 0 and
// scissored to `scissor` (in viewport pixels) or not at all: the state a draw of the renderer's
// sets; the rest it relies on (no culling, filled polygons, a pixel-wide point, no depth or
// stencil test, ...) and the restoring of the host's are a StateGuard's (gl/state_guard.h),
// which every renderer entry point holds.
inline void SetDrawTarget(GLuint target, glm::ivec4 viewport, Blend blend,
                          std::optional<glm::ivec4> scissor = std::nullopt) {
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, target);
    glViewportIndexedf(0, static_cast<GLfloat>(viewport.x), static_cast<GLfloat>(viewport.y),
                       static_cast<GLfloat>(viewport.z), static_cast<GLfloat>(viewport.w));
    switch (blend) {
        case Blend::kReplace:
            glDisablei(GL_BLEND, 0);
            break;
        case Blend::kAdd:
            glEnablei(GL_BLEND, 0);
            glBlendFunci(0, GL_ONE, GL_ONE);
            break;
        case Blend::kPremultiplied:
            glEnablei(GL_BLEND, 0);
            glBlendFuncSeparatei(0, GL_ONE, GL_SRC_ALPHA, GL_ZERO, GL_ONE);
            break;
    }
    if (scissor) {
        glEnablei(GL_SCISSOR_TEST, 0);
        glScissorIndexed(0, viewport.x + scissor->x, viewport.y + scissor->y, scissor->z,
                         scissor->w);
    } else {
        glDisablei(GL_SCISSOR_TEST, 0);
    }
}

// Draws `program` over `viewport` of `target` (SetDrawTarget), timed by `query` when it is not 0.
inline void DrawFullscreen(const Program& program, GLuint vertex_array, GLuint target,
                           glm::ivec4 viewport, Blend blend, GLuint query = 0,
                           std::optional<glm::ivec4> scissor = std::nullopt) {
    program.Use();
    SetDrawTarget(target, viewport, blend, scissor);
    glBindVertexArray(vertex_array);
    if (query != 0) glBeginQuery(GL_TIME_ELAPSED, query);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    if (query != 0) glEndQuery(GL_TIME_ELAPSED);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
}

}  // namespace zenith::sky::gl
