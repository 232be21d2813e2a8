#include "gl/state_guard.h"

#include <algorithm>

namespace zenith::sky::gl {
namespace {

// Capabilities the passes need off. Culling (a host's GL_CW front faces, or GL_FRONT culling,
// removed the full-screen triangle), depth and stencil tests, rasterizer discard and the
// multisample coverage operations would drop fragments; sRGB encoding, logic ops and dithering
// would alter the values written (zenith writes linear luminance as computed). Primitive restart
// is for indexed draws, but NVIDIA's driver applies it to glDrawArrays* too: a host's restart
// index 7 cut the host-geometry march's triangle list on an H200 (the rain's streaks are drawn
// the same way).
constexpr std::array<GLenum, StateGuard::kCapabilityCount> kCapabilities = {
    GL_CULL_FACE,
    GL_DEPTH_TEST,
    GL_STENCIL_TEST,
    GL_FRAMEBUFFER_SRGB,
    GL_RASTERIZER_DISCARD,
    GL_COLOR_LOGIC_OP,
    GL_SAMPLE_ALPHA_TO_COVERAGE,
    GL_SAMPLE_ALPHA_TO_ONE,
    GL_SAMPLE_COVERAGE,
    GL_SAMPLE_MASK,
    GL_SAMPLE_SHADING,
    GL_POLYGON_SMOOTH,
    GL_DITHER,
    GL_PROGRAM_POINT_SIZE,
    GL_PRIMITIVE_RESTART,
    GL_PRIMITIVE_RESTART_FIXED_INDEX};
static_assert(kCapabilities.back() != 0, "kCapabilityCount names more capabilities than listed");

// Pixel store parameters of uploads (the noise, the weather maps, the night sky) and read-backs
// (RenderOffscreen, the LUTs), with GL's initial values.
struct PixelStore {
    GLenum name;
    GLint initial;
};
constexpr std::array<PixelStore, 14> kPixelStore = {{{GL_PACK_SWAP_BYTES, 0},
                                                     {GL_PACK_ROW_LENGTH, 0},
                                                     {GL_PACK_IMAGE_HEIGHT, 0},
                                                     {GL_PACK_SKIP_ROWS, 0},
                                                     {GL_PACK_SKIP_PIXELS, 0},
                                                     {GL_PACK_SKIP_IMAGES, 0},
                                                     {GL_PACK_ALIGNMENT, 4},
                                                     {GL_UNPACK_SWAP_BYTES, 0},
                                                     {GL_UNPACK_ROW_LENGTH, 0},
                                                     {GL_UNPACK_IMAGE_HEIGHT, 0},
                                                     {GL_UNPACK_SKIP_ROWS, 0},
                                                     {GL_UNPACK_SKIP_PIXELS, 0},
                                                     {GL_UNPACK_SKIP_IMAGES, 0},
                                                     {GL_UNPACK_ALIGNMENT, 4}}};

GLuint U(GLint name) { return static_cast<GLuint>(name); }
GLenum E(GLint value) { return static_cast<GLenum>(value); }

void SetEnabled(GLenum capability, GLboolean enabled) {
    if (enabled) {
        glEnable(capability);
    } else {
        glDisable(capability);
    }
}

void SetEnabledi(GLenum capability, GLuint index, GLboolean enabled) {
    if (enabled) {
        glEnablei(capability, index);
    } else {
        glDisablei(capability, index);
    }
}

}  // namespace

StateGuard::StateGuard(bool preserve) : preserve_(preserve) {
    GLint draw_buffers = 0, clip_distances = 0;
    glGetIntegerv(GL_MAX_DRAW_BUFFERS, &draw_buffers);
    glGetIntegerv(GL_MAX_CLIP_DISTANCES, &clip_distances);
    draw_buffers_ = std::clamp(draw_buffers, 1, kMaxDrawBuffers);
    clip_distances_ = std::clamp(clip_distances, 0, kMaxClipDistances);
    if (preserve_) Save();
    Establish(draw_buffers_, clip_distances_);
}

StateGuard::~StateGuard() {
    if (preserve_) Restore();
}

void StateGuard::Establish(int draw_buffers, int clip_distances) {
    for (GLenum capability : kCapabilities) glDisable(capability);
    for (int i = 0; i < clip_distances; ++i) glDisable(GL_CLIP_DISTANCE0 + static_cast<GLenum>(i));
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    glPointSize(1.0f);  // the stars: a pixel each (GL_PROGRAM_POINT_SIZE is off, above)
    // The upper-left origin would flip the frame; the depth mode is set for completeness (the
    // full-screen triangle lies at z = 0, inside either clip volume).
    glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
    // Each draw sets blending of draw buffer 0 (gl::DrawFullscreen); the others stay off.
    glDisable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    for (int i = 0; i < draw_buffers; ++i) {
        glColorMaski(static_cast<GLuint>(i), GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    }
    glDisablei(GL_SCISSOR_TEST, 0);
    glBindSamplers(0, kTextureUnits, nullptr);  // a host's sampler objects override filtering
    glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
    glBindBuffer(GL_QUERY_BUFFER, 0);
    for (const PixelStore& p : kPixelStore) glPixelStorei(p.name, p.initial);
}

void StateGuard::Save() {
    for (std::size_t i = 0; i < kCapabilities.size(); ++i) {
        capabilities_[i] = glIsEnabled(kCapabilities[i]);
    }
    for (int i = 0; i < clip_distances_; ++i) {
        clip_distance_[static_cast<std::size_t>(i)] =
            glIsEnabled(GL_CLIP_DISTANCE0 + static_cast<GLenum>(i));
    }
    glGetIntegerv(GL_POLYGON_MODE, polygon_mode_);
    glGetFloatv(GL_POINT_SIZE, &point_size_);
    glGetIntegerv(GL_CLIP_ORIGIN, &clip_origin_);
    glGetIntegerv(GL_CLIP_DEPTH_MODE, &clip_depth_mode_);
    for (int i = 0; i < draw_buffers_; ++i) {
        const GLuint index = static_cast<GLuint>(i);
        DrawBuffer& b = draw_buffer_[index];
        b.blend = glIsEnabledi(GL_BLEND, index);
        glGetIntegeri_v(GL_BLEND_SRC_RGB, index, &b.src_rgb);
        glGetIntegeri_v(GL_BLEND_DST_RGB, index, &b.dst_rgb);
        glGetIntegeri_v(GL_BLEND_SRC_ALPHA, index, &b.src_alpha);
        glGetIntegeri_v(GL_BLEND_DST_ALPHA, index, &b.dst_alpha);
        glGetIntegeri_v(GL_BLEND_EQUATION_RGB, index, &b.equation_rgb);
        glGetIntegeri_v(GL_BLEND_EQUATION_ALPHA, index, &b.equation_alpha);
        glGetBooleani_v(GL_COLOR_WRITEMASK, index, b.colour_mask);
    }
    glGetFloati_v(GL_VIEWPORT, 0, viewport_);
    glGetIntegeri_v(GL_SCISSOR_BOX, 0, scissor_box_);
    scissor_test_ = glIsEnabledi(GL_SCISSOR_TEST, 0);

    glGetIntegerv(GL_CURRENT_PROGRAM, &program_);
    glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &vertex_array_);
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &draw_framebuffer_);
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &read_framebuffer_);
    glGetIntegerv(GL_ACTIVE_TEXTURE, &active_texture_);
    for (std::size_t unit = 0; unit < kTextureUnits; ++unit) {
        glActiveTexture(GL_TEXTURE0 + static_cast<GLenum>(unit));
        glGetIntegerv(GL_TEXTURE_BINDING_2D, &texture_2d_[unit]);
        glGetIntegerv(GL_TEXTURE_BINDING_3D, &texture_3d_[unit]);
        GLint sampler = 0;
        glGetIntegerv(GL_SAMPLER_BINDING, &sampler);
        sampler_[unit] = U(sampler);
    }
    glActiveTexture(E(active_texture_));

    for (std::size_t i = 0; i < kUniformBindings; ++i) {
        const GLuint index = static_cast<GLuint>(i);
        glGetIntegeri_v(GL_UNIFORM_BUFFER_BINDING, index, &uniform_[i].buffer);
        glGetInteger64i_v(GL_UNIFORM_BUFFER_START, index, &uniform_[i].start);
        glGetInteger64i_v(GL_UNIFORM_BUFFER_SIZE, index, &uniform_[i].size);
    }
    glGetIntegerv(GL_UNIFORM_BUFFER_BINDING, &uniform_buffer_);
    glGetIntegeri_v(GL_SHADER_STORAGE_BUFFER_BINDING, static_cast<GLuint>(kLightStorageBinding),
                    &storage_.buffer);
    glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_START, static_cast<GLuint>(kLightStorageBinding),
                      &storage_.start);
    glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_SIZE, static_cast<GLuint>(kLightStorageBinding),
                      &storage_.size);
    glGetIntegerv(GL_SHADER_STORAGE_BUFFER_BINDING, &storage_buffer_);
    glGetIntegerv(GL_DRAW_INDIRECT_BUFFER_BINDING, &draw_indirect_buffer_);
    for (std::size_t i = 0; i < kImageUnits; ++i) {
        const GLuint index = static_cast<GLuint>(i);
        ImageUnit& u = image_[i];
        glGetIntegeri_v(GL_IMAGE_BINDING_NAME, index, &u.texture);
        glGetIntegeri_v(GL_IMAGE_BINDING_LEVEL, index, &u.level);
        glGetIntegeri_v(GL_IMAGE_BINDING_LAYERED, index, &u.layered);
        glGetIntegeri_v(GL_IMAGE_BINDING_LAYER, index, &u.layer);
        glGetIntegeri_v(GL_IMAGE_BINDING_ACCESS, index, &u.access);
        glGetIntegeri_v(GL_IMAGE_BINDING_FORMAT, index, &u.format);
    }

    glGetIntegerv(GL_PIXEL_PACK_BUFFER_BINDING, &pack_buffer_);
    glGetIntegerv(GL_PIXEL_UNPACK_BUFFER_BINDING, &unpack_buffer_);
    glGetIntegerv(GL_QUERY_BUFFER_BINDING, &query_buffer_);
    for (std::size_t i = 0; i < kPixelStore.size(); ++i) {
        glGetIntegerv(kPixelStore[i].name, &pixel_store_[i]);
    }
}

void StateGuard::Restore() const {
    for (std::size_t i = 0; i < kCapabilities.size(); ++i) {
        SetEnabled(kCapabilities[i], capabilities_[i]);
    }
    for (int i = 0; i < clip_distances_; ++i) {
        SetEnabled(GL_CLIP_DISTANCE0 + static_cast<GLenum>(i),
                   clip_distance_[static_cast<std::size_t>(i)]);
    }
    glPolygonMode(GL_FRONT_AND_BACK, E(polygon_mode_[0]));
    glPointSize(point_size_);
    glClipControl(E(clip_origin_), E(clip_depth_mode_));
    for (int i = 0; i < draw_buffers_; ++i) {
        const GLuint index = static_cast<GLuint>(i);
        const DrawBuffer& b = draw_buffer_[index];
        SetEnabledi(GL_BLEND, index, b.blend);
        glBlendFuncSeparatei(index, E(b.src_rgb), E(b.dst_rgb), E(b.src_alpha), E(b.dst_alpha));
        glBlendEquationSeparatei(index, E(b.equation_rgb), E(b.equation_alpha));
        glColorMaski(index, b.colour_mask[0], b.colour_mask[1], b.colour_mask[2], b.colour_mask[3]);
    }
    glViewportIndexedfv(0, viewport_);
    glScissorIndexedv(0, scissor_box_);
    SetEnabledi(GL_SCISSOR_TEST, 0, scissor_test_);

    glUseProgram(U(program_));
    glBindVertexArray(U(vertex_array_));
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, U(draw_framebuffer_));
    glBindFramebuffer(GL_READ_FRAMEBUFFER, U(read_framebuffer_));
    for (std::size_t unit = 0; unit < kTextureUnits; ++unit) {
        glActiveTexture(GL_TEXTURE0 + static_cast<GLenum>(unit));
        glBindTexture(GL_TEXTURE_2D, U(texture_2d_[unit]));
        glBindTexture(GL_TEXTURE_3D, U(texture_3d_[unit]));
    }
    glActiveTexture(E(active_texture_));
    glBindSamplers(0, kTextureUnits, sampler_.data());

    // glBindBufferBase and glBindBufferRange set the generic binding too: it goes back last.
    const auto bind = [](GLenum target, GLuint index, const BufferRange& r) {
        if (r.buffer == 0 || r.size == 0) {
            glBindBufferBase(target, index, U(r.buffer));
        } else {
            glBindBufferRange(target, index, U(r.buffer), static_cast<GLintptr>(r.start),
                              static_cast<GLsizeiptr>(r.size));
        }
    };
    for (std::size_t i = 0; i < kUniformBindings; ++i) {
        bind(GL_UNIFORM_BUFFER, static_cast<GLuint>(i), uniform_[i]);
    }
    glBindBuffer(GL_UNIFORM_BUFFER, U(uniform_buffer_));
    bind(GL_SHADER_STORAGE_BUFFER, static_cast<GLuint>(kLightStorageBinding), storage_);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, U(storage_buffer_));
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, U(draw_indirect_buffer_));
    for (std::size_t i = 0; i < kImageUnits; ++i) {
        const ImageUnit& u = image_[i];
        glBindImageTexture(static_cast<GLuint>(i), U(u.texture), u.level,
                           static_cast<GLboolean>(u.layered), u.layer, E(u.access), E(u.format));
    }

    glBindBuffer(GL_PIXEL_PACK_BUFFER, U(pack_buffer_));
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, U(unpack_buffer_));
    glBindBuffer(GL_QUERY_BUFFER, U(query_buffer_));
    for (std::size_t i = 0; i < kPixelStore.size(); ++i) {
        glPixelStorei(kPixelStore[i].name, pixel_store_[i]);
    }
}

}  // namespace zenith::sky::gl
