// The GL 4.5 atmosphere renderer (Hillaire 2020): LUTs as compute passes, then the sky image.
// Needs a current GL 4.5 core context whose functions are loaded (a HeadlessContext, or the
// host's context through gl::LoadGlFunctions). All GL objects are owned and freed here.
#pragma once

#include <filesystem>
#include <glm/glm.hpp>
#include <memory>
#include <optional>

#include "zenith/base/error.h"
#include "zenith/sky/atmosphere.h"
#include "zenith/sky/clouds/noise.h"
#include "zenith/sky/clouds/weather.h"
#include "zenith/sky/environment.h"
#include "zenith/sky/frame.h"
#include "zenith/sky/lut.h"

namespace zenith::sky {

// The GL stage of the clouds' per-cell and per-pixel passes: the trace, the sky shade's trace,
// the reconstruction, the ground's shadow and the light shafts (CloudSettings::pass_stage). The
// same shared GLSL either way, and the same frames.
enum class CloudPassStage {
    kAuto,      // compute, except on Mesa's llvmpipe: see CloudSettings::pass_stage
    kFragment,  // one fragment per cell, direction or pixel (clouds/*.frag)
    kCompute,   // one invocation each, 8 x 8 work groups (clouds/*.comp)
};

// The stage the clouds' passes take for `stage` in the current GL context (functions loaded):
// kAuto resolved to kFragment where GL_RENDERER names llvmpipe and to kCompute elsewhere.
CloudPassStage ResolveCloudPassStage(CloudPassStage stage);

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
    // The light the diffuse field misses at the lit face (1-18 % of the incident light, most at
    // low suns and optical depths 0.5-4) put back as a source there, sized per phase function so
    // that a non-absorbing slab sends out all it receives, and taking back the excess where a
    // grazing Sun makes the rest send out more (clouds/functions.glsl, CloudSlabTables); false
    // leaves it out (the diffuse field keeps the exact slab's transmission either way).
    bool lit_face_source = true;
    // F16 §5.5.1: scale of the sky's ambient light on the clouds (not on rain and snow, which
    // are lit by the light beneath the clouds, as the air there is)
    double ambient_scale = 1.0;
    // Shape: world size of one tile of each noise (H16 §4.3: the shape volume is 4x wider than
    // tall, so it covers shape_period x shape_period / 4 x shape_period)
    double shape_period = 14000.0;  // m
    double detail_period = 1800.0;  // m
    double erosion = 0.45;          // [0, 0.9]: how much the detail noise eats the edges
    // March (H16 §5.2, §6.2; F16 §5.5.2). The shadow march's depth toward the light is also
    // the depth of the slab that carries a sample's diffuse light, so F16's four samples
    // (1.2 km) cut a thunderstorm's towers short and lit their shadowed sides as if the Sun
    // were 1.2 km behind them: the ground's light under `cumulonimbus` with the Sun 17 deg up
    // was 2.1x the path tracer's, 1.6x with seven (BENCHMARKS.md, "The shadow march's reach";
    // 1.01-1.09x the cloudy frame's time).
    double min_step = 120.0;          // m: the step of a short crossing
    int max_steps = 64;               // primary steps per layer crossing at most
    int shadow_steps = 7;             // samples toward each light: seven reach 10.2 km
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
    // A step's density sample stands for its column across the step (its weather and noise
    // held, the height's parts evaluated at up to four heights: clouds/march.glsl,
    // CloudStepColumnDensity), in the shadow march and in a thick primary step, so a step
    // leaving a cloud's top counts only its part inside and one across a deck's profile its
    // curve. Against the path tracer the deck grid's worst error went from 11.8 to 8.8 %
    // (the light below a deck of optical depth 32); false is the midpoint rule, the march
    // before, for a frame 1.2x faster on llvmpipe (BENCHMARKS.md).
    bool column_steps = true;
    double min_transmittance = 0.01;   // early exit
    double max_distance = 250000.0;    // m marched in one layer at most, from where a ray enters
    int aerial_perspective_steps = 8;  // atmosphere between the camera and the clouds
    // Light shafts: samples per ray of the clouds' shadow in the air below their base (the
    // single scattering where the shadow map puts light or shade, instead of its mean), one ray
    // per 2x2 trace cells; 0 draws the air under the clouds evenly dimmed (the shadow map's
    // mean), as before.
    int light_shaft_steps = 24;
    // Rain or snow falling at the camera (inside a precipitation shaft), drawn over the frame as
    // motion-blurred streaks (sky/shaders/atmosphere/precipitation.vert); false: only the
    // shaft's veil.
    bool precipitation_streaks = true;
    // Reconstruction (H16 §6.1): each frame traces one pixel of every block x block (a Bayer
    // order over block^2 frames) and reprojects the rest from the previous frames. 1 traces
    // every pixel every frame (the reference, and single still frames).
    int block = 4;
    double history_weight = 0.5;  // share of the reprojected history kept when a pixel is traced
    // The stage of those passes (CloudPassStage): on an NVIDIA H200 the compute stage's trace
    // took 0.32 ms where the fragment stage's took 2.45 and the cloudy frame 1.3 ms instead of
    // 3.9 (720p, block 4; a datacentre chip's fragment work runs on a fraction of it); on
    // llvmpipe the compute stage's frame was 2x as long. kAuto takes the fragment stage when
    // GL_RENDERER names llvmpipe and the compute stage otherwise (BENCHMARKS.md).
    CloudPassStage pass_stage = CloudPassStage::kAuto;
    // The ground shadow map: sun transmittance through all layers over a square around the
    // camera's ground point
    int shadow_map_size = 128;           // 470 m texels
    double shadow_map_extent = 60000.0;  // m, side of the square
    int shadow_map_steps = 16;           // per layer
    int shadow_map_interval = 4;         // frames between updates (the Sun and wind are slow)
    // The far sun-depth volume, updated with the shadow map: the optical depth toward the Sun (the
    // Moon at night) through every cloud layer over a square around the camera's ground point, at
    // evenly spaced altitudes from the lowest base to the highest top, which a sample's light takes
    // beyond its shadow march's reach (clouds/march.glsl, CloudFarSunDepth). Without it a
    // thunderstorm's towers in the shadow of cloud more than 10.2 km away toward a low Sun were lit
    // as if that cloud were not there (BENCHMARKS.md, "The far sun-depth volume"). sun_depth_size
    // 0: the shadow march alone.
    int sun_depth_size = 64;  // texels per side (1.6 km at the default extent)
    // Altitudes: the depth between them is interpolated linearly, which misses the kink at
    // the clouds' tops: over clouds 8.8 km tall, 12 levels were up to 0.22 optical depth off
    // (cloud_sun_depth_test), 24 up to 0.05.
    int sun_depth_levels = 24;
    double sun_depth_extent = 100000.0;  // m, side of the square
    // Noise volumes: generated on first use and cached
    clouds::CloudNoiseSettings noise;
    std::filesystem::path noise_cache_directory = clouds::DefaultNoiseCacheDirectory();

    // Throws zenith::ArgumentError naming the field, its value and the allowed range.
    void Validate() const;
};

// What the clouds do to the light beneath them (Frostbite 2016 §5.9.2, Eq. 22), found by
// Update with the shadow map (every shadow_map_interval frames): the air below base_altitude
// gets each light's direct part times direct_transmittance and the sky's part times
// sky_transmittance, and the clouds' own light as a source of luminance `luminance` over the
// upper hemisphere; the ground, a horizontal surface, the same with the means weighted by the
// cosine from the zenith: sky light times ground_sky_transmittance and the clouds' irradiance
// pi x ground_luminance.
struct CloudShade {
    double base_altitude = 0.0;         // m above the ground; 0: no clouds
    double direct_transmittance = 1.0;  // toward the Sun (Moon at night), mean over the shadow map
    double sky_transmittance = 1.0;     // mean over the upper hemisphere, from the ground
    glm::dvec3 luminance{0.0};          // cd/m^2, the clouds' mean over the upper hemisphere
    double ground_sky_transmittance = 1.0;  // the same two weighted by the cosine
    glm::dvec3 ground_luminance{0.0};
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

    // The environment from now on (zenith/sky/environment.h): size 0 removes it; another size
    // makes it anew; throws zenith::ArgumentError for bad settings. Each Update then draws the
    // next faces_per_frame faces of the cube map after the frame's LUTs, and after the sixth
    // makes its mip levels and its spherical harmonics. A round starts over with face 0 at a
    // cut (CloudView::reset_history).
    void SetEnvironment(const EnvironmentSettings& settings);
    const EnvironmentSettings& environment_settings() const;

    // The front door, every frame: Update makes the per-frame LUTs (Sky-View, aerial
    // perspective) for this scene and view (with weather, first the clouds' shadow map and their
    // shading of the air and the ground beneath them, Frostbite 2016 Eq. 22) and keeps both;
    // Render draws them into `target`. Render may run more than once after an Update: each run
    // traces the clouds again with the jitter moved, and the reprojection averages them (a still
    // frame's passes). Render throws std::logic_error before the first Update, and
    // zenith::ArgumentError for a viewport outside 1..16384 pixels a side or a scene depth
    // without a host framebuffer.
    void Update(const SkyScene& scene, const SkyView& view);
    void Render(const RenderTarget& target);

    // The clouds' transmittance from `position` (m, the renderer's frame) toward `direction`
    // through every layer, the wind having blown for view.time: the shadow map's density march,
    // `steps` samples per layer, on the CPU over the same functions and textures as the GPU (no
    // GL call, nothing to wait for). 1 without weather. For a host's sunlight at the aircraft.
    double CloudTransmittance(const glm::dvec3& position, const glm::dvec3& direction,
                              const CloudView& view, int steps = 64) const;
    // The same through the rain and snow shafts alone (clouds::WithPrecipitationShafts) over the
    // `distance` (m) from `position`: a host's fog in precipitation. 1 without any.
    double PrecipitationTransmittance(const glm::dvec3& position, const glm::dvec3& direction,
                                      double distance, const CloudView& view, int steps = 32) const;

    // The air for a host's own shading, on the CPU: the shared functions over the renderer's own
    // LUTs (read back when the atmosphere was set), the last Update's lights and the clouds'
    // shade of the air beneath them as LatestCloudShade has it (the clouds themselves are not
    // in these: they are in the frame and the environment). No GL call, nothing to wait for;
    // ~10 us each. `position` m in the renderer's frame, `direction` a unit vector; `steps` of
    // the ray march. Throw std::logic_error before the first Update.
    //   SkyLuminance: the sky's luminance along `direction` (cd/m^2, RGB), our ground below the
    //     horizon, as the composite draws the clear air (its Sky-View LUT agrees to ~1 %).
    //   AirInScattering: the air between `position` and `distance` m along `direction`: the
    //     luminance it scatters toward `position` (rgb) and its mean transmittance (a), what the
    //     frame blends over a host's geometry there (colour x T + L).
    glm::dvec3 SkyLuminance(const glm::dvec3& position, const glm::dvec3& direction,
                            int steps = 64) const;
    glm::dvec4 AirInScattering(const glm::dvec3& position, const glm::dvec3& direction,
                               double distance, int steps = 64) const;

    // The most recent CloudShade the GPU has finished, without waiting for it: each Update
    // copies the frame's shade into a read-back buffer behind a fence, and this takes the newest
    // copy whose fence has signalled (usually the previous frame's; a frame's own once the GPU
    // has run it). nullopt before the first copy has arrived. For a host's sky light under the
    // clouds (SkySystem's SkyLighting::sky_irradiance).
    std::optional<CloudShade> LatestCloudShade() const;
    // The night sky's illuminance on the horizontal ground below the camera (lux per channel,
    // NightSkyGroundIrradiance) that the last Update lit the ground with: 0 by day or without
    // a night sky. Kept between Updates until it can have changed by ~1 %.
    glm::dvec3 NightGroundIrradiance() const;

    // The newest spherical harmonics of the environment (world frame) that the GPU has finished,
    // without waiting (a read-back behind a fence, as LatestCloudShade): a round's usually
    // arrive by the next Update. nullopt without an environment or before the first round's.
    std::optional<SphericalHarmonics9> LatestEnvironmentSh() const;
    // Rounds of the six faces completed since SetEnvironment (0 without an environment).
    long long environment_rounds() const;

    // GL texture names, for hosts that sample them (aerial perspective on their geometry).
    unsigned transmittance_texture() const;
    unsigned aerial_perspective_texture() const;
    unsigned frame_texture() const;
    unsigned cloud_shadow_texture() const;  // 0 without weather
    // The environment's cube map (GL_TEXTURE_CUBE_MAP, RGBA32F, mip-mapped; cd/m^2) and a
    // buffer of its nine coefficients (9 x vec4, rgb = coefficient i, std430 or std140), which
    // a host's shader may read as a storage or uniform block; 0 without an environment. Enable
    // GL_TEXTURE_CUBE_MAP_SEAMLESS to filter across the faces' edges.
    unsigned environment_texture() const;
    unsigned environment_sh_buffer() const;

  private:
    friend class RendererInspection;  // read-backs and timers: zenith/sky/inspection.h
    // SkyLuminance's and AirInScattering's march (the shared IntegrateScatteredLuminance):
    // luminance (rgb) and mean transmittance (a).
    glm::dvec4 MarchAir(const glm::dvec3& position, const glm::dvec3& direction, double distance,
                        int steps, bool ground) const;
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace zenith::sky
