// Smoke test of the GL layer: each headless context kind comes up with OpenGL >= 4.5 core, runs a
// compute shader and reads the result back; every way of not getting a context is a ContextError
// or zenith::ArgumentError whose message says what was tried.
#include <glad/gl.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "gl/shader.h"
#include "zenith/base/error.h"
#include "zenith/sky/gl/context.h"
#include "zenith/sky/gl/loader.h"

namespace zenith::sky::gl {
namespace {

// EXPECT_CONTAINS(text, part): the test links GoogleTest without gMock, so no HasSubstr.
#define EXPECT_CONTAINS(text, part)                                      \
    EXPECT_NE(std::string_view(text).find(part), std::string_view::npos) \
        << "expected \"" << (part) << "\" in:\n"                         \
        << (text)

constexpr GLuint kCount = 256;     // values written by the compute shader
constexpr GLuint kLocalSize = 64;  // invocations per work group

// value[i] = i * i + 7, computed in integers so the comparison is exact.
constexpr const char* kSsboShader = R"(#version 450 core
layout(local_size_x = 64) in;
layout(std430, binding = 0) writeonly buffer Result { uint value[]; };
void main() {
    uint i = gl_GlobalInvocationID.x;
    value[i] = i * i + 7u;
}
)";

// texel(x, y) = x + 100 y, through imageStore, as the LUT passes will write.
constexpr const char* kImageShader = R"(#version 450 core
layout(local_size_x = 8, local_size_y = 8) in;
layout(r32f, binding = 0) writeonly uniform image2D result;
void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    imageStore(result, p, vec4(float(p.x + 100 * p.y), 0.0, 0.0, 1.0));
}
)";

// Runs kSsboShader on the current context and checks every value.
void ExpectComputeWritesSsbo() {
    const Program program = Program::Compute(kSsboShader, "ssbo_smoke.comp");
    GLuint buffer = 0;
    glCreateBuffers(1, &buffer);
    glNamedBufferStorage(buffer, kCount * sizeof(GLuint), nullptr, GL_DYNAMIC_STORAGE_BIT);
    const std::vector<GLuint> poison(kCount, 0xDEADBEEFu);
    glNamedBufferSubData(buffer, 0, kCount * sizeof(GLuint), poison.data());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buffer);
    program.Use();
    glDispatchCompute(kCount / kLocalSize, 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<GLuint> result(kCount, 0);
    glGetNamedBufferSubData(buffer, 0, kCount * sizeof(GLuint), result.data());
    glDeleteBuffers(1, &buffer);
    EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
    for (GLuint i = 0; i < kCount; ++i) {
        ASSERT_EQ(result[i], i * i + 7u) << "value[" << i << "]";
    }
}

void ExpectComputeWritesImage() {
    constexpr GLsizei kWidth = 32;
    constexpr GLsizei kHeight = 16;
    const Program program = Program::Compute(kImageShader, "image_smoke.comp");
    GLuint texture = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &texture);
    glTextureStorage2D(texture, 1, GL_R32F, kWidth, kHeight);
    glBindImageTexture(0, texture, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
    program.Use();
    glDispatchCompute(kWidth / 8, kHeight / 8, 1);
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
    std::vector<float> texels(static_cast<size_t>(kWidth * kHeight), -1.0f);
    glGetTextureImage(texture, 0, GL_RED, GL_FLOAT,
                      static_cast<GLsizei>(texels.size() * sizeof(float)), texels.data());
    glDeleteTextures(1, &texture);
    EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
    for (GLsizei y = 0; y < kHeight; ++y) {
        for (GLsizei x = 0; x < kWidth; ++x) {
            ASSERT_EQ(texels[static_cast<size_t>(y * kWidth + x)], static_cast<float>(x + 100 * y))
                << "texel (" << x << ", " << y << ")";
        }
    }
}

// Sets an environment variable for one scope and restores it.
class ScopedEnv {
  public:
    ScopedEnv(const char* name, const char* value) : name_(name) {
        if (const char* old = std::getenv(name)) old_ = old;
        if (value != nullptr) {
            setenv(name, value, 1);
        } else {
            unsetenv(name);
        }
    }
    ~ScopedEnv() {
        if (old_) {
            setenv(name_, old_->c_str(), 1);
        } else {
            unsetenv(name_);
        }
    }
    ScopedEnv(const ScopedEnv&) = delete;
    ScopedEnv& operator=(const ScopedEnv&) = delete;

  private:
    const char* name_;
    std::optional<std::string> old_;
};

// --- parsing and configuration errors (no GL needed) ---

TEST(ContextKindTest, ParsesBothNamesAndRoundTrips) {
    EXPECT_EQ(ParseContextKind("osmesa"), ContextKind::kOsMesa);
    EXPECT_EQ(ParseContextKind("egl"), ContextKind::kEgl);
    for (ContextKind kind : {ContextKind::kOsMesa, ContextKind::kEgl}) {
        EXPECT_EQ(ParseContextKind(ToString(kind)), kind);
    }
}

TEST(ContextKindTest, RejectsUnknownNamesListingTheChoices) {
    for (const char* bad : {"", "vulkan", "OSMesa", "egl ", "glx"}) {
        try {
            ParseContextKind(bad);
            ADD_FAILURE() << "accepted '" << bad << "'";
        } catch (const zenith::ArgumentError& error) {
            EXPECT_CONTAINS(error.what(), "'" + std::string(bad) + "'");
            EXPECT_CONTAINS(error.what(), "'osmesa'");
            EXPECT_CONTAINS(error.what(), "'egl'");
        }
    }
}

TEST(ContextKindTest, EnvironmentDefaultsToOsMesaAndNamesTheVariableOnError) {
    {
        const ScopedEnv env("ZENITH_GL", nullptr);
        EXPECT_EQ(ContextKindFromEnvironment(), ContextKind::kOsMesa);
    }
    {
        const ScopedEnv env("ZENITH_GL", "egl");
        EXPECT_EQ(ContextKindFromEnvironment(), ContextKind::kEgl);
    }
    const ScopedEnv env("ZENITH_GL", "direct3d");
    try {
        ContextKindFromEnvironment();
        ADD_FAILURE() << "accepted ZENITH_GL=direct3d";
    } catch (const zenith::ArgumentError& error) {
        EXPECT_CONTAINS(error.what(), "ZENITH_GL");
        EXPECT_CONTAINS(error.what(), "direct3d");
    }
}

TEST(EglOptionsTest, ParsesPlatformsAndDeviceIndices) {
    EXPECT_EQ(ParseEglOptions("auto").platform, EglPlatform::kAuto);
    EXPECT_EQ(ParseEglOptions("surfaceless").platform, EglPlatform::kSurfaceless);
    const EglOptions any_device = ParseEglOptions("device");
    EXPECT_EQ(any_device.platform, EglPlatform::kDevice);
    EXPECT_EQ(any_device.device_index, -1);
    const EglOptions device3 = ParseEglOptions("device:3");
    EXPECT_EQ(device3.platform, EglPlatform::kDevice);
    EXPECT_EQ(device3.device_index, 3);
    for (const char* bad : {"", "device:", "device:-1", "device:1x", "device:x", "wayland"}) {
        EXPECT_THROW(ParseEglOptions(bad), zenith::ArgumentError) << "'" << bad << "'";
    }
    const ScopedEnv env("ZENITH_EGL_PLATFORM", "x11");
    try {
        EglOptionsFromEnvironment();
        ADD_FAILURE() << "accepted ZENITH_EGL_PLATFORM=x11";
    } catch (const zenith::ArgumentError& error) {
        EXPECT_CONTAINS(error.what(), "ZENITH_EGL_PLATFORM");
        EXPECT_CONTAINS(error.what(), "device:N");
    }
}

// --- contexts ---

class HeadlessContextTest : public ::testing::TestWithParam<ContextKind> {};

TEST_P(HeadlessContextTest, ProvidesGl45CoreAndReportsItself) {
    const std::unique_ptr<HeadlessContext> context = CreateHeadlessContext(GetParam());
    ASSERT_NE(context, nullptr);
    EXPECT_EQ(context->kind(), GetParam());
    const GlInfo& info = context->info();
    std::cout << "[" << ToString(GetParam()) << "] " << context->description() << "\n  "
              << Describe(info) << ", GLSL " << info.shading_language << std::endl;
    RecordProperty("gl_version", info.version_string);
    RecordProperty("gl_renderer", info.renderer);
    EXPECT_GE(info.version, kRequiredGlVersion) << info.version_string;
    EXPECT_TRUE(info.core_profile);
    EXPECT_FALSE(info.renderer.empty());
    EXPECT_FALSE(context->description().empty());
    EXPECT_NE(context->get_proc_address(), nullptr);
}

TEST_P(HeadlessContextTest, ComputeShaderWritesSsbo) {
    const auto context = CreateHeadlessContext(GetParam());
    ExpectComputeWritesSsbo();
}

TEST_P(HeadlessContextTest, ComputeShaderWritesImage) {
    const auto context = CreateHeadlessContext(GetParam());
    ExpectComputeWritesImage();
}

TEST_P(HeadlessContextTest, ShaderErrorsCarryLabelAndInfoLog) {
    const auto context = CreateHeadlessContext(GetParam());
    try {
        Program::Compute(
            "#version 450 core\nlayout(local_size_x = 1) in;\n"
            "void main() { undefined_function(); }\n",
            "broken.comp");
        ADD_FAILURE() << "a broken shader compiled";
    } catch (const ShaderError& error) {
        EXPECT_CONTAINS(error.what(), "broken.comp");
        EXPECT_CONTAINS(error.what(), "compute shader failed to compile");
        EXPECT_CONTAINS(error.what(), "undefined_function");
    }
    // The context is still usable after the failure.
    ExpectComputeWritesSsbo();
}

// The path a host application takes: its own context, its own getProcAddress.
TEST_P(HeadlessContextTest, LoadsThroughAHostCallback) {
    const auto context = CreateHeadlessContext(GetParam());
    const GetProcAddressFn host_loader = context->get_proc_address();
    int lookups = 0;
    const GlInfo info = LoadGlFunctions([&](const char* name) {
        ++lookups;
        return host_loader(name);
    });
    EXPECT_GT(lookups, 100);
    EXPECT_EQ(info.renderer, context->info().renderer);
    ExpectComputeWritesSsbo();
}

TEST_P(HeadlessContextTest, TooHighARequiredVersionIsAClearError) {
    const auto context = CreateHeadlessContext(GetParam());
    try {
        LoadGlFunctions(context->get_proc_address(), GlVersion{9, 9});
        ADD_FAILURE() << "GL 9.9 accepted";
    } catch (const ContextError& error) {
        EXPECT_CONTAINS(error.what(), "OpenGL 9.9 is required");
        EXPECT_CONTAINS(error.what(), context->info().renderer);
    }
}

TEST_P(HeadlessContextTest, RefusedVersionIsAContextError) {
    ContextOptions options;
    options.kind = GetParam();
    options.version = {9, 0};
    try {
        CreateHeadlessContext(options);
        ADD_FAILURE() << "a GL 9.0 context was created";
    } catch (const ContextError& error) {
        std::cout << error.what() << std::endl;
        EXPECT_CONTAINS(error.what(), "9.0");
        EXPECT_CONTAINS(error.what(), "ZENITH_GL=");  // what to try instead
    }
}

INSTANTIATE_TEST_SUITE_P(Kinds, HeadlessContextTest,
                         ::testing::Values(ContextKind::kOsMesa, ContextKind::kEgl),
                         [](const auto& param) { return std::string(ToString(param.param)); });

TEST(HeadlessContextSwitchTest, OsMesaAndEglAlternateInOneProcess) {
    const auto osmesa = CreateHeadlessContext(ContextKind::kOsMesa);
    const auto egl = CreateHeadlessContext(ContextKind::kEgl);
    for (int round = 0; round < 2; ++round) {
        SCOPED_TRACE(round);
        osmesa->MakeCurrent();
        ExpectComputeWritesSsbo();
        egl->MakeCurrent();
        ExpectComputeWritesSsbo();
    }
    // Two contexts on one EGL display: destroying one leaves the display to the other.
    auto egl2 = CreateHeadlessContext(ContextKind::kEgl);
    egl2.reset();
    egl->MakeCurrent();
    ExpectComputeWritesSsbo();
}

TEST(EglContextTest, MissingDeviceListsWhatWasTried) {
    ContextOptions options;
    options.kind = ContextKind::kEgl;
    options.egl = {EglPlatform::kDevice, 99};
    try {
        CreateHeadlessContext(options);
        ADD_FAILURE() << "EGL device 99 exists?";
    } catch (const ContextError& error) {
        std::cout << error.what() << std::endl;
        EXPECT_CONTAINS(error.what(), "Tried:");
        EXPECT_CONTAINS(error.what(), "device 99");
        EXPECT_CONTAINS(error.what(), "apt-get install");
    }
}

TEST(EglContextTest, SurfacelessAndDevicePlatformsWhereOffered) {
    for (const char* platform : {"surfaceless", "device"}) {
        SCOPED_TRACE(platform);
        ContextOptions options;
        options.kind = ContextKind::kEgl;
        options.egl = ParseEglOptions(platform);
        std::unique_ptr<HeadlessContext> context;
        try {
            context = CreateHeadlessContext(options);
        } catch (const ContextError& error) {
            // Not every machine offers both; the message must still say why.
            std::cout << platform << " unavailable: " << error.what() << std::endl;
            EXPECT_CONTAINS(error.what(), "Tried:");
            continue;
        }
        std::cout << context->description() << ": " << Describe(context->info()) << std::endl;
        ExpectComputeWritesSsbo();
    }
}

}  // namespace
}  // namespace zenith::sky::gl
