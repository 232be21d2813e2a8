#include "clouds/cloud_passes.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>

#include "bindings.h"
#include "clouds/cloud_parameters.h"
#include "gl/atmosphere_uniforms.h"
#include "gl/cloud_uniforms.h"
#include "gl/draw.h"
#include "gl/shader_library.h"
#include "gl/textures.h"
#include "zenith/base/error.h"
#include "zenith/sky/gl/error.h"

namespace zenith::sky {
namespace {

constexpr double kKm = 1000.0;
enum Query : std::size_t {
    kShadowQuery,
    kShadeQuery,
    kTraceQuery,
    kReconstructQuery,
    kGroundShadowQuery,
    kLightShaftQuery,
    kGeometryQuery
};

constexpr std::array<std::string_view, 4> kCloudParts = {
    "clouds/definitions.glsl", "clouds/functions.glsl", "clouds/march.glsl",
    "clouds/interface.glsl"};
constexpr std::array<std::string_view, 5> kGeometryListParts = {
    "clouds/definitions.glsl", "clouds/functions.glsl", "clouds/march.glsl",
    "clouds/interface.glsl", "clouds/geometry_list.glsl"};

// A noise volume as 8-bit UNORM texels, tiling (GL_REPEAT) on every axis.
GLuint UploadNoise(const clouds::NoiseVolume& volume) {
    const GLuint texture = gl::CreateTexture3D(volume.size, GL_RGBA8, GL_REPEAT);
    const GLenum format = volume.channels == 4 ? GL_RGBA : volume.channels == 3 ? GL_RGB : GL_RG;
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTextureSubImage3D(texture, 0, 0, 0, 0, volume.size.x, volume.size.y, volume.size.z, format,
                        GL_UNSIGNED_BYTE, volume.texels.data());
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    return texture;
}

GLuint UploadWeatherMap(const clouds::WeatherMap& map) {
    const GLuint texture =
        gl::CreateTexture2D(glm::ivec2(map.size), GL_RGBA32F, GL_REPEAT, GL_REPEAT);
    glTextureSubImage2D(texture, 0, 0, 0, map.size, map.size, GL_RGBA, GL_FLOAT, map.texels.data());
    return texture;
}

// A framebuffer drawing into `textures` (colour attachments 0, 1, ...).
GLuint CreateFramebuffer(std::initializer_list<GLuint> textures) {
    GLuint framebuffer = 0;
    glCreateFramebuffers(1, &framebuffer);
    std::vector<GLenum> buffers;
    for (GLuint texture : textures) {
        const GLenum attachment = GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(buffers.size());
        glNamedFramebufferTexture(framebuffer, attachment, texture, 0);
        buffers.push_back(attachment);
    }
    glNamedFramebufferDrawBuffers(framebuffer, static_cast<GLsizei>(buffers.size()),
                                  buffers.data());
    if (glCheckNamedFramebufferStatus(framebuffer, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
        throw gl::GlError("the cloud render targets are not a complete framebuffer");
    }
    return framebuffer;
}

void DeleteTextures(std::initializer_list<GLuint*> textures) {
    for (GLuint* t : textures) {
        if (*t != 0) glDeleteTextures(1, t);
        *t = 0;
    }
}

void DeleteFramebuffers(std::initializer_list<GLuint*> framebuffers) {
    for (GLuint* f : framebuffers) {
        if (*f != 0) glDeleteFramebuffers(1, f);
        *f = 0;
    }
}

// The ordered-dither (Bayer) index of (x, y) in an n x n matrix, n a power of two:
// M_2n(x, y) = 4 M_n(x mod n, y mod n) + M_2(x / n, y / n), M_2 = [0 2; 3 1]. Consecutive
// indices fall in different quadrants, so successive frames spread over the cell.
int BayerIndex(int x, int y, int n) {
    if (n == 1) return 0;
    const int h = n / 2;
    constexpr int kM2[2][2] = {{0, 2}, {3, 1}};  // [y][x]
    return 4 * BayerIndex(x % h, y % h, h) + kM2[y / h][x / h];
}

// The pixel of a block x block cell traced in frame k: Bayer order for powers of two,
// row-major otherwise.
glm::ivec2 TraceOffset(int block, long long frame) {
    const int k = static_cast<int>(frame % (block * block));
    if ((block & (block - 1)) != 0) return {k % block, k / block};
    for (int y = 0; y < block; ++y) {
        for (int x = 0; x < block; ++x) {
            if (BayerIndex(x, y, block) == k) return {x, y};
        }
    }
    return {0, 0};
}

// The base-2 radical inverse (Van der Corput), in [0, 1).
float VanDerCorput(unsigned long long n) {
    double result = 0.0, f = 0.5;
    for (; n != 0; n >>= 1, f *= 0.5) {
        if ((n & 1ULL) != 0) result += f;
    }
    return static_cast<float>(result);
}

// The programs of CloudPasses, in the order of BuildPrograms().
enum CloudProgram : std::size_t {
    kTraceProgram,
    kComputeTraceProgram,
    kReconstructProgram,
    kComputeReconstructProgram,
    kShadowMapProgram,
    kSunDepthProgram,
    kShadeTraceProgram,
    kComputeShadeTraceProgram,
    kShadeProgram,
    kGroundShadowProgram,
    kComputeGroundShadowProgram,
    kLightShaftProgram,
    kComputeLightShaftProgram,
    kGeometryListProgram,
    kGeometryMarchProgram,
    kCloudProgramCount
};

// Compute programs read the weather maps with constant indices (clouds/definitions.glsl).
constexpr std::string_view kComputeStage = "#define CLOUD_COMPUTE_STAGE 1\n";
static_assert(kCloudMaxLayers == 4, "clouds/interface.glsl's SampleRepeat2D reads 4 maps");

gl::Program BuildCloudProgram(CloudProgram program) {
    switch (program) {
        case kTraceProgram:
            return gl::FullscreenProgram("clouds/trace.frag", {}, kCloudParts);
        case kComputeTraceProgram:
            return gl::ComputeProgram("clouds/trace.comp", kCloudParts, kComputeStage);
        case kReconstructProgram:
            return gl::FullscreenProgram("clouds/reconstruct.frag", {}, kCloudParts);
        case kComputeReconstructProgram:
            return gl::ComputeProgram("clouds/reconstruct.comp", kCloudParts, kComputeStage);
        case kShadowMapProgram:
            return gl::ComputeProgram("clouds/shadow_map.comp", kCloudParts, kComputeStage);
        case kSunDepthProgram:
            return gl::ComputeProgram("clouds/sun_depth.comp", kCloudParts, kComputeStage);
        case kShadeTraceProgram:
            return gl::FullscreenProgram("clouds/sky_shade_trace.frag", {}, kCloudParts);
        case kComputeShadeTraceProgram:
            return gl::ComputeProgram("clouds/sky_shade_trace.comp", kCloudParts, kComputeStage);
        case kShadeProgram:
            return gl::ComputeProgram("clouds/sky_shade.comp", kCloudParts, kComputeStage);
        case kGroundShadowProgram:
            return gl::FullscreenProgram("clouds/ground_shadow.frag", {}, kCloudParts);
        case kComputeGroundShadowProgram:
            return gl::ComputeProgram("clouds/ground_shadow.comp", kCloudParts, kComputeStage);
        case kLightShaftProgram:
            return gl::FullscreenProgram("clouds/light_shafts.frag", {}, kCloudParts);
        case kComputeLightShaftProgram:
            return gl::ComputeProgram("clouds/light_shafts.comp", kCloudParts, kComputeStage);
        case kGeometryListProgram:
            return gl::FullscreenProgram("clouds/geometry_list.frag", {}, kGeometryListParts);
        case kGeometryMarchProgram:
            return gl::Program::Graphics(
                gl::ComposeShader("clouds/geometry_march.vert", {}, kGeometryListParts),
                gl::ComposeShader("clouds/geometry_march.frag", {}, kCloudParts),
                "clouds/geometry_march");
        case kCloudProgramCount:
            break;
    }
    throw gl::GlError("no cloud program " + std::to_string(program));
}

}  // namespace

std::span<const std::string_view> CloudShaderParts() { return kCloudParts; }

CloudPassStage ResolveCloudPassStage(CloudPassStage stage) {
    if (stage != CloudPassStage::kAuto) return stage;
    const auto* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    const bool llvmpipe = renderer != nullptr &&
                          std::string_view(renderer).find("llvmpipe") != std::string_view::npos;
    return llvmpipe ? CloudPassStage::kFragment : CloudPassStage::kCompute;
}

std::vector<gl::Program> CloudPasses::BuildPrograms() {
    std::vector<gl::Program> programs;
    for (std::size_t i = 0; i < kCloudProgramCount; ++i) {
        programs.push_back(BuildCloudProgram(static_cast<CloudProgram>(i)));
    }
    return programs;
}

CloudPasses::CloudPasses(const clouds::Weather& weather, const CloudSettings& settings,
                         const std::vector<clouds::WeatherMap>& maps,
                         const std::vector<double>& tops, const clouds::CloudNoise& noise)
    : weather_(weather),
      settings_(settings),
      compute_passes_(ResolveCloudPassStage(settings.pass_stage) == CloudPassStage::kCompute),
      trace_(BuildCloudProgram(compute_passes_ ? kComputeTraceProgram : kTraceProgram)),
      reconstruct_(
          BuildCloudProgram(compute_passes_ ? kComputeReconstructProgram : kReconstructProgram)),
      shadow_pass_(BuildCloudProgram(kShadowMapProgram)),
      sun_depth_pass_(BuildCloudProgram(kSunDepthProgram)),
      shade_trace_pass_(
          BuildCloudProgram(compute_passes_ ? kComputeShadeTraceProgram : kShadeTraceProgram)),
      shade_pass_(BuildCloudProgram(kShadeProgram)),
      ground_shadow_(
          BuildCloudProgram(compute_passes_ ? kComputeGroundShadowProgram : kGroundShadowProgram)),
      light_shafts_(
          BuildCloudProgram(compute_passes_ ? kComputeLightShaftProgram : kLightShaftProgram)),
      cloud_tops_(tops) {
    // The weather and settings were validated by AtmosphereRenderer::SetWeather.
    if (weather_.layers.size() > static_cast<std::size_t>(kCloudMaxLayers)) {
        throw ArgumentError(
            "weather '" + weather_.name + "' has " + std::to_string(weather_.layers.size()) +
            " layers (the renderer draws at most " + std::to_string(kCloudMaxLayers) + ")");
    }
    for (const clouds::WeatherMap& map : maps) weather_maps_.push_back(UploadWeatherMap(map));
    // The slab's tables for this phase function, here with the programs rather than in the
    // first frame's uniforms (tens of milliseconds once; every frame then looks them up).
    CloudSlabTables(settings_);
    shape_ = UploadNoise(noise.shape);
    detail_ = UploadNoise(noise.detail);
    glCreateBuffers(1, &uniforms_);
    glNamedBufferStorage(uniforms_, sizeof(gl::CloudUniforms), nullptr, GL_DYNAMIC_STORAGE_BIT);
    glCreateBuffers(1, &shade_);
    glNamedBufferStorage(shade_, sizeof(gl::LightUniforms), nullptr, 0);
    shadow_map_ = gl::CreateTexture2D(glm::ivec2(settings_.shadow_map_size));
    sun_depth_ = gl::CreateTexture3D(CloudSunDepthSize(settings_), GL_R32F);
    shade_directions_ = gl::CreateTexture2D(glm::ivec2(kCloudSkyShadeSize));
    shade_framebuffer_ = CreateFramebuffer({shade_directions_});
    glCreateVertexArrays(1, &vertex_array_);
    glCreateQueries(GL_TIME_ELAPSED, static_cast<GLsizei>(queries_.size()), queries_.data());
}

CloudPasses::~CloudPasses() {
    glDeleteQueries(static_cast<GLsizei>(queries_.size()), queries_.data());
    glDeleteVertexArrays(1, &vertex_array_);
    DeleteFramebuffers({&trace_framebuffer_, &history_framebuffer_[0], &history_framebuffer_[1],
                        &shade_framebuffer_, &ground_shadow_framebuffer_, &shaft_framebuffer_,
                        &geometry_framebuffer_, &geometry_list_framebuffer_});
    DeleteTextures({&shape_, &detail_, &trace_color_, &trace_depth_, &trace_profile_,
                    &ground_shadow_color_, &history_color_[0], &history_color_[1], &shadow_map_,
                    &sun_depth_, &shade_directions_, &geometry_color_});
    glDeleteBuffers(1, &geometry_list_buffer_);
    glDeleteTextures(static_cast<GLsizei>(air_shadow_color_.size()), air_shadow_color_.data());
    for (GLuint& t : weather_maps_) glDeleteTextures(1, &t);
    glDeleteBuffers(1, &uniforms_);
    glDeleteBuffers(1, &shade_);
}

void CloudPasses::Resize(glm::ivec2 size) {
    DeleteFramebuffers({&trace_framebuffer_, &ground_shadow_framebuffer_, &shaft_framebuffer_,
                        &history_framebuffer_[0], &history_framebuffer_[1], &geometry_framebuffer_,
                        &geometry_list_framebuffer_});
    DeleteTextures({&trace_color_, &trace_depth_, &trace_profile_, &ground_shadow_color_,
                    &history_color_[0], &history_color_[1], &geometry_color_});
    glDeleteBuffers(1, &geometry_list_buffer_);
    geometry_list_buffer_ = 0;
    glDeleteTextures(static_cast<GLsizei>(air_shadow_color_.size()), air_shadow_color_.data());
    size_ = size;
    const int block = settings_.block;
    trace_size_ = (size + block - 1) / block;
    trace_color_ = gl::CreateTexture2D(trace_size_);
    trace_depth_ = gl::CreateTexture2D(trace_size_, GL_RG32F);
    trace_profile_ = gl::CreateTexture2D(trace_size_);
    trace_framebuffer_ = CreateFramebuffer({trace_color_, trace_depth_, trace_profile_});
    ground_shadow_color_ = gl::CreateTexture2D(trace_size_);
    ground_shadow_framebuffer_ = CreateFramebuffer({ground_shadow_color_});
    shaft_size_ = (trace_size_ + kCloudLightShaftCell - 1) / kCloudLightShaftCell;
    for (GLuint& texture : air_shadow_color_) texture = gl::CreateTexture2D(shaft_size_);
    shaft_framebuffer_ = CreateFramebuffer(
        {air_shadow_color_[0], air_shadow_color_[1], air_shadow_color_[2], air_shadow_color_[3]});
    for (std::size_t i = 0; i < 2; ++i) {
        history_color_[i] = gl::CreateTexture2D(size);
        history_framebuffer_[i] = CreateFramebuffer({history_color_[i]});
    }
    previous_.reset();
}

void CloudPasses::UploadUniforms(const Atmosphere& atmosphere, const Camera& camera,
                                 const Lights& lights, const CloudView& view, bool history_valid,
                                 bool update) {
    gl::CloudUniforms u{};
    std::vector<gl::CloudLayerUniforms> layers;
    for (std::size_t i = 0; i < weather_.layers.size(); ++i) {
        layers.push_back(MakeCloudLayerParameters<gl::CloudLayerUniforms>(
            weather_.layers[i], cloud_tops_[i], settings_, atmosphere.bottom_radius, view.time));
        u.layers[i] = layers.back();
    }
    u.scattering = MakeCloudScatteringParameters<gl::CloudScatteringUniforms>(
        settings_, atmosphere.ground_albedo);
    u.march = MakeCloudMarchParameters<gl::CloudMarchUniforms>(settings_);
    // The volume stays where it was made until the next update.
    if (update) sun_depth_camera_ = view.weather_from_world * camera.position / kKm;
    SetCloudSunDepthFrame(u.march, settings_, layers, sun_depth_camera_);
    u.lights =
        MakeCloudLightSet<gl::LightUniforms>(lights, camera.position, view.weather_from_world);
    for (int i = 0; i < 3; ++i) {
        u.weather_from_frame[i] = glm::vec4(glm::vec3(view.weather_from_world[i]), 0.0f);
    }
    if (previous_) {
        // This frame's vectors -> the weather frame -> the previous frame -> its view.
        const glm::dmat3 previous_from_current =
            glm::transpose(previous_->weather_from_world) * view.weather_from_world;
        const glm::dmat3 previous_view =
            glm::transpose(previous_->camera.world_from_view) * previous_from_current;
        for (int i = 0; i < 3; ++i) {
            u.previous_view_from_frame[i] = glm::vec4(glm::vec3(previous_view[i]), 0.0f);
        }
        u.previous_camera_offset_km = glm::vec3(
            (glm::transpose(previous_from_current) * previous_->camera.position - camera.position) /
            kKm);
        u.previous_tan_half_fov =
            static_cast<float>(std::tan(0.5 * previous_->camera.vertical_fov));
        u.previous_aspect = static_cast<float>(previous_->camera.aspect);
    }
    const int block = settings_.block;
    u.trace_size = trace_size_;
    u.trace_offset = TraceOffset(block, frame_index_);
    u.block = block;
    u.layer_count = static_cast<int>(weather_.layers.size());
    u.light_count = u.lights.count;
    u.history_valid = history_valid ? 1 : 0;
    u.frame_jitter = VanDerCorput(static_cast<unsigned long long>(frame_index_ / (block * block)));
    u.history_weight = static_cast<float>(settings_.history_weight);
    u.aerial_perspective_steps = settings_.aerial_perspective_steps;
    u.shadow_map_extent_km = static_cast<float>(settings_.shadow_map_extent / kKm);
    u.shadow_map_size = settings_.shadow_map_size;
    u.shadow_map_steps = settings_.shadow_map_steps;
    u.sky_shade_size = kCloudSkyShadeSize;
    const std::vector<int> order =
        CloudLayerOrder(weather_, glm::length(camera.position) - atmosphere.bottom_radius);
    const std::vector<int> ground_order = CloudLayerOrder(weather_, 0.0);
    for (std::size_t i = 0; i < order.size(); ++i) {
        u.layer_order[static_cast<int>(i)] = order[i];
        u.ground_layer_order[static_cast<int>(i)] = ground_order[i];
    }
    glNamedBufferSubData(uniforms_, 0, sizeof(u), &u);
}

void CloudPasses::BindTextures() const {
    glBindBufferBase(GL_UNIFORM_BUFFER, kCloudBlockBinding, uniforms_);
    glBindTextureUnit(kShapeNoiseUnit, shape_);
    glBindTextureUnit(kDetailNoiseUnit, detail_);
    glBindTextureUnit(kCloudSunDepthUnit, sun_depth_);
    for (GLuint i = 0; i < static_cast<GLuint>(kCloudMaxLayers); ++i) {
        // Units of absent layers get the first map, so every sampler is complete.
        glBindTextureUnit(kWeatherMapsUnit + i,
                          i < weather_maps_.size() ? weather_maps_[i] : weather_maps_[0]);
    }
}

void CloudPasses::Prepare(const Atmosphere& atmosphere, const Camera& camera, const Lights& lights,
                          const CloudView& view, GLuint light_buffer) {
    // A cut starts the jitter sequence over too, so the frame does not depend on what came
    // before it (replayed frames match whether rendered in order, resumed or sharded).
    if (view.reset_history) frame_index_ = 0;
    const bool history_valid = previous_.has_value() && !view.reset_history;
    // The shadow map, the sun-depth volume and the shade follow the Sun, the wind and the ground
    // below the camera, which move little in shadow_map_interval frames.
    const bool update = !history_valid || frame_index_ % settings_.shadow_map_interval == 0;
    UploadUniforms(atmosphere, camera, lights, view, history_valid, update);
    BindTextures();
    query_used_.fill(false);

    if (update) {
        shadow_pass_.Use();
        glBindImageTexture(kOutputImageUnit, shadow_map_, 0, GL_FALSE, 0, GL_WRITE_ONLY,
                           GL_RGBA32F);
        glBeginQuery(GL_TIME_ELAPSED, queries_[kShadowQuery]);
        const GLuint groups = static_cast<GLuint>(
            (settings_.shadow_map_size + kShadowMapGroupSize - 1) / kShadowMapGroupSize);
        glDispatchCompute(groups, groups, 1);
        UpdateSunDepth();
        glEndQuery(GL_TIME_ELAPSED);
        query_used_[kShadowQuery] = true;
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT |
                        GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);

        glBeginQuery(GL_TIME_ELAPSED, queries_[kShadeQuery]);
        RunCellPass(shade_trace_pass_, shade_framebuffer_, {{shade_directions_, GL_RGBA32F}},
                    glm::ivec2(kCloudSkyShadeSize), 0);
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
        shade_pass_.Use();
        glBindImageTexture(kShadeDirectionsImageUnit, shade_directions_, 0, GL_FALSE, 0,
                           GL_READ_ONLY, GL_RGBA32F);
        glBindImageTexture(kShadowMapImageUnit, shadow_map_, 0, GL_FALSE, 0, GL_READ_ONLY,
                           GL_RGBA32F);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kLightStorageBinding, shade_);
        glDispatchCompute(1, 1, 1);
        glEndQuery(GL_TIME_ELAPSED);
        query_used_[kShadeQuery] = true;
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kLightStorageBinding, 0);
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    }
    // Every frame: the light block was just uploaded without the clouds; the last shade goes
    // into its cloud members, which the later passes read as uniforms. So does the cloud
    // block's, for the cloud passes after the shade's own trace (which read cloud_shaded 0).
    CopyShade(light_buffer, 0);
    CopyShade(uniforms_, offsetof(gl::CloudUniforms, lights));
}

void CloudPasses::CopyShade(GLuint buffer, GLintptr lights_offset) const {
    // The cloud members only: the eclipse's follow them.
    constexpr GLintptr kCloudMembers = offsetof(gl::LightUniforms, cloud_base);
    constexpr GLintptr kCloudMembersEnd = offsetof(gl::LightUniforms, eclipse_sun_illuminance);
    glCopyNamedBufferSubData(shade_, buffer, kCloudMembers, lights_offset + kCloudMembers,
                             kCloudMembersEnd - kCloudMembers);
}

void CloudPasses::UpdateSunDepth() const {
    if (settings_.sun_depth_size == 0) return;
    sun_depth_pass_.Use();
    glBindImageTexture(kOutputImageUnit, sun_depth_, 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_R32F);
    const GLuint groups = static_cast<GLuint>((settings_.sun_depth_size + kShadowMapGroupSize - 1) /
                                              kShadowMapGroupSize);
    // From the top level down: each reads the one above it through the sampler.
    for (int level = settings_.sun_depth_levels - 1; level >= 0; --level) {
        glProgramUniform1i(sun_depth_pass_.name(), gl::kSunDepthLevelLocation, level);
        glDispatchCompute(groups, groups, 1);
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
    }
}

void CloudPasses::RunCellPass(const gl::Program& program, GLuint framebuffer,
                              std::initializer_list<PassTarget> targets, glm::ivec2 size,
                              GLuint query) const {
    if (!compute_passes_) {
        gl::DrawFullscreen(program, vertex_array_, framebuffer, glm::ivec4(0, 0, size),
                           gl::Blend::kReplace, query);
        return;
    }
    GLuint unit = kCloudPassImageUnit;
    for (const PassTarget& target : targets) {
        glBindImageTexture(unit++, target.texture, 0, GL_FALSE, 0, GL_WRITE_ONLY, target.format);
    }
    program.Use();
    if (query != 0) glBeginQuery(GL_TIME_ELAPSED, query);
    const glm::ivec2 groups = (size + kCloudPassGroupSize - 1) / kCloudPassGroupSize;
    glDispatchCompute(static_cast<GLuint>(groups.x), static_cast<GLuint>(groups.y), 1);
    if (query != 0) glEndQuery(GL_TIME_ELAPSED);
    // What the images hold is then ready for the passes that sample or load it, and read-backs.
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT |
                    GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
}

void CloudPasses::Render(const Atmosphere& atmosphere, const Camera& camera, const Lights& lights,
                         glm::ivec2 size, const CloudView& view) {
    if (size != size_) Resize(size);
    const bool history_valid = previous_.has_value() && !view.reset_history;
    // The sun-depth volume stays around the camera Prepare made it for.
    UploadUniforms(atmosphere, camera, lights, view, history_valid, /*update=*/false);
    CopyShade(uniforms_, offsetof(gl::CloudUniforms, lights));
    BindTextures();

    RunCellPass(
        trace_, trace_framebuffer_,
        {{trace_color_, GL_RGBA32F}, {trace_depth_, GL_RG32F}, {trace_profile_, GL_RGBA32F}},
        trace_size_, queries_[kTraceQuery]);
    query_used_[kTraceQuery] = true;

    const std::size_t previous = current_;
    current_ = 1 - current_;
    glBindTextureUnit(kCloudTraceUnit, trace_color_);
    glBindTextureUnit(kCloudTraceDepthUnit, trace_depth_);
    glBindTextureUnit(kCloudHistoryUnit, history_color_[previous]);
    RunCellPass(reconstruct_, history_framebuffer_[current_],
                {{history_color_[current_], GL_RGBA32F}}, size_, queries_[kReconstructQuery]);
    query_used_[kReconstructQuery] = true;

    glBindTextureUnit(kCloudShadowMapUnit, shadow_map_);
    RunCellPass(ground_shadow_, ground_shadow_framebuffer_, {{ground_shadow_color_, GL_RGBA32F}},
                trace_size_, queries_[kGroundShadowQuery]);
    query_used_[kGroundShadowQuery] = true;
    if (settings_.light_shaft_steps > 0) {
        RunCellPass(light_shafts_, shaft_framebuffer_,
                    {{air_shadow_color_[0], GL_RGBA32F},
                     {air_shadow_color_[1], GL_RGBA32F},
                     {air_shadow_color_[2], GL_RGBA32F},
                     {air_shadow_color_[3], GL_RGBA32F}},
                    shaft_size_, queries_[kLightShaftQuery]);
        query_used_[kLightShaftQuery] = true;
    }

    previous_ = Previous{camera, view.weather_from_world};
    ++frame_index_;
}

void CloudPasses::MarchToGeometry() {
    if (!geometry_list_) {
        geometry_list_.emplace(BuildCloudProgram(kGeometryListProgram));
        geometry_march_.emplace(BuildCloudProgram(kGeometryMarchProgram));
    }
    if (geometry_color_ == 0) {
        geometry_color_ = gl::CreateTexture2D(size_);
        geometry_framebuffer_ = CreateFramebuffer({geometry_color_});
        // The list pass writes no colour: a framebuffer without attachments, the trace's size.
        glCreateFramebuffers(1, &geometry_list_framebuffer_);
        glNamedFramebufferParameteri(geometry_list_framebuffer_, GL_FRAMEBUFFER_DEFAULT_WIDTH,
                                     trace_size_.x);
        glNamedFramebufferParameteri(geometry_list_framebuffer_, GL_FRAMEBUFFER_DEFAULT_HEIGHT,
                                     trace_size_.y);
        // Room for every cell (4 bytes each, 230 kB at 1280 x 720 and block 4), so that which
        // cells are marched never depends on the order in which the GPU's invocations reach the
        // list's counter: with fewer slots than cells found, an NVIDIA GPU marched a different
        // subset each frame and the rest flickered in 4 x 4 blocks. The march's cost is bounded
        // by the frame's pixels, each marched once at most.
        geometry_capacity_ = static_cast<GLuint>(trace_size_.x * trace_size_.y);
        glCreateBuffers(1, &geometry_list_buffer_);
        glNamedBufferStorage(geometry_list_buffer_,
                             static_cast<GLsizeiptr>(offsetof(gl::CloudGeometryList, cells) +
                                                     sizeof(std::uint32_t) * geometry_capacity_),
                             nullptr, GL_DYNAMIC_STORAGE_BIT);
    }
    const gl::CloudGeometryList header{0, 1, 0, 0, geometry_capacity_, {0, 0, 0}, {}};
    glNamedBufferSubData(geometry_list_buffer_, 0, offsetof(gl::CloudGeometryList, cells), &header);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kCloudGeometryListBinding, geometry_list_buffer_);

    const float unmarched[4] = {0.0f, 0.0f, 0.0f, -1.0f};
    glClearTexImage(geometry_color_, 0, GL_RGBA, GL_FLOAT, unmarched);

    glBeginQuery(GL_TIME_ELAPSED, queries_[kGeometryQuery]);
    gl::DrawFullscreen(*geometry_list_, vertex_array_, geometry_list_framebuffer_,
                       glm::ivec4(0, 0, trace_size_), gl::Blend::kReplace);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
    gl::SetDrawTarget(geometry_framebuffer_, glm::ivec4(0, 0, size_), gl::Blend::kReplace);
    geometry_march_->Use();
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, geometry_list_buffer_);
    glDrawArraysIndirect(GL_TRIANGLES, nullptr);
    glEndQuery(GL_TIME_ELAPSED);
    query_used_[kGeometryQuery] = true;
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kCloudGeometryListBinding, 0);
}

void CloudPasses::BindForComposite() const {
    glBindBufferBase(GL_UNIFORM_BUFFER, kCloudBlockBinding, uniforms_);
    glBindTextureUnit(kCloudTraceUnit, trace_color_);
    glBindTextureUnit(kCloudTraceDepthUnit, trace_depth_);
    glBindTextureUnit(kCloudTraceProfileUnit, trace_profile_);
    glBindTextureUnit(kCloudHistoryUnit, history_color_[current_]);
    glBindTextureUnit(kCloudGroundShadowUnit, ground_shadow_color_);
    glBindTextureUnit(kCloudGeometryUnit, geometry_color_);
    for (std::size_t k = 0; k < air_shadow_color_.size(); ++k) {
        glBindTextureUnit(kCloudAirShadowUnit + static_cast<GLuint>(k), air_shadow_color_[k]);
    }
}

void CloudPasses::BindForTrace() const {
    BindTextures();
    glBindTextureUnit(kCloudShadowMapUnit, shadow_map_);
}

LutImage CloudPasses::ReadClouds() const {
    if (size_.x == 0) throw gl::GlError("ReadClouds before any Render with weather");
    return gl::ReadTexture(history_color_[current_], glm::ivec3(size_, 1));
}

LutImage CloudPasses::ReadSunDepth() const {
    return gl::ReadTexture(sun_depth_, CloudSunDepthSize(settings_));
}

LutImage CloudPasses::ReadShadowMap() const {
    return gl::ReadTexture(shadow_map_, glm::ivec3(glm::ivec2(settings_.shadow_map_size), 1));
}

std::array<double, CloudPasses::kPassCount> CloudPasses::LastPassTimes() const {
    std::array<double, kPassCount> times{};
    for (std::size_t i = 0; i < times.size(); ++i) {
        if (!query_used_[i]) continue;
        GLuint64 ns = 0;
        glGetQueryObjectui64v(queries_[i], GL_QUERY_RESULT, &ns);
        times[i] = static_cast<double>(ns) * 1e-6;
    }
    return times;
}

}  // namespace zenith::sky
