// The display pass (zenith/sky/display.h): meter (display/histogram.comp, display/meter.comp),
// then display (display/display.frag), with the shared formulas of common/display.glsl.
#include "zenith/sky/display.h"

#include <glad/gl.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

#include "gl/display_uniforms.h"
#include "gl/draw.h"
#include "gl/shader_library.h"
#include "gl/state_guard.h"
#include "zenith/base/error.h"

namespace zenith::sky {
namespace {

constexpr std::size_t kHistogramOffset = offsetof(gl::DisplayStorage, histogram);
constexpr std::size_t kStorageBytes = sizeof(gl::DisplayStorage);

constexpr std::array<std::string_view, 2> kParts = {"common/display.glsl", "display/storage.glsl"};

}  // namespace

namespace gl {
std::vector<Program> BuildDisplayPrograms() {
    std::vector<Program> programs;
    programs.push_back(ComputeProgram("display/histogram.comp", kParts));
    programs.push_back(ComputeProgram("display/meter.comp", kParts));
    programs.push_back(FullscreenProgram("display/display.frag", {}, kParts));
    return programs;
}
}  // namespace gl

void DisplaySettings::Validate() const {
    if (ev100) Require("display.ev100", *ev100, "EV100", Range::Closed(-20.0, 30.0));
    Require("display.adaptation_time_s", adaptation_time_s, "s", Range::Closed(0.0, 3600.0));
    Require("display.compensation_ev", compensation_ev, "EV", Range::Closed(-20.0, 20.0));
}

struct DisplayPass::Impl {
    std::vector<gl::Program> programs = gl::BuildDisplayPrograms();
    gl::Program& histogram = programs[gl::kDisplayHistogramProgram];
    gl::Program& meter = programs[gl::kDisplayMeterProgram];
    gl::Program& display = programs[gl::kDisplayDisplayProgram];
    GLuint storage = 0;
    GLuint vertex_array = 0;
    bool preserve = true;
    bool metered = false;  // the last Run
    std::optional<double> given_ev100;
    bool ran = false;

    Impl() {
        gl::StateGuard guard(true);
        glCreateBuffers(1, &storage);
        glNamedBufferStorage(storage, static_cast<GLsizeiptr>(kStorageBytes), nullptr,
                             GL_DYNAMIC_STORAGE_BIT);
        const std::array<std::uint8_t, 1> zero = {0};
        glClearNamedBufferData(storage, GL_R8UI, GL_RED_INTEGER, GL_UNSIGNED_BYTE, zero.data());
        glCreateVertexArrays(1, &vertex_array);  // core profile draws need one, even empty
    }
    ~Impl() {
        glDeleteVertexArrays(1, &vertex_array);
        glDeleteBuffers(1, &storage);
    }

    // The storage up to the histogram (which stays on the GPU).
    gl::DisplayStorage ReadHeader() const {
        gl::DisplayStorage header{};
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        glGetNamedBufferSubData(storage, 0, static_cast<GLsizeiptr>(kHistogramOffset), &header);
        return header;
    }
};

DisplayPass::DisplayPass() : impl_(std::make_unique<Impl>()) {}
DisplayPass::~DisplayPass() = default;

void DisplayPass::set_preserve_gl_state(bool preserve) { impl_->preserve = preserve; }

void DisplayPass::ResetAdaptation() {
    gl::StateGuard guard(impl_->preserve);
    const std::uint32_t zero = 0;
    glNamedBufferSubData(impl_->storage, offsetof(gl::DisplayStorage, valid), sizeof(zero), &zero);
}

void DisplayPass::Run(unsigned input, unsigned framebuffer, const glm::ivec4& viewport,
                      const DisplaySettings& settings, double dt_s,
                      const std::optional<SceneDepth>& scene_depth) {
    settings.Validate();
    if (!(viewport.z > 0 && viewport.w > 0)) {
        throw ArgumentError("DisplayPass::Run: viewport size must be positive");
    }
    Impl& d = *impl_;
    gl::StateGuard guard(d.preserve);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kDisplayStorageBinding, d.storage);
    glBindTextureUnit(kDisplayInputUnit, input);
    glBindSampler(kDisplayInputUnit, 0);
    const bool night = settings.night_adaptation;
    if (settings.ev100) {
        // A given exposure: written for the display shader, no metering.
        const float ev =
            static_cast<float>(std::clamp(*settings.ev100 + settings.compensation_ev, -20.0, 30.0));
        glNamedBufferSubData(d.storage, 0, sizeof(ev), &ev);
        d.given_ev100 = static_cast<double>(ev);
        d.metered = false;
    } else {
        const std::uint32_t zero = 0;
        glClearNamedBufferSubData(d.storage, GL_R32UI, kHistogramOffset,
                                  kStorageBytes - kHistogramOffset, GL_RED_INTEGER, GL_UNSIGNED_INT,
                                  &zero);
        d.histogram.Use();
        glProgramUniform2i(d.histogram.name(), gl::kDisplaySizeLocation, viewport.z, viewport.w);
        constexpr int kGroupPixels = kDisplayGroupSize * kDisplayPixelsPerInvocation;
        glDispatchCompute(static_cast<GLuint>((viewport.z + kGroupPixels - 1) / kGroupPixels),
                          static_cast<GLuint>((viewport.w + kGroupPixels - 1) / kGroupPixels), 1);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        d.meter.Use();
        const double ratio = settings.adaptation_time_s > 0.0 && dt_s > 0.0
                                 ? dt_s / settings.adaptation_time_s
                                 : 0.0;
        glProgramUniform1f(d.meter.name(), gl::kDisplayDtOverTauLocation,
                           static_cast<float>(std::min(ratio, 1e6)));
        glProgramUniform1i(d.meter.name(), gl::kDisplayMeterNightLocation, night ? 1 : 0);
        glProgramUniform1f(d.meter.name(), gl::kDisplayCompensationLocation,
                           static_cast<float>(settings.compensation_ev));
        glDispatchCompute(1, 1, 1);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        d.given_ev100.reset();
        d.metered = true;
    }
    int depth_mode = 0;
    if (scene_depth && scene_depth->texture != 0) {
        depth_mode = scene_depth->reversed ? 2 : 1;
        glBindTextureUnit(kSceneDepthUnit, scene_depth->texture);
        glBindSampler(kSceneDepthUnit, 0);
    }
    glProgramUniform2i(d.display.name(), gl::kDisplayOriginLocation, viewport.x, viewport.y);
    glProgramUniform1i(d.display.name(), gl::kDisplayNightLocation, night ? 1 : 0);
    glProgramUniform1i(d.display.name(), gl::kDisplayDepthModeLocation, depth_mode);
    gl::DrawFullscreen(d.display, d.vertex_array, framebuffer, viewport, gl::Blend::kReplace);
    d.ran = true;
}

std::optional<double> DisplayPass::exposure_ev100() const {
    if (!impl_->ran) return std::nullopt;
    if (impl_->given_ev100) return impl_->given_ev100;
    gl::StateGuard guard(impl_->preserve);
    return static_cast<double>(impl_->ReadHeader().ev100);
}

std::optional<double> DisplayPass::metered_target_ev100() const {
    if (!impl_->ran || !impl_->metered) return std::nullopt;
    gl::StateGuard guard(impl_->preserve);
    return static_cast<double>(impl_->ReadHeader().target_ev100);
}

std::optional<double> DisplayPass::metered_log2_average() const {
    if (!impl_->ran || !impl_->metered) return std::nullopt;
    gl::StateGuard guard(impl_->preserve);
    return static_cast<double>(impl_->ReadHeader().log2_average);
}

}  // namespace zenith::sky
