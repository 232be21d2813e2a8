// The GL 4.5 atmosphere renderer (Hillaire 2020): LUTs as compute passes, then the sky image.
// Needs a current GL 4.5 core context whose functions are loaded (a HeadlessContext, or the
// host's context through gl::LoadGlFunctions). All GL objects are owned and freed here.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "zenith/sky/atmosphere.h"
#include "zenith/sky/lut.h"

namespace zenith::sky {

// The host's depth buffer, to draw aerial perspective over its geometry: a depth texture (0..1,
// standard OpenGL perspective projection with these near and far planes, metres) of the
// viewport's size. Pixels nearer than the far plane get in-scattering and transmittance
// blended over the host's colour (framebuffer = L + T * colour); the others get the sky.
struct SceneDepth {
    unsigned texture = 0;
    double near_m = 0.5;
    double far_m = 100000.0;
};

struct RenderOptions {
    glm::ivec2 size{1280, 720};
    // Inside the atmosphere the sky comes from the Sky-View LUT; above it (or always, if
    // force_ray_march) each pixel is ray marched with ray_march_steps steps.
    bool force_ray_march = false;
    int ray_march_steps = 32;
    bool draw_sun_disk = true;  // drawn as a point (energy-conserving) when below a pixel
    MoonDisk moon;
    std::vector<StarPoint> stars;  // splatted into the pixel holding each, as E / pixel solid angle
    // Draw into this framebuffer object of the host (0 = the default framebuffer) over the
    // viewport (x, y, width, height) instead of the renderer's own RGBA32F frame; `size` must be
    // the viewport's size. The host's framebuffer binding and viewport are restored afterwards.
    std::optional<unsigned> target_framebuffer;
    glm::ivec4 target_viewport{0, 0, 0, 0};
    std::optional<SceneDepth> scene_depth;  // with a host framebuffer only
};

// GPU time of each pass in milliseconds, measured with GL timer queries.
struct PassTimes {
    double transmittance = 0.0;
    double multiple_scattering = 0.0;
    double irradiance = 0.0;
    double sky_view = 0.0;
    double aerial_perspective = 0.0;
    double render = 0.0;
};

class AtmosphereRenderer {
public:
    explicit AtmosphereRenderer(const Atmosphere& atmosphere, const LutSettings& settings = {});
    ~AtmosphereRenderer();
    AtmosphereRenderer(const AtmosphereRenderer&) = delete;
    AtmosphereRenderer& operator=(const AtmosphereRenderer&) = delete;

    // Recomputes the transmittance, multiple-scattering and ground-irradiance LUTs.
    void SetAtmosphere(const Atmosphere& atmosphere);
    const Atmosphere& atmosphere() const;
    const LutSettings& settings() const;

    // The per-frame LUTs (Sky-View, aerial perspective) for this camera and these lights.
    void UpdateFrameLuts(const Camera& camera, const Lights& lights);
    // Renders the frame into the renderer's RGBA32F colour texture (after UpdateFrameLuts for
    // the same camera and lights).
    void Render(const Camera& camera, const Lights& lights, const RenderOptions& options);

    // Read back for tests, tools and offscreen output (synchronous).
    LutImage ReadTransmittance() const;
    LutImage ReadMultipleScattering() const;
    LutImage ReadGroundIrradiance() const;
    LutImage ReadSkyView() const;
    LutImage ReadAerialPerspective() const;
    LutImage ReadFrame() const;  // row 0 = bottom of the image (GL convention)

    // GL texture names, for hosts that sample them (aerial perspective on their geometry).
    unsigned transmittance_texture() const;
    unsigned aerial_perspective_texture() const;
    unsigned frame_texture() const;

    // Bytes of GPU memory held by the LUTs (not the frame).
    std::size_t LutMemoryBytes() const;
    // Times of the most recent run of each pass (waits for the GPU).
    PassTimes LastPassTimes() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace zenith::sky
