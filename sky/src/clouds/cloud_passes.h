// The GL side of the clouds (Högfeldt 2016 §5-6, Frostbite 2016 §5): noise and weather maps as
// textures, the reduced-resolution trace, the temporal reconstruction and the ground shadow map;
// the atmosphere's sky pass composites them (atmosphere/render.frag with ZENITH_CLOUDS 1,
// compiled with CloudShaderParts()). Owned by AtmosphereRenderer, which binds the atmosphere's
// uniform blocks and LUTs before each call; the clouds bind their own (bindings.glsl has them
// all).
#pragma once

#include <glad/gl.h>

#include <array>
#include <initializer_list>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "gl/shader.h"
#include "zenith/base/error.h"
#include "zenith/sky/atmosphere_renderer.h"

namespace zenith::sky {

// The cloud files, which follow the atmosphere prelude in every program that uses the clouds.
std::span<const std::string_view> CloudShaderParts();

class CloudPasses {
  public:
    // For a validated weather with at least one layer, its maps (clouds::BuildWeatherMap of
    // each layer) and their clouds::CloudTopFraction, validated settings and the noise they
    // give. Throws zenith::ArgumentError for more than kCloudMaxLayers.
    CloudPasses(const clouds::Weather& weather, const CloudSettings& settings,
                const std::vector<clouds::WeatherMap>& maps, const std::vector<double>& tops,
                const clouds::CloudNoise& noise);
    ~CloudPasses();
    CloudPasses(const CloudPasses&) = delete;
    CloudPasses& operator=(const CloudPasses&) = delete;

    // The programs a CloudPasses builds (the trace, the sky shade's trace, the reconstruction,
    // the ground's shadow and the light shafts in both stages, the shadow map, the sky shade,
    // ...), for tests of the GL contract (renderer_programs.h).
    static std::vector<gl::Program> BuildPrograms();

    const clouds::Weather& weather() const { return weather_; }
    const CloudSettings& settings() const { return settings_; }

    // First in a frame, before the atmosphere's per-frame LUTs: updates the shadow map and what
    // the clouds do to the light beneath them (sky_shade.comp; both every shadow_map_interval
    // frames), and writes the latter into the LightSet in `light_buffer` (the atmosphere's light
    // block, already holding this frame's lights).
    void Prepare(const Atmosphere& atmosphere, const Camera& camera, const Lights& lights,
                 const CloudView& view, GLuint light_buffer);
    // Then, before the sky pass, traces the clouds and reconstructs them at full resolution,
    // with their shadow on the ground the atmosphere draws.
    // `size` is the frame's; `view` the one Prepare was given this frame.
    void Render(const Atmosphere& atmosphere, const Camera& camera, const Lights& lights,
                glm::ivec2 size, const CloudView& view);
    // Over a host's geometry (its depth bound at kSceneDepthUnit, the atmosphere's blocks and
    // this frame's clouds bound for the composite), after Render: marches the pixels whose trace
    // cells disagree about the clouds in front of the geometry on their own rays
    // (clouds/interface.glsl CloudOwnRayWeight), cell by cell, at most twice the trace's rays in
    // number, so that it never costs more than two more traces.
    void MarchToGeometry();
    // Binds what the sky pass reads to composite the last Render's clouds.
    void BindForComposite() const;
    // Binds what TraceClouds and GroundShadowCorrection read, as Prepare left them this frame
    // (the environment's faces trace the clouds after it).
    void BindForTrace() const;

    LutImage ReadClouds() const;
    LutImage ReadShadowMap() const;
    LutImage ReadSunDepth() const;
    GLuint shadow_map_texture() const { return shadow_map_; }

    // GPU times (ms) of the last frame: shadow map, shade, trace, reconstruct, the ground's
    // shadow, the light shafts, the march to a host's geometry (listing and marching).
    static constexpr std::size_t kPassCount = 7;
    std::array<double, kPassCount> LastPassTimes() const;

  private:
    void Resize(glm::ivec2 size);
    void UploadUniforms(const Atmosphere& atmosphere, const Camera& camera, const Lights& lights,
                        const CloudView& view, bool history_valid, bool update);
    // clouds/sun_depth.comp over every level, top down (settings_.sun_depth_size > 0).
    void UpdateSunDepth() const;
    // The last shade's cloud members (sky_shade.comp's) into the LightSet at `lights_offset`
    // bytes into `buffer`.
    void CopyShade(GLuint buffer, GLintptr lights_offset) const;
    void BindTextures() const;
    // A per-cell (or per-pixel, per-direction) pass over `size` in the stage chosen, into
    // `targets`: the fragment stage draws `framebuffer`, whose colour attachments they are in
    // order; the compute stage binds them in that order to image units kCloudPassImageUnit + 0,
    // 1, ... (clouds/*.comp). Timed by `query` (0: none).
    struct PassTarget {
        GLuint texture;
        GLenum format;
    };
    void RunCellPass(const gl::Program& program, GLuint framebuffer,
                     std::initializer_list<PassTarget> targets, glm::ivec2 size,
                     GLuint query) const;

    clouds::Weather weather_;
    CloudSettings settings_;
    bool compute_passes_ = false;  // settings_.pass_stage, kAuto resolved for this context
    gl::Program trace_, reconstruct_, shadow_pass_, sun_depth_pass_, shade_trace_pass_, shade_pass_,
        ground_shadow_, light_shafts_;
    GLuint uniforms_ = 0;
    GLuint shape_ = 0, detail_ = 0;
    std::vector<GLuint> weather_maps_;
    std::vector<double> cloud_tops_;  // clouds::CloudTopFraction of each map
    // The trace, one ray per cell: (L, T); (mean depth, entry) (km); the transmittance's profile
    // (CloudMarchState.crossing), for a host's geometry inside the clouds.
    GLuint trace_color_ = 0, trace_depth_ = 0, trace_profile_ = 0, trace_framebuffer_ = 0;
    GLuint ground_shadow_color_ = 0, ground_shadow_framebuffer_ = 0;  // per trace cell
    // The light shafts, per kCloudLightShaftCell^2 trace cells (clouds/light_shafts.frag): the
    // parts of each cell's CloudShaftProfile.
    std::array<GLuint, 4> air_shadow_color_{};
    GLuint shaft_framebuffer_ = 0;
    glm::ivec2 shaft_size_{0, 0};
    std::array<GLuint, 2> history_color_{}, history_framebuffer_{};
    GLuint shadow_map_ = 0;
    // The far sun-depth volume (R32F, sun_depth_size^2 x sun_depth_levels; 1 texel without one)
    // and the camera it was made around (the weather frame, km).
    GLuint sun_depth_ = 0;
    glm::dvec3 sun_depth_camera_{0.0};
    GLuint shade_directions_ = 0;  // (L, T) of the clouds along each sky-shade direction
    GLuint shade_ = 0;             // a LightSet whose cloud members sky_shade.comp writes
    GLuint shade_framebuffer_ = 0;
    GLuint vertex_array_ = 0;
    // MarchToGeometry's: its programs (built on first use), the clouds in front of the geometry
    // at the pixels marched ((L, T), T = -1 elsewhere; full resolution) and the list of the
    // cells marched (clouds/geometry_list.glsl), which holds the indirect draw.
    std::optional<gl::Program> geometry_list_, geometry_march_;
    GLuint geometry_color_ = 0, geometry_framebuffer_ = 0, geometry_list_framebuffer_ = 0;
    GLuint geometry_list_buffer_ = 0;
    GLuint geometry_capacity_ = 0;
    std::array<GLuint, kPassCount> queries_{};
    std::array<bool, kPassCount> query_used_{};
    glm::ivec2 size_{0, 0};
    glm::ivec2 trace_size_{0, 0};
    std::size_t current_ = 0;  // history set written by the last Render
    long long frame_index_ = 0;
    // The previous frame, for the reprojection.
    struct Previous {
        Camera camera;
        glm::dmat3 weather_from_world{1.0};
    };
    std::optional<Previous> previous_;
};

}  // namespace zenith::sky
