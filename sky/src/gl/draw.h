// One full-screen triangle into a framebuffer, leaving the host's GL state as it found it.
#pragma once

#include <glad/gl.h>

#include <glm/glm.hpp>
#include <optional>

#include "zenith/sky/gl/shader.h"

namespace zenith::sky::gl {

enum class Blend {
    kReplace,        // framebuffer = output
    kAdd,            // framebuffer += output
    kPremultiplied,  // framebuffer = output.rgb + output.a * framebuffer (alpha kept)
};

// Draws `program` over `viewport` of `target` (optionally scissored to `scissor`, in viewport
// pixels), timed by `query` when it is not 0. The draw framebuffer binding, viewport, scissor
// and blending are restored afterwards, so a host's state survives.
inline void DrawFullscreen(const Program& program, GLuint vertex_array, GLuint target,
                           glm::ivec4 viewport, Blend blend, GLuint query = 0,
                           std::optional<glm::ivec4> scissor = std::nullopt) {
    GLint host_framebuffer = 0;
    GLint host_viewport[4] = {0, 0, 0, 0};
    GLint host_scissor[4] = {0, 0, 0, 0};
    const GLboolean host_scissor_test = glIsEnabled(GL_SCISSOR_TEST);
    const GLboolean host_blend = glIsEnabled(GL_BLEND);
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &host_framebuffer);
    glGetIntegerv(GL_VIEWPORT, host_viewport);
    glGetIntegerv(GL_SCISSOR_BOX, host_scissor);
    program.Use();
    glBindFramebuffer(GL_FRAMEBUFFER, target);
    glViewport(viewport.x, viewport.y, viewport.z, viewport.w);
    glDisable(GL_DEPTH_TEST);
    switch (blend) {
        case Blend::kReplace:
            glDisable(GL_BLEND);
            break;
        case Blend::kAdd:
            glEnable(GL_BLEND);
            glBlendFunc(GL_ONE, GL_ONE);
            break;
        case Blend::kPremultiplied:
            glEnable(GL_BLEND);
            glBlendFuncSeparate(GL_ONE, GL_SRC_ALPHA, GL_ZERO, GL_ONE);
            break;
    }
    if (scissor) {
        glEnable(GL_SCISSOR_TEST);
        glScissor(viewport.x + scissor->x, viewport.y + scissor->y, scissor->z, scissor->w);
    } else {
        glDisable(GL_SCISSOR_TEST);
    }
    glBindVertexArray(vertex_array);
    if (query != 0) glBeginQuery(GL_TIME_ELAPSED, query);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    if (query != 0) glEndQuery(GL_TIME_ELAPSED);
    if (host_blend) {
        glEnable(GL_BLEND);
    } else {
        glDisable(GL_BLEND);
    }
    if (host_scissor_test) {
        glEnable(GL_SCISSOR_TEST);
    } else {
        glDisable(GL_SCISSOR_TEST);
    }
    glScissor(host_scissor[0], host_scissor[1], host_scissor[2], host_scissor[3]);
    glBindFramebuffer(GL_FRAMEBUFFER, static_cast<GLuint>(host_framebuffer));
    glViewport(host_viewport[0], host_viewport[1], host_viewport[2], host_viewport[3]);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
}

}  // namespace zenith::sky::gl
