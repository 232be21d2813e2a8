// SceneDepth's conventions: the same host geometry (5 km away over the left half of the frame,
// nothing over the right half) in a standard or reversed-Z depth buffer, with a finite or an
// infinite far plane, gets the same aerial perspective and the same sky; a multisampled depth
// texture is refused with a message instead of drawing no sky.
#include <glad/gl.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <glm/gtc/constants.hpp>
#include <limits>
#include <string>
#include <vector>

#include "host_frame.h"
#include "zenith/sim/sky_system.h"
#include "zenith/sky/clouds/weather.h"

namespace zenith::sim {
namespace {

constexpr int kSize = 32;
constexpr double kNear = 1.0, kFar = 200000.0, kEyeDepth = 5000.0;
constexpr float kColour = 1000.0f;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

// The window depth of eye depth z (sky::SceneDepth's formulas).
double WindowDepth(double z, double n, double f, bool reversed) {
    if (std::isinf(f)) return reversed ? n / z : 1.0 - n / z;
    return reversed ? n * (f - z) / (z * (f - n)) : f * (z - n) / (z * (f - n));
}

class DepthConventionsTest : public ::testing::Test {
  protected:
    static void SetUpTestSuite() {
        sky_ = SkySystem::CreateHeadless().release();
        sky_->SetTime(geo::TimeFromIso8601("2024-06-21T09:00:00Z"));
        sky_->SetGeodetic(46.5, 8.0, 1500.0);
        sky_->SetAttitude(glm::radians(120.0), 0.0, 0.0);
        sky_->SetProjection(1.0, 1.0);
        sky_->Update();
    }
    static void TearDownTestSuite() { delete sky_; }

    // The host's frame after Render over geometry at kEyeDepth on the left half.
    static std::vector<glm::vec4> Draw(double far_m, bool reversed) {
        const float geometry = static_cast<float>(WindowDepth(kEyeDepth, kNear, far_m, reversed));
        const float cleared = reversed ? 0.0f : 1.0f;
        std::vector<float> depth(kSize * kSize, cleared);
        for (int y = 0; y < kSize; ++y) {
            for (int x = 0; x < kSize / 2; ++x)
                depth[static_cast<std::size_t>(y * kSize + x)] = geometry;
        }
        test::HostFrame frame(kSize, kSize);
        return frame.Render(*sky_, depth, kColour, kNear, far_m, reversed);
    }

    static SkySystem* sky_;
};
SkySystem* DepthConventionsTest::sky_ = nullptr;

TEST_F(DepthConventionsTest, EveryConventionGivesTheSameFrame) {
    const std::vector<glm::vec4> standard = Draw(kFar, false);
    const sky::LutImage sky_only = sky_->RenderOffscreen({kSize, kSize});
    // The standard frame: aerial perspective over the geometry (neither the host's colour nor
    // the sky), the sky beside it.
    const glm::vec4& geometry = standard[static_cast<std::size_t>(16 * kSize + 4)];
    EXPECT_GT(std::abs(geometry.g - kColour), 0.01f * kColour);
    EXPECT_GT(std::abs(geometry.g - sky_only.at(4, 16).g), 0.01f * sky_only.at(4, 16).g);
    for (int x = kSize / 2; x < kSize; ++x) {
        ASSERT_NEAR(standard[static_cast<std::size_t>(16 * kSize + x)].g, sky_only.at(x, 16).g,
                    1e-5f * sky_only.at(x, 16).g);
    }
    struct Convention {
        const char* name;
        double far_m;
        bool reversed;
    };
    for (const Convention c : {Convention{"reversed-Z, finite far", kFar, true},
                               Convention{"standard, infinite far", kInfinity, false},
                               Convention{"reversed-Z, infinite far", kInfinity, true}}) {
        const std::vector<glm::vec4> pixels = Draw(c.far_m, c.reversed);
        double worst_geometry = 0.0, worst_sky = 0.0;
        for (int y = 0; y < kSize; ++y) {
            for (int x = 0; x < kSize; ++x) {
                const std::size_t i = static_cast<std::size_t>(y * kSize + x);
                for (int ch = 0; ch < 3; ++ch) {
                    const double d =
                        std::abs(pixels[i][ch] - standard[i][ch]) / std::abs(standard[i][ch]);
                    (x < kSize / 2 ? worst_geometry : worst_sky) =
                        std::max(x < kSize / 2 ? worst_geometry : worst_sky, d);
                }
            }
        }
        std::printf("%s: geometry within %.3g, sky within %.3g of the standard frame\n", c.name,
                    worst_geometry, worst_sky);
        // float depth: 1e-7 of d is ~1e-3 m at 5 km in reversed-Z, ~1.5 m in standard depth.
        EXPECT_LT(worst_geometry, 1e-3) << c.name;
        EXPECT_LT(worst_sky, 1e-5) << c.name;
    }
}

// With clouds: host geometry 300 m away (in front of every cloud), 60 km away in the upper half
// of the frame (above the cumulus layer there, 1.5-4 km high, behind the cumulus in view) and
// none, from 500 m looking up through scattered cumulus. The clouds' depth test against the
// host's (render.frag: only the clouds nearer than the geometry) gives the same frame in every
// convention; and the far geometry is hidden by the clouds where the near is not. Geometry
// inside a cloud is kept out: there the clouds in front of it come from its own ray marched to
// its depth where the trace cells disagree, and the standard convention's depth 30 km away is
// 50 m uncertain (a float's step below 1), which inside a cumulus' core is 2 optical depths.
TEST_F(DepthConventionsTest, CloudsOccludeTheSameGeometryInEveryConvention) {
    sky_->SetGeodetic(46.5, 8.0, 500.0);
    sky_->SetAttitude(glm::radians(120.0), 0.15, 0.0);
    sky::CloudSettings settings;
    settings.noise_cache_directory = std::filesystem::path(ZENITH_BINARY_DIR) / "cloud-noise-cache";
    const auto draw = [&](double far_m, bool reversed) {
        const float near_geometry = static_cast<float>(WindowDepth(300.0, kNear, far_m, reversed));
        const float far_geometry = static_cast<float>(WindowDepth(60000.0, kNear, far_m, reversed));
        std::vector<float> depth(kSize * kSize, reversed ? 0.0f : 1.0f);
        for (int y = 0; y < kSize; ++y) {
            for (int x = 0; x < 2 * kSize / 3; ++x) {
                if (x >= kSize / 3 && y < kSize / 2) continue;
                depth[static_cast<std::size_t>(y * kSize + x)] =
                    x < kSize / 3 ? near_geometry : far_geometry;
            }
        }
        sky_->ResetCloudHistory();  // each frame the first of its history: comparable
        sky_->Update();
        test::HostFrame frame(kSize, kSize);
        return frame.Render(*sky_, depth, kColour, kNear, far_m, reversed);
    };
    const std::vector<glm::vec4> clear = draw(kFar, false);
    sky_->SetWeather(sky::clouds::LoadWeather("scattered_cumulus"), settings);
    const std::vector<glm::vec4> standard = draw(kFar, false);
    // What the clouds change in each band: little in front of the near geometry (the air under
    // the clouds is shaded a little), much over the far geometry and the sky.
    double change[3] = {0.0, 0.0, 0.0};
    for (int y = 0; y < kSize; ++y) {
        for (int x = 0; x < kSize; ++x) {
            const std::size_t i = static_cast<std::size_t>(y * kSize + x);
            change[std::min(3 * x / kSize, 2)] +=
                std::abs(standard[i].g - clear[i].g) / clear[i].g / (kSize * kSize / 3.0);
        }
    }
    std::printf("clouds change the frame by %.3f (near geometry), %.3f (far), %.3f (sky)\n",
                change[0], change[1], change[2]);
    EXPECT_GT(change[1], 3.0 * change[0]);
    EXPECT_GT(change[2], 3.0 * change[0]);
    for (const bool reversed : {false, true}) {
        for (const double far_m : {kFar, kInfinity}) {
            if (!reversed && far_m == kFar) continue;
            const std::vector<glm::vec4> pixels = draw(far_m, reversed);
            double worst = 0.0;
            for (std::size_t i = 0; i < pixels.size(); ++i) {
                for (int ch = 0; ch < 3; ++ch) {
                    const double d =
                        std::abs(pixels[i][ch] - standard[i][ch]) / std::abs(standard[i][ch]);
                    worst = std::max(worst, d);
                }
            }
            std::printf("clouds, %s, far %g m: within %.3g of the standard frame\n",
                        reversed ? "reversed-Z" : "standard", far_m, worst);
            EXPECT_LT(worst, 1e-3);
        }
    }
    sky_->SetWeather({});
    sky_->SetGeodetic(46.5, 8.0, 1500.0);
    sky_->SetAttitude(glm::radians(120.0), 0.0, 0.0);
    sky_->Update();
}

TEST_F(DepthConventionsTest, AMultisampledDepthTextureIsRefused) {
    GLuint multisampled = 0, volume = 0;
    glCreateTextures(GL_TEXTURE_2D_MULTISAMPLE, 1, &multisampled);
    glTextureStorage2DMultisample(multisampled, 4, GL_DEPTH_COMPONENT32F, kSize, kSize, GL_TRUE);
    glCreateTextures(GL_TEXTURE_3D, 1, &volume);
    glTextureStorage3D(volume, 1, GL_R32F, 4, 4, 4);
    try {
        sky_->SetSceneDepth(multisampled, kNear, kFar);
        ADD_FAILURE() << "a multisampled depth texture was accepted";
    } catch (const ArgumentError& e) {
        EXPECT_NE(std::string(e.what()).find("multisampled"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("glBlitFramebuffer"), std::string::npos) << e.what();
    }
    EXPECT_THROW(sky_->SetSceneDepth(volume, kNear, kFar), ArgumentError);
    EXPECT_THROW(sky_->SetSceneDepth(987654, kNear, kFar), ArgumentError);
    EXPECT_THROW(sky_->SetSceneDepth(volume, kNear, kNear), ArgumentError);
    glDeleteTextures(1, &multisampled);
    glDeleteTextures(1, &volume);
    EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

}  // namespace
}  // namespace zenith::sim
