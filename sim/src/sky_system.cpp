#include "zenith/sim/sky_system.h"

#include <glad/gl.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <glm/gtc/constants.hpp>
#include <stdexcept>

#include "zenith/base/error.h"
#include "zenith/geo/earth_orientation.h"
#include "zenith/geo/frames.h"
#include "zenith/sky/atmosphere_renderer.h"
#include "zenith/sky/display.h"
#include "zenith/sky/gl/context.h"
#include "zenith/sky/inspection.h"
#include "zenith/sky/lighting.h"
#include "zenith/weather/altimetry.h"
#include "zenith/weather/cloud_weather.h"

namespace zenith::sim {
namespace {

std::string Hex(GLint value) {
    char text[16];
    std::snprintf(text, sizeof(text), "%04X", static_cast<unsigned>(value));
    return text;
}

DayPhase PhaseOf(double sun_elevation) {
    // Sunrise/sunset at -0.833 deg (refraction and the Sun's radius); twilights by the usual
    // civil/nautical/astronomical depressions of 6, 12 and 18 deg.
    const double deg = glm::degrees(sun_elevation);
    if (deg > -0.833) return DayPhase::kDay;
    if (deg > -6.0) return DayPhase::kCivilTwilight;
    if (deg > -12.0) return DayPhase::kNauticalTwilight;
    if (deg > -18.0) return DayPhase::kAstronomicalTwilight;
    return DayPhase::kNight;
}

}  // namespace

const char* ToString(DayPhase phase) {
    switch (phase) {
        case DayPhase::kDay:
            return "day";
        case DayPhase::kCivilTwilight:
            return "civil twilight";
        case DayPhase::kNauticalTwilight:
            return "nautical twilight";
        case DayPhase::kAstronomicalTwilight:
            return "astronomical twilight";
        case DayPhase::kNight:
            return "night";
    }
    return "?";
}

struct SkySystem::Impl {
    std::unique_ptr<sky::gl::HeadlessContext> context;  // null inside a host's context
    SkySystemSettings settings;
    sky::Atmosphere atmosphere;         // what is drawn: the preset, with the visibility applied
    sky::Atmosphere preset_atmosphere;  // SetAtmosphere's, before the visibility
    std::optional<double> visibility_m;
    bool visibility_is_fog = false;
    std::optional<geo::RefractionAir> refraction;  // settings.refraction, then SetRefraction's
    sky::RefractionCache refraction_table;
    std::optional<geo::StarCatalog> catalog;
    std::shared_ptr<const sky::StarlightMap> starlight;  // the night sky's integrated starlight
    std::unique_ptr<sky::AtmosphereRenderer> renderer;
    sky::LutImage ground_irradiance;

    geo::SimulationClock clock{geo::TimeNow()};
    std::vector<std::string> notices;
    geo::Observer observer{0.0, 0.0, 0.0};
    std::optional<geo::Attitude> attitude = geo::Attitude{};
    glm::dmat3 world_from_view{1.0};
    double vertical_fov = glm::radians(60.0);
    double aspect = 16.0 / 9.0;

    // Stars' apparent places at whole multiples of star_refresh_s (geo::Ephemeris), so that a
    // frame depends only on its own time and place.
    std::optional<geo::Ephemeris> calculator;
    sky::SkyFrame frame;  // the last Update's
    SkyLighting lighting;
    std::optional<sky::SceneDepth> scene_depth;
    // Clouds: the weather map's origin (lat, lon deg) and the simulation time its wind started.
    std::optional<glm::dvec2> weather_origin;
    std::optional<double> weather_epoch_jd;
    bool reset_history = false;  // ResetCloudHistory: for the next Update
    // The display pass (settings.display.output == kDisplay), made when first needed, and the
    // time of its last Render (the adaptation's clock).
    std::unique_ptr<sky::DisplayPass> display;
    std::optional<std::chrono::steady_clock::time_point> last_display;
    bool reset_adaptation = false;
    bool display_rendered = false;  // a Render has run the display pass (not only Prepare)

    // The clear sky's light on a horizontal surface (the ground-irradiance LUT), lux, and with
    // the Sun below the horizon the night sky's own, as the renderer lit its ground with it
    // (airglow, zodiacal light, starlight, their glow in the air, light pollution).
    glm::dvec3 ClearSkyIrradiance() const {
        const sky::Lights& lights = frame.scene.lights;
        return lights.sun_illuminance *
                   sky::SampleGroundIrradiance(ground_irradiance, lights.sun_direction.z) +
               lights.moon_illuminance *
                   sky::SampleGroundIrradiance(ground_irradiance, lights.moon_direction.z) +
               renderer->NightGroundIrradiance();
    }

    sky::DisplayPass& DisplayPassMade() {
        if (!display) {
            display = std::make_unique<sky::DisplayPass>();
            display->set_preserve_gl_state(settings.preserve_gl_state);
        }
        return *display;
    }

    // The sky's light on the ground; under the clouds, their sky transmittance and their own
    // light, as the renderer lights its ground (functions.glsl's ground term), from the newest
    // shade the GPU has finished.
    void TakeSkyIrradiance() {
        SkyLighting& l = lighting;
        l.sky_irradiance = ClearSkyIrradiance();
        if (const std::optional<sky::CloudShade> shade = renderer->LatestCloudShade();
            shade && observer.height_m() < shade->base_altitude) {
            l.sky_irradiance = l.sky_irradiance * shade->ground_sky_transmittance +
                               glm::pi<double>() * shade->ground_luminance;
            l.sky_cloud_transmittance = shade->ground_sky_transmittance;
        } else {
            l.sky_cloud_transmittance = 1.0;
        }
    }

    // The newest finished spherical harmonics of the environment into the lighting.
    void TakeEnvironmentSh() {
        const std::optional<sky::SphericalHarmonics9> sh = renderer->LatestEnvironmentSh();
        lighting.sky_radiance_sh = sh.value_or(sky::SphericalHarmonics9{});
        lighting.sky_radiance_sh_valid = sh.has_value();
    }

    void Notify(std::string message) {
        if (settings.on_notice) {
            settings.on_notice(message);
        } else {
            std::fprintf(stderr, "zenith: %s\n", message.c_str());
        }
        notices.push_back(std::move(message));
    }

    Impl(const SkySystemSettings& s, std::unique_ptr<sky::gl::HeadlessContext> c)
        : context(std::move(c)),
          settings(s),
          atmosphere(sky::LoadAtmosphere(s.preset)),
          preset_atmosphere(atmosphere),
          refraction(s.refraction) {
        if (refraction) refraction->Validate();
        try {
            catalog = geo::StarCatalog::Load(s.star_magnitude_limit, s.star_directory);
        } catch (const geo::CatalogError& e) {
            // Everything else works without stars; the host hears why they are missing.
            Notify(std::string("no stars: ") + e.what());
        }
        s.night_sky.Validate();
        try {
            // The catalogue down to its own end (V = 8) for the stars not drawn one by one.
            starlight = std::make_shared<const sky::StarlightMap>(sky::StarlightMap::FromCatalog(
                geo::StarCatalog::Load(std::max(8.0, s.star_magnitude_limit), s.star_directory),
                s.star_magnitude_limit));
        } catch (const geo::CatalogError&) {
            starlight = std::make_shared<const sky::StarlightMap>(sky::StarlightMap::ModelOnly());
        }
        calculator.emplace(catalog ? &*catalog : nullptr, s.star_refresh_s);
        renderer = std::make_unique<sky::AtmosphereRenderer>(atmosphere, s.lut_settings);
        renderer->set_preserve_gl_state(s.preserve_gl_state);
        ground_irradiance = sky::Inspect(*renderer).ReadGroundIrradiance();
        renderer->SetWeather(sky::clouds::LoadWeather(s.weather), s.clouds);
        renderer->SetEnvironment(s.environment);
        s.display.Validate();
        if (s.display.output == sky::DisplaySettings::Output::kDisplay) DisplayPassMade();
    }
};

std::optional<geo::RefractionAir> PresetRefraction(const std::string& preset) {
    if (preset == "earth") return geo::RefractionAir{};
    return std::nullopt;
}

SkySystem::SkySystem(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
SkySystem::~SkySystem() = default;

std::unique_ptr<SkySystem> SkySystem::CreateHeadless(const SkySystemSettings& settings) {
    auto context = sky::gl::CreateHeadlessContextFromEnvironment();
    return std::unique_ptr<SkySystem>(
        new SkySystem(std::make_unique<Impl>(settings, std::move(context))));
}

std::unique_ptr<SkySystem> SkySystem::CreateInHostContext(GetProcAddressFn get_proc_address,
                                                          const SkySystemSettings& settings) {
    if (get_proc_address == nullptr) {
        throw ArgumentError("CreateInHostContext: get_proc_address is null");
    }
    sky::gl::LoadGlFunctions(get_proc_address);
    return std::unique_ptr<SkySystem>(new SkySystem(std::make_unique<Impl>(settings, nullptr)));
}

void SkySystem::SetTime(const geo::Time& utc) { impl_->clock.Set(utc); }

void SkySystem::SetTime(const geo::Time& epoch, double seconds_since_epoch) {
    if (!std::isfinite(seconds_since_epoch)) {
        throw ArgumentError("SetTime: seconds_since_epoch = " +
                            std::to_string(seconds_since_epoch) + " must be finite");
    }
    geo::SimulationClock& clock = impl_->clock;
    const geo::Time& start = clock.start();
    // Set() works out the epoch's time scales; do it only when the epoch changes.
    if (!(start.jd_utc == epoch.jd_utc && start.jd_ut1 == epoch.jd_ut1 &&
          start.jd_tt == epoch.jd_tt)) {
        clock.Set(epoch);
    }
    clock.SetElapsed(seconds_since_epoch);
}

void SkySystem::SetUnixTime(double unix_s, const geo::TimeOptions& options) {
    impl_->clock.Set(geo::TimeFromUnixSeconds(unix_s, options));
}

void SkySystem::AdvanceTime(double seconds, double warp) {
    if (!(std::isfinite(seconds) && std::isfinite(warp) && std::isfinite(seconds * warp))) {
        throw ArgumentError("AdvanceTime: seconds = " + std::to_string(seconds) +
                            " and warp = " + std::to_string(warp) + " must be finite");
    }
    impl_->clock.Advance(seconds, warp);
}

const geo::Time& SkySystem::time() const { return impl_->clock.time(); }

void SkySystem::SetGeodetic(double lat_deg, double lon_deg, double height_m) {
    impl_->observer = geo::Observer(lat_deg, lon_deg, height_m);
}

void SkySystem::SetEcef(const glm::dvec3& p) { impl_->observer = geo::Observer::FromEcef(p); }

void SkySystem::SetAttitude(double heading, double pitch, double roll) {
    impl_->attitude = geo::Attitude{heading, pitch, roll};
}

void SkySystem::SetViewFromEnu(const glm::dmat3& world_from_view) {
    impl_->attitude.reset();
    impl_->world_from_view = world_from_view;
}

glm::dmat3 SkySystem::enu_from_view() const {
    return impl_->attitude ? geo::EnuFromView(*impl_->attitude) : impl_->world_from_view;
}

void SkySystem::SetProjection(double vertical_fov, double aspect) {
    sky::ValidateProjection(vertical_fov, aspect);
    impl_->vertical_fov = vertical_fov;
    impl_->aspect = aspect;
}

void SkySystem::SetAtmosphere(const sky::Atmosphere& atmosphere) {
    Impl& d = *impl_;
    sky::Validate(atmosphere);
    std::vector<std::string> notes;
    const sky::Atmosphere drawn =
        d.visibility_m ? weather::AtmosphereForVisibility(atmosphere, *d.visibility_m,
                                                          d.visibility_is_fog, &notes)
                       : atmosphere;
    d.renderer->SetAtmosphere(drawn);
    d.atmosphere = drawn;
    d.preset_atmosphere = atmosphere;
    d.ground_irradiance = sky::Inspect(*d.renderer).ReadGroundIrradiance();
    for (std::string& note : notes) d.Notify(std::move(note));
}

void SkySystem::SetNightSky(const sky::NightSkySettings& night_sky) {
    night_sky.Validate();
    impl_->settings.night_sky = night_sky;
}

void SkySystem::SetVisibility(std::optional<double> visibility_m, bool fog) {
    if (visibility_m) Require("visibility", *visibility_m, "m", Range::LeftOpen(0.0, 1e6));
    impl_->visibility_m = visibility_m;
    impl_->visibility_is_fog = fog;
    SetAtmosphere(impl_->preset_atmosphere);
}

std::vector<std::string> SkySystem::SetMetar(const weather::Metar& report,
                                             double station_elevation_m,
                                             const sky::CloudSettings& settings) {
    weather::MetarWeather mapped =
        weather::CloudWeatherFromMetar(report, station_elevation_m, settings.extinction);
    std::vector<std::string> notes;
    for (const weather::MetarWarning& w : report.warnings)
        notes.push_back("METAR: " + w.ToString());
    notes.insert(notes.end(), mapped.notes.begin(), mapped.notes.end());
    SetWeather(mapped.clouds, settings);
    SetVisibility(mapped.visibility_m, mapped.fog);
    if (impl_->refraction) {
        SetRefraction(weather::RefractionAirOf(weather::StationAirOf(report, station_elevation_m)));
    }
    return notes;
}

void SkySystem::SetRefraction(const std::optional<geo::RefractionAir>& air) {
    if (air) air->Validate();
    impl_->refraction = air;
}

void SkySystem::SetWeather(const sky::clouds::Weather& weather,
                           const sky::CloudSettings& settings) {
    impl_->renderer->SetWeather(weather, settings);
    impl_->weather_epoch_jd.reset();
}

void SkySystem::SetWeatherOrigin(double lat_deg, double lon_deg) {
    geo::Observer(lat_deg, lon_deg, 0.0);  // validates, naming the value
    impl_->weather_origin = glm::dvec2(lat_deg, lon_deg);
}

void SkySystem::SetWeatherEpoch(const geo::Time& utc) { impl_->weather_epoch_jd = utc.jd_utc; }

bool SkySystem::has_clouds() const { return !impl_->renderer->weather().layers.empty(); }
const sky::Atmosphere& SkySystem::atmosphere() const { return impl_->atmosphere; }
const sky::clouds::Weather& SkySystem::weather() const { return impl_->renderer->weather(); }

void SkySystem::ResetCloudHistory() {
    impl_->reset_history = true;
    impl_->reset_adaptation = true;
}

void SkySystem::SetDisplay(const sky::DisplaySettings& display) {
    display.Validate();
    impl_->settings.display = display;
    if (display.output == sky::DisplaySettings::Output::kDisplay) impl_->DisplayPassMade();
}

const sky::DisplaySettings& SkySystem::display() const { return impl_->settings.display; }

std::optional<double> SkySystem::exposure_ev100() const {
    if (impl_->settings.display.output != sky::DisplaySettings::Output::kDisplay ||
        !impl_->display || !impl_->display_rendered) {
        return std::nullopt;
    }
    return impl_->display->exposure_ev100();
}

void SkySystem::SetSceneDepth(unsigned depth_texture, double near_m, double far_m, bool reversed) {
    SetSceneDepth(sky::SceneDepth{depth_texture, near_m, far_m, reversed});
}

void SkySystem::SetSceneDepth(const sky::SceneDepth& depth) {
    if (!(depth.texture != 0 && std::isfinite(depth.near_m) && depth.near_m > 0.0 &&
          depth.far_m > depth.near_m)) {
        throw ArgumentError(
            "SetSceneDepth: needs a texture and 0 < near_m < far_m (far_m may be infinity)");
    }
    // The composite samples it as a sampler2D: anything else would draw no sky, silently.
    if (glIsTexture(depth.texture) == GL_FALSE) {
        throw ArgumentError("SetSceneDepth: " + std::to_string(depth.texture) +
                            " is not a texture name");
    }
    GLint target = 0;
    glGetTextureParameteriv(depth.texture, GL_TEXTURE_TARGET, &target);
    if (target == GL_TEXTURE_2D_MULTISAMPLE) {
        throw ArgumentError("SetSceneDepth: texture " + std::to_string(depth.texture) +
                            " is multisampled; resolve the depth into a single-sample "
                            "GL_TEXTURE_2D first (glBlitFramebuffer with GL_DEPTH_BUFFER_BIT)");
    }
    if (target != GL_TEXTURE_2D) {
        throw ArgumentError("SetSceneDepth: texture " + std::to_string(depth.texture) +
                            " is not a GL_TEXTURE_2D (target 0x" + Hex(target) + ")");
    }
    impl_->scene_depth = depth;
}

void SkySystem::ClearSceneDepth() { impl_->scene_depth.reset(); }

void SkySystem::Update() {
    Impl& d = *impl_;
    sky::FrameSetup setup;
    setup.time = d.clock.time();
    setup.observer = d.observer;
    if (d.attitude) {
        setup.attitude = *d.attitude;
    } else {
        setup.enu_from_view = d.world_from_view;
    }
    setup.vertical_fov = d.vertical_fov;
    setup.aspect = d.aspect;
    setup.refraction = d.refraction;
    if (d.reset_history) d.refraction_table.Clear();  // a cut owes nothing to earlier frames
    d.frame = sky::BuildSkyFrame(*d.calculator, setup, d.atmosphere, &d.refraction_table);
    if (!d.weather_origin) {
        d.weather_origin = glm::dvec2(d.observer.lat_deg(), d.observer.lon_deg());
    }
    const geo::Time& time = setup.time;
    if (!d.weather_epoch_jd) d.weather_epoch_jd = time.jd_utc;
    sky::CloudView& clouds = d.frame.scene.clouds;
    clouds.time = (time.jd_utc - *d.weather_epoch_jd) * geo::kSecondsPerDay;
    clouds.weather_from_world =
        sky::WeatherFrame(d.observer, d.weather_origin->x, d.weather_origin->y);
    clouds.reset_history = d.reset_history;
    d.reset_history = false;  // the renderer applies it to this frame's first Render
    d.frame.scene.night_sky.settings = d.settings.night_sky;
    d.frame.scene.night_sky.starlight = d.starlight;
    d.renderer->Update(d.frame.scene, d.frame.view);

    const sky::Lights& lights = d.frame.scene.lights;
    const sky::MoonDisk& moon = d.frame.scene.moon;
    SkyLighting& l = d.lighting;
    const glm::dmat3 ecef_from_enu = d.observer.ecef_from_enu();
    l.ecef_from_enu = ecef_from_enu;
    l.sun_direction_enu = lights.sun_direction;
    l.moon_direction_enu = lights.moon_direction;
    l.sun_direction_ecef = ecef_from_enu * l.sun_direction_enu;
    l.moon_direction_ecef = ecef_from_enu * l.moon_direction_enu;
    const double height = d.observer.height_m();
    l.sun_illuminance = lights.sun_illuminance *
                        sky::TransmittanceToLight(d.atmosphere, height, l.sun_direction_enu.z,
                                                  d.atmosphere.sun_angular_radius);
    l.moon_illuminance = lights.moon_illuminance * sky::TransmittanceToLight(d.atmosphere, height,
                                                                             l.moon_direction_enu.z,
                                                                             moon.angular_radius);
    // The clouds between the aircraft and each light that is up (a CPU march, 8-12 us each).
    const auto through_clouds = [&](const glm::dvec3& illuminance, const glm::dvec3& direction) {
        if (illuminance == glm::dvec3(0.0)) return 1.0;
        return d.renderer->CloudTransmittance(d.frame.view.camera.position, direction, clouds);
    };
    l.venus_illuminance = glm::dvec3(0.0);
    for (const geo::PlanetPosition& planet : d.frame.ephemeris.planets) {
        if (planet.planet != geo::Planet::kVenus) continue;
        l.venus_direction_enu = planet.topocentric.horizontal.direction_enu;
        l.venus_direction_ecef = ecef_from_enu * l.venus_direction_enu;
        l.venus_illuminance =
            sky::PlanetIlluminance(planet) *
            sky::TransmittanceToLight(d.atmosphere, height, l.venus_direction_enu.z,
                                      0.5 * glm::radians(planet.angular_diameter_arcsec / 3600.0));
    }
    l.sun_cloud_transmittance = through_clouds(l.sun_illuminance, l.sun_direction_enu);
    l.moon_cloud_transmittance = through_clouds(l.moon_illuminance, l.moon_direction_enu);
    l.venus_cloud_transmittance = through_clouds(l.venus_illuminance, l.venus_direction_enu);
    l.sun_illuminance *= l.sun_cloud_transmittance;
    l.moon_illuminance *= l.moon_cloud_transmittance;
    l.venus_illuminance *= l.venus_cloud_transmittance;
    d.TakeSkyIrradiance();
    d.TakeEnvironmentSh();
    l.sun_elevation = d.frame.ephemeris.sun.topocentric.horizontal.elevation;
    l.moon_illuminated_fraction = d.frame.ephemeris.moon_phase.illuminated_fraction;
    l.phase = PhaseOf(l.sun_elevation);
}

void SkySystem::Prepare(const glm::ivec2& size) {
    if (!(size.x > 0 && size.y > 0)) {
        throw ArgumentError("Prepare: size " + std::to_string(size.x) + "x" +
                            std::to_string(size.y) + " must be positive");
    }
    Impl& d = *impl_;
    // A whole round of the environment's faces from face 0 (a cut), so that its lighting is
    // there from the first frame on.
    const sky::EnvironmentSettings environment = d.renderer->environment_settings();
    d.reset_history = true;
    if (environment.enabled()) {
        sky::EnvironmentSettings all = environment;
        all.faces_per_frame = 6;
        d.renderer->SetEnvironment(all);
    }
    Update();
    if (environment.enabled()) d.renderer->SetEnvironment(environment);
    d.renderer->Render(sky::RenderTarget::Offscreen(size));
    if (d.settings.display.output == sky::DisplaySettings::Output::kDisplay) {
        // The display pass over that frame, metered (all three of its programs run; a given
        // exposure runs one), into a scratch RGBA8 target of the same size.
        sky::DisplayPass& pass = d.DisplayPassMade();
        GLuint texture = 0, framebuffer = 0;
        glCreateTextures(GL_TEXTURE_2D, 1, &texture);
        glTextureStorage2D(texture, 1, GL_RGBA8, size.x, size.y);
        glCreateFramebuffers(1, &framebuffer);
        glNamedFramebufferTexture(framebuffer, GL_COLOR_ATTACHMENT0, texture, 0);
        sky::DisplaySettings metered = d.settings.display;
        metered.ev100.reset();
        pass.Run(d.renderer->frame_texture(), framebuffer, {0, 0, size.x, size.y}, metered, 0.0);
        glDeleteFramebuffers(1, &framebuffer);
        glDeleteTextures(1, &texture);
        d.reset_adaptation = true;  // the next Render meters from its own frame
    }
    glFinish();  // the driver's compilation happens when the GPU runs the frame
    // The clouds' shade and the environment's round, now finished: Update took what the GPU had
    // finished before the frame (on a GPU, not yet this weather's shade).
    d.TakeSkyIrradiance();
    d.TakeEnvironmentSh();
    d.reset_history = true;
}

void SkySystem::Render(unsigned framebuffer, const glm::ivec4& viewport) {
    Impl& d = *impl_;
    if (d.settings.display.output == sky::DisplaySettings::Output::kDisplay) {
        // The linear frame into the renderer's own RGBA32F target, then the display pass from it
        // into the host's framebuffer (the host's geometry, where a scene depth says so, kept).
        d.renderer->Render(sky::RenderTarget::Offscreen({viewport.z, viewport.w}));
        sky::DisplayPass& pass = d.DisplayPassMade();
        if (d.reset_adaptation) {
            pass.ResetAdaptation();
            d.reset_adaptation = false;
        }
        const auto now = std::chrono::steady_clock::now();
        const double dt_s =
            d.last_display ? std::chrono::duration<double>(now - *d.last_display).count() : 0.0;
        d.last_display = now;
        pass.Run(d.renderer->frame_texture(), framebuffer, viewport, d.settings.display, dt_s,
                 d.scene_depth);
        d.display_rendered = true;
        return;
    }
    d.renderer->Render(sky::RenderTarget::Host(framebuffer, viewport, d.scene_depth));
}

sky::LutImage SkySystem::RenderOffscreen(const glm::ivec2& size) {
    impl_->renderer->Render(sky::RenderTarget::Offscreen(size));
    return sky::Inspect(*impl_->renderer).ReadFrame();
}

void SkySystem::SetEnvironment(const sky::EnvironmentSettings& environment) {
    impl_->renderer->SetEnvironment(environment);
}
unsigned SkySystem::environment_texture() const { return impl_->renderer->environment_texture(); }
unsigned SkySystem::environment_sh_buffer() const {
    return impl_->renderer->environment_sh_buffer();
}

glm::dvec3 SkyLighting::SkyIrradianceEnu(const glm::dvec3& normal_enu) const {
    return sky::ShIrradiance(sky_radiance_sh, normal_enu);
}
glm::dvec3 SkyLighting::SkyIrradianceEcef(const glm::dvec3& normal_ecef) const {
    return SkyIrradianceEnu(glm::transpose(ecef_from_enu) * normal_ecef);
}

const SkyLighting& SkySystem::lighting() const { return impl_->lighting; }

// The renderer's frame is the aircraft's ENU frame (sky_state.h).
glm::dvec3 SkySystem::SkyLuminanceEnu(const glm::dvec3& direction_enu) const {
    return impl_->renderer->SkyLuminance(impl_->frame.view.camera.position, direction_enu);
}
glm::dvec3 SkySystem::SkyLuminanceEcef(const glm::dvec3& direction_ecef) const {
    return SkyLuminanceEnu(glm::transpose(impl_->lighting.ecef_from_enu) * direction_ecef);
}

SkySystem::Fog SkySystem::FogEnu(const glm::dvec3& direction_enu, double distance_m) const {
    const Impl& d = *impl_;
    const glm::dvec3& camera = d.frame.view.camera.position;
    const glm::dvec4 air = d.renderer->AirInScattering(camera, direction_enu, distance_m);
    Fog fog;
    fog.in_scattered = glm::dvec3(air);
    fog.transmittance = air.a;
    // Rain and snow on the way (the shafts under a raining layer): they dim the air's light
    // evenly along the path, and scatter the light around them. Along a path through a
    // homogeneous medium the scattered light is L (1 - T), L what an endless path gives; with a
    // phase function symmetric about the horizontal that is the mean of the light from above
    // and from below, both as the clouds' shade has them on the ground: the sky's mean over
    // the upper hemisphere (the rain's own light in it), and the ground's albedo E / pi.
    const double rain = d.renderer->PrecipitationTransmittance(camera, direction_enu, distance_m,
                                                               d.frame.scene.clouds);
    const std::optional<sky::CloudShade> shade = d.renderer->LatestCloudShade();
    if (rain < 1.0 && shade) {
        constexpr double kPi = glm::pi<double>();
        const sky::Lights& lights = d.frame.scene.lights;
        const glm::dvec3 clear = d.ClearSkyIrradiance();
        const double sun_up = std::max(lights.sun_direction.z, 0.0);
        const glm::dvec3 sun =
            lights.sun_illuminance * shade->direct_transmittance * sun_up *
            sky::TransmittanceToLight(d.atmosphere, 0.0, sun_up, d.atmosphere.sun_angular_radius);
        const glm::dvec3 ground_light =
            sun + clear * shade->ground_sky_transmittance + kPi * shade->ground_luminance;
        const glm::dvec3 above = shade->luminance + shade->sky_transmittance * clear / kPi;
        const glm::dvec3 around = 0.5 * (above + d.atmosphere.ground_albedo * ground_light / kPi);
        const double depth = -std::log(rain);
        fog.in_scattered =
            fog.in_scattered * (depth > 1e-9 ? (1.0 - rain) / depth : 1.0) + (1.0 - rain) * around;
        fog.transmittance *= rain;
    }
    if (distance_m > 0.0 && fog.transmittance > 0.0 && fog.transmittance < 1.0) {
        fog.density_per_m = -std::log(fog.transmittance) / distance_m;
        fog.colour = fog.in_scattered / (1.0 - fog.transmittance);
    }
    return fog;
}
SkySystem::Fog SkySystem::FogEcef(const glm::dvec3& direction_ecef, double distance_m) const {
    return FogEnu(glm::transpose(impl_->lighting.ecef_from_enu) * direction_ecef, distance_m);
}
const std::vector<std::string>& SkySystem::notices() const { return impl_->notices; }
const geo::SkyEphemeris& SkySystem::ephemeris() const { return impl_->frame.ephemeris; }
unsigned SkySystem::aerial_perspective_texture() const {
    return impl_->renderer->aerial_perspective_texture();
}
unsigned SkySystem::transmittance_texture() const {
    return impl_->renderer->transmittance_texture();
}
unsigned SkySystem::cloud_shadow_texture() const { return impl_->renderer->cloud_shadow_texture(); }

}  // namespace zenith::sim
