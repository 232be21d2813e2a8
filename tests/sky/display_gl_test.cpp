// The GPU display pass (zenith/sky/display.h) against the CPU path of `zenith render`'s PNGs
// (image_io.h ToneMapToSrgb8, AutoExposureEV100) and against the closed forms of the exposure
// (Lagarde & de Rousiers 2014 §5.1), the tone map (Narkowicz 2016) and sRGB (IEC 61966-2-1).
#include <glad/gl.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "colour_target.h"
#include "gl_test_support.h"
#include "reference/display_functions.h"
#include "zenith/sky/display.h"
#include "zenith/sky/image_io.h"

namespace zenith::sky {
namespace {

class DisplayPassTest : public gl::test::HeadlessGlTest {
  protected:
    // An RGBA32F texture holding `image` (texture row y = image row y: the transform is per
    // pixel, so the rows' order does not matter here).
    static GLuint Upload(const Image& image) {
        GLuint texture = 0;
        glCreateTextures(GL_TEXTURE_2D, 1, &texture);
        glTextureStorage2D(texture, 1, GL_RGBA32F, image.width, image.height);
        glTextureSubImage2D(texture, 0, 0, 0, image.width, image.height, GL_RGBA, GL_FLOAT,
                            image.pixels.data());
        return texture;
    }

    // The stored bytes of a host target, RGB of each pixel (no sRGB decoding:
    // glGetTextureImage returns what is stored).
    static std::vector<std::uint8_t> Rgb(const zenith::test::ColourTarget& target) {
        const std::vector<std::uint8_t> rgba = target.ReadBytes();
        std::vector<std::uint8_t> rgb;
        rgb.reserve(rgba.size() / 4 * 3);
        for (std::size_t i = 0; i < rgba.size(); i += 4) {
            rgb.insert(rgb.end(), rgba.begin() + static_cast<std::ptrdiff_t>(i),
                       rgba.begin() + static_cast<std::ptrdiff_t>(i + 3));
        }
        return rgb;
    }

    static DisplaySettings Given(double ev100, bool night) {
        DisplaySettings s;
        s.output = DisplaySettings::Output::kDisplay;
        s.ev100 = ev100;
        s.night_adaptation = night;
        return s;
    }
    static DisplaySettings Metered(bool night, double tau = 0.0) {
        DisplaySettings s;
        s.output = DisplaySettings::Output::kDisplay;
        s.night_adaptation = night;
        s.adaptation_time_s = tau;
        return s;
    }
};

// 14 decades of luminance (1e-5 to 1e9 cd/m^2) across, a colour per row (grey, sky blue,
// sunset orange, green, the primaries, a dim blue), and a few bad pixels: NaN, +inf, negative.
Image TestImage() {
    const glm::vec3 colours[] = {{1, 1, 1},       {0.3f, 0.5f, 1.0f}, {1.0f, 0.6f, 0.3f},
                                 {0.2f, 1, 0.2f}, {1, 0, 0},          {0, 1, 0},
                                 {0, 0, 1},       {0.05f, 0.1f, 0.4f}};
    constexpr int kWidth = 512, kRowsPerColour = 4;
    Image image(kWidth, 8 * kRowsPerColour);
    for (int y = 0; y < image.height; ++y) {
        const glm::vec3 c = colours[y / kRowsPerColour];
        const float y_of_c = 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b;
        for (int x = 0; x < kWidth; ++x) {
            const double l = std::pow(10.0, -5.0 + 14.0 * (x + 0.25 * (y % 4)) / (kWidth - 1));
            image.at(x, y) = glm::vec4(c * static_cast<float>(l / y_of_c), 1.0f);
        }
    }
    image.at(0, 0) = glm::vec4(std::numeric_limits<float>::quiet_NaN(), 1.0f, 1.0f, 1.0f);
    image.at(1, 0) = glm::vec4(std::numeric_limits<float>::infinity(), 1.0f, 1.0f, 1.0f);
    image.at(2, 0) = glm::vec4(-5.0f, 100.0f, -1.0f, 1.0f);
    return image;
}

// Same luminance in, same 8-bit values out as the PNG path, within 1 LSB, in an RGBA8 target
// and in an SRGB8_ALPHA8 one (the same bytes: the pass encodes, GL_FRAMEBUFFER_SRGB stays off).
TEST_F(DisplayPassTest, MatchesTheCpuPngPathWithinOneLsb) {
    const Image image = TestImage();
    const GLuint input = Upload(image);
    DisplayPass pass;
    for (GLenum format : {GLenum{GL_RGBA8}, GLenum{GL_SRGB8_ALPHA8}}) {
        const zenith::test::ColourTarget target(format, image.width, image.height);
        for (bool night : {false, true}) {
            for (double ev : {-6.0, 0.0, 6.0, 12.0, 15.0}) {
                SCOPED_TRACE(testing::Message()
                             << "format " << format << " night " << night << " EV100 " << ev);
                pass.Run(input, target.framebuffer(), {0, 0, image.width, image.height},
                         Given(ev, night), 0.0);
                const std::vector<std::uint8_t> gpu = Rgb(target);
                const Srgb8Image cpu = ToneMapToSrgb8(image, ev, night);
                ASSERT_EQ(gpu.size(), cpu.rgb.size());
                int worst = 0;
                std::size_t off_by_one = 0, distinct = 0;
                for (std::size_t i = 0; i < gpu.size(); ++i) {
                    const int d = std::abs(int{gpu[i]} - int{cpu.rgb[i]});
                    worst = std::max(worst, d);
                    off_by_one += d == 1 ? 1u : 0u;
                    distinct += cpu.rgb[i] != 0 && cpu.rgb[i] != 255 ? 1u : 0u;
                }
                EXPECT_LE(worst, 1);
                for (std::size_t i = 0; i < gpu.size() && worst > 1; ++i) {
                    const std::size_t p = i / 3;
                    const glm::vec4 v = image.pixels[p];
                    if (std::abs(int{gpu[i]} - int{cpu.rgb[i]}) > 1) {
                        ADD_FAILURE() << "pixel " << p % 512 << "," << p / 512 << " (" << v.r
                                      << ", " << v.g << ", " << v.b << ") channel " << i % 3
                                      << ": GPU " << int{gpu[i]} << ", CPU " << int{cpu.rgb[i]};
                        break;
                    }
                }
                EXPECT_GT(distinct, gpu.size() / 20);  // the EV puts part of the ramp mid-range
                std::printf(
                    "format %04X night %d EV100 %5.1f: worst %d LSB, %zu of %zu values "
                    "1 LSB off, %zu mid-range\n",
                    format, night ? 1 : 0, ev, worst, off_by_one, gpu.size(), distinct);
            }
        }
    }
    glDeleteTextures(1, &input);
}

// A given EV100 against the closed forms written out here (not through display.glsl):
// L_max = 78 / (q S) 2^EV100 with q = 0.65, S = 100; x = L / L_max; ACES fitted; sRGB.
TEST_F(DisplayPassTest, GivenEv100IsTheClosedForm) {
    constexpr double kEv = 10.0;
    const double l_max = 78.0 / (0.65 * 100.0) * std::pow(2.0, kEv);  // 1228.8 cd/m^2
    EXPECT_DOUBLE_EQ(l_max, 1228.8);
    EXPECT_DOUBLE_EQ(ExposureScale(kEv), 1.0 / 1228.8);
    const double luminances[] = {5.0, 20.0, 100.0, 0.18 * l_max, 500.0, l_max, 5000.0, 1e5};
    Image image(8, 1);
    for (int i = 0; i < 8; ++i) {
        const auto l = static_cast<float>(luminances[i]);
        image.at(i, 0) = glm::vec4(l, l, l, 1.0f);
    }
    const GLuint input = Upload(image);
    const zenith::test::ColourTarget target(GL_RGBA8, 8, 1);
    DisplayPass pass;
    pass.Run(input, target.framebuffer(), {0, 0, 8, 1}, Given(kEv, false), 0.0);
    ASSERT_TRUE(pass.exposure_ev100().has_value());
    EXPECT_DOUBLE_EQ(*pass.exposure_ev100(), kEv);
    const std::vector<std::uint8_t> rgb = Rgb(target);
    for (int i = 0; i < 8; ++i) {
        const double x = static_cast<double>(image.at(i, 0).r) / l_max;
        const double aces =
            std::clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
        const double srgb =
            aces <= 0.0031308 ? 12.92 * aces : 1.055 * std::pow(aces, 1.0 / 2.4) - 0.055;
        const double want = static_cast<double>(std::lround(255.0 * srgb));
        SCOPED_TRACE(testing::Message() << "L = " << luminances[i] << " cd/m^2, x = " << x);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(rgb[static_cast<std::size_t>(3 * i + c)], want, 1);
    }
    glDeleteTextures(1, &input);
}

// The GPU meter (histogram, 0.05 EV bins) against AutoExposureEV100's sort, and the night
// compensation on top of it (Krawczyk et al.'s key, display.glsl).
TEST_F(DisplayPassTest, MeterIsTheCpuMeter) {
    Image image(320, 180);
    std::uint32_t state = 12345;
    for (glm::vec4& p : image.pixels) {
        state = state * 1664525u + 1013904223u;
        const double u = (state >> 8) / 16777216.0;
        const auto l = static_cast<float>(std::pow(10.0, -4.0 + 9.0 * u));  // 1e-4..1e5
        p = glm::vec4(l * 0.8f, l, l * 1.3f, 1.0f);
    }
    const GLuint input = Upload(image);
    const zenith::test::ColourTarget target(GL_RGBA8, image.width, image.height);
    DisplayPass pass;
    const double cpu = AutoExposureEV100(image);
    pass.Run(input, target.framebuffer(), {0, 0, image.width, image.height}, Metered(false), 0.0);
    const double gpu = *pass.exposure_ev100();
    std::printf("metered EV100: CPU %.4f, GPU %.4f\n", cpu, gpu);
    EXPECT_NEAR(gpu, cpu, 0.03);  // half a bin (0.025 EV) and float sums

    pass.Run(input, target.framebuffer(), {0, 0, image.width, image.height}, Metered(true), 0.0);
    const double log2_average = cpu - std::log2(100.0 / 12.5);
    const double night = cpu + ref::DisplayNightCompensationEV(std::exp2(log2_average));
    std::printf("with night compensation: CPU %.4f, GPU %.4f\n", night, *pass.exposure_ev100());
    EXPECT_NEAR(*pass.exposure_ev100(), night, 0.03);
    glDeleteTextures(1, &input);
}

// Metered exposure adapts in EV with the time constant: EV += (target - EV)(1 - exp(-dt/tau)).
TEST_F(DisplayPassTest, AdaptationFollowsItsTimeConstant) {
    Image bright(64, 64, glm::vec4(1000.0f, 1000.0f, 1000.0f, 1.0f));
    Image dim(64, 64, glm::vec4(10.0f, 10.0f, 10.0f, 1.0f));
    const GLuint a = Upload(bright), b = Upload(dim);
    const zenith::test::ColourTarget target(GL_RGBA8, 64, 64);
    DisplayPass pass;
    const glm::ivec4 viewport{0, 0, 64, 64};
    pass.Run(a, target.framebuffer(), viewport, Metered(false, 2.0), 0.0);
    const double ev_a = *pass.exposure_ev100();
    EXPECT_NEAR(ev_a, std::log2(1000.0 * 100.0 / 12.5), 0.03);  // a first frame: no adaptation
    pass.Run(b, target.framebuffer(), viewport, Metered(false, 2.0), 0.5);
    const double ev_b = std::log2(10.0 * 100.0 / 12.5);
    const double target_b = *pass.metered_target_ev100();  // ev_b within half a bin
    EXPECT_NEAR(target_b, ev_b, 0.03);
    const double want = ev_a + (target_b - ev_a) * (1.0 - std::exp(-0.5 / 2.0));
    EXPECT_NEAR(*pass.exposure_ev100(), want, 1e-4);
    pass.ResetAdaptation();  // a cut: the next frame is its own
    pass.Run(b, target.framebuffer(), viewport, Metered(false, 2.0), 0.5);
    EXPECT_NEAR(*pass.exposure_ev100(), ev_b, 0.03);
    glDeleteTextures(1, &a);
    glDeleteTextures(1, &b);
}

TEST(DisplaySettingsTest, BadSettingsAreRefused) {
    DisplaySettings s;
    s.ev100 = 31.0;
    EXPECT_THROW(s.Validate(), ArgumentError);
    s.ev100.reset();
    s.adaptation_time_s = -1.0;
    EXPECT_THROW(s.Validate(), ArgumentError);
    s.adaptation_time_s = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW(s.Validate(), ArgumentError);
}

// The constants image_io.h publishes are the shared text's.
TEST(DisplayFunctionsTest, PublicConstantsAreTheSharedOnes) {
    EXPECT_EQ(kMinExposureEV100, ref::kDisplayMinEV100);
    EXPECT_EQ(kMaxExposureEV100, ref::kDisplayMaxEV100);
    EXPECT_EQ(kMinMeteredLuminance, ref::kDisplayMinMeteredLuminance);
    // Night compensation: none in daylight, about 3.2 EV at a moonlit 1e-3 cd/m^2.
    EXPECT_EQ(ref::DisplayNightCompensationEV(5000.0), 0.0);
    EXPECT_EQ(ref::DisplayNightCompensationEV(4.0), 0.0);
    EXPECT_NEAR(ref::DisplayNightCompensationEV(1e-3), 3.25, 0.05);
    // The rods' share: 1 below 0.01 cd/m^2, 0 above 4.
    EXPECT_EQ(ref::DisplayScotopicWeight(1e-3), 1.0);
    EXPECT_EQ(ref::DisplayScotopicWeight(5.0), 0.0);
    // Photopic colours are untouched by the night adaptation.
    const glm::dvec3 day(200.0, 300.0, 500.0);
    EXPECT_EQ(ref::DisplayNightAdaptation(day), day);
}

}  // namespace
}  // namespace zenith::sky
