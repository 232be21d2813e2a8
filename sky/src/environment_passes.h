// The environment's GL side (zenith/sky/environment.h): the atlas of the six cube faces that
// atmosphere/environment.frag draws a few faces of each frame, the cube map the host samples
// (the atlas' faces copied in, with mip levels), and the spherical harmonics that
// atmosphere/environment_sh.comp projects the atlas onto after each round of the six faces,
// read back behind a fence. Owned by AtmosphereRenderer, which runs it at the end of Update.
#pragma once

#include <glad/gl.h>

#include <array>
#include <optional>

#include "gl/fenced_readback.h"
#include "gl/shader.h"
#include "zenith/sky/environment.h"

namespace zenith::sky {

class AtmospherePasses;
class CloudPasses;

class EnvironmentPasses {
  public:
    explicit EnvironmentPasses(const EnvironmentSettings& settings);  // validated, enabled
    ~EnvironmentPasses();
    EnvironmentPasses(const EnvironmentPasses&) = delete;
    EnvironmentPasses& operator=(const EnvironmentPasses&) = delete;

    // The programs of every variant, for tests of the GL contract (renderer_programs.h).
    static std::vector<gl::Program> BuildPrograms();

    const EnvironmentSettings& settings() const { return settings_; }
    void set_faces_per_frame(int faces) { settings_.faces_per_frame = faces; }

    // The next faces_per_frame faces, from the frame's LUTs (AtmospherePasses::UpdateFrameLuts
    // has run, with the environment's size in the frame block) and, when given, the clouds
    // (CloudPasses::Prepare has run this frame). `ray_march`: the camera is above the
    // atmosphere, where the Sky-View LUT does not reach. After a round's last face: the cube's
    // mip levels, the spherical harmonics and their read-back.
    void Update(const AtmospherePasses& atmosphere, const CloudPasses* clouds, bool ray_march);
    // The next Update starts a round with face 0 (after a cut, so that the round is all of one
    // place and time).
    void Restart() { next_face_ = 0; }

    GLuint cube() const { return cube_; }
    GLuint atlas() const { return atlas_; }
    GLuint sh_buffer() const { return sh_buffer_; }
    // Rounds completed since creation.
    long long rounds() const { return rounds_; }
    // The newest spherical harmonics the GPU has finished, without waiting; nullopt before the
    // first round's have arrived.
    std::optional<SphericalHarmonics9> LatestSh();
    // GPU time (ms) of the last Update's faces and, when it ran, its projection.
    double LastMilliseconds() const;

  private:
    const gl::Program& FaceProgram(bool clouds, bool ray_march);

    EnvironmentSettings settings_;
    std::array<std::optional<gl::Program>, 4> face_programs_;  // [clouds][ray_march], when used
    gl::Program sh_program_;
    GLuint atlas_ = 0, cube_ = 0, framebuffer_ = 0, vertex_array_ = 0, sh_buffer_ = 0;
    std::array<GLuint, 2> queries_{};
    std::array<bool, 2> query_used_{};
    gl::FencedReadback sh_readback_;
    int next_face_ = 0;
    long long rounds_ = 0;
};

}  // namespace zenith::sky
