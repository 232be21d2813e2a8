// The atmosphere's GL side (Hillaire 2020), beside the clouds' (clouds/cloud_passes.h): its LUTs
// as compute passes, the per-frame constants, and the composite that draws the sky, the stars,
// the Sun's and the Moon's disks and, laid over them, the clouds CloudPasses traced. Owned by
// AtmosphereRenderer, which orders the passes of a frame (atmosphere_renderer.cpp).
#pragma once

#include <glad/gl.h>

#include <array>
#include <cstddef>
#include <optional>
#include <utility>
#include <vector>

#include "gl/atmosphere_uniforms.h"
#include "gl/shader.h"
#include "reference/shared_math.h"
#include "zenith/sky/atmosphere.h"
#include "zenith/sky/frame.h"
#include "zenith/sky/lut.h"

namespace zenith::sky {

class CloudPasses;

// One point source as atmosphere/stars.vert draws it.
struct StarVertex {
    glm::vec2 ndc;        // its pixel's centre
    glm::vec4 luminance;  // cd/m^2 over that pixel; a: its Y when it is part of a resolved disk
};

// Rain or snow falling at the camera (AtmosphereRenderer::Update works it out from the
// precipitation shafts): a box of drops around the camera, fixed in the weather's frame.
struct PrecipitationDraw {
    double intensity = 0.0;  // the map's precipitation at the camera (0: none)
    bool snow = false;
    glm::dmat3 world_from_box{1.0};  // the weather frame's axes in the renderer's frame
    glm::dvec3 camera{0.0};          // m, the camera in the weather frame
    glm::dvec3 up{0.0, 0.0, 1.0};    // the camera's vertical in the weather frame
    glm::dvec3 wind{0.0};            // m/s, the raining layer's, in the weather frame
    double time_s = 0.0;             // CloudView::time
};

// The night sky's map (zenith/sky/night_sky.h) in the Sky-View LUT's parameterisation: 2.8 deg
// in azimuth, finer toward the horizon.
inline constexpr glm::ivec2 kNightSkyMapSize{128, 64};

class AtmospherePasses {
  public:
    enum Pass : std::size_t {
        kTransmittancePass,
        kMultipleScatteringPass,
        kIrradiancePass,
        kSkyViewPass,
        kAerialPerspectivePass,
        kRenderPass,          // the composite with the Sky-View LUT
        kRenderRayMarchPass,  // the composite ray marching every pixel (space views)
        kRenderDepthPass,     // the same two over the host's depth buffer (aerial perspective)
        kRenderRayMarchDepthPass,
        kDiskPass,       // the Sun and the Moon, added over their disks only
        kDiskDepthPass,  // the same, behind the host's geometry
        kPassCount
    };
    // Timer queries: one per pass, and a second for the disk pass, which may draw twice a frame.
    static constexpr std::size_t kSecondDiskQuery = kPassCount;
    static constexpr std::size_t kQueryCount = kPassCount + 1;

    // Builds the programs and the LUT textures, then the LUTs that depend on the atmosphere
    // only (transmittance, multiple scattering, ground irradiance).
    AtmospherePasses(const Atmosphere& atmosphere, const LutSettings& settings);
    ~AtmospherePasses();
    AtmospherePasses(const AtmospherePasses&) = delete;
    AtmospherePasses& operator=(const AtmospherePasses&) = delete;

    // The LUTs that depend on the atmosphere only, again.
    void SetAtmosphere(const Atmosphere& atmosphere);
    const Atmosphere& atmosphere() const { return atmosphere_; }
    const LutSettings& settings() const { return settings_; }

    // The six composites again, laying the clouds over the sky and the disks (once).
    void BuildCloudComposites();

    // This frame's lights (into the light block, which CloudPasses::Prepare then completes with
    // the clouds' shading) and its per-frame constants: what the view and the scene fix, worked
    // out once a frame; Render adds what the target fixes. `environment_size`: the environment's
    // faces' size for its passes (0: none).
    void SetFrame(const SkyScene& scene, const SkyView& view, int environment_size = 0);
    GLuint light_buffer() const { return buffers_[1]; }
    // Binds the uniform blocks and the LUTs every pass reads (CloudPasses' passes too).
    void BindInputs() const;
    // The Sky-View and aerial-perspective LUTs for SetFrame's camera and lights.
    void UpdateFrameLuts();
    // Then, for each Render of that frame, what the target fixes: the frame's size (the own
    // frame and the points' texture follow it), the points splatted, the viewport's offset...
    void SetTarget(const SkyScene& scene, const SkyView& view, const RenderTarget& target);
    // ...and, once CloudPasses has traced, the composite into `target`: the sky (over the host's
    // depth, if the view has one) with `clouds`' last trace laid over it when given, then the
    // Sun's and the Moon's disks; over the host's geometry, first CloudPasses::MarchToGeometry.
    // The target's size is checked by the caller.
    void Composite(const SkyScene& scene, const SkyView& view, const RenderTarget& target,
                   CloudPasses* clouds);
    // Then the rain or snow falling at the camera, over what Composite drew (precipitation.vert).
    void DrawPrecipitation(const PrecipitationDraw& precipitation, const RenderTarget& target);

    GLuint transmittance() const { return transmittance_; }
    GLuint multiple_scattering() const { return multiple_scattering_; }
    GLuint irradiance() const { return irradiance_; }
    GLuint sky_view() const { return sky_view_; }
    GLuint aerial_perspective() const { return aerial_perspective_; }
    GLuint frame() const { return frame_; }  // 0 before the first Render into the own frame
    const ref::TransmittanceTexture& transmittance_cpu() const { return transmittance_cpu_; }
    const ref::MultipleScatteringTexture& multiple_scattering_cpu() const {
        return multiple_scattering_cpu_;
    }
    const ref::IrradianceTexture& irradiance_cpu() const { return irradiance_cpu_; }
    glm::ivec2 frame_size() const { return frame_size_; }
    // The night sky's illuminance on the ground below the camera (lux), as the last SetFrame
    // lit the ground with; 0 by day.
    const glm::dvec3& night_ground_irradiance() const { return night_ground_.value; }
    // GPU time of a query (ms), 0 when it did not run.
    double QueryMilliseconds(std::size_t query) const;

  private:
    void Dispatch(Pass pass, GLuint output, bool layered, GLuint gx, GLuint gy, GLuint gz);
    void Draw(Pass pass, std::size_t query, GLuint target, glm::ivec4 viewport,
              const CloudPasses* clouds, GLuint scene_depth = 0,
              std::optional<glm::ivec4> scissor = std::nullopt);
    void BuildStaticLuts();
    void BuildMultipleScattering();
    void ResizeFrame(glm::ivec2 size);
    bool SunDiskResolved(const SkyView& view, glm::ivec2 size) const;
    // The framebuffer and viewport a target draws into: the host's, or the own frame's.
    std::pair<GLuint, glm::ivec4> Destination(const RenderTarget& target) const;
    struct NightSkyMapInputs;
    static bool NightSkyInputsHold(const NightSkyMapInputs& last, const SkyScene& scene,
                                   const glm::dvec3& camera_position, double angle,
                                   double distance);
    bool NightSkyMapHolds(const SkyScene& scene, const glm::dvec3& camera_position) const;
    // NightSkyGroundIrradiance for this frame, made again only when it can have changed by more
    // than ~1 %.
    void UpdateNightGroundIrradiance(const SkyScene& scene, const glm::dvec3& camera_position);
    void DrawPoints(glm::ivec2 size);

    Atmosphere atmosphere_;
    LutSettings settings_;
    std::array<gl::Program, kPassCount> programs_;
    std::vector<gl::Program> cloud_composites_;  // BuildCloudComposites
    std::array<GLuint, 4> buffers_{};            // atmosphere, lights, settings, frame
    GLuint transmittance_ = 0, multiple_scattering_ = 0, irradiance_ = 0, sky_view_ = 0,
           aerial_perspective_ = 0, frame_ = 0, stars_ = 0, night_sky_ = 0;
    GLuint framebuffer_ = 0, vertex_array_ = 0;  // the composite draws a triangle into frame_
    // The stars as points into stars_ (DrawPoints).
    gl::Program star_program_;
    gl::Program precipitation_program_;
    GLuint precipitation_buffer_ = 0;  // PrecipitationBlock
    GLuint star_framebuffer_ = 0, star_buffer_ = 0, star_vertex_array_ = 0;
    std::vector<StarVertex> star_vertices_;
    std::vector<glm::vec4> night_sky_pixels_;  // the night sky's map, filled on the CPU...
    struct NightSkyMapInputs {                 // ...for these (NightSkyMapHolds)
        NightSky night;
        glm::dvec3 sun_direction;
        glm::dvec3 camera_position;
    };
    std::optional<NightSkyMapInputs> night_sky_map_for_;
    struct NightGroundIrradiance {  // ...and the ground's light, for these
        std::optional<NightSkyMapInputs> inputs;
        glm::dvec3 value{0.0};
    } night_ground_;
    // The static LUTs as the GPU made them, for CPU work: the stars' extinction, a host's
    // queries (AtmosphereRenderer::SkyLuminance, AerialPerspective).
    ref::TransmittanceTexture transmittance_cpu_;
    ref::MultipleScatteringTexture multiple_scattering_cpu_;
    ref::IrradianceTexture irradiance_cpu_;
    glm::ivec2 frame_size_{0, 0};
    std::array<GLuint, kQueryCount> queries_{};
    std::array<bool, kQueryCount> query_used_{};
    int light_count_ = 1;                 // with the Sun alone, the Sky-View LUT is symmetric...
    bool eclipse_active_ = false;         // ...unless the Moon covers part of the Sun
    gl::FrameUniforms frame_uniforms_{};  // SetFrame's part of the frame block
};

}  // namespace zenith::sky
