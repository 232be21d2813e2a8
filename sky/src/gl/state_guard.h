// The renderer's side of the GL state contract (sim/include/zenith/sim/sky_system.h documents
// it for hosts): every AtmosphereRenderer entry point that issues GL commands holds a StateGuard.
// Its constructor sets every piece of state the passes depend on but do not set per pass, so a
// host may leave the context in any state; with `preserve` it first saves everything zenith
// sets or changes (the state it establishes and the bindings the passes make), and its
// destructor puts it back, so the host finds its context as it left it.
//
// What zenith changes inside a guard must be in the saved set: state_guard.cpp lists both, and
// tests/sim/gl_state_contract_gl_test.cpp compares ~250 values before and after each call.
#pragma once

#include <glad/gl.h>

#include <array>

#include "bindings.h"

namespace zenith::sky::gl {

class StateGuard {
  public:
    // Texture units 0..kTextureUnitCount - 1, uniform blocks 0..kPrecipitationBlockBinding,
    // storage block 1, image units 0..kImageUnitCount - 1 and the indirect draw buffer: every
    // one the passes bind (sky/shaders/bindings.glsl).
    static constexpr int kTextureUnits = kTextureUnitCount;
    static constexpr int kUniformBindings = kPrecipitationBlockBinding + 1;
    static constexpr int kImageUnits = kImageUnitCount;
    static constexpr int kMaxDrawBuffers = 8;  // GL 4.5's minimum; more are left alone
    static constexpr int kMaxClipDistances = 8;
    static constexpr std::size_t kCapabilityCount = 16;  // state_guard.cpp's kCapabilities

    explicit StateGuard(bool preserve);
    ~StateGuard();
    StateGuard(const StateGuard&) = delete;
    StateGuard& operator=(const StateGuard&) = delete;

  private:
    void Save();
    void Restore() const;
    static void Establish(int draw_buffers, int clip_distances);

    bool preserve_;
    int draw_buffers_ = 0;    // min(GL_MAX_DRAW_BUFFERS, kMaxDrawBuffers)
    int clip_distances_ = 0;  // min(GL_MAX_CLIP_DISTANCES, kMaxClipDistances)

    // Capabilities (glIsEnabled), in the order of state_guard.cpp's kCapabilities.
    std::array<GLboolean, kCapabilityCount> capabilities_{};
    std::array<GLboolean, kMaxClipDistances> clip_distance_{};
    GLint polygon_mode_[2] = {};
    GLfloat point_size_ = 1.0f;
    GLint clip_origin_ = 0, clip_depth_mode_ = 0;

    // Per draw buffer: blending and colour writes.
    struct DrawBuffer {
        GLboolean blend = GL_FALSE;
        GLint src_rgb = 0, dst_rgb = 0, src_alpha = 0, dst_alpha = 0;
        GLint equation_rgb = 0, equation_alpha = 0;
        GLboolean colour_mask[4] = {};
    };
    std::array<DrawBuffer, kMaxDrawBuffers> draw_buffer_{};
    // Viewport and scissor 0: the passes draw with gl_ViewportIndex 0 only.
    GLfloat viewport_[4] = {};
    GLint scissor_box_[4] = {};
    GLboolean scissor_test_ = GL_FALSE;

    GLint program_ = 0, vertex_array_ = 0, draw_framebuffer_ = 0, read_framebuffer_ = 0;
    GLint active_texture_ = 0;
    std::array<GLint, kTextureUnits> texture_2d_{}, texture_3d_{};
    std::array<GLuint, kTextureUnits> sampler_{};

    struct BufferRange {
        GLint buffer = 0;
        GLint64 start = 0, size = 0;
    };
    std::array<BufferRange, kUniformBindings> uniform_{};
    BufferRange storage_{};  // kLightStorageBinding
    GLint uniform_buffer_ = 0, storage_buffer_ = 0;
    GLint draw_indirect_buffer_ = 0;  // clouds/geometry_march.*'s draw

    struct ImageUnit {
        GLint texture = 0, level = 0, layered = 0, layer = 0, access = 0, format = 0;
    };
    std::array<ImageUnit, kImageUnits> image_{};

    // Read-backs and uploads: buffer bindings and pixel store parameters, in the order of
    // state_guard.cpp's kPixelStore.
    GLint pack_buffer_ = 0, unpack_buffer_ = 0, query_buffer_ = 0;
    std::array<GLint, 14> pixel_store_{};
};

}  // namespace zenith::sky::gl
