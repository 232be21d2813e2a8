// The shared cloud GLSL on the GPU (OSMesa llvmpipe, float) against the same text compiled as
// C++ (double): it compiles as GLSL 4.50, and density, phase, the sun's scattering (first order
// and diffuse field) and the analytic step agree under named tolerances, so the renderer and the
// reference cannot drift.
#include <glad/gl.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "cloud_test_support.h"
#include "gl/shader.h"
#include "gl/shader_library.h"
#include "reference/cloud_functions.h"
#include "zenith/sky/gl/context.h"

namespace zenith::sky {
namespace {

constexpr int kPoints = 512;
// Density: float texture coordinates and the GPU's fixed-point filter weights (8 bits on
// llvmpipe) move a sample by a fraction of one texel step of the noise.
constexpr double kDensityTolerance = 0.01;
// Closed-form functions in float vs double.
constexpr double kRelativeTolerance = 1e-4;

constexpr const char* kPass = R"(
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Points { vec4 points[]; };
layout(std430, binding = 1) writeonly buffer Results { vec4 results[]; };
layout(binding = 0) uniform sampler2D weather_map;
layout(binding = 1) uniform sampler3D shape_noise;
layout(binding = 2) uniform sampler3D detail_noise;
uniform CloudLayerParameters layer;
uniform CloudScatteringParameters scattering;
void main() {
    uint i = gl_GlobalInvocationID.x;
    vec4 p = points[i];
    CloudSample s = SampleCloudDensityAt(layer, weather_map, shape_noise, detail_noise,
                                         vec2(p.x, p.y), p.z);
    vec3 luminance = vec3(0.0);
    float transmittance = 1.0;
    CloudIntegrateStep(vec3(p.w * 3.0), p.w * 40.0, 0.05, luminance, transmittance);
    results[i] = vec4(s.density, CloudDualLobePhase(0.8, -0.4, 0.25, 2.0 * p.w - 1.0),
                      CloudSunScattering(scattering, 10.0 * p.w, 30.0 * (1.0 - p.w),
                                         0.1 + 0.9 * p.w, 2.0 * p.w - 1.0, 1.0 - 2.0 * p.w,
                                         0.1 * p.w),
                      luminance.x);
}
)";

// Drifted by the wind, so the GPU's offset path is exercised too.
ref::CloudLayerParameters Layer() { return clouds::test::CumulusLayer(1.25, -3.5); }

ref::CloudScatteringParameters Scattering() {
    ref::CloudScatteringParameters p{};
    p.forward_g = 0.8;
    p.backward_g = -0.4;
    p.lobe_weight = 0.25;
    p.albedo = 1.0;
    p.multiple_scattering = 0.75;
    p.ground_albedo = 0.3;
    return p;
}

void SetUniform(GLuint program, const std::string& name, float value) {
    // -1: inactive. A compiler may drop a uniform the pass never reads (NVIDIA's does, Mesa's
    // keeps struct members); one the pass reads but misnamed here stays 0 and the comparison
    // below fails.
    const GLint location = glGetUniformLocation(program, name.c_str());
    if (location < 0) return;
    glProgramUniform1f(program, location, value);
}

GLuint Texture3D(const clouds::NoiseVolume& v) {
    GLuint texture = 0;
    glCreateTextures(GL_TEXTURE_3D, 1, &texture);
    glTextureStorage3D(texture, 1, v.channels == 4 ? GL_RGBA8 : GL_RGB8, v.size.x, v.size.y,
                       v.size.z);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTextureSubImage3D(texture, 0, 0, 0, 0, v.size.x, v.size.y, v.size.z,
                        v.channels == 4 ? GL_RGBA : GL_RGB, GL_UNSIGNED_BYTE, v.texels.data());
    for (const GLenum wrap :
         {GLenum{GL_TEXTURE_WRAP_S}, GLenum{GL_TEXTURE_WRAP_T}, GLenum{GL_TEXTURE_WRAP_R}}) {
        glTextureParameteri(texture, wrap, GL_REPEAT);
    }
    glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    return texture;
}

TEST(CloudShaderGl, SharedFunctionsMatchTheCppReference) {
    const auto context = gl::CreateHeadlessContextFromEnvironment();
    const std::string source =
        "#version 450 core\n" + std::string(gl::EmbeddedShaderFile("common/definitions.glsl")) +
        "\n" + std::string(gl::EmbeddedShaderFile("clouds/definitions.glsl")) + "\n" +
        std::string(gl::EmbeddedShaderFile("clouds/functions.glsl")) + kPass;
    const gl::Program program = gl::Program::Compute(source, "cloud_parity.comp");

    const clouds::CloudNoise& noise = clouds::test::CachedNoise();
    clouds::CloudLayer weather_layer;
    weather_layer.coverage = 0.6;
    weather_layer.precipitation = 0.3;
    weather_layer.map.kind = clouds::WeatherMapSource::Kind::kPatches;
    weather_layer.map.size = 64;
    const clouds::WeatherMap weather = clouds::BuildWeatherMap(weather_layer);

    GLuint textures[3];
    glCreateTextures(GL_TEXTURE_2D, 1, &textures[0]);
    glTextureStorage2D(textures[0], 1, GL_RGBA32F, weather.size, weather.size);
    glTextureSubImage2D(textures[0], 0, 0, 0, weather.size, weather.size, GL_RGBA, GL_FLOAT,
                        weather.texels.data());
    glTextureParameteri(textures[0], GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTextureParameteri(textures[0], GL_TEXTURE_WRAP_T, GL_REPEAT);
    glTextureParameteri(textures[0], GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(textures[0], GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    textures[1] = Texture3D(noise.shape);
    textures[2] = Texture3D(noise.detail);
    for (GLuint unit = 0; unit < 3; ++unit) glBindTextureUnit(unit, textures[unit]);

    const ref::CloudLayerParameters layer = Layer();
    const ref::CloudScatteringParameters scattering = Scattering();
    const GLuint name = program.name();
    const char* layer_fields[] = {"bottom_radius",  "base_altitude",    "top_altitude",
                                  "weather_period", "shape_period",     "shape_period_y",
                                  "detail_period",  "erosion_strength", "wind_offset_x",
                                  "wind_offset_y",  "extinction_scale", "ground_fog"};
    const double layer_values[] = {
        layer.bottom_radius, layer.base_altitude,  layer.top_altitude,     layer.weather_period,
        layer.shape_period,  layer.shape_period_y, layer.detail_period,    layer.erosion_strength,
        layer.wind_offset_x, layer.wind_offset_y,  layer.extinction_scale, layer.ground_fog};
    for (int i = 0; i < 12; ++i) {
        SetUniform(name, std::string("layer.") + layer_fields[i],
                   static_cast<float>(layer_values[i]));
    }
    // The padding is unused and may be optimised away.
    const char* scattering_fields[] = {"forward_g", "backward_g",          "lobe_weight",
                                       "albedo",    "multiple_scattering", "ground_albedo"};
    const double scattering_values[] = {scattering.forward_g,           scattering.backward_g,
                                        scattering.lobe_weight,         scattering.albedo,
                                        scattering.multiple_scattering, scattering.ground_albedo};
    for (int i = 0; i < 6; ++i) {
        SetUniform(name, std::string("scattering.") + scattering_fields[i],
                   static_cast<float>(scattering_values[i]));
    }

    // Points on the ground (km), altitudes across the layer, and a parameter in [0, 1]; float
    // values so both sides see the same inputs.
    std::mt19937 rng(17);
    std::uniform_real_distribution<float> g(-60.0f, 60.0f), a(1.3f, 4.2f), w(0.0f, 1.0f);
    std::vector<glm::vec4> points(kPoints);
    for (glm::vec4& p : points) p = glm::vec4(g(rng), g(rng), a(rng), w(rng));
    GLuint buffers[2];
    glCreateBuffers(2, buffers);
    glNamedBufferStorage(buffers[0], kPoints * sizeof(glm::vec4), points.data(), 0);
    glNamedBufferStorage(buffers[1], kPoints * sizeof(glm::vec4), nullptr, 0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buffers[0]);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, buffers[1]);
    program.Use();
    glDispatchCompute(kPoints / 64, 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<glm::vec4> gpu(kPoints);
    glGetNamedBufferSubData(buffers[1], 0, kPoints * sizeof(glm::vec4), gpu.data());
    glDeleteBuffers(2, buffers);
    glDeleteTextures(3, textures);
    ASSERT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));

    const ref::RepeatTexture2D weather_texture = ref::ToTexture(weather);
    const ref::Texture3D shape = ref::ToTexture(noise.shape);
    const ref::Texture3D detail = ref::ToTexture(noise.detail);
    int cloudy = 0;
    double worst_density = 0.0;
    for (int i = 0; i < kPoints; ++i) {
        const glm::dvec4 p(points[static_cast<std::size_t>(i)]);
        const glm::vec4 r = gpu[static_cast<std::size_t>(i)];
        const double density = ref::SampleCloudDensityAt(layer, weather_texture, shape, detail,
                                                         glm::dvec2(p.x, p.y), p.z)
                                   .density;
        cloudy += density > 0.0;
        worst_density = std::max(worst_density, std::abs(r.x - density));
        EXPECT_NEAR(r.x, density, kDensityTolerance) << "point " << i;
        const double nu = 2.0 * p.w - 1.0;
        const double phase = ref::CloudDualLobePhase(0.8, -0.4, 0.25, nu);
        EXPECT_NEAR(r.y, phase, kRelativeTolerance * phase) << "point " << i;
        const double sun = ref::CloudSunScattering(scattering, 10.0 * p.w, 30.0 * (1.0 - p.w),
                                                   0.1 + 0.9 * p.w, nu, -nu, 0.1 * p.w);
        EXPECT_NEAR(r.z, sun, kRelativeTolerance * sun + 1e-9) << "point " << i;
        glm::dvec3 luminance(0.0);
        double transmittance = 1.0;
        ref::CloudIntegrateStep(glm::dvec3(p.w * 3.0), p.w * 40.0, 0.05, luminance, transmittance);
        EXPECT_NEAR(r.w, luminance.x, kRelativeTolerance * luminance.x + 1e-7) << "point " << i;
    }
    std::printf("cloud density GPU vs CPU: %d of %d points cloudy, largest difference %.2g\n",
                cloudy, kPoints, worst_density);
    EXPECT_GT(cloudy, kPoints / 20);
}

}  // namespace
}  // namespace zenith::sky
