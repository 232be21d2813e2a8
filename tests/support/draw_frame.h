// One frame through the renderer's front door, for the GL tests and benches: Update with the
// scene and the view, Render into the renderer's own frame `passes` times (a still frame's cloud
// passes), read back (row 0 = bottom). A GL context must be current.
#pragma once

#include <glm/glm.hpp>

#include "zenith/sky/atmosphere_renderer.h"
#include "zenith/sky/frame.h"
#include "zenith/sky/inspection.h"
#include "zenith/sky/lut.h"

namespace zenith::test {

inline sky::LutImage DrawFrame(sky::AtmosphereRenderer& renderer, const sky::SkyScene& scene,
                               const sky::SkyView& view, glm::ivec2 size, int passes = 1) {
    renderer.Update(scene, view);
    for (int i = 0; i < passes; ++i) renderer.Render(sky::RenderTarget::Offscreen(size));
    return sky::Inspect(renderer).ReadFrame();
}

// A scene of these lights alone: no Moon, no stars, the Sun's disk as asked.
inline sky::SkyScene LightsOnly(const sky::Lights& lights, bool draw_sun_disk = true) {
    sky::SkyScene scene;
    scene.lights = lights;
    scene.draw_sun_disk = draw_sun_disk;
    return scene;
}

// What a frame of lights alone draws besides the camera: its size, the Sun's disk, where the
// weather is (a cut resets the clouds' history).
struct FrameOptions {
    glm::ivec2 size{1280, 720};
    bool draw_sun_disk = true;
    sky::CloudView clouds{};
};

inline sky::SkyScene SceneOf(const sky::Lights& lights, const FrameOptions& options) {
    sky::SkyScene scene = LightsOnly(lights, options.draw_sun_disk);
    scene.clouds = options.clouds;
    return scene;
}

// Update, then `frames` renders into the renderer's own frame (nothing read back).
inline void DrawFrames(sky::AtmosphereRenderer& renderer, const sky::Camera& camera,
                       const sky::Lights& lights, const FrameOptions& options, int frames = 1) {
    renderer.Update(SceneOf(lights, options), {camera});
    for (int i = 0; i < frames; ++i) renderer.Render(sky::RenderTarget::Offscreen(options.size));
}

}  // namespace zenith::test
