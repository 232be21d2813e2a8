// SkySystem's display pass as a host sees it (issue 16 item 6): an RGBA8 target, a noon frame
// and a moonlit-night frame metered from the rendered luminance.
#include <glad/gl.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <glm/gtc/constants.hpp>
#include <memory>
#include <vector>

#include "colour_target.h"
#include "zenith/sim/sky_system.h"
#include "zenith/sky/gl/context.h"

namespace zenith::sim {
namespace {

constexpr int kWidth = 320, kHeight = 180;

// The host's 8-bit target.
struct Rgba8Target : zenith::test::ColourTarget {
    Rgba8Target() : ColourTarget(GL_RGBA8, kWidth, kHeight) {}
};

// What a frame looks like on the screen: mean Rec.709 luma of the encoded values (0-255), the
// share of white pixels, and the mean HSV saturation (max - min) / max of pixels that are not
// black (max >= 8).
struct Look {
    double mean = 0.0, white = 0.0, saturation = 0.0;
    double red = 0.0, blue = 0.0;  // mean encoded values
};
Look LookOf(const std::vector<std::uint8_t>& rgba) {
    Look look;
    double saturation_sum = 0.0;
    std::size_t coloured = 0, white = 0;
    const std::size_t n = rgba.size() / 4;
    for (std::size_t i = 0; i < n; ++i) {
        const double r = rgba[4 * i], g = rgba[4 * i + 1], b = rgba[4 * i + 2];
        look.mean += 0.2126 * r + 0.7152 * g + 0.0722 * b;
        look.red += r;
        look.blue += b;
        const double hi = std::max({r, g, b}), lo = std::min({r, g, b});
        if (lo >= 255.0) ++white;
        if (hi >= 8.0) {
            saturation_sum += (hi - lo) / hi;
            ++coloured;
        }
    }
    look.mean /= static_cast<double>(n);
    look.red /= static_cast<double>(n);
    look.blue /= static_cast<double>(n);
    look.white = static_cast<double>(white) / static_cast<double>(n);
    look.saturation = coloured > 0 ? saturation_sum / static_cast<double>(coloured) : 0.0;
    return look;
}

class DisplaySkyTest : public ::testing::Test {
  protected:
    static void SetUpTestSuite() {
        context_ = sky::gl::CreateHeadlessContextFromEnvironment().release();
    }
    static void TearDownTestSuite() {
        delete context_;
        context_ = nullptr;
    }

    // Zurich, looking south 6 deg up: ground below, sky above.
    static std::unique_ptr<SkySystem> MakeSky(const sky::DisplaySettings& display) {
        SkySystemSettings settings;
        settings.display = display;
        auto sky = SkySystem::CreateInHostContext(context_->get_proc_address(), settings);
        sky->SetGeodetic(47.45, 8.56, 420.0);
        sky->SetAttitude(glm::pi<double>(), 0.1, 0.0);
        sky->SetProjection(1.0, static_cast<double>(kWidth) / kHeight);
        return sky;
    }
    static Look Frame(SkySystem& sky, const char* utc, const Rgba8Target& target) {
        sky.SetTime(geo::TimeFromIso8601(utc));
        sky.ResetCloudHistory();
        sky.Update();
        sky.Render(target.framebuffer(), {0, 0, kWidth, kHeight});
        const Look look = LookOf(target.ReadBytes());
        const std::optional<double> ev = sky.exposure_ev100();
        std::printf("%s: mean %.1f / 255, white %.4f, saturation %.3f, EV100 %s (%s)\n", utc,
                    look.mean, look.white, look.saturation,
                    ev ? std::to_string(*ev).c_str() : "none", ToString(sky.lighting().phase));
        return look;
    }

    static sky::gl::HeadlessContext* context_;
};
sky::gl::HeadlessContext* DisplaySkyTest::context_ = nullptr;

constexpr const char* kNoon = "2024-06-21T11:30:00Z";
// The full Moon of 2024-12-15 (09:02 UTC) stands ~65 deg high in the south at midnight.
constexpr const char* kMoonlit = "2024-12-14T23:30:00Z";

sky::DisplaySettings MeteredDisplay() {
    sky::DisplaySettings display;
    display.output = sky::DisplaySettings::Output::kDisplay;
    display.adaptation_time_s = 0.0;
    return display;
}

// Linear output into an RGBA8 target is white (today's default, unchanged); the display pass
// is not.
TEST_F(DisplaySkyTest, AnRgba8TargetIsNoLongerWhite) {
    const Rgba8Target target;
    const auto linear = MakeSky({});
    const Look before = Frame(*linear, kNoon, target);
    EXPECT_GT(before.white, 0.9);  // cd/m^2 in [0, 1] storage
    EXPECT_FALSE(linear->exposure_ev100().has_value());
    const auto display = MakeSky(MeteredDisplay());
    const Look after = Frame(*display, kNoon, target);
    EXPECT_LT(after.white, 0.01);  // at most the Sun's neighbourhood
}

// Metered noon and moonlit night. Thresholds: a metered daylit frame lands mid-range (the
// meter's K = 12.5 puts the log-average at ~13 % of saturation, 0.4 after the tone map and sRGB,
// ~100/255), so its mean is asked to be in [60, 170]. A moonlit night is metered to the same
// grey and then darkened by the night compensation (3.2 EV at 1e-3 cd/m^2: 1/9 of the light),
// so it is asked to be in [5, 50] and below 40 % of noon's; its colours take the rods' blue-grey,
// so its saturation is asked to be below noon's (and below 0.35: not a saturated blue), with
// more blue than red. Without
// the night adaptation the same night meters to day brightness, which the last check shows.
TEST_F(DisplaySkyTest, NoonAndAMoonlitNightLandWhereAnEyeWouldPutThem) {
    const Rgba8Target target;
    const auto sky = MakeSky(MeteredDisplay());
    const Look noon = Frame(*sky, kNoon, target);
    const Look night = Frame(*sky, kMoonlit, target);
    EXPECT_EQ(sky->lighting().phase, DayPhase::kNight);
    EXPECT_GT(noon.mean, 60.0);
    EXPECT_LT(noon.mean, 170.0);
    EXPECT_GT(night.mean, 5.0);
    EXPECT_LT(night.mean, 50.0);
    EXPECT_LT(night.mean, 0.4 * noon.mean);
    EXPECT_LT(night.saturation, noon.saturation);
    EXPECT_LT(night.saturation, 0.35);
    EXPECT_GT(night.blue, night.red);  // the blue shift

    sky::DisplaySettings day_vision = MeteredDisplay();
    day_vision.night_adaptation = false;
    sky->SetDisplay(day_vision);
    const Look night_as_day = Frame(*sky, kMoonlit, target);
    EXPECT_GT(night_as_day.mean, 2.0 * night.mean);  // metering alone makes night look like day
}

// A given EV100 is what exposure_ev100() reports, and SetDisplay validates.
TEST_F(DisplaySkyTest, GivenExposureIsReported) {
    const Rgba8Target target;
    sky::DisplaySettings display = MeteredDisplay();
    display.ev100 = 14.0;
    const auto sky = MakeSky(display);
    Frame(*sky, kNoon, target);
    ASSERT_TRUE(sky->exposure_ev100().has_value());
    EXPECT_DOUBLE_EQ(*sky->exposure_ev100(), 14.0);
    display.ev100 = 99.0;
    EXPECT_THROW(sky->SetDisplay(display), ArgumentError);
}

// Prepare runs the display pass too (llvmpipe compiles each shader at its first dispatch or
// draw; what that saves is measured by first_frame_report --display, not here), and it is a
// warm-up, not a state change: it reports no exposure, and the first frame after it is the
// frame without it, byte for byte.
TEST_F(DisplaySkyTest, PrepareWarmsTheDisplayPassWithoutChangingTheFrame) {
    const Rgba8Target target;
    const auto prepared = MakeSky(MeteredDisplay());
    prepared->SetTime(geo::TimeFromIso8601(kNoon));
    prepared->Prepare({kWidth, kHeight});
    EXPECT_FALSE(prepared->exposure_ev100().has_value());
    prepared->Update();
    prepared->Render(target.framebuffer(), {0, 0, kWidth, kHeight});
    const std::vector<std::uint8_t> after_prepare = target.ReadBytes();
    EXPECT_TRUE(prepared->exposure_ev100().has_value());

    const auto fresh = MakeSky(MeteredDisplay());
    fresh->SetTime(geo::TimeFromIso8601(kNoon));
    fresh->Update();
    fresh->Render(target.framebuffer(), {0, 0, kWidth, kHeight});
    EXPECT_EQ(after_prepare, target.ReadBytes());
    EXPECT_EQ(prepared->exposure_ev100(), fresh->exposure_ev100());
}

}  // namespace
}  // namespace zenith::sim
