// The GL contract between the renderer's C++ and its GLSL, checked on the linked programs: for
// every program the renderer builds (BuildRendererPrograms), every uniform and storage block's
// binding and size, and every member's offset, type and array stride as the driver laid them out
// (glGetProgramResourceiv), against the C++ mirrors' offsetof/sizeof; every sampler's and image's
// unit and every compute pass's work-group size against bindings.glsl. The static_asserts in the
// mirrors pin a few offsets to numbers; this closes the loop: a member moved, retyped or renamed
// in one language only fails here.
#include <glad/gl.h>
#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <glm/glm.hpp>
#include <map>
#include <set>
#include <string>
#include <type_traits>
#include <vector>

#include "bindings.h"
#include "gl/atmosphere_uniforms.h"
#include "gl/cloud_uniforms.h"
#include "gl/display_uniforms.h"
#include "gl_test_support.h"
#include "renderer_programs.h"

namespace zenith::sky::gl {
namespace {

// GL's type of a block member for the C++ type that mirrors it.
template <typename T>
constexpr GLenum GlType() {
    if constexpr (std::is_same_v<T, float>)
        return GL_FLOAT;
    else if constexpr (std::is_same_v<T, int>)
        return GL_INT;
    else if constexpr (std::is_same_v<T, std::uint32_t>)
        return GL_UNSIGNED_INT;
    else if constexpr (std::is_same_v<T, glm::vec2>)
        return GL_FLOAT_VEC2;
    else if constexpr (std::is_same_v<T, glm::vec3>)
        return GL_FLOAT_VEC3;
    else if constexpr (std::is_same_v<T, glm::vec4>)
        return GL_FLOAT_VEC4;
    else if constexpr (std::is_same_v<T, glm::ivec2>)
        return GL_INT_VEC2;
    else if constexpr (std::is_same_v<T, glm::ivec3>)
        return GL_INT_VEC3;
    else if constexpr (std::is_same_v<T, glm::ivec4>)
        return GL_INT_VEC4;
    else
        static_assert(sizeof(T) == 0, "a mirror member type this test does not know");
}

struct Expected {
    std::size_t offset = 0;
    GLenum type = 0;
    std::size_t array_stride = 0;  // 0: not an array
};
// By the name GL gives the member ("atmosphere.mie_g", "world_from_view[0]").
using Layout = std::map<std::string, Expected>;

// A member of C++ type M at `offset`; an array of a basic type is one GL resource, "name[0]".
template <typename M>
void Add(Layout& layout, const std::string& name, std::size_t offset) {
    if constexpr (std::is_array_v<M>) {
        using E = std::remove_extent_t<M>;
        layout[name + "[0]"] = {offset, GlType<E>(), sizeof(E)};
    } else {
        layout[name] = {offset, GlType<M>(), 0};
    }
}

// GLSL member `glsl` mirrored by Struct::member, in a struct at `base`.
#define ZENITH_MEMBER(glsl, Struct, member) \
    Add<decltype(Struct::member)>(layout, prefix + glsl, base + offsetof(Struct, member))
// The same name on both sides.
#define ZENITH_SAME(Struct, member) ZENITH_MEMBER(#member, Struct, member)

void AddAtmosphere(Layout& layout, const std::string& prefix, std::size_t base) {
    using S = AtmosphereUniforms;
    ZENITH_SAME(S, rayleigh_scattering);
    ZENITH_SAME(S, rayleigh_scale_height);
    ZENITH_SAME(S, mie_scattering);
    ZENITH_SAME(S, mie_scale_height);
    ZENITH_SAME(S, mie_extinction);
    ZENITH_SAME(S, mie_g);
    ZENITH_SAME(S, absorption_extinction);
    ZENITH_SAME(S, absorption_center);
    ZENITH_SAME(S, ground_albedo);
    ZENITH_SAME(S, absorption_half_width);
    ZENITH_SAME(S, solar_illuminance);
    ZENITH_SAME(S, sun_angular_radius);
    ZENITH_SAME(S, bottom_radius);
    ZENITH_SAME(S, top_radius);
    ZENITH_SAME(S, padding0);
    ZENITH_SAME(S, padding1);
}

void AddLights(Layout& layout, const std::string& prefix, std::size_t base) {
    using S = LightUniforms;
    for (int i = 0; i < kMaxLights; ++i) {
        const std::string light = prefix + "light[" + std::to_string(i) + "].";
        const std::size_t at =
            base + offsetof(S, light) + static_cast<std::size_t>(i) * sizeof(S::Light);
        Add<decltype(S::Light::direction)>(layout, light + "direction",
                                           at + offsetof(S::Light, direction));
        Add<decltype(S::Light::padding0)>(layout, light + "padding0",
                                          at + offsetof(S::Light, padding0));
        Add<decltype(S::Light::illuminance)>(layout, light + "illuminance",
                                             at + offsetof(S::Light, illuminance));
        Add<decltype(S::Light::padding1)>(layout, light + "padding1",
                                          at + offsetof(S::Light, padding1));
    }
    ZENITH_SAME(S, count);
    ZENITH_SAME(S, cloud_base);
    ZENITH_SAME(S, cloud_direct);
    ZENITH_SAME(S, cloud_sky);
    ZENITH_SAME(S, cloud_luminance);
    ZENITH_SAME(S, cloud_ground_sky);
    ZENITH_SAME(S, cloud_ground_luminance);
    ZENITH_SAME(S, cloud_shaded);
    ZENITH_SAME(S, eclipse_sun_illuminance);
    ZENITH_SAME(S, eclipse);
    ZENITH_SAME(S, eclipse_axis_point);
    ZENITH_SAME(S, eclipse_axis_distance);
    ZENITH_SAME(S, eclipse_sun_radius);
    ZENITH_SAME(S, eclipse_moon_radius);
    ZENITH_SAME(S, padding1);
    ZENITH_SAME(S, padding2);
    ZENITH_SAME(S, eclipse_around_illuminance);
    ZENITH_SAME(S, padding3);
    ZENITH_SAME(S, eclipse_limb);
    ZENITH_SAME(S, night_ground_irradiance);
    ZENITH_SAME(S, padding4);
}

void AddSettings(Layout& layout, const std::string& prefix, std::size_t base) {
    using S = SettingsUniforms;
    ZENITH_SAME(S, transmittance_size);
    ZENITH_SAME(S, multiple_scattering_size);
    ZENITH_SAME(S, irradiance_size);
    ZENITH_SAME(S, sky_view_size);
    ZENITH_SAME(S, aerial_perspective_size);
    ZENITH_SAME(S, transmittance_steps);
    ZENITH_SAME(S, multiple_scattering_directions_sqrt);
    ZENITH_SAME(S, multiple_scattering_steps);
    ZENITH_SAME(S, irradiance_directions_sqrt);
    ZENITH_SAME(S, irradiance_steps);
    ZENITH_SAME(S, sky_view_steps);
    ZENITH_SAME(S, aerial_perspective_steps);
    ZENITH_SAME(S, aerial_perspective_range_km);
}

void AddPrecipitation(Layout& layout, const std::string& prefix, std::size_t base) {
    using S = PrecipitationUniforms;
    ZENITH_SAME(S, world_from_box);
    ZENITH_SAME(S, phase);
    ZENITH_SAME(S, box_size);
    ZENITH_SAME(S, box_velocity);
    ZENITH_SAME(S, exposure_s);
    ZENITH_SAME(S, diameter_m);
    ZENITH_SAME(S, coverage_scale);
    ZENITH_SAME(S, snow);
    ZENITH_SAME(S, has_scene_depth);
}

void AddFrame(Layout& layout, const std::string& prefix, std::size_t base) {
    using S = FrameUniforms;
    ZENITH_SAME(S, camera_km);
    ZENITH_SAME(S, tan_half_fov);
    ZENITH_SAME(S, world_from_view);
    ZENITH_SAME(S, output_size);
    ZENITH_SAME(S, aspect);
    ZENITH_SAME(S, ray_march_steps);
    ZENITH_SAME(S, viewport_x);
    ZENITH_SAME(S, draw_sun_disk);
    ZENITH_SAME(S, camera_altitude_km);
    ZENITH_SAME(S, moon_enabled);
    ZENITH_SAME(S, moon_direction);
    ZENITH_SAME(S, moon_angular_radius);
    ZENITH_SAME(S, moon_albedo);
    ZENITH_SAME(S, stars_enabled);
    ZENITH_SAME(S, horizon_zenith);
    ZENITH_SAME(S, cos_sun_radius);
    ZENITH_SAME(S, sky_view_up);
    ZENITH_SAME(S, cos_moon_radius);
    ZENITH_SAME(S, sky_view_x);
    ZENITH_SAME(S, viewport_y);
    ZENITH_SAME(S, scene_near_m);
    ZENITH_SAME(S, scene_depth_offset);
    ZENITH_SAME(S, scene_depth_slope);
    ZENITH_SAME(S, scene_depth_reversed);
    ZENITH_SAME(S, moon_sunlight);
    ZENITH_SAME(S, night_sky_enabled);
    ZENITH_SAME(S, star_visibility);
    ZENITH_SAME(S, environment_size);
    ZENITH_SAME(S, sun_disk_scale);
    ZENITH_SAME(S, moon_disk_scale);
    ZENITH_SAME(S, sun_disk_direction);
    ZENITH_SAME(S, frame_padding1);
    ZENITH_SAME(S, moon_disk_direction);
    ZENITH_SAME(S, frame_padding2);
    ZENITH_SAME(S, moon_shadow);
    ZENITH_SAME(S, moon_shadow_axis_min_km);
    ZENITH_SAME(S, moon_shadow_axis_max_km);
    ZENITH_SAME(S, moon_distance_km);
    ZENITH_SAME(S, moon_shadow_enabled);
}

void AddCloudLayer(Layout& layout, const std::string& prefix, std::size_t base) {
    using S = CloudLayerUniforms;
    ZENITH_SAME(S, bottom_radius);
    ZENITH_SAME(S, base_altitude);
    ZENITH_SAME(S, top_altitude);
    ZENITH_SAME(S, weather_period);
    ZENITH_SAME(S, shape_period);
    ZENITH_SAME(S, shape_period_y);
    ZENITH_SAME(S, detail_period);
    ZENITH_SAME(S, erosion_strength);
    ZENITH_SAME(S, wind_offset_x);
    ZENITH_SAME(S, wind_offset_y);
    ZENITH_SAME(S, cloud_top_altitude);
    ZENITH_SAME(S, extinction_scale);
    ZENITH_SAME(S, ground_fog);
    ZENITH_SAME(S, precipitation_shaft);
    ZENITH_SAME(S, shear_x);
    ZENITH_SAME(S, shear_y);
}

void AddCloudScattering(Layout& layout, const std::string& prefix, std::size_t base) {
    using S = CloudScatteringUniforms;
    ZENITH_SAME(S, forward_g);
    ZENITH_SAME(S, backward_g);
    ZENITH_SAME(S, lobe_weight);
    ZENITH_SAME(S, albedo);
    ZENITH_SAME(S, multiple_scattering);
    ZENITH_SAME(S, ground_albedo);
    ZENITH_SAME(S, padding1);
    ZENITH_SAME(S, padding2);
    ZENITH_SAME(S, slab_tables);
}

void AddCloudMarch(Layout& layout, const std::string& prefix, std::size_t base) {
    using S = CloudMarchUniforms;
    ZENITH_SAME(S, extinction);
    ZENITH_SAME(S, min_step);
    ZENITH_SAME(S, max_steps);
    ZENITH_SAME(S, shadow_steps);
    ZENITH_SAME(S, shadow_first_step);
    ZENITH_SAME(S, shadow_growth);
    ZENITH_SAME(S, ambient_scale);
    ZENITH_SAME(S, thick_step_refinement);
    ZENITH_SAME(S, min_transmittance);
    ZENITH_SAME(S, max_distance);
    ZENITH_SAME(S, oriented_slabs);
    ZENITH_SAME(S, light_shaft_steps);
    ZENITH_SAME(S, column_steps);
    ZENITH_SAME(S, sun_depth_center_x);
    ZENITH_SAME(S, sun_depth_center_y);
    ZENITH_SAME(S, sun_depth_extent);
    ZENITH_SAME(S, sun_depth_base);
    ZENITH_SAME(S, sun_depth_top);
    ZENITH_SAME(S, padding1);
    ZENITH_SAME(S, padding2);
}

void AddCloud(Layout& layout, const std::string& prefix, std::size_t base) {
    using S = CloudUniforms;
    for (int i = 0; i < kCloudMaxLayers; ++i) {
        AddCloudLayer(
            layout, prefix + "cloud_layers[" + std::to_string(i) + "].",
            base + offsetof(S, layers) + static_cast<std::size_t>(i) * sizeof(CloudLayerUniforms));
    }
    AddCloudScattering(layout, prefix + "cloud_scattering.", base + offsetof(S, scattering));
    AddCloudMarch(layout, prefix + "cloud_march.", base + offsetof(S, march));
    AddLights(layout, prefix + "cloud_lights.", base + offsetof(S, lights));
    ZENITH_SAME(S, weather_from_frame);
    ZENITH_SAME(S, previous_view_from_frame);
    ZENITH_SAME(S, previous_camera_offset_km);
    ZENITH_SAME(S, previous_tan_half_fov);
    ZENITH_SAME(S, trace_size);
    ZENITH_SAME(S, trace_offset);
    ZENITH_SAME(S, block);
    ZENITH_MEMBER("cloud_layer_count", S, layer_count);
    ZENITH_MEMBER("cloud_light_count", S, light_count);
    ZENITH_SAME(S, history_valid);
    ZENITH_SAME(S, frame_jitter);
    ZENITH_SAME(S, history_weight);
    ZENITH_SAME(S, previous_aspect);
    ZENITH_MEMBER("cloud_aerial_perspective_steps", S, aerial_perspective_steps);
    ZENITH_SAME(S, shadow_map_extent_km);
    ZENITH_SAME(S, shadow_map_size);
    ZENITH_SAME(S, shadow_map_steps);
    ZENITH_SAME(S, sky_shade_size);
    ZENITH_MEMBER("cloud_layer_order", S, layer_order);
    ZENITH_MEMBER("cloud_ground_layer_order", S, ground_layer_order);
}

void AddDisplayStorage(Layout& layout, const std::string& prefix, std::size_t base) {
    using S = DisplayStorage;
    ZENITH_MEMBER("display_ev100", S, ev100);
    ZENITH_MEMBER("display_target_ev100", S, target_ev100);
    ZENITH_MEMBER("display_log2_average", S, log2_average);
    ZENITH_MEMBER("display_valid", S, valid);
    ZENITH_MEMBER("display_histogram", S, histogram);
}

void AddEnvironmentSh(Layout& layout, const std::string& prefix, std::size_t base) {
    using S = EnvironmentShStorage;
    ZENITH_SAME(S, environment_sh);
}

void AddCloudGeometryList(Layout& layout, const std::string& prefix, std::size_t base) {
    using S = CloudGeometryList;
    ZENITH_MEMBER("geometry_vertices", S, vertices);
    ZENITH_MEMBER("geometry_instances", S, instances);
    ZENITH_MEMBER("geometry_first", S, first);
    ZENITH_MEMBER("geometry_base_instance", S, base_instance);
    ZENITH_MEMBER("geometry_capacity", S, capacity);
    ZENITH_MEMBER("geometry_unused", S, unused);
    ZENITH_MEMBER("geometry_cells", S, cells);
}

#undef ZENITH_SAME
#undef ZENITH_MEMBER

struct BlockMirror {
    GLenum block_interface;   // GL_UNIFORM_BLOCK or GL_SHADER_STORAGE_BLOCK
    GLenum member_interface;  // GL_UNIFORM or GL_BUFFER_VARIABLE
    int binding;
    std::size_t size;
    Layout members;
};

template <typename Mirror>
BlockMirror MakeBlock(GLenum block_interface, int binding,
                      void (*add)(Layout&, const std::string&, std::size_t),
                      const std::string& prefix) {
    BlockMirror block{
        block_interface,
        block_interface == GL_UNIFORM_BLOCK ? GLenum{GL_UNIFORM} : GLenum{GL_BUFFER_VARIABLE},
        binding,
        sizeof(Mirror),
        {}};
    add(block.members, prefix, 0);
    return block;
}

// Every block of bindings.glsl, by its GLSL block name, with its C++ mirror.
std::map<std::string, BlockMirror> Mirrors() {
    std::map<std::string, BlockMirror> m;
    m.emplace("AtmosphereBlock",
              MakeBlock<AtmosphereUniforms>(GL_UNIFORM_BLOCK, kAtmosphereBlockBinding,
                                            AddAtmosphere, "atmosphere."));
    m.emplace("LightBlock",
              MakeBlock<LightUniforms>(GL_UNIFORM_BLOCK, kLightBlockBinding, AddLights, "lights."));
    m.emplace("SettingsBlock", MakeBlock<SettingsUniforms>(GL_UNIFORM_BLOCK, kSettingsBlockBinding,
                                                           AddSettings, ""));
    m.emplace("FrameBlock",
              MakeBlock<FrameUniforms>(GL_UNIFORM_BLOCK, kFrameBlockBinding, AddFrame, ""));
    m.emplace("CloudBlock",
              MakeBlock<CloudUniforms>(GL_UNIFORM_BLOCK, kCloudBlockBinding, AddCloud, ""));
    m.emplace("PrecipitationBlock",
              MakeBlock<PrecipitationUniforms>(GL_UNIFORM_BLOCK, kPrecipitationBlockBinding,
                                               AddPrecipitation, ""));
    m.emplace("LightStorage",
              MakeBlock<LightUniforms>(GL_SHADER_STORAGE_BLOCK, kLightStorageBinding, AddLights,
                                       "shaded_lights."));
    m.emplace("DisplayStorage",
              MakeBlock<DisplayStorage>(GL_SHADER_STORAGE_BLOCK, kDisplayStorageBinding,
                                        AddDisplayStorage, ""));
    m.emplace("EnvironmentShStorage",
              MakeBlock<EnvironmentShStorage>(GL_SHADER_STORAGE_BLOCK, kEnvironmentStorageBinding,
                                              AddEnvironmentSh, ""));
    m.emplace("CloudGeometryList",
              MakeBlock<CloudGeometryList>(GL_SHADER_STORAGE_BLOCK, kCloudGeometryListBinding,
                                           AddCloudGeometryList, ""));
    return m;
}

// The unit of every sampler and image the renderer's programs declare, from bindings.glsl.
const std::map<std::string, int>& ExpectedUnits() {
    static const std::map<std::string, int> units = {
        {"transmittance_texture", kTransmittanceUnit},
        {"multiple_scattering_texture", kMultipleScatteringUnit},
        {"irradiance_texture", kIrradianceUnit},
        {"sky_view_texture", kSkyViewUnit},
        {"star_texture", kStarUnit},
        {"night_sky_texture", kNightSkyUnit},
        {"scene_depth_texture", kSceneDepthUnit},
        {"aerial_perspective_texture", kAerialPerspectiveUnit},
        {"shape_noise", kShapeNoiseUnit},
        {"detail_noise", kDetailNoiseUnit},
        {"weather_maps[0]", kWeatherMapsUnit},  // and the next kCloudMaxLayers - 1
        {"cloud_trace", kCloudTraceUnit},
        {"cloud_trace_depth", kCloudTraceDepthUnit},
        {"cloud_trace_profile", kCloudTraceProfileUnit},
        {"cloud_history", kCloudHistoryUnit},
        {"cloud_shadow_map", kCloudShadowMapUnit},
        {"cloud_ground_shadow", kCloudGroundShadowUnit},
        {"cloud_air_shadow[0]", kCloudAirShadowUnit},  // and the next 3
        {"cloud_geometry", kCloudGeometryUnit},
        {"cloud_sun_depth", kCloudSunDepthUnit},
        {"display_input", kDisplayInputUnit},
        {"display_scene_depth", kSceneDepthUnit},
        // Images.
        {"output_image", kOutputImageUnit},
        {"shadow_map", kOutputImageUnit},
        {"sun_depth_volume", kOutputImageUnit},
        {"shade_directions", kShadeDirectionsImageUnit},
        {"shadow_map_image", kShadowMapImageUnit},
        {"environment_atlas", kEnvironmentImageUnit},
        {"order_image", kScatteringOrderImageUnit},
        {"column_image", kColumnCorrectionImageUnit},
        {"shade_image", kCloudPassImageUnit},
        {"history_image", kCloudPassImageUnit},
        {"ground_shadow_image", kCloudPassImageUnit},
        {"air_shadow_images[0]", kCloudPassImageUnit},  // and the next 3
        {"trace_cloud_image", kCloudPassImageUnit},
        {"trace_depth_image", kCloudPassImageUnit + 1},
        {"trace_profile_image", kCloudPassImageUnit + 2},
    };
    return units;
}

// Each compute pass's work-group size, from bindings.glsl.
const std::map<std::string, glm::ivec3>& ExpectedGroupSizes() {
    static const std::map<std::string, glm::ivec3> sizes = {
        {"atmosphere/transmittance.comp", {kLutGroupSize, kLutGroupSize, 1}},
        {"atmosphere/multiple_scattering.comp", {kDirectionsGroupSize, 1, 1}},
        {"atmosphere/irradiance.comp", {kDirectionsGroupSize, 1, 1}},
        {"atmosphere/sky_view.comp", {kLutGroupSize, kLutGroupSize, 1}},
        {"atmosphere/aerial_perspective.comp", {kLutGroupSize, kLutGroupSize, 1}},
        {"clouds/shadow_map.comp", {kShadowMapGroupSize, kShadowMapGroupSize, 1}},
        {"clouds/sky_shade.comp", {1, 1, 1}},
        {"clouds/trace.comp", {kCloudPassGroupSize, kCloudPassGroupSize, 1}},
        {"clouds/sky_shade_trace.comp", {kCloudPassGroupSize, kCloudPassGroupSize, 1}},
        {"clouds/reconstruct.comp", {kCloudPassGroupSize, kCloudPassGroupSize, 1}},
        {"clouds/ground_shadow.comp", {kCloudPassGroupSize, kCloudPassGroupSize, 1}},
        {"clouds/light_shafts.comp", {kCloudPassGroupSize, kCloudPassGroupSize, 1}},
        {"atmosphere/environment_sh.comp", {kEnvironmentShGroupSize, 1, 1}},
        {"display/histogram.comp", {kDisplayGroupSize, kDisplayGroupSize, 1}},
        {"display/meter.comp", {1, 1, 1}},
    };
    return sizes;
}

// The plain (non-block, non-opaque) uniforms, set with glProgramUniform* at the locations of
// gl/display_uniforms.h and gl/atmosphere_uniforms.h: by program label and name, the location and
// GL type C++ uses.
struct ExpectedUniform {
    GLint location;
    GLenum type;
};
const std::map<std::string, ExpectedUniform>& ExpectedPlainUniforms() {
    static const std::map<std::string, ExpectedUniform> uniforms = {
        {"display/histogram.comp:display_size", {kDisplaySizeLocation, GL_INT_VEC2}},
        {"display/meter.comp:display_dt_over_tau", {kDisplayDtOverTauLocation, GL_FLOAT}},
        {"display/meter.comp:display_night", {kDisplayMeterNightLocation, GL_INT}},
        {"display/meter.comp:display_compensation_ev", {kDisplayCompensationLocation, GL_FLOAT}},
        {"display/display.frag:display_origin", {kDisplayOriginLocation, GL_INT_VEC2}},
        {"display/display.frag:display_night", {kDisplayNightLocation, GL_INT}},
        {"display/display.frag:display_depth_mode", {kDisplayDepthModeLocation, GL_INT}},
        {"atmosphere/multiple_scattering.comp:scattering_order",
         {kScatteringOrderLocation, GL_INT}},
        {"atmosphere/multiple_scattering.comp:last_scattering_order",
         {kLastScatteringOrderLocation, GL_INT}},
        {"clouds/sun_depth.comp:sun_depth_level", {kSunDepthLevelLocation, GL_INT}},
    };
    return uniforms;
}

std::string Hex(GLint value) {
    char text[16];
    std::snprintf(text, sizeof(text), "0x%04x", static_cast<unsigned>(value));
    return text;
}
std::string Hex(GLenum value) { return Hex(static_cast<GLint>(value)); }

std::string ResourceName(GLuint program, GLenum interface, GLuint index) {
    GLint length = 0;
    const GLenum property = GL_NAME_LENGTH;
    glGetProgramResourceiv(program, interface, index, 1, &property, 1, nullptr, &length);
    std::string name(static_cast<std::size_t>(length), '\0');
    glGetProgramResourceName(program, interface, index, length, nullptr, name.data());
    name.resize(name.find('\0') == std::string::npos ? name.size() : name.find('\0'));
    return name;
}

GLint ResourceInt(GLuint program, GLenum interface, GLuint index, GLenum property) {
    GLint value = 0;
    glGetProgramResourceiv(program, interface, index, 1, &property, 1, nullptr, &value);
    return value;
}

// What differs between `program`'s blocks and `mirrors`, one line each; `seen` collects the
// names of the blocks it has.
std::vector<std::string> CheckBlocks(const Program& program,
                                     const std::map<std::string, BlockMirror>& mirrors,
                                     std::set<std::string>& seen) {
    std::vector<std::string> errors;
    const std::string where = program.label() + ": ";
    for (GLenum block_interface : {GLenum{GL_UNIFORM_BLOCK}, GLenum{GL_SHADER_STORAGE_BLOCK}}) {
        GLint blocks = 0;
        glGetProgramInterfaceiv(program.name(), block_interface, GL_ACTIVE_RESOURCES, &blocks);
        for (GLuint b = 0; b < static_cast<GLuint>(blocks); ++b) {
            const std::string block = ResourceName(program.name(), block_interface, b);
            const auto mirror = mirrors.find(block);
            if (mirror == mirrors.end() || mirror->second.block_interface != block_interface) {
                errors.push_back(where + "block " + block + " has no C++ mirror in this test");
                continue;
            }
            seen.insert(block);
            const BlockMirror& m = mirror->second;
            const GLint binding =
                ResourceInt(program.name(), block_interface, b, GL_BUFFER_BINDING);
            if (binding != m.binding) {
                errors.push_back(where + block + " binding " + std::to_string(binding) +
                                 ", bindings.glsl " + std::to_string(m.binding));
            }
            // GL_BUFFER_DATA_SIZE is the implementation's minimum size for the block, which may
            // pad the mirror's to 16 bytes: Mesa does for a runtime-sized array's block, NVIDIA
            // does not (every other block's mirror is a multiple of 16 already).
            const GLint size = ResourceInt(program.name(), block_interface, b, GL_BUFFER_DATA_SIZE);
            const std::size_t padded = (m.size + 15) / 16 * 16;
            if (static_cast<std::size_t>(size) < m.size ||
                static_cast<std::size_t>(size) > padded) {
                errors.push_back(where + block + " is " + std::to_string(size) +
                                 " bytes, its C++ mirror " + std::to_string(m.size));
            }
            const GLint count =
                ResourceInt(program.name(), block_interface, b, GL_NUM_ACTIVE_VARIABLES);
            std::vector<GLint> indices(static_cast<std::size_t>(count));
            const GLenum active = GL_ACTIVE_VARIABLES;
            glGetProgramResourceiv(program.name(), block_interface, b, 1, &active, count, nullptr,
                                   indices.data());
            std::set<std::string> members;
            for (GLint index : indices) {
                const GLuint i = static_cast<GLuint>(index);
                const std::string name = ResourceName(program.name(), m.member_interface, i);
                members.insert(name);
                const auto expected = m.members.find(name);
                if (expected == m.members.end()) {
                    errors.push_back(where + block + "." + name + " has no C++ mirror member");
                    continue;
                }
                const Expected& e = expected->second;
                const auto get = [&](GLenum property) {
                    return ResourceInt(program.name(), m.member_interface, i, property);
                };
                const GLint offset = get(GL_OFFSET), type = get(GL_TYPE);
                const GLint array_stride = get(GL_ARRAY_STRIDE);
                const GLint matrix_stride = get(GL_MATRIX_STRIDE);
                if (static_cast<std::size_t>(offset) != e.offset) {
                    errors.push_back(where + block + "." + name + " at offset " +
                                     std::to_string(offset) + ", in C++ at " +
                                     std::to_string(e.offset));
                }
                if (static_cast<GLenum>(type) != e.type) {
                    errors.push_back(where + block + "." + name + " has GL type " + Hex(type) +
                                     ", its C++ mirror " + Hex(e.type));
                }
                if (static_cast<std::size_t>(array_stride) != e.array_stride) {
                    errors.push_back(where + block + "." + name + " array stride " +
                                     std::to_string(array_stride) + ", C++ element size " +
                                     std::to_string(e.array_stride));
                }
                if (matrix_stride != 0) {  // no mirror has a matrix member
                    errors.push_back(where + block + "." + name + " is a matrix (stride " +
                                     std::to_string(matrix_stride) + "): mirror it here");
                }
            }
            for (const auto& [name, e] : m.members) {
                if (members.count(name) == 0) {
                    errors.push_back(where + block + "." + name +
                                     " is in the C++ mirror but not in the GLSL block");
                }
            }
        }
    }
    return errors;
}

// Samplers and images outside blocks: each on its bindings.glsl unit.
// `seen_plain` collects the plain uniforms found (program label:name).
std::vector<std::string> CheckUnits(const Program& program, std::set<std::string>& seen_plain) {
    std::vector<std::string> errors;
    const std::string where = program.label() + ": ";
    GLint uniforms = 0;
    glGetProgramInterfaceiv(program.name(), GL_UNIFORM, GL_ACTIVE_RESOURCES, &uniforms);
    for (GLuint u = 0; u < static_cast<GLuint>(uniforms); ++u) {
        if (ResourceInt(program.name(), GL_UNIFORM, u, GL_BLOCK_INDEX) != -1) continue;
        const std::string name = ResourceName(program.name(), GL_UNIFORM, u);
        const auto plain = ExpectedPlainUniforms().find(program.label() + ":" + name);
        if (plain != ExpectedPlainUniforms().end()) {
            seen_plain.insert(plain->first);
            const GLint location = ResourceInt(program.name(), GL_UNIFORM, u, GL_LOCATION);
            const GLint type = ResourceInt(program.name(), GL_UNIFORM, u, GL_TYPE);
            if (location != plain->second.location) {
                errors.push_back(where + name + " at location " + std::to_string(location) +
                                 ", in C++ at " + std::to_string(plain->second.location));
            }
            if (static_cast<GLenum>(type) != plain->second.type) {
                errors.push_back(where + name + " has GL type " + Hex(type) + ", in C++ " +
                                 Hex(plain->second.type));
            }
            continue;
        }
        const auto expected = ExpectedUnits().find(name);
        if (expected == ExpectedUnits().end()) {
            errors.push_back(where + "uniform " + name +
                             " is outside the blocks and not a sampler of bindings.glsl");
            continue;
        }
        const GLint location = ResourceInt(program.name(), GL_UNIFORM, u, GL_LOCATION);
        const GLint size = ResourceInt(program.name(), GL_UNIFORM, u, GL_ARRAY_SIZE);
        for (GLint element = 0; element < size; ++element) {
            GLint unit = -1;
            glGetUniformiv(program.name(), location + element, &unit);
            if (unit != expected->second + element) {
                errors.push_back(where + name + " element " + std::to_string(element) +
                                 " on unit " + std::to_string(unit) + ", bindings.glsl " +
                                 std::to_string(expected->second + element));
            }
        }
    }
    const auto group = ExpectedGroupSizes().find(program.label());
    if (group != ExpectedGroupSizes().end()) {
        glm::ivec3 size(0);
        glGetProgramiv(program.name(), GL_COMPUTE_WORK_GROUP_SIZE, &size.x);
        if (size != group->second) {
            errors.push_back(where + "work group " + std::to_string(size.x) + "x" +
                             std::to_string(size.y) + "x" + std::to_string(size.z) +
                             ", bindings.glsl " + std::to_string(group->second.x) + "x" +
                             std::to_string(group->second.y) + "x" +
                             std::to_string(group->second.z));
        }
    }
    return errors;
}

class GlBindingsTest : public test::HeadlessGlTest {
  protected:
    static void SetUpTestSuite() {
        HeadlessGlTest::SetUpTestSuite();
        programs_ = BuildRendererPrograms();
    }
    static void TearDownTestSuite() {
        programs_.clear();
        HeadlessGlTest::TearDownTestSuite();
    }
    static inline std::vector<Program> programs_;
};

std::string Join(const std::vector<std::string>& lines) {
    std::string text;
    for (const std::string& line : lines) text += line + "\n";
    return text;
}

TEST_F(GlBindingsTest, EveryBlockMatchesItsCppMirror) {
    // 5 LUT passes, 6 composites, the stars' points, the precipitation's streaks, the 6
    // composites again with clouds, 15 cloud programs (the trace, the sky shade's trace, the
    // reconstruction, the ground's shadow and the light shafts in both stages; the shadow map,
    // the sun-depth volume, the sky shade, the host geometry's list and march), 3 display
    // programs, 4 environment faces (with and without clouds, ray march) and its projection.
    ASSERT_EQ(programs_.size(), 42u);
    const std::map<std::string, BlockMirror> mirrors = Mirrors();
    std::set<std::string> seen;
    std::vector<std::string> errors;
    for (const Program& program : programs_) {
        for (std::string& e : CheckBlocks(program, mirrors, seen)) errors.push_back(e);
    }
    EXPECT_TRUE(errors.empty()) << Join(errors);
    for (const auto& [name, mirror] : mirrors) {
        EXPECT_EQ(seen.count(name), 1u) << name << " is in no program the renderer builds";
    }
}

TEST_F(GlBindingsTest, EverySamplerImageAndWorkGroupIsOnItsBindingsGlslValue) {
    std::vector<std::string> errors;
    std::set<std::string> compute, plain;
    for (const Program& program : programs_) {
        for (std::string& e : CheckUnits(program, plain)) errors.push_back(e);
        if (ExpectedGroupSizes().count(program.label()) != 0) compute.insert(program.label());
    }
    EXPECT_TRUE(errors.empty()) << Join(errors);
    EXPECT_EQ(compute.size(), ExpectedGroupSizes().size());
    for (const auto& [name, uniform] : ExpectedPlainUniforms()) {
        EXPECT_EQ(plain.count(name), 1u) << name << " is in no program the renderer builds";
    }
}

// The check is not vacuous: a mirror with two members swapped (as a change in one language
// only would leave it) or a block on another binding is reported.
TEST_F(GlBindingsTest, AMemberMovedInOneLanguageIsReported) {
    std::map<std::string, BlockMirror> mirrors = Mirrors();
    Layout& lights = mirrors.at("LightBlock").members;
    std::swap(lights.at("lights.cloud_direct").offset, lights.at("lights.cloud_sky").offset);
    mirrors.at("FrameBlock").binding = kCloudBlockBinding;
    std::set<std::string> seen;
    std::vector<std::string> errors;
    for (const Program& program : programs_) {
        for (std::string& e : CheckBlocks(program, mirrors, seen)) errors.push_back(e);
    }
    const std::string text = Join(errors);
    EXPECT_NE(text.find("LightBlock.lights.cloud_direct at offset 72, in C++ at 76"),
              std::string::npos)
        << text;
    EXPECT_NE(text.find("FrameBlock binding 3, bindings.glsl 4"), std::string::npos) << text;
}

}  // namespace
}  // namespace zenith::sky::gl
