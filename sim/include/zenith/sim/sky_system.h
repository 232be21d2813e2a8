// zenith::sim::SkySystem — what a flight-simulator host creates once and drives every frame.
//
//   auto sky = SkySystem::CreateHeadless();                 // or CreateInHostContext(getProc)
//   sky->SetTime(geo::TimeFromIso8601("2024-06-21T19:00:00Z"));   // or SetUnixTime(s)
//   every frame:
//     sky->AdvanceTime(dt_s);                               // simulation time, optional warp
//                                                           // (or SetTime(epoch, host_clock_s))
//     sky->SetGeodetic(lat_deg, lon_deg, height_m);         // or SetEcef(position_m)
//     sky->SetAttitude(heading, pitch, roll);               // radians; or SetViewFromEnu(m)
//     sky->SetProjection(vertical_fov, aspect);
//     sky->Update();                                        // ephemeris, lights, per-frame LUTs
//     sky->Render(framebuffer, viewport);                   // or RenderOffscreen(size)
//     const SkyLighting& light = sky->lighting();           // for the host's own shading
//
// Units are SI (metres, seconds, radians); light in lux, luminance in cd/m^2. The world frame of
// directions is the observer's local ENU (east, north, up = WGS84 ellipsoid normal); ECEF
// versions are given too.
#pragma once

#include <filesystem>
#include <functional>
#include <glm/glm.hpp>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "zenith/base/error.h"
#include "zenith/geo/ephemeris.h"
#include "zenith/geo/refraction.h"
#include "zenith/geo/time.h"
#include "zenith/sky/atmosphere.h"
#include "zenith/sky/atmosphere_renderer.h"
#include "zenith/sky/display.h"
#include "zenith/sky/environment.h"
#include "zenith/sky/gl/loader.h"
#include "zenith/sky/lut.h"
#include "zenith/sky/sky_state.h"
#include "zenith/weather/metar.h"

namespace zenith::sim {

// A getProcAddress callback: eglGetProcAddress, OSMesaGetProcAddress, glfwGetProcAddress, ...
using GetProcAddressFn = sky::gl::GetProcAddressFn;

// Receives each notice once, when it arises: something zenith cannot do (a missing star
// catalogue, ...) and what it does instead. One line of text, no trailing newline.
using NoticeFn = std::function<void(const std::string& message)>;

// The air of refraction for a preset: ISA's for "earth"; none for the other built-in presets
// (Mars's thin CO2 and the thick test atmosphere are not Earth's air) and for preset files, for
// which a host sets its own (SkySystemSettings::refraction, SkySystem::SetRefraction).
std::optional<geo::RefractionAir> PresetRefraction(const std::string& preset);

struct SkySystemSettings {
    std::string preset = "earth";   // built-in preset name or JSON file
    sky::LutSettings lut_settings;  // LUT sizes and step counts
    double star_magnitude_limit = 6.5;
    // The night sky's diffuse light and light pollution (zenith/sky/night_sky.h); the stars
    // fainter than star_magnitude_limit in the catalogue (to V = 8) are part of it.
    sky::NightSkySettings night_sky;
    // Where the star catalogue is read from; empty: geo::DefaultStarDirectory() ($ZENITH_STAR_DIR
    // or /usr/share/kstars). Without it the sky has no stars and a notice says why.
    std::filesystem::path star_directory;
    // Where notices go as they arise; null: to stderr, prefixed "zenith: ". Either way they are
    // also kept in SkySystem::notices().
    NoticeFn on_notice;
    // Stars' apparent places (0.9 ms for 8,400 stars) are computed at TT instants that are
    // whole multiples of this and the Earth's rotation applied exactly every frame
    // (geo::Ephemeris), so a frame depends only on its own time and place; the places drift
    // < 0.02"/s. 0: exact every frame.
    double star_refresh_s = 1.0;
    // The air the Sun, Moon, planets and stars are seen through (zenith/geo/refraction.h):
    // ISA's until SetMetar or SetRefraction gives another; none draws them at their geometric
    // places (another planet's preset: this is Earth's air).
    std::optional<geo::RefractionAir> refraction = geo::RefractionAir{};
    // Clouds: a weather preset name or JSON file ("clear": none), and how they are drawn. The
    // default traces one pixel in 16 per frame and reprojects the rest (a host's frame loop).
    std::string weather = "clear";
    sky::CloudSettings clouds;
    // The GL state contract below: with true, every call leaves the host's GL state as it found
    // it (about 220 glGet calls to save and 200 to set and restore: 2.4 us per call on llvmpipe,
    // two calls a frame; BENCHMARKS.md). A host that sets all of its own state before it draws may
    // turn it off to skip the glGet calls, which on drivers with a threaded dispatch (Mesa's
    // glthread, NVIDIA's threaded optimisation) can wait for the driver thread; zenith then still
    // sets everything it depends on, and leaves behind the values it set.
    bool preserve_gl_state = true;
    // What Render writes (zenith/sky/display.h): linear cd/m^2 (the default), or display values
    // (exposed, night-adapted, tone mapped, sRGB-encoded) for an 8-bit or sRGB target.
    sky::DisplaySettings display;
    // An environment cube map of the sky around the aircraft, clouds included, and its
    // spherical harmonics for the host's reflections and diffuse light (zenith/sky/
    // environment.h; SkyLighting::sky_radiance_sh, environment_texture()). Off (size 0) by default.
    sky::EnvironmentSettings environment;
};

enum class DayPhase { kDay, kCivilTwilight, kNauticalTwilight, kAstronomicalTwilight, kNight };
const char* ToString(DayPhase phase);

// What the host's own shading needs, at the aircraft.
// Directions are unit vectors toward the body, in the aircraft's ENU frame and in ECEF;
// ecef_from_enu turns the host's own ENU vectors (a surface normal) into ECEF.
struct SkyLighting {
    glm::dmat3 ecef_from_enu{1.0};  // columns east, north, up (WGS84 normal) at the aircraft
    glm::dvec3 sun_direction_enu{0.0, 0.0, 1.0};
    glm::dvec3 sun_direction_ecef{0.0, 0.0, 1.0};
    glm::dvec3 moon_direction_enu{0.0, 0.0, 1.0};
    glm::dvec3 moon_direction_ecef{0.0, 0.0, 1.0};
    // Illuminance on a surface facing the light, after the atmosphere and the clouds between
    // the aircraft and the light (lux, RGB).
    glm::dvec3 sun_illuminance{0.0};
    glm::dvec3 moon_illuminance{0.0};
    // The clouds' part of that: their transmittance toward the light from the aircraft
    // (sky::AtmosphereRenderer::CloudTransmittance; 1 without weather or below the horizon).
    double sun_cloud_transmittance = 1.0;
    double moon_cloud_transmittance = 1.0;
    // Venus, the one planet bright enough to cast shadows (to -4.9 mag, ~2e-4 lux, against the
    // quarter Moon's ~0.01 lux): its light after the atmosphere and the clouds like the Moon's
    // (0 below the horizon, or outside 1950-2100 where the planets are not computed).
    glm::dvec3 venus_direction_enu{0.0, 0.0, 1.0};
    glm::dvec3 venus_direction_ecef{0.0, 0.0, 1.0};
    glm::dvec3 venus_illuminance{0.0};
    double venus_cloud_transmittance = 1.0;
    // Sky (not Sun or Moon) illuminance on a horizontal surface (lux, RGB), from the
    // ground-irradiance LUT: exact at the ground, an overestimate at altitude. Below the clouds'
    // base it is the clear sky's times the clouds' sky transmittance plus their own light
    // (pi x their mean luminance over the upper hemisphere, both weighted by the cosine from the
    // zenith: CloudShade's ground members), as zenith lights its own ground:
    // the shade the GPU works out every shadow_map_interval frames, read back behind a fence
    // without waiting for it (AtmosphereRenderer::LatestCloudShade), so it lags a frame or two.
    // With the Sun below the horizon it adds the night sky's own light (airglow, zodiacal light,
    // starlight, their glow in the air, light pollution: sky::NightSkyGroundIrradiance; ~9e-4
    // lux at a dark site, ~0.03 under Bortle 7).
    glm::dvec3 sky_irradiance{0.0};
    double sky_cloud_transmittance = 1.0;  // the clouds' part of the clear sky's light (1 above)
    // The sky's light from every direction around the aircraft, clouds and our ground included
    // (the Sun's and the Moon's disks are the lights above): L2 spherical harmonics of its
    // luminance in the aircraft's ENU frame, from the environment cube map (SkySystemSettings::
    // environment). SkyIrradianceEnu/Ecef give the irradiance on a surface of any orientation
    // (lux; a horizontal one's near sky_irradiance). Made after each round of the cube's faces
    // and read back behind a fence without waiting, so a round or two late; zero, with
    // sky_radiance_sh_valid false, without an environment or before the first round has arrived.
    sky::SphericalHarmonics9 sky_radiance_sh;
    bool sky_radiance_sh_valid = false;
    glm::dvec3 SkyIrradianceEnu(const glm::dvec3& normal_enu) const;
    glm::dvec3 SkyIrradianceEcef(const glm::dvec3& normal_ecef) const;
    double sun_elevation = 0.0;  // rad, geometric
    double moon_illuminated_fraction = 0.0;
    DayPhase phase = DayPhase::kDay;
};

// The GL state contract. It covers every call that issues GL commands: creation, SetAtmosphere,
// SetVisibility, SetMetar, SetWeather, SetEnvironment, Prepare, Update, Render and RenderOffscreen
// (and the same members of sky::AtmosphereRenderer).
//
// A host may leave any of this in any state; zenith sets what it needs before its passes:
//   face culling (so the front face does not matter), polygon mode, point size (and
//   GL_PROGRAM_POINT_SIZE), clip control (origin and depth
//   mode), depth and stencil tests, colour masks and blending (enables, functions, equations; every
//   draw buffer), scissor test and box, viewport, GL_FRAMEBUFFER_SRGB, rasterizer discard, logic
//   op, alpha-to-coverage / alpha-to-one / sample coverage / sample mask / sample shading, polygon
//   smooth, dither, clip distances, primitive restart (and its fixed index: zenith draws no
//   indexed primitives, but NVIDIA's driver restarts glDrawArrays at the index too), program,
//   VAO, framebuffer bindings, textures and sampler objects on any unit, the active unit, uniform
//   and storage buffer bindings, image units, the pixel pack / unpack / query buffers and every
//   pixel store parameter.
// It may also leave anything else in any state, which zenith's passes do not depend on: depth
//   func, mask and range, stencil funcs, ops and masks, polygon offset, depth clamp, the
//   primitive restart index, provoking vertex, point and line sizes,
//   program pipelines (a glUseProgram(0) program gives them back), bound vertex/index/indirect
//   buffers, a bound transform feedback object that is not active.
// Preserved (preserve_gl_state, the default): each call restores exactly what it set or
//   changed: the capabilities listed first, polygon mode, clip control, blending and colour
//   masks of draw buffers 0..7, viewport 0, scissor box and test 0, program, VAO, draw and
//   read framebuffers, the active texture unit, the 2-D and 3-D textures and the sampler
//   objects of units 0..26, uniform buffer bindings 0..5 and storage buffer binding 1 (ranges
//   included) and the generic bindings of both, image units 0..3, the pack/unpack/query buffers
//   and the pixel store parameters. Everything else zenith does not touch (it changes the
//   state of its own GL objects only; Render writes only the viewport's colour).
// A host must not call with: transform feedback active (begun and not paused), a
//   GL_TIME_ELAPSED query active (zenith times its passes with its own), or conditional
//   rendering active. Render writes draw buffer 0 of the host's framebuffer, which must be
//   complete (other draw buffers get undefined values: give Render a framebuffer with one draw
//   buffer). It
//   writes no depth or stencil; sampling a scene depth texture (SetSceneDepth) that is also
//   attached to that framebuffer is a feedback loop in GL's terms, so attach a copy or none.
// tests/sim/gl_state_contract_gl_test.cpp draws under a hostile host state and compares ~250
// state values before and after each call.
class SkySystem {
  public:
    // Owns a headless GL context (ZENITH_GL = osmesa | egl). Throws sky::gl::GlError when none
    // can be made, saying what was tried and what to install.
    static std::unique_ptr<SkySystem> CreateHeadless(const SkySystemSettings& settings = {});
    // Uses the host's current GL 4.5 context: the host keeps it current whenever it calls
    // Update or Render.
    static std::unique_ptr<SkySystem> CreateInHostContext(GetProcAddressFn get_proc_address,
                                                          const SkySystemSettings& settings = {});
    ~SkySystem();
    SkySystem(const SkySystem&) = delete;
    SkySystem& operator=(const SkySystem&) = delete;

    // Time is kept by a geo::SimulationClock: the instant set last and the seconds elapsed
    // since, summed without rounding drift (an hour of 0.01 s steps is 3600 s to ~1e-12 s and
    // the same Time as SetTime of the end instant). Days are 86400 s: a leap second is not
    // counted, as in POSIX time and host simulation clocks.
    void SetTime(const geo::Time& utc);
    // A host that keeps its own simulation clock: the time is epoch + seconds_since_epoch,
    // formed exactly each call (nothing accumulates here). Call it every frame with the same
    // epoch and the host's clock reading.
    void SetTime(const geo::Time& epoch, double seconds_since_epoch);
    // POSIX seconds since 1970-01-01T00:00:00Z (a double resolves 0.24 us in 2024), with the
    // time scales' options (DUT1, a TT - UT1 override). Throws geo::TimeError out of range.
    void SetUnixTime(double unix_s, const geo::TimeOptions& options = {});
    // Moves simulation time on by seconds x warp (warp 60: a minute per second); either may be
    // negative. Throws ArgumentError when not finite.
    void AdvanceTime(double seconds, double warp = 1.0);
    // Throws geo::TimeError when time has been moved outside the years 1000..3000.
    const geo::Time& time() const;

    // Throws geo::ObserverError for an impossible position.
    void SetGeodetic(double lat_deg, double lon_deg, double height_m);
    void SetEcef(const glm::dvec3& position_m);
    // The camera looks along the aircraft's nose, its up the aircraft's up. Aerospace 3-2-1
    // (intrinsic z-y'-x'') Euler angles of the body relative to local NED (geo::Attitude): rotate
    // by heading about down (0 = true north, pi/2 = east), then by pitch about the new right wing
    // (nose up positive), then by roll about the new nose (right wing down positive). Radians.
    void SetAttitude(double heading, double pitch, double roll);
    // Columns right, up, backward of the camera in the observer's ENU frame.
    void SetViewFromEnu(const glm::dmat3& world_from_view);
    // The camera's columns right, up, backward in ENU, from SetAttitude or SetViewFromEnu.
    glm::dmat3 enu_from_view() const;
    void SetProjection(double vertical_fov, double aspect);
    // The preset drawn from now on (with the visibility, if one is set, applied to it).
    void SetAtmosphere(const sky::Atmosphere& atmosphere);
    // The meteorological optical range at the ground, metres: the preset's aerosols are scaled so
    // that its extinction is ln 20 / V (weather::AtmosphereForVisibility); with `fog`, a fog layer
    // carries the visibility below 1 km and the air gives 1 km. nullopt: the preset's own air.
    // For hosts with their own weather engine. Throws zenith::ArgumentError unless 0 < V <= 1e6.
    void SetVisibility(std::optional<double> visibility_m, bool fog = false);
    // The night sky's settings from the next frame on: airglow, zodiacal light, starlight, and
    // light pollution (NightSkySettings::artificial_zenith_brightness, or from a Bortle class
    // with sky::ArtificialZenithBrightness(sky::BortleZenithBrightness(n))). Throws
    // zenith::ArgumentError for a field out of range.
    void SetNightSky(const sky::NightSkySettings& night_sky);
    // The air refraction is traced through from the next frame on (none: geometric places).
    // Throws zenith::ArgumentError for a pressure or temperature out of range.
    void SetRefraction(const std::optional<geo::RefractionAir>& air);
    // The weather of a METAR report (weather::DecodeMetar): its layers through SetWeather (bases
    // above station_elevation_m, metres above the ellipsoid), its visibility through
    // SetVisibility, and its QNH and temperature as the air of refraction (unless refraction is
    // off). Returns the decoder's warnings and the choices the mapping made.
    std::vector<std::string> SetMetar(const weather::Metar& report, double station_elevation_m,
                                      const sky::CloudSettings& settings = {});
    // Clouds from now on (an empty Weather: none). Layer altitudes are metres above the WGS84
    // ellipsoid at the aircraft, the same reference as SetGeodetic's height_m: the planet is a
    // sphere (the atmosphere's bottom_radius) whose surface passes through the ellipsoid below
    // the aircraft. A host with heights above mean sea level adds the geoid undulation (-106 to
    // +85 m, EGM96); cloud bases reported above ground (METAR) add the terrain's height.
    // The weather map's origin stays where it is set (SetWeatherOrigin), else at the aircraft's
    // position at the next Update; the wind carries the layers from the simulation time of that
    // Update on. Throws sky::clouds::WeatherError or zenith::ArgumentError, keeping the previous
    // weather.
    void SetWeather(const sky::clouds::Weather& weather, const sky::CloudSettings& settings = {});
    void SetWeatherOrigin(double lat_deg, double lon_deg);
    // The simulation time at which the wind starts carrying the layers (default: the first
    // Update after SetWeather).
    void SetWeatherEpoch(const geo::Time& utc);
    bool has_clouds() const;
    const sky::Atmosphere& atmosphere() const;
    const sky::clouds::Weather& weather() const;
    // The next frame does not reproject earlier ones (after a cut or a jump in time or place),
    // its jitter sequence starts over and what a frame loop keeps while it cannot show (the
    // night sky's light, the refraction table) is made again, so it is the same whatever was
    // drawn before (replayed, resumed and sharded frames match); a
    // metered display exposure starts from that frame's own (no adaptation across the cut). Call
    // it before that frame's Update(), which renews the clouds' shadow map on a cut.
    void ResetCloudHistory();
    // The host's depth texture (0..1, a perspective projection with these planes, metres; far_m
    // may be infinity) for the next Render calls: its geometry gets aerial perspective,
    // framebuffer = L + T * colour, and the sky is drawn only where the depth is at the far
    // plane. `reversed`: reversed-Z (glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE), 1 at near, 0
    // at far, cleared to 0); sky::SceneDepth has the formulas. Throws ArgumentError for a texture
    // that is not a single-sample 2-D texture (a multisampled depth buffer must be resolved
    // first). Clear with ClearSceneDepth().
    void SetSceneDepth(unsigned depth_texture, double near_m, double far_m, bool reversed = false);
    void SetSceneDepth(const sky::SceneDepth& depth);
    void ClearSceneDepth();

    // Warm-up before the first frame, so that it costs what any frame costs: the programs are
    // compiled and the clouds' noise built (or read from its cache) at creation and SetWeather;
    // what is left is what GL drivers do at first use, notably llvmpipe's JIT compilation of
    // each shader at its first dispatch or draw, and the frame targets of a new size. Prepare
    // runs Update and draws one frame of `size` (the host's viewport size) into the system's
    // own target, then waits for the GPU. Time, place, view and lighting are as an Update would
    // leave them; the clouds' history starts over (as after ResetCloudHistory), so the next
    // frame is the one it would have been. With display.output == kDisplay it also runs the
    // display pass, metered, over that frame into a scratch target (~100 ms once on llvmpipe at
    // 1280x720, taken from the first Render; BENCHMARKS.md), restarts its adaptation and reports
    // no exposure (exposure_ev100() waits for a Render). With an environment it draws all six
    // faces, so the lighting has the sky's harmonics (sky_radiance_sh_valid) from then on; its
    // sky_irradiance is under that frame's clouds (an Update's shade may lag on a GPU). A
    // host with scene depth still compiles the depth variant at its first Render.
    void Prepare(const glm::ivec2& size);

    // Ephemeris, lights, lighting and per-frame LUTs for the current state.
    void Update();
    // Draws the sky into the host's framebuffer object over viewport (x, y, width, height);
    // framebuffer 0 is the default one. GL_FRAMEBUFFER_SRGB is off while zenith draws.
    //   display.output == kLinear (default): linear Rec.709 luminance, cd/m^2 per channel, as
    //     computed (a noon sky ~1e4, a moonlit one ~1e-3, the Sun's disk up to ~7e7 after its
    //     pixel footprint): for an RGBA32F target and a host that exposes and tone maps itself.
    //     An RGBA16F target clips at 65504, an 8-bit one at 1 (white).
    //   kDisplay: the frame is drawn into zenith's own RGBA32F target, then the display pass
    //     (sky::DisplayPass) writes sRGB-encoded display values, the same as `zenith render`'s
    //     PNGs, into an RGBA8 or SRGB8_ALPHA8 target (the same bytes in both). Its exposure is
    //     display.ev100 or metered from the frame (adapted over display.adaptation_time_s of
    //     wall-clock time between Render calls); with a scene depth (SetSceneDepth) the host's
    //     geometry pixels are left as they are (no aerial perspective over them in this mode):
    //     draw the geometry afterwards with exposure_ev100(), or use kLinear.
    void Render(unsigned framebuffer, const glm::ivec4& viewport);
    // The environment from now on (sky::AtmosphereRenderer::SetEnvironment; throws
    // zenith::ArgumentError for bad settings, keeping the previous one).
    void SetEnvironment(const sky::EnvironmentSettings& environment);
    // The display from now on (throws zenith::ArgumentError for bad settings).
    void SetDisplay(const sky::DisplaySettings& display);
    const sky::DisplaySettings& display() const;
    // The exposure (EV100) of the last Render in kDisplay mode, metered or given; nullopt in
    // kLinear mode or before that Render. A host shading its own geometry to match multiplies
    // its linear cd/m^2 by 1 / (1.2 * 2^EV100) (image_io.h's ExposureScale, Lagarde & de
    // Rousiers 2014 §5.1) before the same tone map. Metered, it is read back from the GPU, which
    // waits for the frame to finish: call it once a frame, after Render, or less often.
    std::optional<double> exposure_ev100() const;
    // Draws into the system's own RGBA32F frame and reads it back (row 0 = bottom).
    sky::LutImage RenderOffscreen(const glm::ivec2& size);

    const SkyLighting& lighting() const;

    // The sky and the air as the host's own shading may want them, from the aircraft, for the
    // last Update (sky::AtmosphereRenderer::SkyLuminance / AirInScattering: a CPU ray march over
    // the renderer's own LUTs, ~10 us, no GL call; the clouds' shade of the air beneath them
    // included, the clouds themselves not: they are in the frame and the environment). Throw
    // std::logic_error before the first Update.
    //   SkyLuminance: the sky's luminance toward a direction (cd/m^2, RGB; our ground below the
    //     horizon): a background or horizon colour.
    //   Fog: the air between the aircraft and a point `distance_m` away toward a direction, as
    //     the frame blends it over a host's geometry there (colour x transmittance + in_scattered),
    //     and the exponential fog that gives the same at that distance.
    struct Fog {
        glm::dvec3 in_scattered{0.0};  // cd/m^2
        double transmittance = 1.0;    // mean over RGB
        double density_per_m = 0.0;    // -ln(transmittance) / distance: exp(-density d)...
        glm::dvec3 colour{0.0};        // ...and in_scattered / (1 - transmittance), cd/m^2
    };
    glm::dvec3 SkyLuminanceEnu(const glm::dvec3& direction_enu) const;
    glm::dvec3 SkyLuminanceEcef(const glm::dvec3& direction_ecef) const;
    Fog FogEnu(const glm::dvec3& direction_enu, double distance_m) const;
    Fog FogEcef(const glm::dvec3& direction_ecef, double distance_m) const;
    // Every notice so far, oldest first (also given to SkySystemSettings::on_notice).
    const std::vector<std::string>& notices() const;
    const geo::SkyEphemeris& ephemeris() const;
    // GL names, for sampling on the host's side: the aerial-perspective froxel volume (rgb
    // in-scattered luminance, a mean transmittance) and the transmittance LUT.
    unsigned aerial_perspective_texture() const;
    unsigned transmittance_texture() const;
    // The clouds' shadow on the ground around the aircraft (sky::RendererInspection::
    // ReadCloudShadowMap has the layout); 0 without clouds.
    unsigned cloud_shadow_texture() const;
    // The environment's cube map (GL_TEXTURE_CUBE_MAP, RGBA32F, mip-mapped, cd/m^2, faces in the
    // aircraft's ENU frame by OpenGL's convention: sample with the ENU direction) and a buffer of
    // sky_radiance_sh's nine coefficients (9 x vec4) for the host's shaders; 0 without an
    // environment. Both are changed by Update: sample them after it.
    unsigned environment_texture() const;
    unsigned environment_sh_buffer() const;

  private:
    struct Impl;
    explicit SkySystem(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
};

}  // namespace zenith::sim
