// Read-backs, GPU timers and memory figures of an AtmosphereRenderer: for tests, tools and
// offscreen output, kept off the renderer's front door (Update / Render). Every read waits for
// the GPU (glGetTextureImage, query results), so a host's frame loop does not call these.
#pragma once

#include <cstddef>
#include <glm/glm.hpp>

#include "zenith/sky/atmosphere_renderer.h"
#include "zenith/sky/lut.h"

namespace zenith::sky {

// GPU time of each pass in milliseconds, measured with GL timer queries.
struct PassTimes {
    double transmittance = 0.0;
    double multiple_scattering = 0.0;
    double irradiance = 0.0;
    double sky_view = 0.0;
    double aerial_perspective = 0.0;
    double render = 0.0;            // the composite: sky, disks and, with weather, the clouds
    double cloud_shadow_map = 0.0;  // and the far sun-depth volume; 0 without weather
    double cloud_shade = 0.0;       // the clouds' effect on the light beneath them
    double cloud_trace = 0.0;
    double cloud_reconstruct = 0.0;
    double cloud_ground_shadow = 0.0;  // per trace cell, which the composite interpolates
    double cloud_light_shafts = 0.0;   // per 2x2 trace cells, likewise
    double cloud_geometry = 0.0;       // host geometry's pixels marched on their own rays, if any
    double environment = 0.0;          // the environment's faces and, after a round, its projection
};

// A view of one renderer (which must outlive it); cheap to make, e.g. Inspect(renderer).
class RendererInspection {
  public:
    explicit RendererInspection(const AtmosphereRenderer& renderer) : renderer_(renderer) {}

    LutImage ReadTransmittance() const;
    LutImage ReadMultipleScattering() const;
    LutImage ReadGroundIrradiance() const;
    LutImage ReadSkyView() const;
    LutImage ReadAerialPerspective() const;
    LutImage ReadFrame() const;  // the renderer's own frame; row 0 = bottom (GL convention)
    // The environment's atlas (zenith/sky/environment.h: size x 6 size, face f in rows f size..)
    // and its cube map's faces read back from the cube (level `level`, the same layout); throw
    // without an environment.
    LutImage ReadEnvironmentAtlas() const;
    LutImage ReadEnvironmentCube(int level = 0) const;
    // The last frame's clouds: rgb luminance in front of the sky (aerial perspective applied),
    // a their transmittance, so frame = rgb + a * sky. Frame-sized; throws without weather.
    LutImage ReadClouds() const;
    // Transmittance toward the Sun (the Moon at night) through every layer at the ground,
    // shadow_map_size^2 texels over shadow_map_extent around the camera's ground point: texel
    // (i, j) at east/north offsets ((i + 0.5) / size - 0.5) extent, in the renderer's frame.
    // Throws without weather.
    LutImage ReadCloudShadowMap() const;
    // The far sun-depth volume (CloudSettings::sun_depth_*): r, the optical depth toward the Sun
    // (the Moon at night) through every cloud layer; sun_depth_size^2 texels by sun_depth_levels,
    // one texel without a volume. Throws without weather.
    LutImage ReadCloudSunDepth() const;
    // This frame's CloudShade (the clear-sky values without weather), waiting for the GPU
    // (AtmosphereRenderer::LatestCloudShade is the one that does not wait).
    CloudShade ReadCloudShade() const;

    // Bytes of GPU memory held by the LUTs (not the frame).
    std::size_t LutMemoryBytes() const;
    // Times of the most recent run of each pass (waits for the GPU).
    PassTimes LastPassTimes() const;

  private:
    LutImage Read(unsigned texture, const glm::ivec3& size) const;
    const AtmosphereRenderer& renderer_;
};

inline RendererInspection Inspect(const AtmosphereRenderer& renderer) {
    return RendererInspection(renderer);
}

}  // namespace zenith::sky
