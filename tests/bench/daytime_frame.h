// The benches' daytime frame: a headless GL context and a renderer for the Earth preset, the
// camera 1.5 km up looking at the horizon toward the Sun 10 deg up, 1280x720. One per process
// (Shared), so every benchmark in it measures the same warm renderer.
#pragma once

#include <memory>

#include "zenith/sky/atmosphere_renderer.h"
#include "zenith/sky/gl/context.h"

namespace zenith::sky::bench {

struct DaytimeFrame {
    std::unique_ptr<gl::HeadlessContext> context = gl::CreateHeadlessContextFromEnvironment();
    Atmosphere earth;
    AtmosphereRenderer renderer{earth};
    SkyScene scene;  // the Sun alone
    SkyView view;
    RenderTarget target = RenderTarget::Offscreen({1280, 720});

    DaytimeFrame() {
        Camera& camera = view.camera;
        camera.position = glm::dvec3(0.0, 0.0, earth.bottom_radius + 1500.0);
        camera.world_from_view =
            glm::dmat3(glm::dvec3(0, 1, 0), glm::dvec3(0, 0, 1), glm::dvec3(-1, 0, 0));
        camera.vertical_fov = 1.0471975511965976;
        camera.aspect = 16.0 / 9.0;
        scene.lights.sun_direction = glm::normalize(glm::dvec3(0.98, 0.0, 0.17));
    }
};

// The process's one instance of Frame (DaytimeFrame or a fixture built on it).
template <typename Frame = DaytimeFrame>
Frame& Shared() {
    static Frame frame;
    return frame;
}

}  // namespace zenith::sky::bench
