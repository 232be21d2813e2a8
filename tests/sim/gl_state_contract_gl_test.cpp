// The GL state contract of SkySystem (sky_system.h): a host leaves its context in a hostile
// state (culling that removes a counter-clockwise triangle, line polygons, a depth test that
// never passes, masked colour, odd blending, a tiny scissor box, a failing stencil test, sRGB,
// rasterizer discard, its own program, VAO, textures and samplers on every unit zenith uses,
// uniform and storage buffers, image units, pixel pack/unpack and query buffers, odd pixel
// store parameters, upper-left clip control...). Prepare, Update, Render and RenderOffscreen
// must each leave every one of ~200 state values exactly as they found it, raise no GL error,
// and draw the same sky as under the default state.
#include <glad/gl.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <glm/gtc/constants.hpp>
#include <initializer_list>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "luminance.h"
#include "zenith/sim/sky_system.h"
#include "zenith/sky/gl/context.h"
#include "zenith/weather/cloud_weather.h"

namespace zenith::sim {
namespace {

// Image units the host binds and the check reads: GL 4.5's minimum of GL_MAX_IMAGE_UNITS;
// zenith binds units 0..3 (its clouds' passes in the compute stage).
constexpr GLuint kImageUnits = 8;

using zenith::test::Luminance;

constexpr int kWidth = 64, kHeight = 48;
constexpr GLuint kUnits = 28;  // zenith uses units 0-24 (sky/shaders/bindings.glsl); a few more

// A named list of state values, each read with the matching glGet*; floats kept as doubles so
// that the comparison is exact.
class Snapshot {
  public:
    static Snapshot Take() {
        Snapshot s;
        const GLenum caps[] = {GL_CULL_FACE,
                               GL_DEPTH_TEST,
                               GL_STENCIL_TEST,
                               GL_FRAMEBUFFER_SRGB,
                               GL_RASTERIZER_DISCARD,
                               GL_PRIMITIVE_RESTART,
                               GL_PRIMITIVE_RESTART_FIXED_INDEX,
                               GL_COLOR_LOGIC_OP,
                               GL_SAMPLE_ALPHA_TO_COVERAGE,
                               GL_SAMPLE_ALPHA_TO_ONE,
                               GL_SAMPLE_COVERAGE,
                               GL_SAMPLE_MASK,
                               GL_SAMPLE_SHADING,
                               GL_CLIP_DISTANCE0,
                               GL_CLIP_DISTANCE1,
                               GL_DEPTH_CLAMP,
                               GL_POLYGON_OFFSET_FILL,
                               GL_POLYGON_SMOOTH,
                               GL_MULTISAMPLE,
                               GL_DITHER,
                               GL_PROGRAM_POINT_SIZE};
        for (GLenum cap : caps) s.Add("enabled " + Hex(cap), {glIsEnabled(cap) ? 1.0 : 0.0});
        for (GLuint i = 0; i < 2; ++i) {
            s.Add("blend enabled " + std::to_string(i), {glIsEnabledi(GL_BLEND, i) ? 1.0 : 0.0});
            s.Add("scissor enabled " + std::to_string(i),
                  {glIsEnabledi(GL_SCISSOR_TEST, i) ? 1.0 : 0.0});
            for (GLenum e : std::initializer_list<GLenum>{
                     GL_BLEND_SRC_RGB, GL_BLEND_DST_RGB, GL_BLEND_SRC_ALPHA, GL_BLEND_DST_ALPHA,
                     GL_BLEND_EQUATION_RGB, GL_BLEND_EQUATION_ALPHA}) {
                s.Indexed("blend " + Hex(e), e, i, 1);
            }
            s.IndexedBool("colour mask", GL_COLOR_WRITEMASK, i, 4);
            s.IndexedFloat("viewport", GL_VIEWPORT, i, 4);
            s.Indexed("scissor box", GL_SCISSOR_BOX, i, 4);
        }
        const std::pair<GLenum, int> integers[] = {{GL_CULL_FACE_MODE, 1},
                                                   {GL_FRONT_FACE, 1},
                                                   {GL_POLYGON_MODE, 2},
                                                   {GL_DEPTH_FUNC, 1},
                                                   {GL_DEPTH_WRITEMASK, 1},
                                                   {GL_STENCIL_FUNC, 1},
                                                   {GL_STENCIL_REF, 1},
                                                   {GL_STENCIL_VALUE_MASK, 1},
                                                   {GL_STENCIL_WRITEMASK, 1},
                                                   {GL_STENCIL_FAIL, 1},
                                                   {GL_STENCIL_PASS_DEPTH_PASS, 1},
                                                   {GL_LOGIC_OP_MODE, 1},
                                                   {GL_CLIP_ORIGIN, 1},
                                                   {GL_CLIP_DEPTH_MODE, 1},
                                                   {GL_PRIMITIVE_RESTART_INDEX, 1},
                                                   {GL_PROVOKING_VERTEX, 1},
                                                   {GL_CURRENT_PROGRAM, 1},
                                                   {GL_PROGRAM_PIPELINE_BINDING, 1},
                                                   {GL_VERTEX_ARRAY_BINDING, 1},
                                                   {GL_DRAW_FRAMEBUFFER_BINDING, 1},
                                                   {GL_READ_FRAMEBUFFER_BINDING, 1},
                                                   {GL_RENDERBUFFER_BINDING, 1},
                                                   {GL_ACTIVE_TEXTURE, 1},
                                                   {GL_ARRAY_BUFFER_BINDING, 1},
                                                   {GL_UNIFORM_BUFFER_BINDING, 1},
                                                   {GL_SHADER_STORAGE_BUFFER_BINDING, 1},
                                                   {GL_PIXEL_PACK_BUFFER_BINDING, 1},
                                                   {GL_PIXEL_UNPACK_BUFFER_BINDING, 1},
                                                   {GL_QUERY_BUFFER_BINDING, 1},
                                                   {GL_DRAW_INDIRECT_BUFFER_BINDING, 1},
                                                   {GL_DISPATCH_INDIRECT_BUFFER_BINDING, 1},
                                                   {GL_COPY_READ_BUFFER_BINDING, 1},
                                                   {GL_COPY_WRITE_BUFFER_BINDING, 1},
                                                   {GL_TRANSFORM_FEEDBACK_BINDING, 1},
                                                   {GL_PACK_ALIGNMENT, 1},
                                                   {GL_PACK_ROW_LENGTH, 1},
                                                   {GL_PACK_SKIP_ROWS, 1},
                                                   {GL_PACK_SKIP_PIXELS, 1},
                                                   {GL_PACK_IMAGE_HEIGHT, 1},
                                                   {GL_PACK_SWAP_BYTES, 1},
                                                   {GL_UNPACK_ALIGNMENT, 1},
                                                   {GL_UNPACK_ROW_LENGTH, 1},
                                                   {GL_UNPACK_SKIP_ROWS, 1},
                                                   {GL_UNPACK_SKIP_PIXELS, 1},
                                                   {GL_UNPACK_IMAGE_HEIGHT, 1},
                                                   {GL_UNPACK_SKIP_IMAGES, 1},
                                                   {GL_UNPACK_SWAP_BYTES, 1}};
        for (const auto& [e, n] : integers) s.Integer("integer " + Hex(e), e, n);
        const std::pair<GLenum, int> floats[] = {
            {GL_BLEND_COLOR, 4},          {GL_DEPTH_RANGE, 2}, {GL_DEPTH_CLEAR_VALUE, 1},
            {GL_COLOR_CLEAR_VALUE, 4},    {GL_LINE_WIDTH, 1},  {GL_POINT_SIZE, 1},
            {GL_POLYGON_OFFSET_FACTOR, 1}};
        for (const auto& [e, n] : floats) s.Float("float " + Hex(e), e, n);

        // Texture units: every target zenith binds (and two it does not), and the samplers.
        GLint active = 0;
        glGetIntegerv(GL_ACTIVE_TEXTURE, &active);
        for (GLuint unit = 0; unit < kUnits; ++unit) {
            glActiveTexture(GL_TEXTURE0 + unit);
            for (GLenum e : std::initializer_list<GLenum>{
                     GL_TEXTURE_BINDING_2D, GL_TEXTURE_BINDING_3D, GL_TEXTURE_BINDING_CUBE_MAP,
                     GL_TEXTURE_BINDING_2D_MULTISAMPLE}) {
                s.Integer("unit " + std::to_string(unit) + " " + Hex(e), e, 1);
            }
            s.Integer("unit " + std::to_string(unit) + " sampler", GL_SAMPLER_BINDING, 1);
        }
        glActiveTexture(static_cast<GLenum>(active));
        // Indexed buffer bindings and image units.
        for (GLuint i = 0; i < 8; ++i) {
            for (GLenum e : std::initializer_list<GLenum>{
                     GL_UNIFORM_BUFFER_BINDING, GL_UNIFORM_BUFFER_START, GL_UNIFORM_BUFFER_SIZE}) {
                s.Indexed("ubo " + Hex(e), e, i, 1);
            }
        }
        for (GLuint i = 0; i < 4; ++i) {
            for (GLenum e : std::initializer_list<GLenum>{GL_SHADER_STORAGE_BUFFER_BINDING,
                                                          GL_SHADER_STORAGE_BUFFER_START,
                                                          GL_SHADER_STORAGE_BUFFER_SIZE}) {
                s.Indexed("ssbo " + Hex(e), e, i, 1);
            }
        }
        for (GLuint i = 0; i < kImageUnits; ++i) {
            for (GLenum e : std::initializer_list<GLenum>{
                     GL_IMAGE_BINDING_NAME, GL_IMAGE_BINDING_LEVEL, GL_IMAGE_BINDING_LAYERED,
                     GL_IMAGE_BINDING_LAYER, GL_IMAGE_BINDING_ACCESS, GL_IMAGE_BINDING_FORMAT}) {
                s.Indexed("image " + Hex(e), e, i, 1);
            }
        }
        return s;
    }

    std::size_t size() const { return values_.size(); }

    // The values that differ, one line each ("" when none do).
    std::string Differences(const Snapshot& after) const {
        std::string out;
        for (std::size_t i = 0; i < values_.size(); ++i) {
            if (values_[i].second == after.values_[i].second) continue;
            out.append("  ").append(values_[i].first).append(":");
            for (double v : values_[i].second) out.append(" ").append(Number(v));
            out.append(" ->");
            for (double v : after.values_[i].second) out.append(" ").append(Number(v));
            out.append("\n");
        }
        return out;
    }

  private:
    static std::string Hex(GLenum e) {
        char text[16];
        std::snprintf(text, sizeof(text), "0x%04X", e);
        return text;
    }
    static std::string Number(double v) {
        char text[32];
        std::snprintf(text, sizeof(text), "%.9g", v);
        return text;
    }
    void Add(std::string name, std::vector<double> v) {
        values_.emplace_back(std::move(name), std::move(v));
    }
    void Integer(std::string name, GLenum e, int n) {
        std::array<GLint64, 4> v{};
        glGetInteger64v(e, v.data());
        Add(std::move(name), std::vector<double>(v.begin(), v.begin() + n));
    }
    void Float(std::string name, GLenum e, int n) {
        std::array<GLfloat, 4> v{};
        glGetFloatv(e, v.data());
        Add(std::move(name), std::vector<double>(v.begin(), v.begin() + n));
    }
    void Indexed(std::string name, GLenum e, GLuint i, int n) {
        std::array<GLint64, 4> v{};
        glGetInteger64i_v(e, i, v.data());
        Add(name + " [" + std::to_string(i) + "]", std::vector<double>(v.begin(), v.begin() + n));
    }
    void IndexedBool(std::string name, GLenum e, GLuint i, int n) {
        std::array<GLboolean, 4> v{};
        glGetBooleani_v(e, i, v.data());
        Add(name + " [" + std::to_string(i) + "]", std::vector<double>(v.begin(), v.begin() + n));
    }
    void IndexedFloat(std::string name, GLenum e, GLuint i, int n) {
        std::array<GLfloat, 4> v{};
        glGetFloati_v(e, i, v.data());
        Add(name + " [" + std::to_string(i) + "]", std::vector<double>(v.begin(), v.begin() + n));
    }
    std::vector<std::pair<std::string, std::vector<double>>> values_;
};

// The host's GL objects: a framebuffer (RGBA32F colour, depth-stencil), and things to bind.
struct Host {
    GLuint colour = 0, depth_stencil = 0, framebuffer = 0, read_framebuffer = 0, read_colour = 0;
    GLuint program = 0, vertex_array = 0, texture_2d = 0, texture_3d = 0, image = 0, sampler = 0;
    GLuint buffer = 0, other_buffer = 0, transform_feedback = 0;
    GLint ubo_alignment = 256, ssbo_alignment = 256;

    Host() {
        glCreateTextures(GL_TEXTURE_2D, 1, &colour);
        glTextureStorage2D(colour, 1, GL_RGBA32F, kWidth, kHeight);
        glCreateRenderbuffers(1, &depth_stencil);
        glNamedRenderbufferStorage(depth_stencil, GL_DEPTH24_STENCIL8, kWidth, kHeight);
        glCreateFramebuffers(1, &framebuffer);
        glNamedFramebufferTexture(framebuffer, GL_COLOR_ATTACHMENT0, colour, 0);
        glNamedFramebufferRenderbuffer(framebuffer, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER,
                                       depth_stencil);
        glCreateTextures(GL_TEXTURE_2D, 1, &read_colour);
        glTextureStorage2D(read_colour, 1, GL_RGBA8, 4, 4);
        glCreateFramebuffers(1, &read_framebuffer);
        glNamedFramebufferTexture(read_framebuffer, GL_COLOR_ATTACHMENT0, read_colour, 0);

        const char* vs = "#version 450 core\nvoid main() { gl_Position = vec4(0.0); }\n";
        const char* fs = "#version 450 core\nout vec4 c;\nvoid main() { c = vec4(1.0); }\n";
        program = glCreateProgram();
        for (auto [type, source] :
             {std::pair<GLenum, const char*>{GL_VERTEX_SHADER, vs}, {GL_FRAGMENT_SHADER, fs}}) {
            const GLuint shader = glCreateShader(type);
            glShaderSource(shader, 1, &source, nullptr);
            glCompileShader(shader);
            glAttachShader(program, shader);
            glDeleteShader(shader);
        }
        glLinkProgram(program);
        glCreateVertexArrays(1, &vertex_array);
        glCreateTextures(GL_TEXTURE_2D, 1, &texture_2d);
        glTextureStorage2D(texture_2d, 1, GL_RGBA8, 2, 2);
        glCreateTextures(GL_TEXTURE_3D, 1, &texture_3d);
        glTextureStorage3D(texture_3d, 1, GL_RGBA8, 2, 2, 2);
        glCreateTextures(GL_TEXTURE_2D, 1, &image);
        glTextureStorage2D(image, 1, GL_R32F, 2, 2);
        glCreateSamplers(1, &sampler);
        glSamplerParameteri(sampler, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glSamplerParameteri(sampler, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glSamplerParameteri(sampler, GL_TEXTURE_WRAP_S, GL_MIRRORED_REPEAT);
        glSamplerParameteri(sampler, GL_TEXTURE_WRAP_T, GL_MIRRORED_REPEAT);
        glSamplerParameteri(sampler, GL_TEXTURE_WRAP_R, GL_MIRRORED_REPEAT);
        glCreateBuffers(1, &buffer);
        glNamedBufferStorage(buffer, 16384, nullptr, GL_DYNAMIC_STORAGE_BIT);
        glCreateBuffers(1, &other_buffer);
        glNamedBufferStorage(other_buffer, 1024, nullptr, GL_DYNAMIC_STORAGE_BIT);
        glCreateTransformFeedbacks(1, &transform_feedback);
        glGetIntegerv(GL_UNIFORM_BUFFER_OFFSET_ALIGNMENT, &ubo_alignment);
        glGetIntegerv(GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT, &ssbo_alignment);
    }
    ~Host() {
        glDeleteFramebuffers(1, &framebuffer);
        glDeleteFramebuffers(1, &read_framebuffer);
        glDeleteRenderbuffers(1, &depth_stencil);
        for (GLuint t : {colour, read_colour, texture_2d, texture_3d, image})
            glDeleteTextures(1, &t);
        glDeleteProgram(program);
        glDeleteVertexArrays(1, &vertex_array);
        glDeleteSamplers(1, &sampler);
        glDeleteBuffers(1, &buffer);
        glDeleteBuffers(1, &other_buffer);
        glDeleteTransformFeedbacks(1, &transform_feedback);
    }

    // The colour the sky was drawn into (row 0 = bottom), read with default pixel state.
    std::vector<glm::vec4> Read() const {
        std::vector<glm::vec4> pixels(static_cast<std::size_t>(kWidth * kHeight));
        glGetTextureImage(colour, 0, GL_RGBA, GL_FLOAT,
                          static_cast<GLsizei>(pixels.size() * sizeof(glm::vec4)), pixels.data());
        return pixels;
    }
    void Clear() const {
        const float marker[4] = {-1.0f, -1.0f, -1.0f, -1.0f};
        glClearNamedFramebufferfv(framebuffer, GL_COLOR, 0, marker);
        glClearNamedFramebufferfi(framebuffer, GL_DEPTH_STENCIL, 0, 1.0f, 0);
    }
};

// What differs between the hostile states (everything else is hostile in all of them).
struct Hostility {
    const char* name;
    GLenum cull_face;
    GLenum front_face;
    GLenum polygon_mode;
    GLenum clip_origin;
};
constexpr Hostility kHostilities[] = {
    {"back-face culling, clockwise front faces", GL_BACK, GL_CW, GL_FILL, GL_LOWER_LEFT},
    {"front-face culling, line polygons", GL_FRONT, GL_CCW, GL_LINE, GL_LOWER_LEFT},
    {"culling both, point polygons, upper-left origin", GL_FRONT_AND_BACK, GL_CCW, GL_POINT,
     GL_UPPER_LEFT},
};

void ApplyHostileState(const Host& host, const Hostility& h) {
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, host.framebuffer);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, host.read_framebuffer);
    glBindRenderbuffer(GL_RENDERBUFFER, host.depth_stencil);
    glEnable(GL_CULL_FACE);
    glCullFace(h.cull_face);
    glFrontFace(h.front_face);
    glPolygonMode(GL_FRONT_AND_BACK, h.polygon_mode);
    glClipControl(h.clip_origin, GL_ZERO_TO_ONE);  // reversed-Z hosts set this
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_NEVER);
    glDepthMask(GL_FALSE);
    glDepthRangef(0.25f, 0.75f);
    glClearDepthf(0.0f);
    glClearColor(0.1f, 0.2f, 0.3f, 0.4f);
    glColorMaski(0, GL_TRUE, GL_FALSE, GL_TRUE, GL_FALSE);
    glColorMaski(1, GL_FALSE, GL_TRUE, GL_FALSE, GL_TRUE);
    glEnablei(GL_BLEND, 0);
    glBlendFuncSeparatei(0, GL_ZERO, GL_ONE_MINUS_SRC_COLOR, GL_DST_ALPHA, GL_ZERO);
    glBlendEquationSeparatei(0, GL_MIN, GL_FUNC_REVERSE_SUBTRACT);
    glBlendFunci(1, GL_CONSTANT_COLOR, GL_SRC_ALPHA_SATURATE);
    glBlendColor(0.1f, 0.2f, 0.3f, 0.4f);
    glEnable(GL_SCISSOR_TEST);
    glScissorIndexed(0, 3, 3, 2, 2);
    glScissorIndexed(1, 5, 6, 7, 8);
    glDisablei(GL_SCISSOR_TEST, 1);
    glViewportIndexedf(0, 1.0f, 2.0f, 3.0f, 4.0f);
    glViewportIndexedf(1, 5.0f, 6.0f, 7.0f, 8.0f);
    glEnable(GL_STENCIL_TEST);
    glStencilFunc(GL_NEVER, 3, 0x0f);
    glStencilOp(GL_INVERT, GL_INCR, GL_DECR_WRAP);
    glStencilMask(0x3c);
    glEnable(GL_FRAMEBUFFER_SRGB);
    glEnable(GL_RASTERIZER_DISCARD);
    glEnable(GL_PRIMITIVE_RESTART);
    glPrimitiveRestartIndex(7);
    glEnable(GL_COLOR_LOGIC_OP);
    glLogicOp(GL_CLEAR);
    glEnable(GL_SAMPLE_ALPHA_TO_COVERAGE);
    glEnable(GL_SAMPLE_COVERAGE);
    glEnable(GL_SAMPLE_MASK);
    glEnable(GL_SAMPLE_SHADING);
    glEnable(GL_CLIP_DISTANCE0);
    glEnable(GL_CLIP_DISTANCE1);
    glEnable(GL_DEPTH_CLAMP);
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(3.0f, 4.0f);
    glEnable(GL_POLYGON_SMOOTH);
    glDisable(GL_DITHER);
    glEnable(GL_PROGRAM_POINT_SIZE);
    glPointSize(3.0f);
    glProvokingVertex(GL_FIRST_VERTEX_CONVENTION);
    glUseProgram(host.program);
    glBindVertexArray(host.vertex_array);
    glBindBuffer(GL_ARRAY_BUFFER, host.other_buffer);
    for (GLuint unit = 0; unit < kUnits; ++unit) {
        glBindTextureUnit(unit, host.texture_2d);
        glBindTextureUnit(unit, host.texture_3d);
        glBindSampler(unit, host.sampler);
    }
    glActiveTexture(GL_TEXTURE5);
    for (GLuint i = 0; i < 8; ++i) {
        glBindBufferRange(GL_UNIFORM_BUFFER, i, host.buffer,
                          static_cast<GLintptr>(i) * host.ubo_alignment, 64);
    }
    glBindBuffer(GL_UNIFORM_BUFFER, host.other_buffer);
    for (GLuint i = 0; i < 4; ++i) {
        glBindBufferRange(GL_SHADER_STORAGE_BUFFER, i, host.buffer,
                          static_cast<GLintptr>(i) * host.ssbo_alignment, 128);
    }
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, host.other_buffer);
    for (GLuint i = 0; i < kImageUnits; ++i) {
        glBindImageTexture(i, host.image, 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32F);
    }
    glBindBuffer(GL_PIXEL_PACK_BUFFER, host.buffer);
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, host.other_buffer);
    glBindBuffer(GL_QUERY_BUFFER, host.other_buffer);
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, host.other_buffer);
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, host.other_buffer);
    glBindBuffer(GL_COPY_READ_BUFFER, host.buffer);
    glBindBuffer(GL_COPY_WRITE_BUFFER, host.other_buffer);
    glBindTransformFeedback(GL_TRANSFORM_FEEDBACK, host.transform_feedback);  // bound, not active
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glPixelStorei(GL_PACK_ROW_LENGTH, 3);
    glPixelStorei(GL_PACK_SKIP_ROWS, 1);
    glPixelStorei(GL_PACK_SKIP_PIXELS, 2);
    glPixelStorei(GL_PACK_IMAGE_HEIGHT, 5);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 8);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 5);
    glPixelStorei(GL_UNPACK_SKIP_ROWS, 2);
    glPixelStorei(GL_UNPACK_SKIP_PIXELS, 1);
    glPixelStorei(GL_UNPACK_IMAGE_HEIGHT, 3);
    glPixelStorei(GL_UNPACK_SKIP_IMAGES, 1);
}

// Back to GL's initial state (of what ApplyHostileState touches), for the reference frames and
// the test's own read-backs.
void ApplyDefaultState() {
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glBindRenderbuffer(GL_RENDERBUFFER, 0);
    glDisable(GL_CULL_FACE);
    glCullFace(GL_BACK);
    glFrontFace(GL_CCW);
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
    glDisable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDepthRangef(0.0f, 1.0f);
    glClearDepthf(1.0f);
    glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDisable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ZERO);
    glBlendEquation(GL_FUNC_ADD);
    glBlendColor(0.0f, 0.0f, 0.0f, 0.0f);
    glDisable(GL_SCISSOR_TEST);
    glScissor(0, 0, kWidth, kHeight);
    glViewport(0, 0, kWidth, kHeight);
    glDisable(GL_STENCIL_TEST);
    glStencilFunc(GL_ALWAYS, 0, ~0u);
    glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
    glStencilMask(~0u);
    for (GLenum cap : std::initializer_list<GLenum>{
             GL_FRAMEBUFFER_SRGB, GL_RASTERIZER_DISCARD, GL_PRIMITIVE_RESTART, GL_COLOR_LOGIC_OP,
             GL_SAMPLE_ALPHA_TO_COVERAGE, GL_SAMPLE_COVERAGE, GL_SAMPLE_MASK, GL_SAMPLE_SHADING,
             GL_CLIP_DISTANCE0, GL_CLIP_DISTANCE1, GL_DEPTH_CLAMP, GL_POLYGON_OFFSET_FILL,
             GL_POLYGON_SMOOTH, GL_PROGRAM_POINT_SIZE}) {
        glDisable(cap);
    }
    glEnable(GL_DITHER);
    glPrimitiveRestartIndex(0);
    glLogicOp(GL_COPY);
    glPolygonOffset(0.0f, 0.0f);
    glPointSize(1.0f);
    glProvokingVertex(GL_LAST_VERTEX_CONVENTION);
    glUseProgram(0);
    glBindVertexArray(0);
    for (GLuint unit = 0; unit < kUnits; ++unit) {
        glBindTextureUnit(unit, 0);
        glBindSampler(unit, 0);
    }
    glActiveTexture(GL_TEXTURE0);
    for (GLuint i = 0; i < 8; ++i) glBindBufferBase(GL_UNIFORM_BUFFER, i, 0);
    for (GLuint i = 0; i < 4; ++i) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, i, 0);
    for (GLuint i = 0; i < kImageUnits; ++i)
        glBindImageTexture(i, 0, 0, GL_FALSE, 0, GL_READ_ONLY, GL_R8);
    for (GLenum target : std::initializer_list<GLenum>{
             GL_ARRAY_BUFFER, GL_UNIFORM_BUFFER, GL_SHADER_STORAGE_BUFFER, GL_PIXEL_PACK_BUFFER,
             GL_PIXEL_UNPACK_BUFFER, GL_QUERY_BUFFER, GL_DRAW_INDIRECT_BUFFER,
             GL_DISPATCH_INDIRECT_BUFFER, GL_COPY_READ_BUFFER, GL_COPY_WRITE_BUFFER}) {
        glBindBuffer(target, 0);
    }
    glBindTransformFeedback(GL_TRANSFORM_FEEDBACK, 0);
    for (GLenum e : std::initializer_list<GLenum>{
             GL_PACK_ROW_LENGTH, GL_PACK_SKIP_ROWS, GL_PACK_SKIP_PIXELS, GL_PACK_IMAGE_HEIGHT,
             GL_UNPACK_ROW_LENGTH, GL_UNPACK_SKIP_ROWS, GL_UNPACK_SKIP_PIXELS,
             GL_UNPACK_IMAGE_HEIGHT, GL_UNPACK_SKIP_IMAGES}) {
        glPixelStorei(e, 0);
    }
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
}

double MeanLuminance(const std::vector<glm::vec4>& pixels) {
    double sum = 0.0;
    for (const glm::vec4& p : pixels) sum += Luminance(p);
    return sum / static_cast<double>(pixels.size());
}

// The largest relative difference of any channel of any pixel (against the reference's scale).
double WorstDifference(const std::vector<glm::vec4>& a, const std::vector<glm::vec4>& b) {
    double worst = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        for (int c = 0; c < 3; ++c) {
            const double scale = std::max(1e-3, std::abs(static_cast<double>(b[i][c])));
            worst = std::max(worst, std::abs(static_cast<double>(a[i][c] - b[i][c])) / scale);
        }
    }
    return worst;
}

std::string GlErrors() {
    std::string out;
    for (GLenum e = glGetError(); e != GL_NO_ERROR; e = glGetError()) {
        out.append(" ").append(std::to_string(e));
    }
    return out;
}

// The test plays a host: its own context, zenith attached to it with CreateInHostContext.
class GlStateContractTest : public ::testing::Test {
  protected:
    static void SetUpTestSuite() {
        context_ = sky::gl::CreateHeadlessContextFromEnvironment().release();
    }
    static void TearDownTestSuite() {
        delete context_;
        context_ = nullptr;
    }

    static std::unique_ptr<SkySystem> MakeSky(bool preserve_gl_state) {
        SkySystemSettings settings;
        settings.preserve_gl_state = preserve_gl_state;
        auto sky = SkySystem::CreateInHostContext(context_->get_proc_address(), settings);
        sky->SetTime(geo::TimeFromIso8601("2024-06-21T17:30:00Z"));
        sky->SetGeodetic(47.45, 8.56, 1200.0);
        sky->SetAttitude(glm::radians(290.0), 0.08, 0.05);
        sky->SetProjection(1.0, static_cast<double>(kWidth) / kHeight);
        return sky;
    }

    // MakeSky's, under the overcast_stratus deck, its passes in `stage`.
    static std::unique_ptr<SkySystem> MakeOvercastSky(
        sky::CloudPassStage stage = sky::CloudPassStage::kAuto) {
        auto sky = MakeSky(true);
        sky::CloudSettings settings;
        settings.pass_stage = stage;
        settings.noise_cache_directory =
            std::filesystem::path(ZENITH_BINARY_DIR) / "cloud-noise-cache";
        sky->SetWeather(sky::clouds::LoadWeather("overcast_stratus"), settings);
        return sky;
    }

    // One frame into the host's framebuffer under the state in force; the first history.
    static void Frame(SkySystem& sky, const Host& host) {
        sky.ResetCloudHistory();
        sky.Update();
        sky.Render(host.framebuffer, {0, 0, kWidth, kHeight});
    }

    // The frame under the default state, read back.
    static std::vector<glm::vec4> Reference(SkySystem& sky, const Host& host) {
        ApplyDefaultState();
        host.Clear();
        Frame(sky, host);
        return host.Read();
    }

    // Prepare, Update, Render and RenderOffscreen under each hostile state: the state after each
    // call is the state before it, no GL error, and the sky the same as `reference`.
    static void CheckEveryCall(SkySystem& sky, const Host& host,
                               const std::vector<glm::vec4>& reference,
                               const sky::LutImage& reference_offscreen) {
        const double reference_mean = MeanLuminance(reference);
        for (const Hostility& h : kHostilities) {
            SCOPED_TRACE(h.name);
            ApplyDefaultState();
            host.Clear();
            ApplyHostileState(host, h);
            ASSERT_EQ(GlErrors(), "");
            const Snapshot before = Snapshot::Take();
            const auto expect_unchanged = [&](const char* call) {
                const Snapshot after = Snapshot::Take();
                EXPECT_EQ(before.Differences(after), "") << call << " changed the host's state";
                EXPECT_EQ(GlErrors(), "") << call << " raised GL errors";
            };
            sky.Prepare({kWidth, kHeight});
            expect_unchanged("Prepare");
            sky.ResetCloudHistory();
            sky.Update();
            expect_unchanged("Update");
            sky.Render(host.framebuffer, {0, 0, kWidth, kHeight});
            expect_unchanged("Render");
            sky.ResetCloudHistory();
            sky.Update();
            const sky::LutImage offscreen = sky.RenderOffscreen({kWidth, kHeight});
            expect_unchanged("RenderOffscreen");

            ApplyDefaultState();
            const std::vector<glm::vec4> pixels = host.Read();
            const double mean = MeanLuminance(pixels);
            const double worst = WorstDifference(pixels, reference);
            std::printf("%s: mean %.6g cd/m^2 (default state %.6g), worst pixel %.3g\n", h.name,
                        mean, reference_mean, worst);
            EXPECT_NEAR(mean, reference_mean, 1e-5 * reference_mean);
            EXPECT_LT(worst, 1e-4);
            ASSERT_EQ(offscreen.texels.size(), reference_offscreen.texels.size());
            double worst_offscreen = 0.0;
            for (std::size_t i = 0; i < offscreen.texels.size(); ++i) {
                for (int c = 0; c < 3; ++c) {
                    const double want = reference_offscreen.texels[i][c];
                    const double got = offscreen.texels[i][c];
                    worst_offscreen = std::max(
                        worst_offscreen, std::abs(got - want) / std::max(1e-3, std::abs(want)));
                }
            }
            EXPECT_LT(worst_offscreen, 1e-4) << "RenderOffscreen";
        }
        ApplyDefaultState();
    }

    static sky::LutImage ReferenceOffscreen(SkySystem& sky) {
        ApplyDefaultState();
        sky.ResetCloudHistory();
        sky.Update();
        return sky.RenderOffscreen({kWidth, kHeight});
    }

    static sky::gl::HeadlessContext* context_;
};
sky::gl::HeadlessContext* GlStateContractTest::context_ = nullptr;

TEST_F(GlStateContractTest, ClearSkyUnderAHostileHostState) {
    const Host host;
    const auto sky = MakeSky(true);
    const std::vector<glm::vec4> reference = Reference(*sky, host);
    const sky::LutImage offscreen = ReferenceOffscreen(*sky);
    ASSERT_GT(MeanLuminance(reference), 100.0);  // a daylit sky
    std::printf("%zu state values compared after each call\n", Snapshot::Take().size());
    CheckEveryCall(*sky, host, reference, offscreen);
}

// In both stages of the clouds' passes (compute: image units the fragment stage leaves alone).
TEST_F(GlStateContractTest, CloudsUnderAHostileHostState) {
    const Host host;
    for (const sky::CloudPassStage stage :
         {sky::CloudPassStage::kFragment, sky::CloudPassStage::kCompute}) {
        SCOPED_TRACE(stage == sky::CloudPassStage::kCompute ? "compute" : "fragment");
        const auto sky = MakeOvercastSky(stage);
        // With the environment's faces (all six each Update), mip levels, projection and
        // read-back.
        sky::EnvironmentSettings environment;
        environment.size = 16;
        environment.faces_per_frame = 6;
        sky->SetEnvironment(environment);
        const std::vector<glm::vec4> reference = Reference(*sky, host);
        const sky::LutImage offscreen = ReferenceOffscreen(*sky);
        CheckEveryCall(*sky, host, reference, offscreen);
    }
}

// Over the host's depth, the clouds in front of its geometry: the cells where they disagree are
// listed in a storage buffer and marched by an indirect draw (CloudPasses::MarchToGeometry), the
// host's own indirect and storage bindings restored after.
TEST_F(GlStateContractTest, CloudsOverTheHostsDepthUnderAHostileHostState) {
    const Host host;
    const auto sky = MakeOvercastSky();
    // The lower half 1.5 km away, the upper half at the far plane (near 1 m, far 100 km).
    GLuint depth = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &depth);
    glTextureStorage2D(depth, 1, GL_DEPTH_COMPONENT32F, kWidth, kHeight);
    constexpr double kNear = 1.0, kFar = 100000.0, kEyeDepth = 1500.0;
    const float geometry = static_cast<float>(
        0.5 * ((kFar + kNear - 2.0 * kNear * kFar / kEyeDepth) / (kFar - kNear) + 1.0));
    std::vector<float> values(static_cast<std::size_t>(kWidth * kHeight), 1.0f);
    std::fill(values.begin(), values.begin() + kWidth * kHeight / 2, geometry);
    glTextureSubImage2D(depth, 0, 0, 0, kWidth, kHeight, GL_DEPTH_COMPONENT, GL_FLOAT,
                        values.data());
    sky->SetSceneDepth(depth, kNear, kFar);
    const std::vector<glm::vec4> reference = Reference(*sky, host);
    const sky::LutImage offscreen = ReferenceOffscreen(*sky);
    CheckEveryCall(*sky, host, reference, offscreen);
    sky->ClearSceneDepth();
    glDeleteTextures(1, &depth);
}

// The display pass (metered, night adaptation on) is under the same contract: Render then draws
// into zenith's own frame, meters it (compute passes, a storage buffer) and writes display values.
TEST_F(GlStateContractTest, DisplayPassUnderAHostileHostState) {
    const Host host;
    const auto sky = MakeSky(true);
    sky::DisplaySettings display;
    display.output = sky::DisplaySettings::Output::kDisplay;
    display.adaptation_time_s = 0.0;  // each frame its own exposure: frames comparable
    sky->SetDisplay(display);
    const std::vector<glm::vec4> reference = Reference(*sky, host);
    const sky::LutImage offscreen = ReferenceOffscreen(*sky);
    const double mean = MeanLuminance(reference);
    EXPECT_GT(mean, 0.05);  // display values, not cd/m^2
    EXPECT_LT(mean, 0.95);
    CheckEveryCall(*sky, host, reference, offscreen);
}

// Without the save and restore, zenith still sets every state it depends on: the sky is right
// under the hostile state; what it leaves behind is the host's to reset.
TEST_F(GlStateContractTest, WithoutPreservingTheSkyIsStillRight) {
    const Host host;
    const auto sky = MakeSky(false);
    const std::vector<glm::vec4> reference = Reference(*sky, host);
    for (const Hostility& h : kHostilities) {
        SCOPED_TRACE(h.name);
        ApplyDefaultState();
        host.Clear();
        ApplyHostileState(host, h);
        Frame(*sky, host);
        EXPECT_EQ(GlErrors(), "");
        ApplyDefaultState();
        EXPECT_LT(WorstDifference(host.Read(), reference), 1e-4);
    }
}

}  // namespace
}  // namespace zenith::sim
