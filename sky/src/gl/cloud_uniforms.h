// C++ mirror of the CloudBlock in sky/shaders/clouds/interface.glsl (std140), checked at
// compile time and by tests/sky/gl_bindings_gl_test.cpp like atmosphere_uniforms.h.
#pragma once

#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>

#include "bindings.h"
#include "gl/atmosphere_uniforms.h"

namespace zenith::sky::gl {

struct CloudLayerUniforms {  // clouds/functions.glsl: struct CloudLayerParameters
    float bottom_radius;
    float base_altitude;
    float top_altitude;
    float weather_period;
    float shape_period;
    float shape_period_y;
    float detail_period;
    float erosion_strength;
    float wind_offset_x;
    float wind_offset_y;
    float cloud_top_altitude;
    float extinction_scale;
    float ground_fog;
    float precipitation_shaft;
    float shear_x;
    float shear_y;
};
static_assert(sizeof(CloudLayerUniforms) == 64);

struct CloudScatteringUniforms {  // clouds/functions.glsl: struct CloudScatteringParameters
    float forward_g;
    float backward_g;
    float lobe_weight;
    float albedo;
    float multiple_scattering;
    float ground_albedo;
    float padding1;
    float padding2;
    glm::vec4 slab_tables[32];
};
static_assert(sizeof(CloudScatteringUniforms) == 32 + 32 * 16);

struct CloudMarchUniforms {  // clouds/march.glsl: struct CloudMarchParameters
    float extinction;
    float min_step;
    float max_steps;
    float shadow_steps;
    float shadow_first_step;
    float shadow_growth;
    float ambient_scale;
    float thick_step_refinement;
    float min_transmittance;
    float max_distance;
    float oriented_slabs;
    float light_shaft_steps;
    float column_steps;
    float sun_depth_center_x;
    float sun_depth_center_y;
    float sun_depth_extent;
    float sun_depth_base;
    float sun_depth_top;
    float padding1;
    float padding2;
};
static_assert(sizeof(CloudMarchUniforms) == 80);

// clouds/sun_depth.comp's plain uniform: the level it makes.
constexpr int kSunDepthLevelLocation = 0;  // int sun_depth_level

struct CloudUniforms {  // clouds/interface.glsl: CloudBlock
    CloudLayerUniforms layers[kCloudMaxLayers];
    CloudScatteringUniforms scattering;
    CloudMarchUniforms march;
    LightUniforms lights;
    glm::vec4 weather_from_frame[3];
    glm::vec4 previous_view_from_frame[3];
    glm::vec3 previous_camera_offset_km;
    float previous_tan_half_fov;
    glm::ivec2 trace_size;
    glm::ivec2 trace_offset;
    int block;
    int layer_count;
    int light_count;
    int history_valid;
    float frame_jitter;
    float history_weight;
    float previous_aspect;
    int aerial_perspective_steps;
    float shadow_map_extent_km;
    int shadow_map_size;
    int shadow_map_steps;
    int sky_shade_size;
    glm::ivec4 layer_order;
    glm::ivec4 ground_layer_order;
};
static_assert(offsetof(CloudUniforms, scattering) == 256);
static_assert(offsetof(CloudUniforms, march) == 800);
static_assert(offsetof(CloudUniforms, lights) == 880);
static_assert(offsetof(CloudUniforms, weather_from_frame) == 1200);
static_assert(offsetof(CloudUniforms, previous_view_from_frame) == 1248);
static_assert(offsetof(CloudUniforms, previous_camera_offset_km) == 1296);
static_assert(offsetof(CloudUniforms, trace_size) == 1312);
static_assert(offsetof(CloudUniforms, block) == 1328);
static_assert(offsetof(CloudUniforms, frame_jitter) == 1344);
static_assert(offsetof(CloudUniforms, shadow_map_extent_km) == 1360);
static_assert(offsetof(CloudUniforms, layer_order) == 1376);
static_assert(offsetof(CloudUniforms, ground_layer_order) == 1392);
static_assert(sizeof(CloudUniforms) == 1408);

// clouds/geometry_list.glsl: CloudGeometryList, a storage block: a glDrawArraysIndirect command
// (its vertex count, 6 per cell listed, written by the shader), the capacity in cells, then the
// cells (x | y << 16; as many as the capacity). One here, as GL counts a runtime-sized array in
// the block's minimum size (GL_BUFFER_DATA_SIZE: 36 bytes on NVIDIA; Mesa pads it to 48).
struct CloudGeometryList {
    std::uint32_t vertices;
    std::uint32_t instances;
    std::uint32_t first;
    std::uint32_t base_instance;
    std::uint32_t capacity;
    std::uint32_t unused[3];
    std::uint32_t cells[1];
};
static_assert(offsetof(CloudGeometryList, capacity) == 16);
static_assert(offsetof(CloudGeometryList, cells) == 32);

}  // namespace zenith::sky::gl
