// The GL 4.5 atmosphere renderer (Hillaire 2020): LUTs as compute passes, then the sky image.
// Needs a current GL 4.5 core context whose functions are loaded (a HeadlessContext, or the
// host's context through gl::LoadGlFunctions). All GL objects are owned and freed here.
#pragma once

#include <filesystem>
#include <glm/glm.hpp>
#include <memory>
#include <optional>
#include <vector>

#include "zenith/base/error.h"
#include "zenith/sky/atmosphere.h"
#include "zenith/sky/clouds/noise.h"
#include "zenith/sky/clouds/weather.h"
#include "zenith/sky/lut.h"

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

// The cloud material and how the layers are marched (Högfeldt 2016, Frostbite 2016 §5). SI
// units; the defaults are what `zenith render --weather` uses.
struct CloudSettings {
    // Material (F16 §5.4.1, §5.7)
    double extinction = 0.04;  // 1/m at density 1: a mean free path of 25 m in a dense core
    double albedo = 1.0;       // water droplets scatter nearly all they remove (F16 §5.2)
    double forward_g = 0.8;    // dual-lobe Henyey-Greenstein (F16 Eq. 18): silver lining...
    double backward_g = -0.3;  // ...and the back-lit side
    double lobe_weight = 0.3;  // share of the backward lobe
    // Share of the light scattered more than once that is added: the delta-Eddington diffuse
    // field of clouds/functions.glsl (CloudSunScattering); 1 is physical, 0 single scattering.
    double multiple_scattering = 1.0;
    double ambient_scale = 1.0;  // F16 §5.5.1: scale of the sky's ambient light
    // Shape: world size of one tile of each noise (H16 §4.3: the shape volume is 4x wider than
    // tall, so it covers shape_period x shape_period / 4 x shape_period)
    double shape_period = 14000.0;  // m
    double detail_period = 1800.0;  // m
    double erosion = 0.45;          // [0, 0.9]: how much the detail noise eats the edges
    // March (H16 §5.2, §6.2; F16 §5.5.2)
    double min_step = 120.0;          // m: the step of a short crossing
    int max_steps = 64;               // primary steps per layer crossing at most
    int shadow_steps = 4;             // samples toward each light (F16 §5.5.2: four)
    double shadow_first_step = 80.0;  // m; each next is shadow_growth times longer
    double shadow_growth = 2.0;
    // A step of more than one optical depth (a dense core, or any cloud met by a long step at
    // the horizon) is lit where its light comes from, not at its jittered sample: its density is
    // read in both halves and its shadow march's first step halved up to this many times (one
    // more shadow sample each). 0 lights it as a thin step: 15 % faster trace on llvmpipe, and
    // the light below decks of optical depth 32-128 1.2-2x too bright (BENCHMARKS.md).
    int thick_step_refinement = 3;
    // The diffuse light's slab lies across the clouds' outward normal (from the weather map's
    // large-scale field), so a cumulus' sunlit side is lit as a side and its shadowed side as
    // the far side of a slab; false keeps every slab horizontal, as over a deck (exact there):
    // an isolated cumulus' sunlit face then comes out 37 % too dark and its shadowed side 49 %
    // too bright against the path tracer, for a 25 % faster frame on llvmpipe (BENCHMARKS.md).
    bool oriented_slabs = true;
    double min_transmittance = 0.01;   // early exit
    double max_distance = 250000.0;    // m marched in one layer at most, from where a ray enters
    int aerial_perspective_steps = 8;  // atmosphere between the camera and the clouds
    // Reconstruction (H16 §6.1): each frame traces one pixel of every block x block (a Bayer
    // order over block^2 frames) and reprojects the rest from the previous frames. 1 traces
    // every pixel every frame (the reference, and single still frames).
    int block = 4;
    double history_weight = 0.5;  // share of the reprojected history kept when a pixel is traced
    // The ground shadow map: sun transmittance through all layers over a square around the
    // camera's ground point
    int shadow_map_size = 128;           // 470 m texels
    double shadow_map_extent = 60000.0;  // m, side of the square
    int shadow_map_steps = 16;           // per layer
    int shadow_map_interval = 4;         // frames between updates (the Sun and wind are slow)
    // Noise volumes: generated on first use and cached
    clouds::CloudNoiseSettings noise;
    std::filesystem::path noise_cache_directory = clouds::DefaultNoiseCacheDirectory();

    // Throws zenith::ArgumentError naming the field, its value and the allowed range.
    void Validate() const;
};

// What the clouds do to the light beneath them (Frostbite 2016 §5.9.2, Eq. 22), found by
// UpdateFrameLuts with the shadow map (every shadow_map_interval frames): the air and the ground
// below base_altitude get each light's direct part times direct_transmittance and the sky's part
// times sky_transmittance, and the clouds' own light as a source of luminance `luminance` over
// the upper hemisphere.
struct CloudShade {
    double base_altitude = 0.0;         // m above the ground; 0: no clouds
    double direct_transmittance = 1.0;  // toward the Sun (Moon at night), mean over the shadow map
    double sky_transmittance = 1.0;     // mean over the upper hemisphere, from the ground
    glm::dvec3 luminance{0.0};          // cd/m^2, the clouds' mean over the upper hemisphere
};

// Per frame: where the weather is.
struct CloudView {
    double time = 0.0;  // s since the weather's epoch: how far the wind has carried the layers
    // Rotation from the renderer's planet-centred frame to the weather's (+z through the
    // weather map's origin; x east and y north there). Identity puts the map's origin under the
    // camera; a host that moves keeps it fixed on the planet (WeatherFrame in sky_state.h) so
    // the clouds stay where they are as it flies.
    glm::dmat3 weather_from_world{1.0};
    // A cut: do not reproject earlier frames, and start the jitter sequence over (the frame is
    // then the same whatever was drawn before it).
    bool reset_history = false;
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
    CloudView clouds;                       // used when the renderer has weather (SetWeather)
};

// GPU time of each pass in milliseconds, measured with GL timer queries.
struct PassTimes {
    double transmittance = 0.0;
    double multiple_scattering = 0.0;
    double irradiance = 0.0;
    double sky_view = 0.0;
    double aerial_perspective = 0.0;
    double render = 0.0;            // the composite: sky, disks and, with weather, the clouds
    double cloud_shadow_map = 0.0;  // 0 without weather
    double cloud_shade = 0.0;       // the clouds' effect on the light beneath them
    double cloud_trace = 0.0;
    double cloud_reconstruct = 0.0;
    double cloud_ground_shadow = 0.0;  // per trace cell, which the composite interpolates
};

class AtmosphereRenderer {
  public:
    explicit AtmosphereRenderer(const Atmosphere& atmosphere, const LutSettings& settings = {});
    ~AtmosphereRenderer();
    AtmosphereRenderer(const AtmosphereRenderer&) = delete;
    AtmosphereRenderer& operator=(const AtmosphereRenderer&) = delete;

    // GL state (zenith/sim/sky_system.h has the whole contract): every member that issues GL
    // commands first sets the state its passes depend on (no culling, filled polygons, no depth
    // or stencil test, ...), so the context may be in any state; and, unless this is turned
    // off, it saves the state it sets or changes beforehand and restores it afterwards.
    // Construction always saves and restores.
    void set_preserve_gl_state(bool preserve);
    bool preserve_gl_state() const;

    // Recomputes the transmittance, multiple-scattering and ground-irradiance LUTs.
    void SetAtmosphere(const Atmosphere& atmosphere);
    const Atmosphere& atmosphere() const;
    const LutSettings& settings() const;

    // Clouds from now on (an empty Weather: none). Builds the weather maps and loads the noise
    // (generated and cached on first use); throws clouds::WeatherError for a bad weather or map
    // and zenith::ArgumentError for bad settings. Resets the reprojection history.
    void SetWeather(const clouds::Weather& weather, const CloudSettings& settings = {});
    const clouds::Weather& weather() const;
    const CloudSettings& cloud_settings() const;

    // The per-frame LUTs (Sky-View, aerial perspective) for this camera and these lights; with
    // weather, first the clouds' shadow map and their shading of the air and the ground beneath
    // them (Frostbite 2016 Eq. 22), for the clouds placed by `clouds`.
    void UpdateFrameLuts(const Camera& camera, const Lights& lights, const CloudView& clouds = {});
    // Renders the frame into the renderer's RGBA32F colour texture (after UpdateFrameLuts for
    // the same camera, lights and CloudView).
    void Render(const Camera& camera, const Lights& lights, const RenderOptions& options);

    // Read back for tests, tools and offscreen output (synchronous).
    LutImage ReadTransmittance() const;
    LutImage ReadMultipleScattering() const;
    LutImage ReadGroundIrradiance() const;
    LutImage ReadSkyView() const;
    LutImage ReadAerialPerspective() const;
    LutImage ReadFrame() const;  // row 0 = bottom of the image (GL convention)
    // The last frame's clouds: rgb luminance in front of the sky (aerial perspective applied),
    // a their transmittance, so frame = rgb + a * sky. Frame-sized; throws without weather.
    LutImage ReadClouds() const;
    // Transmittance toward the Sun (the Moon at night) through every layer at the ground,
    // shadow_map_size^2 texels over shadow_map_extent around the camera's ground point: texel
    // (i, j) at east/north offsets ((i + 0.5) / size - 0.5) extent, in the renderer's frame.
    // Throws without weather.
    LutImage ReadCloudShadowMap() const;
    // This frame's CloudShade (the clear-sky values without weather).
    CloudShade ReadCloudShade() const;
    // The clouds' transmittance from `position` (m, the renderer's frame) toward `direction`
    // through every layer, the wind having blown for view.time: the shadow map's density march,
    // `steps` samples per layer, on the CPU over the same functions and textures as the GPU (no
    // GL call, nothing to wait for). 1 without weather. For a host's sunlight at the aircraft.
    double CloudTransmittance(const glm::dvec3& position, const glm::dvec3& direction,
                              const CloudView& view, int steps = 64) const;

    // GL texture names, for hosts that sample them (aerial perspective on their geometry).
    unsigned transmittance_texture() const;
    unsigned aerial_perspective_texture() const;
    unsigned frame_texture() const;
    unsigned cloud_shadow_texture() const;  // 0 without weather

    // Bytes of GPU memory held by the LUTs (not the frame).
    std::size_t LutMemoryBytes() const;
    // Times of the most recent run of each pass (waits for the GPU).
    PassTimes LastPassTimes() const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace zenith::sky
