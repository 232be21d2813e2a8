// What one frame of the renderer is made of, in the shape of Filament's Scene / View /
// RenderTarget:
//   SkyScene      what is in the sky: the lights, the Moon's disk, point sources, where the
//                 weather is;
//   SkyView       where it is seen from: the camera and its projection, how finely the sky is
//                 marched;
//   RenderTarget  where the pixels go: the renderer's own frame or the host's framebuffer, the
//                 viewport, and the host's depth there.
// AtmosphereRenderer::Update(scene, view) makes the per-frame LUTs and keeps both; Render(target)
// draws them, so the LUTs and the image cannot be made for different cameras or lights.
// BuildSkyFrame (sky_state.h) makes the scene and the view from a time, a place, an attitude and
// a projection.
#pragma once

#include <glm/glm.hpp>
#include <optional>
#include <vector>

#include "zenith/sky/lut.h"
#include "zenith/sky/night_sky.h"

namespace zenith::sky {

// The host's depth buffer, to draw aerial perspective over its geometry: a single-sample 2-D
// depth texture (window depth 0..1) of the viewport's size, from a perspective projection with
// these near and far planes (metres). Pixels nearer than the far plane get in-scattering and
// transmittance blended over the host's colour (framebuffer = L + T * colour); the others get
// the sky. Conventions, with eye depth z:
//   standard (reversed = false): OpenGL's projection and depth range, glClipControl(...,
//     GL_NEGATIVE_ONE_TO_ONE); the depth cleared to 1, 0 at near and 1 at far:
//     d = f (z - n) / (z (f - n)); an infinite far plane (far_m = infinity) gives d = 1 - n / z.
//   reversed (reversed = true): reversed-Z, glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE), a
//     projection that maps near to 1 and far to 0, depth cleared to 0 and GL_GREATER:
//     d = n (f - z) / (z (f - n)); with an infinite far plane d = n / z.
// A zero-to-one projection that is not reversed (near to 0, far to 1) gives the standard d. A
// multisampled depth texture is refused (SkySystem::SetSceneDepth): resolve it first
// (glBlitFramebuffer of the depth into a single-sample texture).
struct SceneDepth {
    unsigned texture = 0;
    double near_m = 0.5;
    double far_m = 100000.0;  // may be infinity
    bool reversed = false;    // reversed-Z: 1 at near, 0 at far (see above)
};

// Where the weather is this frame.
struct CloudView {
    double time = 0.0;  // s since the weather's epoch: how far the wind has carried the layers
    // Rotation from the renderer's planet-centred frame to the weather's (+z through the
    // weather map's origin; x east and y north there). Identity puts the map's origin under the
    // camera; a host that moves keeps it fixed on the planet (WeatherFrame in sky_state.h) so
    // the clouds stay where they are as it flies.
    glm::dmat3 weather_from_world{1.0};
    // A cut: do not reproject earlier frames, and start the jitter sequence over (the frame is
    // then the same whatever was drawn before it). It applies to the first Render after the
    // Update that was given it.
    bool reset_history = false;
};

// What is in the sky.
struct SkyScene {
    Lights lights;
    bool draw_sun_disk = true;  // drawn as a point (energy-conserving) when below a pixel
    std::optional<ApparentPlace> sun_apparent;  // where the disk is drawn; none: sun_direction
    MoonDisk moon;
    std::vector<StarPoint> stars;  // splatted into the pixel holding each, as E / pixel solid angle
    // Each pixel's stars are drawn in the share the eye sees against the sky behind them
    // (StarVisibility in zenith/sky/night_sky.h: none under the threshold, all from one
    // magnitude above it); false draws them all (a sensor's view, and energy tests).
    bool star_visibility = true;
    // The diffuse night light (airglow, zodiacal light, starlight, light pollution), added to
    // the sky through the atmosphere; MakeSkyState fills it (enabled, no starlight map). Off by
    // default.
    NightSky night_sky;
    CloudView clouds;  // used when the renderer has weather (SetWeather)
};

// Where the sky is seen from, and how finely it is marched.
struct SkyView {
    Camera camera;  // its aspect is the target viewport's width / height
    // Inside the atmosphere the sky comes from the Sky-View LUT; above it (or always, if
    // force_ray_march) each pixel is ray marched with ray_march_steps steps.
    bool force_ray_march = false;
    int ray_march_steps = 32;
};

// Where the pixels go: the renderer's own RGBA32F frame of the viewport's size (read back by
// RendererInspection::ReadFrame, sampled through frame_texture()), or the host's framebuffer
// object (0 = the default framebuffer) over the viewport, whose binding and viewport are
// restored afterwards. The host's depth belongs to its framebuffer (it is of the viewport's
// size, and the host may change it between Update and Render), so it is here and not in the
// view.
struct RenderTarget {
    std::optional<unsigned> framebuffer;    // nullopt: the renderer's own frame
    glm::ivec4 viewport{0, 0, 1280, 720};   // x, y, width, height (x, y ignored for the own frame)
    std::optional<SceneDepth> scene_depth;  // with a host framebuffer only

    static RenderTarget Offscreen(glm::ivec2 size) {
        return {std::nullopt, {0, 0, size.x, size.y}, std::nullopt};
    }
    static RenderTarget Host(unsigned framebuffer, const glm::ivec4& viewport,
                             std::optional<SceneDepth> scene_depth = std::nullopt) {
        return {framebuffer, viewport, scene_depth};
    }
    glm::ivec2 size() const { return {viewport.z, viewport.w}; }
};

}  // namespace zenith::sky
