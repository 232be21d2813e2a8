#include "atmosphere_passes.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <string_view>
#include <utility>

#include "bindings.h"
#include "clouds/cloud_passes.h"
#include "environment_passes.h"
#include "gl/display_uniforms.h"
#include "gl/draw.h"
#include "gl/shader_library.h"
#include "gl/textures.h"
#include "multiple_scattering_column.h"
#include "night_sky_map.h"
#include "reference/atmosphere_functions.h"
#include "reference/lut_texture.h"
#include "renderer_programs.h"
#include "shader_parameters.h"
#include "zenith/sky/gl/error.h"

namespace zenith::sky {
namespace {

using Pass = AtmospherePasses::Pass;
using enum AtmospherePasses::Pass;
constexpr double kKm = 1000.0;

// Where the disks are drawn: their apparent places, or unsqueezed in their own directions.
ApparentPlace SunDiskPlace(const SkyScene& scene) {
    return scene.sun_apparent.value_or(ApparentPlace{scene.lights.sun_direction, 1.0});
}
ApparentPlace MoonDiskPlace(const MoonDisk& moon) {
    return moon.apparent.value_or(ApparentPlace{moon.direction, 1.0});
}

constexpr std::array<std::string_view, AtmospherePasses::kPassCount> kPassFiles = {
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
gl::Program CompositeProgram(Pass pass, bool clouds) {
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

std::array<gl::Program, AtmospherePasses::kPassCount> BuildPrograms() {
    return {gl::ComputeProgram(kPassFiles[0]), gl::ComputeProgram(kPassFiles[1]),
            gl::ComputeProgram(kPassFiles[2]), gl::ComputeProgram(kPassFiles[3]),
            gl::ComputeProgram(kPassFiles[4]),
            // Six programs from one source: llvmpipe runs both sides of a branch under a mask,
            // so a per-frame choice made in the shader cost every pixel the 32-step ray march
            // (or the disks); chosen here it costs nothing.
            CompositeProgram(kRenderPass, false), CompositeProgram(kRenderRayMarchPass, false),
            CompositeProgram(kRenderDepthPass, false),
            CompositeProgram(kRenderRayMarchDepthPass, false), CompositeProgram(kDiskPass, false),
            CompositeProgram(kDiskDepthPass, false)};
}

// The points' program (atmosphere/stars.*): no prelude, nothing but its vertex inputs.
gl::Program StarProgram() {
    const std::string version = "#version 450 core\n";
    return gl::Program::Graphics(
        version + std::string(gl::EmbeddedShaderFile("atmosphere/stars.vert")),
        version + std::string(gl::EmbeddedShaderFile("atmosphere/stars.frag")), "atmosphere/stars");
}

gl::Program PrecipitationProgram() {
    constexpr std::string_view kBlock[] = {"atmosphere/precipitation_block.glsl"};
    return gl::Program::Graphics(gl::ComposeShader("atmosphere/precipitation.vert", {}, kBlock),
                                 gl::ComposeShader("atmosphere/precipitation.frag", {}, kBlock),
                                 "atmosphere/precipitation");
}

// The six composites again, laying the clouds over the sky and the disks.
std::vector<gl::Program> CloudComposites() {
    std::vector<gl::Program> programs;
    for (std::size_t pass = kRenderPass; pass < AtmospherePasses::kPassCount; ++pass) {
        programs.push_back(CompositeProgram(static_cast<Pass>(pass), true));
    }
    return programs;
}

// The binding point of each of the uniform buffers, in the order of AtmospherePasses::buffers_.
constexpr std::array<GLuint, 4> kBufferBindings = {kAtmosphereBlockBinding, kLightBlockBinding,
                                                   kSettingsBlockBinding, kFrameBlockBinding};

// Each point source as a point on the pixel its direction falls in (its centre, in normalised
// device coordinates) with luminance T E / (pixel solid angle), so the image they add up to
// integrates to each source's illuminance seen through the atmosphere (transmittance T to
// space, 0 below the horizon) whatever the resolution.
void SplatPoints(const std::vector<StarPoint>& points, const Camera& camera, glm::ivec2 size,
                 const ref::AtmosphereParameters& atmosphere,
                 const ref::TransmittanceTexture& transmittance,
                 std::vector<StarVertex>& vertices) {
    vertices.clear();
    const glm::dvec3 camera_km = camera.position / kKm;
    const double altitude_km = glm::length(camera_km) - atmosphere.bottom_radius;
    const glm::dmat3 view_from_world = glm::transpose(camera.world_from_view);
    const double tan_y = std::tan(0.5 * camera.vertical_fov);
    const double tan_x = tan_y * camera.aspect;
    // Tangent-plane size of one pixel; a pixel at tangent-plane (x, y) subtends
    // dx dy / (1 + x^2 + y^2)^(3/2) steradians.
    const double dx = 2.0 * tan_x / size.x, dy = 2.0 * tan_y / size.y;
    const double pixel_angle = camera.vertical_fov / size.y;  // ResolveDisks' measure
    for (const StarPoint& point : points) {
        const glm::dvec3 v = view_from_world * point.direction;
        if (!(v.z < 0.0)) continue;  // behind the camera
        const double x = v.x / -v.z, y = v.y / -v.z;
        const double px = (x / tan_x + 1.0) * 0.5 * size.x, py = (y / tan_y + 1.0) * 0.5 * size.y;
        if (!(px >= 0.0 && py >= 0.0 && px < size.x && py < size.y)) continue;
        const glm::dvec3 t = ref::TransmittanceToSpace(atmosphere, transmittance, camera_km,
                                                       altitude_km, point.direction);
        if (t == glm::dvec3(0.0)) continue;
        const int ix = static_cast<int>(px), iy = static_cast<int>(py);
        // The solid angle of the whole pixel (taken at its centre), the measure a reader of the
        // image integrates with, so luminance x solid angle returns exactly E.
        const double cx = ((ix + 0.5) / size.x * 2.0 - 1.0) * tan_x;
        const double cy = ((iy + 0.5) / size.y * 2.0 - 1.0) * tan_y;
        const double solid_angle = dx * dy / std::pow(1.0 + cx * cx + cy * cy, 1.5);
        // A resolved disk's share (ResolveDisks) is an extended source, seen by its luminance,
        // not by the eye's threshold for points (the composite reads it from alpha).
        const glm::dvec3 luminance = t * point.illuminance / solid_angle;
        const bool extended = point.angular_radius > 0.5 * pixel_angle;
        vertices.push_back(
            {glm::vec2((ix + 0.5) / size.x * 2.0 - 1.0, (iy + 0.5) / size.y * 2.0 - 1.0),
             glm::vec4(luminance,
                       extended ? glm::dot(luminance, glm::dvec3(0.2126, 0.7152, 0.0722)) : 0.0)});
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
}  // namespace

std::vector<gl::Program> BuildRendererPrograms() {
    std::vector<gl::Program> programs;
    for (gl::Program& p : BuildPrograms()) programs.push_back(std::move(p));
    programs.push_back(StarProgram());
    programs.push_back(PrecipitationProgram());
    for (gl::Program& p : CloudComposites()) programs.push_back(std::move(p));
    for (gl::Program& p : CloudPasses::BuildPrograms()) programs.push_back(std::move(p));
    for (gl::Program& p : gl::BuildDisplayPrograms()) programs.push_back(std::move(p));
    for (gl::Program& p : EnvironmentPasses::BuildPrograms()) programs.push_back(std::move(p));
    return programs;
}

AtmospherePasses::AtmospherePasses(const Atmosphere& atmosphere, const LutSettings& s)
    : atmosphere_(atmosphere),
      settings_(s),
      programs_(BuildPrograms()),
      star_program_(StarProgram()),
      precipitation_program_(PrecipitationProgram()) {
    glCreateBuffers(static_cast<GLsizei>(buffers_.size()), buffers_.data());
    glNamedBufferStorage(buffers_[0], sizeof(gl::AtmosphereUniforms), nullptr,
                         GL_DYNAMIC_STORAGE_BIT);
    glNamedBufferStorage(buffers_[1], sizeof(gl::LightUniforms), nullptr, GL_DYNAMIC_STORAGE_BIT);
    glNamedBufferStorage(buffers_[2], sizeof(gl::SettingsUniforms), nullptr,
                         GL_DYNAMIC_STORAGE_BIT);
    glNamedBufferStorage(buffers_[3], sizeof(gl::FrameUniforms), nullptr, GL_DYNAMIC_STORAGE_BIT);
    transmittance_ = gl::CreateTexture2D(s.transmittance_size);
    multiple_scattering_ = gl::CreateTexture2D(s.multiple_scattering_texture_size());
    irradiance_ = gl::CreateTexture2D(s.irradiance_size);
    sky_view_ = gl::CreateTexture2D(s.sky_view_size, GL_RGBA32F, GL_REPEAT);  // azimuth wraps
    aerial_perspective_ = gl::CreateTexture3D(s.aerial_perspective_size);
    night_sky_ = gl::CreateTexture2D(kNightSkyMapSize, GL_RGBA32F, GL_REPEAT);
    glCreateQueries(GL_TIME_ELAPSED, static_cast<GLsizei>(queries_.size()), queries_.data());
    glCreateFramebuffers(1, &framebuffer_);
    glCreateVertexArrays(1, &vertex_array_);  // core profile draws need one, even empty
    glCreateFramebuffers(1, &star_framebuffer_);
    glCreateBuffers(1, &star_buffer_);
    glCreateBuffers(1, &precipitation_buffer_);
    glNamedBufferStorage(precipitation_buffer_, sizeof(gl::PrecipitationUniforms), nullptr,
                         GL_DYNAMIC_STORAGE_BIT);
    glCreateVertexArrays(1, &star_vertex_array_);
    glVertexArrayVertexBuffer(star_vertex_array_, 0, star_buffer_, 0, sizeof(StarVertex));
    glEnableVertexArrayAttrib(star_vertex_array_, 0);
    glVertexArrayAttribFormat(star_vertex_array_, 0, 2, GL_FLOAT, GL_FALSE,
                              offsetof(StarVertex, ndc));
    glVertexArrayAttribBinding(star_vertex_array_, 0, 0);
    glEnableVertexArrayAttrib(star_vertex_array_, 1);
    glVertexArrayAttribFormat(star_vertex_array_, 1, 4, GL_FLOAT, GL_FALSE,
                              offsetof(StarVertex, luminance));
    glVertexArrayAttribBinding(star_vertex_array_, 1, 0);

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
    glNamedBufferSubData(buffers_[2], 0, sizeof(u), &u);
    BuildStaticLuts();
}

AtmospherePasses::~AtmospherePasses() {
    glDeleteVertexArrays(1, &vertex_array_);
    glDeleteFramebuffers(1, &framebuffer_);
    glDeleteVertexArrays(1, &star_vertex_array_);
    glDeleteFramebuffers(1, &star_framebuffer_);
    glDeleteBuffers(1, &star_buffer_);
    glDeleteBuffers(1, &precipitation_buffer_);
    glDeleteQueries(static_cast<GLsizei>(queries_.size()), queries_.data());
    for (GLuint t : {transmittance_, multiple_scattering_, irradiance_, sky_view_,
                     aerial_perspective_, frame_, stars_, night_sky_}) {
        if (t != 0) glDeleteTextures(1, &t);
    }
    glDeleteBuffers(static_cast<GLsizei>(buffers_.size()), buffers_.data());
}

void AtmospherePasses::SetAtmosphere(const Atmosphere& atmosphere) {
    atmosphere_ = atmosphere;
    BuildStaticLuts();
    night_sky_map_for_.reset();  // its extinction was the old atmosphere's
}

void AtmospherePasses::BuildCloudComposites() {
    if (cloud_composites_.empty()) cloud_composites_ = CloudComposites();
}

void AtmospherePasses::BindInputs() const {
    for (std::size_t i = 0; i < buffers_.size(); ++i) {
        glBindBufferBase(GL_UNIFORM_BUFFER, kBufferBindings[i], buffers_[i]);
    }
    glBindTextureUnit(kTransmittanceUnit, transmittance_);
    glBindTextureUnit(kMultipleScatteringUnit, multiple_scattering_);
    glBindTextureUnit(kIrradianceUnit, irradiance_);
    glBindTextureUnit(kSkyViewUnit, sky_view_);
    glBindTextureUnit(kStarUnit, stars_ != 0 ? stars_ : transmittance_);  // unused when no stars
    glBindTextureUnit(kAerialPerspectiveUnit, aerial_perspective_);
    glBindTextureUnit(kNightSkyUnit, night_sky_);
}

// Runs one compute pass writing `output` (bound as kOutputImageUnit), timed by a query.
void AtmospherePasses::Dispatch(Pass pass, GLuint output, bool layered, GLuint gx, GLuint gy,
                                GLuint gz) {
    BindInputs();
    programs_[pass].Use();
    glBindImageTexture(kOutputImageUnit, output, 0, layered ? GL_TRUE : GL_FALSE, 0, GL_WRITE_ONLY,
                       GL_RGBA32F);
    glBeginQuery(GL_TIME_ELAPSED, queries_[pass]);
    glDispatchCompute(gx, gy, gz);
    glEndQuery(GL_TIME_ELAPSED);
    query_used_[pass] = true;
    // Later passes sample what this one wrote; reads back use glGetTextureImage.
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT |
                    GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
}

// The composite: a full-screen triangle into `target` (our frame's FBO or the host's), timed by
// query `query`. The sky pass replaces the sky (blending premultiplied over the host's geometry
// when there is scene depth); a disk pass adds the Sun and the Moon inside `scissor` (viewport
// pixels). With `clouds`, their last trace goes over what it draws.
void AtmospherePasses::Draw(Pass pass, std::size_t query, GLuint target, glm::ivec4 viewport,
                            const CloudPasses* clouds, GLuint scene_depth,
                            std::optional<glm::ivec4> scissor) {
    BindInputs();
    if (clouds != nullptr) clouds->BindForComposite();
    if (scene_depth != 0) glBindTextureUnit(kSceneDepthUnit, scene_depth);
    // Over the host's geometry the sky pass is premultiplied: (L, T) over geometry and (sky, 0)
    // elsewhere.
    const gl::Blend blend = pass == kDiskPass || pass == kDiskDepthPass ? gl::Blend::kAdd
                            : scene_depth != 0                          ? gl::Blend::kPremultiplied
                                                                        : gl::Blend::kReplace;
    const gl::Program& program =
        clouds != nullptr ? cloud_composites_[pass - kRenderPass] : programs_[pass];
    gl::DrawFullscreen(program, vertex_array_, target, viewport, blend, queries_[query], scissor);
    query_used_[query] = true;
}

void AtmospherePasses::BuildStaticLuts() {
    const auto a = MakeShaderParameters<gl::AtmosphereUniforms>(atmosphere_);
    glNamedBufferSubData(buffers_[0], 0, sizeof(a), &a);
    const LutSettings& s = settings_;
    Dispatch(kTransmittancePass, transmittance_, false,
             Groups(s.transmittance_size.x, kLutGroupSize),
             Groups(s.transmittance_size.y, kLutGroupSize), 1);
    // The multiple scattering's column (multiple_scattering_column.h) reads the transmittance
    // LUT on the CPU.
    transmittance_cpu_ =
        ref::FromImage(gl::ReadTexture(transmittance_, glm::ivec3(s.transmittance_size, 1)));
    BuildMultipleScattering();
    Dispatch(kIrradiancePass, irradiance_, false, static_cast<GLuint>(s.irradiance_size.x),
             static_cast<GLuint>(s.irradiance_size.y), 1);
    night_ground_ = {};  // made over the old air
    multiple_scattering_cpu_ = ref::FromImage(
        gl::ReadTexture(multiple_scattering_, glm::ivec3(s.multiple_scattering_texture_size(), 1)));
    irradiance_cpu_ =
        ref::FromImage(gl::ReadTexture(irradiance_, glm::ivec3(s.irradiance_size, 1)));
}

// Orders 2 .. K of the multiple scattering (atmosphere/multiple_scattering.comp), one dispatch
// each, timed together as one pass: order k reads order k - 1 from one of two textures and
// writes itself to the other, adding itself to the LUT; order K adds the column's correction,
// solved on the CPU first (not timed by the pass's query).
void AtmospherePasses::BuildMultipleScattering() {
    const glm::ivec2 size = settings_.multiple_scattering_size;
    const glm::ivec2 texture_size = settings_.multiple_scattering_texture_size();
    const LutImage correction =
        MultipleScatteringColumnCorrection(atmosphere_, transmittance_cpu_, settings_);
    const GLuint column = gl::CreateTexture2D(size);
    glTextureSubImage2D(column, 0, 0, 0, size.x, size.y, GL_RGBA, GL_FLOAT,
                        correction.texels.data());
    std::array<GLuint, 2> orders = {gl::CreateTexture2D(texture_size),
                                    gl::CreateTexture2D(texture_size)};
    const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    glClearTexImage(orders[0], 0, GL_RGBA, GL_FLOAT, zero);  // order 2 reads no order before
    const gl::Program& program = programs_[kMultipleScatteringPass];
    glProgramUniform1i(program.name(), gl::kLastScatteringOrderLocation,
                       settings_.multiple_scattering_orders);
    BindInputs();
    program.Use();
    glBindImageTexture(kOutputImageUnit, multiple_scattering_, 0, GL_FALSE, 0, GL_READ_WRITE,
                       GL_RGBA32F);
    glBindImageTexture(kColumnCorrectionImageUnit, column, 0, GL_FALSE, 0, GL_READ_ONLY,
                       GL_RGBA32F);
    glBeginQuery(GL_TIME_ELAPSED, queries_[kMultipleScatteringPass]);
    for (int k = 2; k <= settings_.multiple_scattering_orders; ++k) {
        const auto previous = static_cast<std::size_t>(k % 2);
        glProgramUniform1i(program.name(), gl::kScatteringOrderLocation, k);
        glBindTextureUnit(kMultipleScatteringUnit, orders[previous]);
        glBindImageTexture(kScatteringOrderImageUnit, orders[1 - previous], 0, GL_FALSE, 0,
                           GL_WRITE_ONLY, GL_RGBA32F);
        glDispatchCompute(static_cast<GLuint>(size.x), static_cast<GLuint>(size.y), 1);
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT |
                        GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    }
    glEndQuery(GL_TIME_ELAPSED);
    query_used_[kMultipleScatteringPass] = true;
    glDeleteTextures(static_cast<GLsizei>(orders.size()), orders.data());
    glDeleteTextures(1, &column);
}

// Whether what the night sky's light was made for still holds for this frame: the same settings
// and starlight, the sky and the Sun turned by less than `angle` rad, the camera moved by less
// than `distance` m.
bool AtmospherePasses::NightSkyInputsHold(const NightSkyMapInputs& last, const SkyScene& scene,
                                          const glm::dvec3& camera_position, double angle,
                                          double distance) {
    const NightSky& now = scene.night_sky;
    const auto turned = [](const glm::dmat3& a, const glm::dmat3& b) {
        double largest = 0.0;
        for (int c = 0; c < 3; ++c) largest = std::max(largest, glm::length(a[c] - b[c]));
        return largest;
    };
    return now.settings == last.night.settings && now.starlight == last.night.starlight &&
           turned(now.ecliptic_from_world, last.night.ecliptic_from_world) < angle &&
           turned(now.icrs_from_world, last.night.icrs_from_world) < angle &&
           std::abs(now.sun_ecliptic_longitude - last.night.sun_ecliptic_longitude) < angle &&
           glm::length(scene.lights.sun_direction - last.sun_direction) < angle &&
           glm::length(camera_position - last.camera_position) < distance;
}

// The night sky's map changes with the sky's turning (0.004 deg/s), the Sun's place and the
// camera's, a few hundredths of one of its 2.8 x 2.8 deg texels a second: filling it on the CPU
// (~2 ms) is the night frame's largest cost on a GPU. The last one holds while the sky, the Sun
// and the camera's vertical have turned by less than kNightSkyMapTolerance rad (0.006 deg: 1/500
// of a texel), the camera has moved by less than 10 m, and the settings, the starlight and the
// atmosphere are the same.
bool AtmospherePasses::NightSkyMapHolds(const SkyScene& scene,
                                        const glm::dvec3& camera_position) const {
    constexpr double kNightSkyMapTolerance = 1e-4;  // rad
    return night_sky_map_for_ && NightSkyInputsHold(*night_sky_map_for_, scene, camera_position,
                                                    kNightSkyMapTolerance, 10.0);
}

// The ground's light from the night sky (0.5 ms on the CPU) changes far more slowly than its
// map: it is made again when the settings or the starlight change, the sky or the Sun turns
// 0.01 rad (2 min of time) or the camera moves 10 km (each well under 1 %); only while the Sun
// is below the horizon (by day it adds ~1e-8 of the daylight).
void AtmospherePasses::UpdateNightGroundIrradiance(const SkyScene& scene,
                                                   const glm::dvec3& camera_position) {
    const NightSky& night = scene.night_sky;
    if (!night.enabled || !night.settings.enabled ||
        glm::dot(glm::normalize(scene.lights.sun_direction), glm::normalize(camera_position)) >
            0.0) {
        night_ground_ = {};
        return;
    }
    if (night_ground_.inputs &&
        NightSkyInputsHold(*night_ground_.inputs, scene, camera_position, 0.01, 10e3)) {
        return;
    }
    night_ground_.value =
        NightSkyGroundIrradiance(night, atmosphere_, transmittance_cpu_, camera_position);
    night_ground_.inputs = NightSkyMapInputs{night, scene.lights.sun_direction, camera_position};
}

void AtmospherePasses::SetFrame(const SkyScene& scene, const SkyView& view, int environment_size) {
    const Camera& camera = view.camera;
    const bool night_sky = scene.night_sky.enabled && scene.night_sky.settings.enabled;
    if (night_sky) scene.night_sky.settings.Validate();
    if (scene.clouds.reset_history) {
        // A cut: this frame's night light is its own, whatever was drawn before (replayed,
        // resumed and sharded frames match).
        night_sky_map_for_.reset();
        night_ground_.inputs.reset();
    }
    UpdateNightGroundIrradiance(scene, camera.position);
    auto lights = MakeLightSet<gl::LightUniforms>(scene.lights, camera.position);
    lights.night_ground_irradiance = glm::vec3(night_ground_.value);
    glNamedBufferSubData(buffers_[1], 0, sizeof(lights), &lights);
    light_count_ = lights.count;
    eclipse_active_ = scene.lights.eclipse.active;

    gl::FrameUniforms& u = frame_uniforms_;
    u = {};
    u.camera_km = glm::vec3(camera.position / kKm);
    u.tan_half_fov = static_cast<float>(std::tan(0.5 * camera.vertical_fov));
    for (int i = 0; i < 3; ++i) u.world_from_view[i] = glm::vec4(camera.world_from_view[i], 0.0);
    u.aspect = static_cast<float>(camera.aspect);
    u.ray_march_steps = view.ray_march_steps;
    u.environment_size = environment_size;
    u.moon_enabled = scene.moon.enabled ? 1 : 0;
    u.moon_direction = glm::vec3(glm::normalize(scene.moon.direction));
    u.moon_angular_radius = static_cast<float>(scene.moon.angular_radius);
    u.moon_albedo = static_cast<float>(scene.moon.albedo);
    u.moon_sunlight = glm::vec3(scene.moon.sunlight);
    u.moon_distance_km = static_cast<float>(scene.moon.distance_m / kKm);
    u.moon_shadow_enabled = scene.moon.shadow ? 1 : 0;
    if (scene.moon.shadow) {
        const MoonDisk::Shadow& shadow = *scene.moon.shadow;
        u.moon_shadow_axis_min_km = static_cast<float>(shadow.axis_min_m / kKm);
        u.moon_shadow_axis_max_km = static_cast<float>(shadow.axis_max_m / kKm);
        for (std::size_t i = 0; i < shadow.sunlight.size(); ++i) {
            u.moon_shadow[i] = glm::vec4(glm::vec3(shadow.sunlight[i]), 0.0f);
        }
    }
    const ApparentPlace sun_disk = SunDiskPlace(scene);
    const ApparentPlace moon_disk = MoonDiskPlace(scene.moon);
    u.sun_disk_direction = glm::vec3(glm::normalize(sun_disk.direction));
    u.sun_disk_scale = static_cast<float>(sun_disk.vertical_scale);
    u.moon_disk_direction = glm::vec3(glm::normalize(moon_disk.direction));
    u.moon_disk_scale = static_cast<float>(moon_disk.vertical_scale);
    // Per-frame constants, from the shared functions compiled as C++ (double).
    const auto a = MakeShaderParameters<ref::AtmosphereParameters>(atmosphere_);
    const glm::dvec3 up = glm::normalize(camera.position);
    u.sky_view_up = glm::vec3(up);
    u.sky_view_x = glm::vec3(ref::SkyViewFrameX(up, glm::normalize(scene.lights.sun_direction)));
    u.horizon_zenith = static_cast<float>(ref::HorizonZenithAngle(
        a, (glm::length(camera.position) - atmosphere_.bottom_radius) / kKm));
    u.cos_sun_radius = static_cast<float>(std::cos(atmosphere_.sun_angular_radius));
    u.cos_moon_radius = static_cast<float>(std::cos(scene.moon.angular_radius));
    u.camera_altitude_km =
        static_cast<float>((glm::length(camera.position) - atmosphere_.bottom_radius) / kKm);
    // The night sky's light along the Sky-View LUT's directions, through the atmosphere.
    u.night_sky_enabled = night_sky ? 1 : 0;
    u.star_visibility = scene.star_visibility ? 1 : 0;
    if (night_sky && !NightSkyMapHolds(scene, camera.position)) {
        FillNightSkyMap(scene.night_sky, atmosphere_, transmittance_cpu_, camera.position / kKm,
                        (glm::length(camera.position) - atmosphere_.bottom_radius) / kKm,
                        scene.lights.sun_direction, kNightSkyMapSize, night_sky_pixels_);
        glTextureSubImage2D(night_sky_, 0, 0, 0, kNightSkyMapSize.x, kNightSkyMapSize.y, GL_RGBA,
                            GL_FLOAT, night_sky_pixels_.data());
        night_sky_map_for_ =
            NightSkyMapInputs{scene.night_sky, scene.lights.sun_direction, camera.position};
    }
    glNamedBufferSubData(buffers_[3], 0, sizeof(u), &u);
}

void AtmospherePasses::UpdateFrameLuts() {
    const LutSettings& s = settings_;
    // With one light, each invocation marches a texel of the first half of the azimuths and
    // writes its mirror image too (sky_view.comp).
    const bool mirrored = light_count_ == 1 && !eclipse_active_;
    const int columns = mirrored ? (s.sky_view_size.x + 1) / 2 : s.sky_view_size.x;
    Dispatch(kSkyViewPass, sky_view_, false, Groups(columns, kLutGroupSize),
             Groups(s.sky_view_size.y, kLutGroupSize), 1);
    Dispatch(kAerialPerspectivePass, aerial_perspective_, true,
             Groups(s.aerial_perspective_size.x, kLutGroupSize),
             Groups(s.aerial_perspective_size.y, kLutGroupSize), 1);
}

void AtmospherePasses::ResizeFrame(glm::ivec2 size) {
    if (size == frame_size_) return;
    for (GLuint* t : {&frame_, &stars_}) {
        if (*t != 0) glDeleteTextures(1, t);
    }
    frame_ = gl::CreateTexture2D(size);
    stars_ = gl::CreateTexture2D(size);
    frame_size_ = size;
    glNamedFramebufferTexture(star_framebuffer_, GL_COLOR_ATTACHMENT0, stars_, 0);
    glNamedFramebufferTexture(framebuffer_, GL_COLOR_ATTACHMENT0, frame_, 0);
    if (glCheckNamedFramebufferStatus(framebuffer_, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
        throw gl::GlError("the RGBA32F frame of " + std::to_string(size.x) + "x" +
                          std::to_string(size.y) +
                          " is not a complete framebuffer on this GL implementation");
    }
}

// The points into their texture: cleared, then each added by blending (a pixel wide, at its
// pixel's centre). Uploading the whole texture from the CPU instead cost a 720p night frame
// ~7 ms on a GPU (14 MB a frame) for a few thousand stars.
void AtmospherePasses::DrawPoints(glm::ivec2 size) {
    gl::SetDrawTarget(star_framebuffer_, glm::ivec4(0, 0, size), gl::Blend::kAdd);
    const GLfloat zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    glClearNamedFramebufferfv(star_framebuffer_, GL_COLOR, 0, zero);
    if (star_vertices_.empty()) return;
    glNamedBufferData(star_buffer_,
                      static_cast<GLsizeiptr>(star_vertices_.size() * sizeof(StarVertex)),
                      star_vertices_.data(), GL_STREAM_DRAW);
    star_program_.Use();
    glBindVertexArray(star_vertex_array_);
    glDrawArrays(GL_POINTS, 0, static_cast<GLsizei>(star_vertices_.size()));
}

bool AtmospherePasses::SunDiskResolved(const SkyView& view, glm::ivec2 size) const {
    // A sun disk narrower than a pixel would fall between pixel centres: it becomes a point.
    return atmosphere_.sun_angular_radius > view.camera.vertical_fov / size.y;
}

void AtmospherePasses::SetTarget(const SkyScene& scene, const SkyView& view,
                                 const RenderTarget& target) {
    const glm::ivec2 size = target.size();
    ResizeFrame(size);  // the stars' texture, and the frame when it is the target
    const bool sun_disk_resolved = SunDiskResolved(view, size);
    std::vector<StarPoint> points = ResolveDisks(scene.stars, view.camera.vertical_fov / size.y);
    if (scene.draw_sun_disk && !sun_disk_resolved) {
        points.push_back({SunDiskPlace(scene).direction, scene.lights.sun_illuminance});
    }
    if (!points.empty()) {
        SplatPoints(points, view.camera, size,
                    MakeShaderParameters<ref::AtmosphereParameters>(atmosphere_),
                    transmittance_cpu_, star_vertices_);
        DrawPoints(size);
    }
    // SetFrame's constants, with what the target fixes.
    gl::FrameUniforms u = frame_uniforms_;
    u.output_size = size;
    u.draw_sun_disk = scene.draw_sun_disk && sun_disk_resolved ? 1 : 0;
    u.stars_enabled = points.empty() ? 0 : 1;
    if (target.framebuffer) {
        u.viewport_x = target.viewport.x;
        u.viewport_y = target.viewport.y;
    }
    if (target.scene_depth) {
        // Eye depth n / (offset + slope d); n / f -> 0 for an infinite far plane.
        const SceneDepth& s = *target.scene_depth;
        const double near_over_far = std::isinf(s.far_m) ? 0.0 : s.near_m / s.far_m;
        u.scene_near_m = static_cast<float>(s.near_m);
        u.scene_depth_offset = static_cast<float>(s.reversed ? near_over_far : 1.0);
        u.scene_depth_slope =
            static_cast<float>(s.reversed ? 1.0 - near_over_far : near_over_far - 1.0);
        u.scene_depth_reversed = s.reversed ? 1 : 0;
    }
    glNamedBufferSubData(buffers_[3], 0, sizeof(u), &u);
}

void AtmospherePasses::Composite(const SkyScene& scene, const SkyView& view,
                                 const RenderTarget& target, CloudPasses* clouds) {
    const Camera& camera = view.camera;
    const glm::ivec2 size = target.size();
    const bool inside = glm::length(camera.position) < atmosphere_.top_radius;
    const bool ray_march = !inside || view.force_ray_march;
    const Pass pass = target.scene_depth ? (ray_march ? kRenderRayMarchDepthPass : kRenderDepthPass)
                                         : (ray_march ? kRenderRayMarchPass : kRenderPass);
    const auto [framebuffer, viewport] = Destination(target);
    const GLuint depth = target.scene_depth ? target.scene_depth->texture : 0;
    // LastPassTimes reports this frame's composite draws only.
    std::fill(query_used_.begin() + kRenderPass, query_used_.end(), false);
    if (clouds != nullptr && depth != 0) {
        // The clouds in front of the host's geometry where its trace cells disagree.
        BindInputs();
        clouds->BindForComposite();
        glBindTextureUnit(kSceneDepthUnit, depth);
        clouds->MarchToGeometry();
    }
    Draw(pass, pass, framebuffer, viewport, clouds, depth);

    // The Sun and the Moon, each over its own box (one box when they overlap, so an eclipse is
    // not added twice).
    std::vector<glm::ivec4> boxes;
    const auto add_disk = [&](const glm::dvec3& direction, double radius) {
        std::optional<glm::ivec4> box = DiskBox(direction, radius, camera, size);
        if (!box) return;
        for (glm::ivec4& other : boxes) {
            if (Overlap(other, *box)) {
                other = Union(other, *box);
                return;
            }
        }
        boxes.push_back(*box);
    };
    if (scene.draw_sun_disk && SunDiskResolved(view, size)) {
        // In a solar eclipse the corona too, out to 6 solar radii (render.frag).
        const Lights::SolarEclipse& eclipse = scene.lights.eclipse;
        add_disk(SunDiskPlace(scene).direction, eclipse.active ? 6.0 * eclipse.sun_angular_radius
                                                               : atmosphere_.sun_angular_radius);
    }
    if (scene.moon.enabled) {
        add_disk(MoonDiskPlace(scene.moon).direction, scene.moon.angular_radius);
    }
    const Pass disk_pass = target.scene_depth ? kDiskDepthPass : kDiskPass;
    for (std::size_t i = 0; i < boxes.size(); ++i) {
        Draw(disk_pass, i == 0 ? disk_pass : kSecondDiskQuery, framebuffer, viewport, clouds, depth,
             boxes[i]);
    }
}

std::pair<GLuint, glm::ivec4> AtmospherePasses::Destination(const RenderTarget& target) const {
    if (target.framebuffer) return {*target.framebuffer, target.viewport};
    return {framebuffer_, glm::ivec4(0, 0, target.size())};
}

void AtmospherePasses::DrawPrecipitation(const PrecipitationDraw& p, const RenderTarget& target) {
    if (!(p.intensity > 0.0)) return;
    // Drops of one representative size, as many as the shaft's extinction sigma says
    // (sigma = n pi D^2 / 2: efficiency 2), at their terminal speed: raindrops of 1.5 mm
    // (5.5 m/s, Atlas et al. 1973), snowflakes of 5 mm (1 m/s). At most kMaxDrops in a
    // kBoxSize box around the camera, each drawn covering for the ones left out; the shader
    // keeps those in its inscribed sphere.
    constexpr double kBoxSize = 6.0;  // m
    constexpr double kMaxDrops = 32768.0;
    constexpr double kExposure = 1.0 / 60.0;  // s: a frame's
    const double diameter = p.snow ? 5e-3 : 1.5e-3;
    const glm::dvec3 velocity = p.wind - (p.snow ? 1.0 : 5.5) * p.up;
    const double sigma = clouds::PrecipitationExtinction(p.intensity, p.snow);
    const double count =
        sigma / (0.5 * std::numbers::pi * diameter * diameter) * kBoxSize * kBoxSize * kBoxSize;
    const double drawn = std::clamp(std::round(count), 1.0, kMaxDrops);
    // (v t - camera) mod L, + L / 2: a drop's wrapped place is (L h + phase) mod L - L / 2.
    glm::dvec3 phase = velocity * p.time_s - p.camera + 0.5 * kBoxSize;
    phase -= kBoxSize * glm::floor(phase / kBoxSize);

    const auto [framebuffer, viewport] = Destination(target);
    BindInputs();
    if (target.scene_depth) glBindTextureUnit(kSceneDepthUnit, target.scene_depth->texture);
    gl::SetDrawTarget(framebuffer, viewport, gl::Blend::kPremultiplied);
    gl::PrecipitationUniforms u{};
    for (int c = 0; c < 3; ++c) u.world_from_box[c] = glm::vec4(p.world_from_box[c], 0.0);
    u.phase = glm::vec3(phase);
    u.box_size = static_cast<float>(kBoxSize);
    u.box_velocity = glm::vec3(velocity);
    u.exposure_s = static_cast<float>(kExposure);
    u.diameter_m = static_cast<float>(diameter);
    u.coverage_scale = static_cast<float>(std::max(count / drawn, 1.0));
    u.snow = p.snow ? 1 : 0;
    u.has_scene_depth = target.scene_depth ? 1 : 0;
    glNamedBufferSubData(precipitation_buffer_, 0, sizeof(u), &u);
    glBindBufferBase(GL_UNIFORM_BUFFER, kPrecipitationBlockBinding, precipitation_buffer_);
    precipitation_program_.Use();
    glBindVertexArray(vertex_array_);
    glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(6.0 * drawn));
}

double AtmospherePasses::QueryMilliseconds(std::size_t query) const {
    if (!query_used_[query]) return 0.0;
    GLuint64 ns = 0;
    glGetQueryObjectui64v(queries_[query], GL_QUERY_RESULT, &ns);
    return static_cast<double>(ns) * 1e-6;
}

}  // namespace zenith::sky
