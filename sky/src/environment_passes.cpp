#include "environment_passes.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "atmosphere_passes.h"
#include "bindings.h"
#include "clouds/cloud_passes.h"
#include "gl/atmosphere_uniforms.h"
#include "gl/draw.h"
#include "gl/shader_library.h"
#include "zenith/sky/gl/error.h"

namespace zenith::sky {
namespace {

gl::Program BuildFaceProgram(bool clouds, bool ray_march) {
    const std::string defines = std::string("#define ZENITH_RAY_MARCH ") +
                                (ray_march ? "1\n" : "0\n") + "#define ZENITH_CLOUDS " +
                                (clouds ? "1\n" : "0\n");
    return gl::FullscreenProgram("atmosphere/environment.frag", defines,
                                 clouds ? CloudShaderParts() : std::span<const std::string_view>{});
}

gl::Program BuildShProgram() { return gl::ComputeProgram("atmosphere/environment_sh.comp"); }

}  // namespace

std::vector<gl::Program> EnvironmentPasses::BuildPrograms() {
    std::vector<gl::Program> programs;
    for (bool clouds : {false, true}) {
        for (bool ray_march : {false, true})
            programs.push_back(BuildFaceProgram(clouds, ray_march));
    }
    programs.push_back(BuildShProgram());
    return programs;
}

EnvironmentPasses::EnvironmentPasses(const EnvironmentSettings& settings)
    : settings_(settings),
      sh_program_(BuildShProgram()),
      sh_readback_(sizeof(gl::EnvironmentShStorage)) {
    const int n = settings_.size;
    glCreateTextures(GL_TEXTURE_2D, 1, &atlas_);
    glTextureStorage2D(atlas_, 1, GL_RGBA32F, n, 6 * n);
    glCreateTextures(GL_TEXTURE_CUBE_MAP, 1, &cube_);
    const int levels = 1 + static_cast<int>(std::floor(std::log2(static_cast<double>(n))));
    glTextureStorage2D(cube_, levels, GL_RGBA32F, n, n);
    glTextureParameteri(cube_, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTextureParameteri(cube_, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(cube_, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(cube_, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glCreateFramebuffers(1, &framebuffer_);
    glNamedFramebufferTexture(framebuffer_, GL_COLOR_ATTACHMENT0, atlas_, 0);
    if (glCheckNamedFramebufferStatus(framebuffer_, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
        throw gl::GlError("the environment's RGBA32F atlas of " + std::to_string(n) + "x" +
                          std::to_string(6 * n) + " is not a complete framebuffer");
    }
    glCreateVertexArrays(1, &vertex_array_);
    glCreateBuffers(1, &sh_buffer_);
    glNamedBufferStorage(sh_buffer_, sizeof(gl::EnvironmentShStorage), nullptr, 0);
    glCreateQueries(GL_TIME_ELAPSED, static_cast<GLsizei>(queries_.size()), queries_.data());
}

EnvironmentPasses::~EnvironmentPasses() {
    glDeleteQueries(static_cast<GLsizei>(queries_.size()), queries_.data());
    glDeleteBuffers(1, &sh_buffer_);
    glDeleteVertexArrays(1, &vertex_array_);
    glDeleteFramebuffers(1, &framebuffer_);
    glDeleteTextures(1, &cube_);
    glDeleteTextures(1, &atlas_);
}

const gl::Program& EnvironmentPasses::FaceProgram(bool clouds, bool ray_march) {
    std::optional<gl::Program>& program =
        face_programs_[(clouds ? 2u : 0u) + (ray_march ? 1u : 0u)];
    if (!program) program = BuildFaceProgram(clouds, ray_march);
    return *program;
}

void EnvironmentPasses::Update(const AtmospherePasses& atmosphere, const CloudPasses* clouds,
                               bool ray_march) {
    const int n = settings_.size;
    const int faces = std::min(settings_.faces_per_frame, 6 - next_face_);
    atmosphere.BindInputs();
    if (clouds != nullptr) clouds->BindForTrace();
    query_used_.fill(false);
    gl::DrawFullscreen(FaceProgram(clouds != nullptr, ray_march), vertex_array_, framebuffer_,
                       glm::ivec4(0, next_face_ * n, n, faces * n), gl::Blend::kReplace,
                       queries_[0]);
    query_used_[0] = true;
    for (int face = next_face_; face < next_face_ + faces; ++face) {
        glCopyImageSubData(atlas_, GL_TEXTURE_2D, 0, 0, face * n, 0, cube_, GL_TEXTURE_CUBE_MAP, 0,
                           0, 0, face, n, n, 1);
    }
    next_face_ += faces;
    if (next_face_ < 6) return;

    next_face_ = 0;
    ++rounds_;
    glGenerateTextureMipmap(cube_);
    sh_program_.Use();
    glBindImageTexture(kEnvironmentImageUnit, atlas_, 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA32F);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kEnvironmentStorageBinding, sh_buffer_);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    glBeginQuery(GL_TIME_ELAPSED, queries_[1]);
    glDispatchCompute(1, 1, 1);
    glEndQuery(GL_TIME_ELAPSED);
    query_used_[1] = true;
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kEnvironmentStorageBinding, 0);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_UNIFORM_BARRIER_BIT);
    sh_readback_.Copy(sh_buffer_);
}

std::optional<SphericalHarmonics9> EnvironmentPasses::LatestSh() {
    const unsigned char* bytes = sh_readback_.Latest();
    if (bytes == nullptr) return std::nullopt;
    gl::EnvironmentShStorage storage{};
    std::memcpy(&storage, bytes, sizeof(storage));
    SphericalHarmonics9 sh;
    for (std::size_t i = 0; i < 9; ++i) sh.coefficients[i] = glm::dvec3(storage.environment_sh[i]);
    return sh;
}

double EnvironmentPasses::LastMilliseconds() const {
    double ms = 0.0;
    for (std::size_t q = 0; q < queries_.size(); ++q) {
        if (!query_used_[q]) continue;
        GLuint64 ns = 0;
        glGetQueryObjectui64v(queries_[q], GL_QUERY_RESULT, &ns);
        ms += static_cast<double>(ns) * 1e-6;
    }
    return ms;
}

}  // namespace zenith::sky
