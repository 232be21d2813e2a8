#include "zenith/sky/atmosphere_renderer.h"

#include <glad/gl.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>

#include "atmosphere_passes.h"
#include "clouds/cloud_parameters.h"
#include "clouds/cloud_passes.h"
#include "environment_passes.h"
#include "gl/atmosphere_uniforms.h"
#include "gl/fenced_readback.h"
#include "gl/state_guard.h"
#include "gl/textures.h"
#include "reference/cloud_march.h"
#include "reference/lut_texture.h"
#include "shader_parameters.h"
#include "zenith/base/error.h"
#include "zenith/sky/gl/error.h"
#include "zenith/sky/inspection.h"

namespace zenith::sky {
namespace {

constexpr double kKm = 1000.0;

// The weather's density on the CPU: its maps and the noise as the GPU samples them.
struct CpuClouds {
    std::vector<ref::RepeatTexture2D> maps;
    std::vector<double> tops;  // clouds::CloudTopFraction of each map
    ref::Texture3D shape, detail;

    CpuClouds(const std::vector<clouds::WeatherMap>& weather_maps,
              std::vector<double> top_fractions, const clouds::CloudNoise& noise)
        : tops(std::move(top_fractions)),
          shape(ref::ToTexture(noise.shape)),
          detail(ref::ToTexture(noise.detail)) {
        for (const clouds::WeatherMap& map : weather_maps) maps.push_back(ref::ToTexture(map));
    }

    // Through every layer of `weather` (the one these maps are of).
    double Transmittance(const clouds::Weather& weather, const CloudSettings& settings,
                         double bottom_radius, const glm::dvec3& position,
                         const glm::dvec3& direction, const CloudView& view, int steps) const {
        const glm::dvec3 origin = view.weather_from_world * (position / kKm);
        const glm::dvec3 toward = view.weather_from_world * glm::normalize(direction);
        const double altitude = (glm::length(position) - bottom_radius) / kKm;
        const auto march = MakeCloudMarchParameters<ref::CloudMarchParameters>(settings);
        double optical_depth = 0.0;
        for (std::size_t i = 0; i < weather.layers.size(); ++i) {
            const auto layer = MakeCloudLayerParameters<ref::CloudLayerParameters>(
                weather.layers[i], tops[i], settings, bottom_radius, view.time);
            optical_depth += ref::CloudLayerShadowDepth(layer, maps[i], shape, detail, march,
                                                        origin, altitude, toward, steps);
        }
        return std::exp(-optical_depth);
    }

    // Through the precipitation shafts of `weather` over `distance` km: `steps` midpoint
    // samples of their density (homogeneous in height, so no finer march is needed).
    double PrecipitationTransmittance(const clouds::Weather& weather, const CloudSettings& settings,
                                      double bottom_radius, const glm::dvec3& position,
                                      const glm::dvec3& direction, double distance,
                                      const CloudView& view, int steps) const {
        const glm::dvec3 origin = view.weather_from_world * (position / kKm);
        const glm::dvec3 toward = view.weather_from_world * glm::normalize(direction);
        const double step = distance / steps;
        const double extinction = settings.extinction * kKm;
        double optical_depth = 0.0;
        for (std::size_t i = 0; i < weather.layers.size(); ++i) {
            if (!weather.layers[i].precipitation_shaft) continue;
            const auto layer = MakeCloudLayerParameters<ref::CloudLayerParameters>(
                weather.layers[i], tops[i], settings, bottom_radius, view.time);
            for (int k = 0; k < steps; ++k) {
                const glm::dvec3 p = origin + toward * ((k + 0.5) * step);
                optical_depth += ref::SampleCloudDensity(layer, maps[i], shape, detail, p).density *
                                 extinction * step;
            }
        }
        return std::exp(-optical_depth);
    }

    // The rain or snow falling at `position` (m): the map's precipitation there in the
    // precipitation shaft it is in; none outside them.
    PrecipitationDraw PrecipitationAt(const clouds::Weather& weather, const CloudSettings& settings,
                                      double bottom_radius, const glm::dvec3& position,
                                      const CloudView& view) const {
        PrecipitationDraw p;
        const double altitude = glm::length(position) - bottom_radius;
        for (std::size_t i = 0; i < weather.layers.size(); ++i) {
            const clouds::CloudLayer& l = weather.layers[i];
            if (!l.precipitation_shaft || altitude < l.base_altitude || altitude > l.top_altitude) {
                continue;
            }
            const auto layer = MakeCloudLayerParameters<ref::CloudLayerParameters>(
                l, tops[i], settings, bottom_radius, view.time);
            const glm::dvec3 at = view.weather_from_world * position;
            p.intensity =
                ref::CloudWeatherAt(layer, maps[i], ref::CloudGroundCoordinates(layer, at / kKm))
                    .precipitation;
            p.snow = l.snow;
            p.world_from_box = glm::transpose(view.weather_from_world);
            p.camera = at;
            p.up = glm::normalize(at);
            p.wind = glm::dvec3(clouds::WindDisplacement(l, 1.0), 0.0);
            p.time_s = view.time;
        }
        return p;
    }
};

CloudShade ShadeOf(const gl::LightUniforms& u) {
    CloudShade shade;
    shade.base_altitude = static_cast<double>(u.cloud_base) * kKm;
    shade.direct_transmittance = u.cloud_direct;
    shade.sky_transmittance = u.cloud_sky;
    shade.luminance = glm::dvec3(u.cloud_luminance);
    shade.ground_sky_transmittance = u.cloud_ground_sky;
    shade.ground_luminance = glm::dvec3(u.cloud_ground_luminance);
    return shade;
}

}  // namespace

struct AtmosphereRenderer::Impl {
    AtmospherePasses atmosphere;
    std::unique_ptr<CloudPasses> clouds;    // with weather that has layers
    std::unique_ptr<CpuClouds> cpu_clouds;  // the same weather's density, for CPU queries
    // With clouds: the light block's cloud shade for LatestCloudShade.
    std::unique_ptr<gl::FencedReadback> shade_readback;
    clouds::Weather weather;          // as last set (also when clear)
    clouds::Weather drawn_weather;    // with its precipitation shafts (WithPrecipitationShafts)
    PrecipitationDraw precipitation;  // falling at the camera at the last Update
    CloudSettings cloud_settings;
    std::unique_ptr<EnvironmentPasses> environment;  // with SetEnvironment's size > 0
    EnvironmentSettings environment_settings;
    bool preserve_gl_state = true;  // what each entry point's gl::StateGuard does
    // The last Update's scene and view, which Render draws.
    std::optional<SkyScene> scene;
    SkyView view;

    Impl(const Atmosphere& a, const LutSettings& s) : atmosphere(a, s) {}
};

AtmosphereRenderer::AtmosphereRenderer(const Atmosphere& atmosphere, const LutSettings& settings) {
    Validate(atmosphere);
    settings.Validate();
    const gl::StateGuard guard(true);
    impl_ = std::make_unique<Impl>(atmosphere, settings);
}

AtmosphereRenderer::~AtmosphereRenderer() = default;

void AtmosphereRenderer::SetAtmosphere(const Atmosphere& atmosphere) {
    Validate(atmosphere);
    const gl::StateGuard guard(impl_->preserve_gl_state);
    impl_->atmosphere.SetAtmosphere(atmosphere);
}

const Atmosphere& AtmosphereRenderer::atmosphere() const { return impl_->atmosphere.atmosphere(); }
void AtmosphereRenderer::set_preserve_gl_state(bool preserve) {
    impl_->preserve_gl_state = preserve;
}
bool AtmosphereRenderer::preserve_gl_state() const { return impl_->preserve_gl_state; }

void AtmosphereRenderer::SetWeather(const clouds::Weather& weather, const CloudSettings& settings) {
    clouds::Validate(weather);
    settings.Validate();
    Impl& d = *impl_;
    const gl::StateGuard guard(d.preserve_gl_state);
    // Built before the old passes go, so a bad map leaves the previous weather in place.
    std::unique_ptr<CloudPasses> passes;
    std::unique_ptr<CpuClouds> cpu;
    // What is drawn: the layers and the rain or snow under the lowest raining one.
    static_assert(clouds::kMaxDrawnLayers == static_cast<std::size_t>(kCloudMaxLayers));
    clouds::Weather drawn = clouds::WithPrecipitationShafts(weather);
    if (!drawn.layers.empty()) {
        std::vector<clouds::WeatherMap> maps;
        std::vector<double> tops;
        for (const clouds::CloudLayer& layer : drawn.layers) {
            maps.push_back(clouds::BuildWeatherMap(layer));
            tops.push_back(clouds::LayerTopFraction(layer, maps.back()));
        }
        const clouds::CloudNoiseLoad noise =
            clouds::LoadOrGenerateCloudNoise(settings.noise, settings.noise_cache_directory);
        passes = std::make_unique<CloudPasses>(drawn, settings, maps, tops, noise.noise);
        cpu = std::make_unique<CpuClouds>(maps, std::move(tops), noise.noise);
        d.atmosphere.BuildCloudComposites();
    }
    d.clouds = std::move(passes);
    d.cpu_clouds = std::move(cpu);
    d.shade_readback =
        d.clouds ? std::make_unique<gl::FencedReadback>(sizeof(gl::LightUniforms)) : nullptr;
    d.weather = weather;
    d.drawn_weather = std::move(drawn);
    d.cloud_settings = settings;
}

void AtmosphereRenderer::SetEnvironment(const EnvironmentSettings& settings) {
    settings.Validate();
    Impl& d = *impl_;
    const gl::StateGuard guard(d.preserve_gl_state);
    if (!settings.enabled()) {
        d.environment.reset();
    } else if (!d.environment || d.environment->settings().size != settings.size) {
        d.environment.reset();  // its GL objects go before the new ones are made
        d.environment = std::make_unique<EnvironmentPasses>(settings);
    } else {
        d.environment->set_faces_per_frame(settings.faces_per_frame);
    }
    d.environment_settings = settings;
}
const EnvironmentSettings& AtmosphereRenderer::environment_settings() const {
    return impl_->environment_settings;
}

const clouds::Weather& AtmosphereRenderer::weather() const { return impl_->weather; }
const CloudSettings& AtmosphereRenderer::cloud_settings() const { return impl_->cloud_settings; }
const LutSettings& AtmosphereRenderer::settings() const { return impl_->atmosphere.settings(); }

void AtmosphereRenderer::Update(const SkyScene& scene, const SkyView& view) {
    Impl& d = *impl_;
    const gl::StateGuard guard(d.preserve_gl_state);
    d.atmosphere.SetFrame(scene, view, d.environment ? d.environment->settings().size : 0);
    if (d.clouds) {
        // What the clouds do to the light beneath them goes into the light block first.
        d.atmosphere.BindInputs();
        d.clouds->Prepare(d.atmosphere.atmosphere(), view.camera, scene.lights, scene.clouds,
                          d.atmosphere.light_buffer());
        d.shade_readback->Copy(d.atmosphere.light_buffer());
    }
    d.atmosphere.UpdateFrameLuts();
    if (d.environment) {
        if (scene.clouds.reset_history) d.environment->Restart();
        const bool inside =
            glm::length(view.camera.position) < d.atmosphere.atmosphere().top_radius;
        d.environment->Update(d.atmosphere, d.clouds.get(), !inside || view.force_ray_march);
    }
    d.scene = scene;
    d.view = view;
    d.precipitation = d.cpu_clouds && d.cloud_settings.precipitation_streaks
                          ? d.cpu_clouds->PrecipitationAt(d.drawn_weather, d.cloud_settings,
                                                          d.atmosphere.atmosphere().bottom_radius,
                                                          view.camera.position, scene.clouds)
                          : PrecipitationDraw{};
}

void AtmosphereRenderer::Render(const RenderTarget& target) {
    Impl& d = *impl_;
    const glm::ivec2 size = target.size();
    if (!(size.x > 0 && size.y > 0 && size.x <= 16384 && size.y <= 16384)) {
        throw ArgumentError("viewport", "viewport size " + std::to_string(size.x) + "x" +
                                            std::to_string(size.y) +
                                            " is out of range (expected 1..16384 per axis)");
    }
    if (!d.scene) throw std::logic_error("AtmosphereRenderer::Render before any Update");
    const SkyView& view = d.view;
    const std::optional<SceneDepth>& depth = target.scene_depth;
    if (depth && !(target.framebuffer && depth->texture != 0 && depth->near_m > 0.0 &&
                   depth->far_m > depth->near_m)) {
        throw ArgumentError("scene_depth",
                            "RenderTarget::scene_depth needs a host framebuffer, a depth "
                            "texture and 0 < near_m < far_m");
    }
    const gl::StateGuard guard(d.preserve_gl_state);
    // The light block is Update's (with the clouds' shading in it).
    d.atmosphere.SetTarget(*d.scene, view, target);
    if (d.clouds) {
        d.atmosphere.BindInputs();
        d.clouds->Render(d.atmosphere.atmosphere(), view.camera, d.scene->lights, size,
                         d.scene->clouds);
    }
    d.atmosphere.Composite(*d.scene, view, target, d.clouds.get());
    d.atmosphere.DrawPrecipitation(d.precipitation, target);
    d.scene->clouds.reset_history = false;  // a cut applies to the first Render only
}

std::optional<CloudShade> AtmosphereRenderer::LatestCloudShade() const {
    if (!impl_->shade_readback) return CloudShade{};
    const unsigned char* bytes = impl_->shade_readback->Latest();
    if (bytes == nullptr) return std::nullopt;
    gl::LightUniforms u{};
    std::memcpy(&u, bytes, sizeof(u));
    return ShadeOf(u);
}

glm::dvec3 AtmosphereRenderer::NightGroundIrradiance() const {
    return impl_->atmosphere.night_ground_irradiance();
}

std::optional<SphericalHarmonics9> AtmosphereRenderer::LatestEnvironmentSh() const {
    if (!impl_->environment) return std::nullopt;
    return impl_->environment->LatestSh();
}
long long AtmosphereRenderer::environment_rounds() const {
    return impl_->environment ? impl_->environment->rounds() : 0;
}
unsigned AtmosphereRenderer::environment_texture() const {
    return impl_->environment ? impl_->environment->cube() : 0;
}
unsigned AtmosphereRenderer::environment_sh_buffer() const {
    return impl_->environment ? impl_->environment->sh_buffer() : 0;
}

unsigned AtmosphereRenderer::transmittance_texture() const {
    return impl_->atmosphere.transmittance();
}
unsigned AtmosphereRenderer::aerial_perspective_texture() const {
    return impl_->atmosphere.aerial_perspective();
}
unsigned AtmosphereRenderer::frame_texture() const { return impl_->atmosphere.frame(); }
unsigned AtmosphereRenderer::cloud_shadow_texture() const {
    return impl_->clouds ? impl_->clouds->shadow_map_texture() : 0;
}

namespace {

// The lights of `scene` for a ray from `position` (m), with `shade`'s cloud members.
ref::LightSet ShadedLights(const SkyScene& scene, const glm::dvec3& position,
                           const CloudShade& shade) {
    auto l = MakeLightSet<ref::LightSet>(scene.lights, position);
    l.cloud_base = shade.base_altitude / kKm;
    l.cloud_direct = shade.direct_transmittance;
    l.cloud_sky = shade.sky_transmittance;
    l.cloud_luminance = shade.luminance;
    l.cloud_ground_sky = shade.ground_sky_transmittance;
    l.cloud_ground_luminance = shade.ground_luminance;
    return l;
}

}  // namespace

glm::dvec4 AtmosphereRenderer::MarchAir(const glm::dvec3& position, const glm::dvec3& direction,
                                        double distance, int steps, bool ground) const {
    const Impl& d = *impl_;
    if (!d.scene) throw std::logic_error("AtmosphereRenderer: an air query before any Update");
    if (!(steps >= 1 && steps <= 4096)) {
        throw ArgumentError(
            "steps", "steps " + std::to_string(steps) + " is out of range (expected 1..4096)");
    }
    const AtmospherePasses& a = d.atmosphere;
    const auto params = MakeShaderParameters<ref::AtmosphereParameters>(a.atmosphere());
    const ref::LightSet lights =
        ShadedLights(*d.scene, position, LatestCloudShade().value_or(CloudShade{}));
    const double altitude_km = glm::length(position) / kKm - params.bottom_radius;
    const ref::ScatteringResult r = ref::IntegrateScatteredLuminance(
        params, a.transmittance_cpu(), a.multiple_scattering_cpu(), a.irradiance_cpu(), lights,
        position / kKm, altitude_km, glm::normalize(direction), 0.0, distance / kKm, steps, ground);
    return {r.luminance, (r.transmittance.x + r.transmittance.y + r.transmittance.z) / 3.0};
}

glm::dvec3 AtmosphereRenderer::SkyLuminance(const glm::dvec3& position, const glm::dvec3& direction,
                                            int steps) const {
    return glm::dvec3(MarchAir(position, direction, 1e12, steps, true));
}

glm::dvec4 AtmosphereRenderer::AirInScattering(const glm::dvec3& position,
                                               const glm::dvec3& direction, double distance,
                                               int steps) const {
    if (!(distance >= 0.0 && std::isfinite(distance))) {
        throw ArgumentError("distance", "distance " + std::to_string(distance) +
                                            " m is out of range (expected finite, >= 0)");
    }
    return MarchAir(position, direction, distance, steps, false);
}

double AtmosphereRenderer::CloudTransmittance(const glm::dvec3& position,
                                              const glm::dvec3& direction, const CloudView& view,
                                              int steps) const {
    if (!(steps >= 1 && steps <= 4096)) {
        throw ArgumentError("CloudTransmittance: steps " + std::to_string(steps) +
                            " is out of range (expected 1..4096)");
    }
    if (!impl_->cpu_clouds) return 1.0;
    const Impl& d = *impl_;
    return d.cpu_clouds->Transmittance(d.drawn_weather, d.cloud_settings,
                                       d.atmosphere.atmosphere().bottom_radius, position, direction,
                                       view, steps);
}

double AtmosphereRenderer::PrecipitationTransmittance(const glm::dvec3& position,
                                                      const glm::dvec3& direction, double distance,
                                                      const CloudView& view, int steps) const {
    if (!(distance >= 0.0 && std::isfinite(distance))) {
        throw ArgumentError("distance", "distance " + std::to_string(distance) +
                                            " m is out of range (expected finite, >= 0)");
    }
    if (!(steps >= 1 && steps <= 4096)) {
        throw ArgumentError("PrecipitationTransmittance: steps " + std::to_string(steps) +
                            " is out of range (expected 1..4096)");
    }
    if (!impl_->cpu_clouds) return 1.0;
    const Impl& d = *impl_;
    return d.cpu_clouds->PrecipitationTransmittance(
        d.drawn_weather, d.cloud_settings, d.atmosphere.atmosphere().bottom_radius, position,
        direction, distance / kKm, view, steps);
}

// --- RendererInspection (zenith/sky/inspection.h) ----------------------------------------------

// A texture of the renderer read back under its GL state guard.
LutImage RendererInspection::Read(unsigned texture, const glm::ivec3& size) const {
    const gl::StateGuard guard(renderer_.preserve_gl_state());
    return gl::ReadTexture(texture, size);
}

LutImage RendererInspection::ReadTransmittance() const {
    const AtmospherePasses& a = renderer_.impl_->atmosphere;
    return Read(a.transmittance(), glm::ivec3(a.settings().transmittance_size, 1));
}
LutImage RendererInspection::ReadMultipleScattering() const {
    const AtmospherePasses& a = renderer_.impl_->atmosphere;
    return Read(a.multiple_scattering(),
                glm::ivec3(a.settings().multiple_scattering_texture_size(), 1));
}
LutImage RendererInspection::ReadGroundIrradiance() const {
    const AtmospherePasses& a = renderer_.impl_->atmosphere;
    return Read(a.irradiance(), glm::ivec3(a.settings().irradiance_size, 1));
}
LutImage RendererInspection::ReadSkyView() const {
    const AtmospherePasses& a = renderer_.impl_->atmosphere;
    return Read(a.sky_view(), glm::ivec3(a.settings().sky_view_size, 1));
}
LutImage RendererInspection::ReadAerialPerspective() const {
    const AtmospherePasses& a = renderer_.impl_->atmosphere;
    return Read(a.aerial_perspective(), a.settings().aerial_perspective_size);
}
LutImage RendererInspection::ReadFrame() const {
    const AtmospherePasses& a = renderer_.impl_->atmosphere;
    if (a.frame() == 0) throw gl::GlError("ReadFrame before any Render");
    return Read(a.frame(), glm::ivec3(a.frame_size(), 1));
}
LutImage RendererInspection::ReadEnvironmentAtlas() const {
    const EnvironmentPasses* environment = renderer_.impl_->environment.get();
    if (environment == nullptr) {
        throw std::logic_error("ReadEnvironmentAtlas: the renderer has no environment");
    }
    const int n = environment->settings().size;
    return Read(environment->atlas(), glm::ivec3(n, 6 * n, 1));
}
LutImage RendererInspection::ReadEnvironmentCube(int level) const {
    const EnvironmentPasses* environment = renderer_.impl_->environment.get();
    if (environment == nullptr) {
        throw std::logic_error("ReadEnvironmentCube: the renderer has no environment");
    }
    const int n = std::max(environment->settings().size >> level, 1);
    LutImage image(n, 6 * n);
    const gl::StateGuard guard(renderer_.preserve_gl_state());
    glGetTextureImage(environment->cube(), level, GL_RGBA, GL_FLOAT,
                      static_cast<GLsizei>(image.bytes()), image.texels.data());
    return image;
}

LutImage RendererInspection::ReadClouds() const {
    const CloudPasses* clouds = renderer_.impl_->clouds.get();
    if (clouds == nullptr) throw std::logic_error("ReadClouds: the renderer has no weather");
    const gl::StateGuard guard(renderer_.preserve_gl_state());
    return clouds->ReadClouds();
}
LutImage RendererInspection::ReadCloudShadowMap() const {
    const CloudPasses* clouds = renderer_.impl_->clouds.get();
    if (clouds == nullptr) {
        throw std::logic_error("ReadCloudShadowMap: the renderer has no weather");
    }
    const gl::StateGuard guard(renderer_.preserve_gl_state());
    return clouds->ReadShadowMap();
}
LutImage RendererInspection::ReadCloudSunDepth() const {
    const CloudPasses* clouds = renderer_.impl_->clouds.get();
    if (clouds == nullptr) {
        throw std::logic_error("ReadCloudSunDepth: the renderer has no weather");
    }
    const gl::StateGuard guard(renderer_.preserve_gl_state());
    return clouds->ReadSunDepth();
}
CloudShade RendererInspection::ReadCloudShade() const {
    gl::LightUniforms u{};
    glGetNamedBufferSubData(renderer_.impl_->atmosphere.light_buffer(), 0, sizeof(u), &u);
    return ShadeOf(u);
}

std::size_t RendererInspection::LutMemoryBytes() const {
    const LutSettings& s = renderer_.settings();
    const auto texels = [](glm::ivec2 v) { return static_cast<std::size_t>(v.x * v.y); };
    const std::size_t ap = static_cast<std::size_t>(s.aerial_perspective_size.x) *
                           static_cast<std::size_t>(s.aerial_perspective_size.y) *
                           static_cast<std::size_t>(s.aerial_perspective_size.z);
    return 16 * (texels(s.transmittance_size) + texels(s.multiple_scattering_texture_size()) +
                 texels(s.irradiance_size) + texels(s.sky_view_size) + ap);
}

PassTimes RendererInspection::LastPassTimes() const {
    const AtmosphereRenderer::Impl& d = *renderer_.impl_;
    const gl::StateGuard guard(d.preserve_gl_state);  // a host's query buffer
    const AtmospherePasses& a = d.atmosphere;
    using P = AtmospherePasses;
    // The composite: whichever sky program ran, plus its disk draws.
    PassTimes times{a.QueryMilliseconds(P::kTransmittancePass),
                    a.QueryMilliseconds(P::kMultipleScatteringPass),
                    a.QueryMilliseconds(P::kIrradiancePass),
                    a.QueryMilliseconds(P::kSkyViewPass),
                    a.QueryMilliseconds(P::kAerialPerspectivePass),
                    0.0};
    for (std::size_t q = P::kRenderPass; q < P::kQueryCount; ++q) {
        times.render += a.QueryMilliseconds(q);
    }
    if (d.clouds) {
        const auto clouds = d.clouds->LastPassTimes();
        times.cloud_shadow_map = clouds[0];
        times.cloud_shade = clouds[1];
        times.cloud_trace = clouds[2];
        times.cloud_reconstruct = clouds[3];
        times.cloud_ground_shadow = clouds[4];
        times.cloud_light_shafts = clouds[5];
        times.cloud_geometry = clouds[6];
    }
    if (d.environment) times.environment = d.environment->LastMilliseconds();
    return times;
}

}  // namespace zenith::sky
