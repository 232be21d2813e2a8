#include "zenith/sky/atmosphere_renderer.h"

#include <glad/gl.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

#include "bindings.h"
#include "clouds/cloud_parameters.h"
#include "clouds/cloud_passes.h"
#include "gl/atmosphere_uniforms.h"
#include "gl/display_uniforms.h"
#include "gl/draw.h"
#include "gl/shader_library.h"
#include "gl/state_guard.h"
#include "gl/textures.h"
#include "reference/atmosphere_functions.h"
#include "reference/cloud_march.h"
#include "reference/lut_texture.h"
#include "renderer_programs.h"
#include "shader_parameters.h"
#include "zenith/base/error.h"
#include "zenith/sky/gl/error.h"
#include "zenith/sky/gl/shader.h"

namespace zenith::sky {
namespace {

constexpr double kKm = 1000.0;

enum Pass : std::size_t {
    kTransmittancePass,
    kMultipleScatteringPass,
    kIrradiancePass,
    kSkyViewPass,
    kAerialPerspectivePass,
    kRenderPass,          // the composite with the Sky-View LUT
    kRenderRayMarchPass,  // the composite ray marching every pixel (space views)
    kRenderDepthPass,     // the same two over the host's depth buffer (aerial perspective)
    kRenderRayMarchDepthPass,
    kDiskPass,       // the Sun and the Moon, added over their disks only
    kDiskDepthPass,  // the same, behind the host's geometry
    kPassCount
};

// Timer queries: one per pass, and a second for the disk pass, which may draw twice a frame.
constexpr std::size_t kSecondDiskQuery = kPassCount;
constexpr std::size_t kQueryCount = kPassCount + 1;

constexpr std::array<std::string_view, kPassCount> kPassFiles = {
    "atmosphere/transmittance.comp",
    "atmosphere/multiple_scattering.comp",
    "atmosphere/irradiance.comp",
    "atmosphere/sky_view.comp",
    "atmosphere/aerial_perspective.comp",
    "atmosphere/render.frag",
    "atmosphere/render.frag",
    "atmosphere/render.frag",
    "atmosphere/render.frag",
    "atmosphere/render.frag",
    "atmosphere/render.frag",
};

GLuint Groups(int n, int local) { return static_cast<GLuint>((n + local - 1) / local); }

// The composite `pass` (kRenderPass...), with or without the clouds laid over it.
gl::Program Composite(Pass pass, bool clouds) {
    const auto define = [](std::string_view name, bool value) {
        return "#define " + std::string(name) + (value ? " 1\n" : " 0\n");
    };
    const std::string defines =
        define("ZENITH_RAY_MARCH",
               pass == kRenderRayMarchPass || pass == kRenderRayMarchDepthPass) +
        define("ZENITH_SCENE_DEPTH", pass == kRenderDepthPass || pass == kRenderRayMarchDepthPass ||
                                         pass == kDiskDepthPass) +
        define("ZENITH_DISKS", pass == kDiskPass || pass == kDiskDepthPass) +
        define("ZENITH_CLOUDS", clouds);
    return gl::FullscreenProgram(kPassFiles[pass], defines,
                                 clouds ? CloudShaderParts() : std::span<const std::string_view>{});
}

std::array<gl::Program, kPassCount> BuildPrograms() {
    return {gl::ComputeProgram(kPassFiles[0]), gl::ComputeProgram(kPassFiles[1]),
            gl::ComputeProgram(kPassFiles[2]), gl::ComputeProgram(kPassFiles[3]),
            gl::ComputeProgram(kPassFiles[4]),
            // Six programs from one source: llvmpipe runs both sides of a branch under a mask,
            // so a per-frame choice made in the shader cost every pixel the 32-step ray march
            // (or the disks); chosen here it costs nothing.
            Composite(kRenderPass, false), Composite(kRenderRayMarchPass, false),
            Composite(kRenderDepthPass, false), Composite(kRenderRayMarchDepthPass, false),
            Composite(kDiskPass, false), Composite(kDiskDepthPass, false)};
}

// The six composites again, laying the clouds over the sky and the disks.
std::vector<gl::Program> BuildCloudComposites() {
    std::vector<gl::Program> programs;
    for (std::size_t pass = kRenderPass; pass < kPassCount; ++pass) {
        programs.push_back(Composite(static_cast<Pass>(pass), true));
    }
    return programs;
}

// The binding point of each of AtmosphereRenderer's uniform buffers, in the order of `buffers`.
constexpr std::array<GLuint, 4> kBufferBindings = {kAtmosphereBlockBinding, kLightBlockBinding,
                                                   kSettingsBlockBinding, kFrameBlockBinding};

// Adds each point source to the pixel its direction falls in, as luminance T E / (pixel solid
// angle), so the image integrates to the source's illuminance seen through the atmosphere
// (transmittance T to space, 0 below the horizon) whatever the resolution.
void SplatPoints(const std::vector<StarPoint>& points, const Camera& camera, glm::ivec2 size,
                 const ref::AtmosphereParameters& atmosphere,
                 const ref::TransmittanceTexture& transmittance, std::vector<glm::vec4>& image) {
    const glm::dvec3 camera_km = camera.position / kKm;
    const double altitude_km = glm::length(camera_km) - atmosphere.bottom_radius;
    const glm::ivec2 transmittance_size(transmittance.width(), transmittance.height());
    const glm::dmat3 view_from_world = glm::transpose(camera.world_from_view);
    const double tan_y = std::tan(0.5 * camera.vertical_fov);
    const double tan_x = tan_y * camera.aspect;
    // Tangent-plane size of one pixel; a pixel at tangent-plane (x, y) subtends
    // dx dy / (1 + x^2 + y^2)^(3/2) steradians.
    const double dx = 2.0 * tan_x / size.x, dy = 2.0 * tan_y / size.y;
    for (const StarPoint& point : points) {
        const glm::dvec3 v = view_from_world * point.direction;
        if (!(v.z < 0.0)) continue;  // behind the camera
        const double x = v.x / -v.z, y = v.y / -v.z;
        const double px = (x / tan_x + 1.0) * 0.5 * size.x, py = (y / tan_y + 1.0) * 0.5 * size.y;
        if (!(px >= 0.0 && py >= 0.0 && px < size.x && py < size.y)) continue;
        const glm::dvec3 t = ref::TransmittanceToSpace(
            atmosphere, transmittance, transmittance_size, camera_km, altitude_km, point.direction);
        if (t == glm::dvec3(0.0)) continue;
        const int ix = static_cast<int>(px), iy = static_cast<int>(py);
        // The solid angle of the whole pixel (taken at its centre), the measure a reader of the
        // image integrates with, so luminance x solid angle returns exactly E.
        const double cx = ((ix + 0.5) / size.x * 2.0 - 1.0) * tan_x;
        const double cy = ((iy + 0.5) / size.y * 2.0 - 1.0) * tan_y;
        const double solid_angle = dx * dy / std::pow(1.0 + cx * cx + cy * cy, 1.5);
        glm::vec4& texel = image[static_cast<std::size_t>(iy) * static_cast<std::size_t>(size.x) +
                                 static_cast<std::size_t>(ix)];
        texel += glm::vec4(glm::vec3(t * point.illuminance / solid_angle), 0.0f);
    }
}

// The pixel box (x, y, width, height) that holds a disk of angular radius `radius` around
// `direction`, with a pixel to spare; nullopt when none of it is in view. In the tangent plane a
// disk at angle theta off the axis reaches at most tan(theta + radius) - tan(theta) from its
// centre (the radial stretch exceeds the tangential one).
std::optional<glm::ivec4> DiskBox(const glm::dvec3& direction, double radius, const Camera& camera,
                                  glm::ivec2 size) {
    const glm::dvec3 v = glm::transpose(camera.world_from_view) * glm::normalize(direction);
    const double theta = std::acos(std::clamp(-v.z, -1.0, 1.0));
    if (theta - radius >= 0.5 * ref::kPi) return std::nullopt;  // behind the camera
    const glm::ivec4 whole(0, 0, size.x, size.y);
    if (theta + radius >= 1.5) return whole;  // near the image plane: the box is unbounded
    const double tan_y = std::tan(0.5 * camera.vertical_fov);
    const double tan_x = tan_y * camera.aspect;
    const double x = v.x / -v.z, y = v.y / -v.z;
    const double reach = std::tan(theta + radius) - std::tan(theta);
    const double px = (x / tan_x + 1.0) * 0.5 * size.x, py = (y / tan_y + 1.0) * 0.5 * size.y;
    const double rx = reach / tan_x * 0.5 * size.x + 1.0, ry = reach / tan_y * 0.5 * size.y + 1.0;
    const int x0 = static_cast<int>(std::max(0.0, std::floor(px - rx)));
    const int y0 = static_cast<int>(std::max(0.0, std::floor(py - ry)));
    const int x1 = static_cast<int>(std::min<double>(size.x, std::ceil(px + rx)));
    const int y1 = static_cast<int>(std::min<double>(size.y, std::ceil(py + ry)));
    if (x1 <= x0 || y1 <= y0) return std::nullopt;
    return glm::ivec4(x0, y0, x1 - x0, y1 - y0);
}

bool Overlap(const glm::ivec4& a, const glm::ivec4& b) {
    return a.x < b.x + b.z && b.x < a.x + a.z && a.y < b.y + b.w && b.y < a.y + a.w;
}

glm::ivec4 Union(const glm::ivec4& a, const glm::ivec4& b) {
    const glm::ivec2 lo = glm::min(glm::ivec2(a), glm::ivec2(b));
    const glm::ivec2 hi =
        glm::max(glm::ivec2(a) + glm::ivec2(a.z, a.w), glm::ivec2(b) + glm::ivec2(b.z, b.w));
    return {lo, hi - lo};
}

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
};

}  // namespace

std::vector<gl::Program> BuildRendererPrograms() {
    std::vector<gl::Program> programs;
    for (gl::Program& p : BuildPrograms()) programs.push_back(std::move(p));
    for (gl::Program& p : BuildCloudComposites()) programs.push_back(std::move(p));
    for (gl::Program& p : CloudPasses::BuildPrograms()) programs.push_back(std::move(p));
    for (gl::Program& p : gl::BuildDisplayPrograms()) programs.push_back(std::move(p));
    return programs;
}

struct AtmosphereRenderer::Impl {
    Atmosphere atmosphere;
    LutSettings settings;
    std::array<gl::Program, kPassCount> programs;
    std::array<GLuint, 4> buffers{};  // atmosphere, lights, settings, frame
    GLuint transmittance = 0, multiple_scattering = 0, irradiance = 0, sky_view = 0,
           aerial_perspective = 0, frame = 0, stars = 0;
    GLuint framebuffer = 0, vertex_array = 0;  // the composite draws a triangle into `frame`
    std::vector<glm::vec4> star_pixels;
    ref::TransmittanceTexture transmittance_cpu;  // for the stars' extinction
    glm::ivec2 frame_size{0, 0};
    std::array<GLuint, kQueryCount> queries{};
    std::array<bool, kQueryCount> query_used{};
    int light_count = 1;  // as last uploaded: with the Sun alone, the Sky-View LUT is symmetric
    std::unique_ptr<CloudPasses> clouds;    // with weather that has layers
    std::unique_ptr<CpuClouds> cpu_clouds;  // the same weather's density, for CPU queries
    // The six composite programs again, laying the clouds over the sky and the disks; built
    // with the first weather that has layers.
    std::vector<gl::Program> cloud_composites;
    clouds::Weather weather;  // as last set (also when clear)
    CloudSettings cloud_settings;
    bool preserve_gl_state = true;  // what each entry point's gl::StateGuard does

    Impl(const Atmosphere& a, const LutSettings& s)
        : atmosphere(a), settings(s), programs(BuildPrograms()) {
        glCreateBuffers(static_cast<GLsizei>(buffers.size()), buffers.data());
        glNamedBufferStorage(buffers[0], sizeof(gl::AtmosphereUniforms), nullptr,
                             GL_DYNAMIC_STORAGE_BIT);
        glNamedBufferStorage(buffers[1], sizeof(gl::LightUniforms), nullptr,
                             GL_DYNAMIC_STORAGE_BIT);
        glNamedBufferStorage(buffers[2], sizeof(gl::SettingsUniforms), nullptr,
                             GL_DYNAMIC_STORAGE_BIT);
        glNamedBufferStorage(buffers[3], sizeof(gl::FrameUniforms), nullptr,
                             GL_DYNAMIC_STORAGE_BIT);
        for (std::size_t i = 0; i < buffers.size(); ++i) {
            glBindBufferBase(GL_UNIFORM_BUFFER, kBufferBindings[i], buffers[i]);
        }
        transmittance = gl::CreateTexture2D(s.transmittance_size);
        multiple_scattering = gl::CreateTexture2D(s.multiple_scattering_size);
        irradiance = gl::CreateTexture2D(s.irradiance_size);
        sky_view = gl::CreateTexture2D(s.sky_view_size, GL_RGBA32F, GL_REPEAT);  // azimuth wraps
        aerial_perspective = gl::CreateTexture3D(s.aerial_perspective_size);
        glCreateQueries(GL_TIME_ELAPSED, static_cast<GLsizei>(queries.size()), queries.data());
        glCreateFramebuffers(1, &framebuffer);
        glCreateVertexArrays(1, &vertex_array);  // core profile draws need one, even empty

        gl::SettingsUniforms u{};
        u.transmittance_size = s.transmittance_size;
        u.multiple_scattering_size = s.multiple_scattering_size;
        u.irradiance_size = s.irradiance_size;
        u.sky_view_size = s.sky_view_size;
        u.aerial_perspective_size = glm::ivec4(s.aerial_perspective_size, 0);
        u.transmittance_steps = s.transmittance_steps;
        u.multiple_scattering_directions_sqrt = s.multiple_scattering_directions_sqrt;
        u.multiple_scattering_steps = s.multiple_scattering_steps;
        u.irradiance_directions_sqrt = s.irradiance_directions_sqrt;
        u.irradiance_steps = s.irradiance_steps;
        u.sky_view_steps = s.sky_view_steps;
        u.aerial_perspective_steps = s.aerial_perspective_steps;
        u.aerial_perspective_range_km = static_cast<float>(s.aerial_perspective_range / kKm);
        glNamedBufferSubData(buffers[2], 0, sizeof(u), &u);
    }

    ~Impl() {
        clouds.reset();
        glDeleteVertexArrays(1, &vertex_array);
        glDeleteFramebuffers(1, &framebuffer);
        glDeleteQueries(static_cast<GLsizei>(queries.size()), queries.data());
        const std::array<GLuint, 7> textures = {transmittance, multiple_scattering, irradiance,
                                                sky_view,      aerial_perspective,  frame,
                                                stars};
        for (GLuint t : textures) {
            if (t != 0) glDeleteTextures(1, &t);
        }
        glDeleteBuffers(static_cast<GLsizei>(buffers.size()), buffers.data());
    }

    void BindInputs() const {
        for (std::size_t i = 0; i < buffers.size(); ++i) {
            glBindBufferBase(GL_UNIFORM_BUFFER, kBufferBindings[i], buffers[i]);
        }
        glBindTextureUnit(kTransmittanceUnit, transmittance);
        glBindTextureUnit(kMultipleScatteringUnit, multiple_scattering);
        glBindTextureUnit(kIrradianceUnit, irradiance);
        glBindTextureUnit(kSkyViewUnit, sky_view);
        glBindTextureUnit(kStarUnit, stars != 0 ? stars : transmittance);  // unused when no stars
        glBindTextureUnit(kAerialPerspectiveUnit, aerial_perspective);
    }

    // Runs one compute pass writing `output` (bound as kOutputImageUnit), timed by a query.
    void Dispatch(Pass pass, GLuint output, bool layered, GLuint gx, GLuint gy, GLuint gz) {
        BindInputs();
        programs[pass].Use();
        glBindImageTexture(kOutputImageUnit, output, 0, layered ? GL_TRUE : GL_FALSE, 0,
                           GL_WRITE_ONLY, GL_RGBA32F);
        glBeginQuery(GL_TIME_ELAPSED, queries[pass]);
        glDispatchCompute(gx, gy, gz);
        glEndQuery(GL_TIME_ELAPSED);
        query_used[pass] = true;
        // Later passes sample what this one wrote; reads back use glGetTextureImage.
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT |
                        GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    }

    // The composite: a full-screen triangle into `target` (our frame's FBO or the host's), timed
    // by query `query`. The sky pass replaces the sky (blending premultiplied over the host's
    // geometry when there is scene depth); a disk pass adds the Sun and the Moon inside
    // `scissor` (viewport pixels).
    // With weather, the clouds (CloudPasses::Render, this frame) go over what it draws.
    void Draw(Pass pass, std::size_t query, GLuint target, glm::ivec4 viewport,
              GLuint scene_depth = 0, std::optional<glm::ivec4> scissor = std::nullopt) {
        BindInputs();
        if (clouds) clouds->BindForComposite();
        if (scene_depth != 0) glBindTextureUnit(kSceneDepthUnit, scene_depth);
        // Over the host's geometry the sky pass is premultiplied: (L, T) over geometry and
        // (sky, 0) elsewhere.
        const gl::Blend blend = pass == kDiskPass || pass == kDiskDepthPass ? gl::Blend::kAdd
                                : scene_depth != 0 ? gl::Blend::kPremultiplied
                                                   : gl::Blend::kReplace;
        const gl::Program& program = clouds ? cloud_composites[pass - kRenderPass] : programs[pass];
        gl::DrawFullscreen(program, vertex_array, target, viewport, blend, queries[query], scissor);
        query_used[query] = true;
    }

    void UploadAtmosphere() {
        const auto u = MakeShaderParameters<gl::AtmosphereUniforms>(atmosphere);
        glNamedBufferSubData(buffers[0], 0, sizeof(u), &u);
    }

    void UploadLights(const Lights& lights, const Camera& camera) {
        const auto u = MakeLightSet<gl::LightUniforms>(lights, camera.position);
        glNamedBufferSubData(buffers[1], 0, sizeof(u), &u);
        light_count = u.count;
    }

    void UploadFrame(const Camera& camera, const Lights& lights, const RenderOptions& options,
                     bool sun_disk_resolved = true, bool stars_enabled = false) {
        gl::FrameUniforms u{};
        u.camera_km = glm::vec3(camera.position / kKm);
        u.tan_half_fov = static_cast<float>(std::tan(0.5 * camera.vertical_fov));
        for (int i = 0; i < 3; ++i)
            u.world_from_view[i] = glm::vec4(camera.world_from_view[i], 0.0);
        u.output_size = options.size;
        u.aspect = static_cast<float>(camera.aspect);
        u.ray_march_steps = options.ray_march_steps;
        u.draw_sun_disk = options.draw_sun_disk && sun_disk_resolved ? 1 : 0;
        u.moon_enabled = options.moon.enabled ? 1 : 0;
        u.moon_direction = glm::vec3(glm::normalize(options.moon.direction));
        u.moon_angular_radius = static_cast<float>(options.moon.angular_radius);
        u.moon_albedo = static_cast<float>(options.moon.albedo);
        u.moon_sunlight = glm::vec3(options.moon.sunlight);
        u.stars_enabled = stars_enabled ? 1 : 0;
        if (options.target_framebuffer) {
            u.viewport_x = options.target_viewport.x;
            u.viewport_y = options.target_viewport.y;
        }
        if (options.scene_depth) {
            // Eye depth n / (offset + slope d); n / f -> 0 for an infinite far plane.
            const SceneDepth& s = *options.scene_depth;
            const double near_over_far = std::isinf(s.far_m) ? 0.0 : s.near_m / s.far_m;
            u.scene_near_m = static_cast<float>(s.near_m);
            u.scene_depth_offset = static_cast<float>(s.reversed ? near_over_far : 1.0);
            u.scene_depth_slope =
                static_cast<float>(s.reversed ? 1.0 - near_over_far : near_over_far - 1.0);
            u.scene_depth_reversed = s.reversed ? 1 : 0;
        }
        // Per-frame constants, from the shared functions compiled as C++ (double).
        const auto a = MakeShaderParameters<ref::AtmosphereParameters>(atmosphere);
        const glm::dvec3 up = glm::normalize(camera.position);
        u.sky_view_up = glm::vec3(up);
        u.sky_view_x = glm::vec3(ref::SkyViewFrameX(up, glm::normalize(lights.sun_direction)));
        u.horizon_zenith = static_cast<float>(ref::HorizonZenithAngle(
            a, (glm::length(camera.position) - atmosphere.bottom_radius) / kKm));
        u.cos_sun_radius = static_cast<float>(std::cos(atmosphere.sun_angular_radius));
        u.cos_moon_radius = static_cast<float>(std::cos(options.moon.angular_radius));
        u.camera_altitude_km =
            static_cast<float>((glm::length(camera.position) - atmosphere.bottom_radius) / kKm);
        glNamedBufferSubData(buffers[3], 0, sizeof(u), &u);
    }

    void BuildStaticLuts() {
        UploadAtmosphere();
        const LutSettings& s = settings;
        Dispatch(kTransmittancePass, transmittance, false,
                 Groups(s.transmittance_size.x, kLutGroupSize),
                 Groups(s.transmittance_size.y, kLutGroupSize), 1);
        Dispatch(kMultipleScatteringPass, multiple_scattering, false,
                 Groups(s.multiple_scattering_size.x, kLutGroupSize),
                 Groups(s.multiple_scattering_size.y, kLutGroupSize), 1);
        Dispatch(kIrradiancePass, irradiance, false,
                 Groups(s.irradiance_size.x, kIrradianceGroupSize),
                 static_cast<GLuint>(s.irradiance_size.y), 1);
        transmittance_cpu =
            ref::FromImage(gl::ReadTexture(transmittance, glm::ivec3(s.transmittance_size, 1)));
    }
};

AtmosphereRenderer::AtmosphereRenderer(const Atmosphere& atmosphere, const LutSettings& settings) {
    Validate(atmosphere);
    settings.Validate();
    const gl::StateGuard guard(true);
    impl_ = std::make_unique<Impl>(atmosphere, settings);
    impl_->BuildStaticLuts();
}

AtmosphereRenderer::~AtmosphereRenderer() = default;

void AtmosphereRenderer::SetAtmosphere(const Atmosphere& atmosphere) {
    Validate(atmosphere);
    const gl::StateGuard guard(impl_->preserve_gl_state);
    impl_->atmosphere = atmosphere;
    impl_->BuildStaticLuts();
}

const Atmosphere& AtmosphereRenderer::atmosphere() const { return impl_->atmosphere; }
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
    if (!weather.layers.empty()) {
        std::vector<clouds::WeatherMap> maps;
        std::vector<double> tops;
        for (const clouds::CloudLayer& layer : weather.layers) {
            maps.push_back(clouds::BuildWeatherMap(layer));
            tops.push_back(clouds::CloudTopFraction(maps.back()));
        }
        const clouds::CloudNoiseLoad noise =
            clouds::LoadOrGenerateCloudNoise(settings.noise, settings.noise_cache_directory);
        passes = std::make_unique<CloudPasses>(weather, settings, maps, tops, noise.noise);
        cpu = std::make_unique<CpuClouds>(maps, std::move(tops), noise.noise);
        if (d.cloud_composites.empty()) d.cloud_composites = BuildCloudComposites();
    }
    d.clouds = std::move(passes);
    d.cpu_clouds = std::move(cpu);
    d.weather = weather;
    d.cloud_settings = settings;
}
const clouds::Weather& AtmosphereRenderer::weather() const { return impl_->weather; }
const CloudSettings& AtmosphereRenderer::cloud_settings() const { return impl_->cloud_settings; }
const LutSettings& AtmosphereRenderer::settings() const { return impl_->settings; }

void AtmosphereRenderer::UpdateFrameLuts(const Camera& camera, const Lights& lights,
                                         const CloudView& clouds) {
    Impl& d = *impl_;
    const gl::StateGuard guard(d.preserve_gl_state);
    d.UploadLights(lights, camera);
    RenderOptions options;
    d.UploadFrame(camera, lights, options);
    if (d.clouds) {
        // What the clouds do to the light beneath them goes into the light block first.
        d.BindInputs();
        d.clouds->Prepare(d.atmosphere, camera, lights, clouds, d.buffers[1]);
    }
    const LutSettings& s = d.settings;
    // With one light, each invocation marches a texel of the first half of the azimuths and
    // writes its mirror image too (sky_view.comp).
    const bool mirrored = d.light_count == 1 && !lights.eclipse.active;
    const int columns = mirrored ? (s.sky_view_size.x + 1) / 2 : s.sky_view_size.x;
    d.Dispatch(kSkyViewPass, d.sky_view, false, Groups(columns, kLutGroupSize),
               Groups(s.sky_view_size.y, kLutGroupSize), 1);
    d.Dispatch(kAerialPerspectivePass, d.aerial_perspective, true,
               Groups(s.aerial_perspective_size.x, kLutGroupSize),
               Groups(s.aerial_perspective_size.y, kLutGroupSize), 1);
}

void AtmosphereRenderer::Render(const Camera& camera, const Lights& lights,
                                const RenderOptions& options) {
    Impl& d = *impl_;
    if (!(options.size.x > 0 && options.size.y > 0 && options.size.x <= 16384 &&
          options.size.y <= 16384)) {
        throw ArgumentError("render size " + std::to_string(options.size.x) + "x" +
                            std::to_string(options.size.y) +
                            " is out of range (expected 1..16384 per axis)");
    }
    const gl::StateGuard guard(d.preserve_gl_state);
    const bool to_host = options.target_framebuffer.has_value();
    if (to_host && (options.target_viewport.z != options.size.x ||
                    options.target_viewport.w != options.size.y)) {
        throw ArgumentError("RenderOptions: target_viewport size " +
                            std::to_string(options.target_viewport.z) + "x" +
                            std::to_string(options.target_viewport.w) + " differs from size " +
                            std::to_string(options.size.x) + "x" + std::to_string(options.size.y));
    }
    if (options.size != d.frame_size) {
        for (GLuint* t : {&d.frame, &d.stars}) {
            if (*t != 0) glDeleteTextures(1, t);
        }
        d.frame = gl::CreateTexture2D(options.size);
        d.stars = gl::CreateTexture2D(options.size);
        d.frame_size = options.size;
        glNamedFramebufferTexture(d.framebuffer, GL_COLOR_ATTACHMENT0, d.frame, 0);
        if (glCheckNamedFramebufferStatus(d.framebuffer, GL_FRAMEBUFFER) !=
            GL_FRAMEBUFFER_COMPLETE) {
            throw gl::GlError("the RGBA32F frame of " + std::to_string(options.size.x) + "x" +
                              std::to_string(options.size.y) +
                              " is not a complete framebuffer on this GL implementation");
        }
    }
    // A sun disk narrower than a pixel would fall between pixel centres: it becomes a point.
    const double pixel_angle = camera.vertical_fov / options.size.y;
    const bool sun_disk_resolved = d.atmosphere.sun_angular_radius > pixel_angle;
    std::vector<StarPoint> points = options.stars;
    if (options.draw_sun_disk && !sun_disk_resolved) {
        points.push_back({lights.sun_direction, lights.sun_illuminance});
    }
    if (!points.empty()) {
        d.star_pixels.assign(
            static_cast<std::size_t>(options.size.x) * static_cast<std::size_t>(options.size.y),
            glm::vec4(0.0f));
        SplatPoints(points, camera, options.size,
                    MakeShaderParameters<ref::AtmosphereParameters>(d.atmosphere),
                    d.transmittance_cpu, d.star_pixels);
        glTextureSubImage2D(d.stars, 0, 0, 0, options.size.x, options.size.y, GL_RGBA, GL_FLOAT,
                            d.star_pixels.data());
    }
    // The light block is UpdateFrameLuts' (with the clouds' shading in it).
    d.UploadFrame(camera, lights, options, sun_disk_resolved, !points.empty());
    if (options.scene_depth &&
        !(to_host && options.scene_depth->texture != 0 && options.scene_depth->near_m > 0.0 &&
          options.scene_depth->far_m > options.scene_depth->near_m)) {
        throw ArgumentError(
            "RenderOptions::scene_depth needs a host framebuffer, a depth "
            "texture and 0 < near_m < far_m");
    }
    const bool inside = glm::length(camera.position) < d.atmosphere.top_radius;
    const bool ray_march = !inside || options.force_ray_march;
    const Pass pass = options.scene_depth
                          ? (ray_march ? kRenderRayMarchDepthPass : kRenderDepthPass)
                          : (ray_march ? kRenderRayMarchPass : kRenderPass);
    const GLuint target = to_host ? *options.target_framebuffer : d.framebuffer;
    const glm::ivec4 viewport =
        to_host ? options.target_viewport : glm::ivec4(0, 0, options.size.x, options.size.y);
    const GLuint depth = options.scene_depth ? options.scene_depth->texture : 0;
    if (d.clouds) {
        d.BindInputs();
        d.clouds->Render(d.atmosphere, camera, lights, options);
    }
    // LastPassTimes reports this frame's composite draws only.
    std::fill(d.query_used.begin() + kRenderPass, d.query_used.end(), false);
    d.Draw(pass, pass, target, viewport, depth);

    // The Sun and the Moon, each over its own box (one box when they overlap, so an eclipse is
    // not added twice).
    std::vector<glm::ivec4> boxes;
    const auto add_disk = [&](const glm::dvec3& direction, double radius) {
        std::optional<glm::ivec4> box = DiskBox(direction, radius, camera, options.size);
        if (!box) return;
        for (glm::ivec4& other : boxes) {
            if (Overlap(other, *box)) {
                other = Union(other, *box);
                return;
            }
        }
        boxes.push_back(*box);
    };
    if (options.draw_sun_disk && sun_disk_resolved) {
        // In a solar eclipse the corona too, out to 6 solar radii (render.frag).
        add_disk(lights.sun_direction, lights.eclipse.active
                                           ? 6.0 * lights.eclipse.sun_angular_radius
                                           : d.atmosphere.sun_angular_radius);
    }
    if (options.moon.enabled) add_disk(options.moon.direction, options.moon.angular_radius);
    const Pass disk_pass = options.scene_depth ? kDiskDepthPass : kDiskPass;
    for (std::size_t i = 0; i < boxes.size(); ++i) {
        d.Draw(disk_pass, i == 0 ? disk_pass : kSecondDiskQuery, target, viewport, depth, boxes[i]);
    }
}

LutImage AtmosphereRenderer::ReadTransmittance() const {
    const gl::StateGuard guard(impl_->preserve_gl_state);
    return gl::ReadTexture(impl_->transmittance, glm::ivec3(impl_->settings.transmittance_size, 1));
}
LutImage AtmosphereRenderer::ReadMultipleScattering() const {
    const gl::StateGuard guard(impl_->preserve_gl_state);
    return gl::ReadTexture(impl_->multiple_scattering,
                           glm::ivec3(impl_->settings.multiple_scattering_size, 1));
}
LutImage AtmosphereRenderer::ReadGroundIrradiance() const {
    const gl::StateGuard guard(impl_->preserve_gl_state);
    return gl::ReadTexture(impl_->irradiance, glm::ivec3(impl_->settings.irradiance_size, 1));
}
LutImage AtmosphereRenderer::ReadSkyView() const {
    const gl::StateGuard guard(impl_->preserve_gl_state);
    return gl::ReadTexture(impl_->sky_view, glm::ivec3(impl_->settings.sky_view_size, 1));
}
LutImage AtmosphereRenderer::ReadAerialPerspective() const {
    const gl::StateGuard guard(impl_->preserve_gl_state);
    return gl::ReadTexture(impl_->aerial_perspective, impl_->settings.aerial_perspective_size);
}
LutImage AtmosphereRenderer::ReadFrame() const {
    if (impl_->frame == 0) throw gl::GlError("ReadFrame before any Render");
    const gl::StateGuard guard(impl_->preserve_gl_state);
    return gl::ReadTexture(impl_->frame, glm::ivec3(impl_->frame_size, 1));
}

unsigned AtmosphereRenderer::transmittance_texture() const { return impl_->transmittance; }
unsigned AtmosphereRenderer::aerial_perspective_texture() const {
    return impl_->aerial_perspective;
}
unsigned AtmosphereRenderer::frame_texture() const { return impl_->frame; }
unsigned AtmosphereRenderer::cloud_shadow_texture() const {
    return impl_->clouds ? impl_->clouds->shadow_map_texture() : 0;
}

LutImage AtmosphereRenderer::ReadClouds() const {
    if (!impl_->clouds) throw std::logic_error("ReadClouds: the renderer has no weather");
    const gl::StateGuard guard(impl_->preserve_gl_state);
    return impl_->clouds->ReadClouds();
}
CloudShade AtmosphereRenderer::ReadCloudShade() const {
    gl::LightUniforms u{};
    glGetNamedBufferSubData(impl_->buffers[1], 0, sizeof(u), &u);
    CloudShade shade;
    shade.base_altitude = static_cast<double>(u.cloud_base) * kKm;
    shade.direct_transmittance = u.cloud_direct;
    shade.sky_transmittance = u.cloud_sky;
    shade.luminance = glm::dvec3(u.cloud_luminance);
    return shade;
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
    return d.cpu_clouds->Transmittance(d.weather, d.cloud_settings, d.atmosphere.bottom_radius,
                                       position, direction, view, steps);
}

LutImage AtmosphereRenderer::ReadCloudShadowMap() const {
    if (!impl_->clouds) throw std::logic_error("ReadCloudShadowMap: the renderer has no weather");
    const gl::StateGuard guard(impl_->preserve_gl_state);
    return impl_->clouds->ReadShadowMap();
}

std::size_t AtmosphereRenderer::LutMemoryBytes() const {
    const LutSettings& s = impl_->settings;
    const auto texels = [](glm::ivec2 v) { return static_cast<std::size_t>(v.x * v.y); };
    const std::size_t ap = static_cast<std::size_t>(s.aerial_perspective_size.x) *
                           static_cast<std::size_t>(s.aerial_perspective_size.y) *
                           static_cast<std::size_t>(s.aerial_perspective_size.z);
    return 16 * (texels(s.transmittance_size) + texels(s.multiple_scattering_size) +
                 texels(s.irradiance_size) + texels(s.sky_view_size) + ap);
}

PassTimes AtmosphereRenderer::LastPassTimes() const {
    const Impl& d = *impl_;
    const gl::StateGuard guard(d.preserve_gl_state);  // a host's query buffer
    auto ms = [&](std::size_t query) {
        if (!d.query_used[query]) return 0.0;
        GLuint64 ns = 0;
        glGetQueryObjectui64v(d.queries[query], GL_QUERY_RESULT, &ns);
        return static_cast<double>(ns) * 1e-6;
    };
    // The composite: whichever sky program ran, plus its disk draws.
    PassTimes times{ms(kTransmittancePass),
                    ms(kMultipleScatteringPass),
                    ms(kIrradiancePass),
                    ms(kSkyViewPass),
                    ms(kAerialPerspectivePass),
                    ms(kRenderPass) + ms(kRenderRayMarchPass) + ms(kRenderDepthPass) +
                        ms(kRenderRayMarchDepthPass) + ms(kDiskPass) + ms(kDiskDepthPass) +
                        ms(kSecondDiskQuery)};
    if (d.clouds) {
        const auto clouds = d.clouds->LastPassTimes();
        times.cloud_shadow_map = clouds[0];
        times.cloud_shade = clouds[1];
        times.cloud_trace = clouds[2];
        times.cloud_reconstruct = clouds[3];
        times.cloud_ground_shadow = clouds[4];
    }
    return times;
}

}  // namespace zenith::sky
