// Issue 17, "what must be shown": rendered frames measured against the report (GL part).
//
// - Visual range: black targets (host depth, black host colour) at distances around the reported
//   visibility V, along a horizontal view from 2 m above the ground, each against the horizon sky
//   directly behind it (the same pixel of a frame without the target). The contrast
//   C = (L_sky - L_target) / L_sky falls with distance; the distance where it crosses 5 % (WMO
//   MOR, Koschmieder: C = e^-sigma V = 1/20), interpolated in ln C between neighbouring targets,
//   must be V within +-15 % for V = 200 m, 1 km, 5 km and 20 km, in daylight.
// - CAVOK / SKC: the frame is bit-for-bit the clear sky of the same time and place.
//
// Frames are 64 x 8 (every column a target at its own distance) on llvmpipe; the printed table
// is what BENCHMARKS.md's issue-17 section quotes (ctest -R MetarFrames -V).
#include <glad/gl.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <glm/gtc/constants.hpp>
#include <optional>
#include <vector>

#include "host_frame.h"
#include "luminance.h"
#include "zenith/sim/sky_system.h"
#include "zenith/sky/reference/atmosphere_reference.h"
#include "zenith/sky/sky_state.h"
#include "zenith/weather/altimetry.h"
#include "zenith/weather/cloud_weather.h"
#include "zenith/weather/metar.h"

namespace zenith::sim {
namespace {

using zenith::test::Luminance;

constexpr int kWidth = 64, kHeight = 8;
constexpr int kRow = kHeight / 2;      // the row just above the horizon
constexpr double kVerticalFov = 0.02;  // rad: row 4's centre is 0.07 deg up
constexpr double kNear = 0.1;
constexpr double kEyeHeight = 2.0;  // m above the ground
constexpr double kLat = 46.5, kLon = 8.0;
constexpr const char* kTime = "2024-06-21T09:00:00Z";  // Sun ~55 deg up, in the south-east

class MetarFramesTest : public ::testing::Test {
  protected:
    static void SetUpTestSuite() {
        sky_ = SkySystem::CreateHeadless().release();
        sky_->SetTime(geo::TimeFromIso8601(kTime));
        sky_->SetGeodetic(kLat, kLon, kEyeHeight);
        frame_ = new test::HostFrame(kWidth, kHeight);
    }
    static void TearDownTestSuite() {
        delete frame_;
        delete sky_;
    }

    // The frame over a black host whose depth puts pixel (x, y) at distance[x] metres along its
    // ray (reversed-Z, infinite far plane); distance 0: nothing there (the sky).
    static std::vector<glm::vec4> Draw(const std::vector<double>& distance) {
        const double t = std::tan(0.5 * kVerticalFov);
        const double aspect = static_cast<double>(kWidth) / kHeight;
        std::vector<float> depth(kWidth * kHeight, 0.0f);
        for (int y = 0; y < kHeight; ++y) {
            for (int x = 0; x < kWidth; ++x) {
                const double d = distance[static_cast<std::size_t>(x)];
                if (d <= 0.0) continue;
                const double nx = 2.0 * (x + 0.5) / kWidth - 1.0;
                const double ny = 2.0 * (y + 0.5) / kHeight - 1.0;
                const double eye_depth =
                    d / std::sqrt(nx * nx * t * t * aspect * aspect + ny * ny * t * t + 1.0);
                depth[static_cast<std::size_t>(y * kWidth + x)] =
                    static_cast<float>(kNear / eye_depth);
            }
        }
        return frame_->Render(*sky_, depth, 0.0f, kNear, std::numeric_limits<double>::infinity(),
                              true);
    }

    struct VisualRange {
        double measured_m = 0.0;     // where C crosses 5 %
        double contrast_at_v = 0.0;  // C of the target at V
    };

    // Targets from 0.4 V to 2.5 V, log-spaced, one per column.
    static VisualRange MeasureVisualRange(double v) {
        std::vector<double> distance(kWidth);
        for (int x = 0; x < kWidth; ++x) {
            distance[static_cast<std::size_t>(x)] =
                v * 0.4 * std::pow(2.5 / 0.4, static_cast<double>(x) / (kWidth - 1));
        }
        const std::vector<glm::vec4> sky = Draw(std::vector<double>(kWidth, 0.0));
        const std::vector<glm::vec4> targets = Draw(distance);
        std::vector<double> contrast(kWidth);
        for (int x = 0; x < kWidth; ++x) {
            const std::size_t i = static_cast<std::size_t>(kRow * kWidth + x);
            contrast[static_cast<std::size_t>(x)] =
                (Luminance(sky[i]) - Luminance(targets[i])) / Luminance(sky[i]);
        }
        if (std::getenv("ZENITH_DEBUG_VR") != nullptr) {
            for (int x = 0; x < kWidth; x += 4) {
                const std::size_t i = static_cast<std::size_t>(kRow * kWidth + x);
                std::printf("  d %8.1f sky %.5g target %.5g C %.4f\n",
                            distance[static_cast<std::size_t>(x)], Luminance(sky[i]),
                            Luminance(targets[i]), contrast[static_cast<std::size_t>(x)]);
            }
            const sky::reference::AtmosphereReference reference(sky_->atmosphere());
            const sky::SkyState state = sky::MakeSkyState(
                sky_->ephemeris(), geo::Observer(kLat, kLon, kEyeHeight), sky_->atmosphere(),
                {0.0, 0.0, 0.0}, kVerticalFov, static_cast<double>(kWidth) / kHeight);
            const glm::dvec3 dir =
                state.view.camera.Direction(0.0, (kRow + 0.5) / kHeight * 2.0 - 1.0);
            for (double d : {0.2 * v, 0.5 * v, v, 2.0 * v, 10.0 * v, 1e6}) {
                const glm::dvec4 ap = reference.InScattering(state.view.camera.position, dir,
                                                             state.scene.lights, d, 4000);
                std::printf("  reference d %9.1f L %.5g T %.4g\n", d,
                            Luminance(glm::vec4(glm::vec3(ap), 0.0f)), ap.w);
            }
            std::printf(
                "  reference ray march %.5g\n",
                Luminance(glm::vec4(glm::vec3(reference.RayMarch(state.view.camera.position, dir,
                                                                 state.scene.lights, 4000)),
                                    0.0f)));
        }
        VisualRange r;
        r.measured_m = std::numeric_limits<double>::quiet_NaN();
        for (int x = 0; x + 1 < kWidth; ++x) {
            const double c0 = contrast[static_cast<std::size_t>(x)];
            const double c1 = contrast[static_cast<std::size_t>(x + 1)];
            const double d0 = distance[static_cast<std::size_t>(x)];
            const double d1 = distance[static_cast<std::size_t>(x + 1)];
            if (c0 >= 0.05 && c1 < 0.05 && c1 > 0.0) {
                const double u = (std::log(c0) - std::log(0.05)) / (std::log(c0) - std::log(c1));
                r.measured_m = d0 + u * (d1 - d0);
                break;
            }
        }
        // C at V: between the two columns around it, in ln C.
        for (int x = 0; x + 1 < kWidth; ++x) {
            const double d0 = distance[static_cast<std::size_t>(x)];
            const double d1 = distance[static_cast<std::size_t>(x + 1)];
            if (d0 <= v && v <= d1) {
                const double u = (v - d0) / (d1 - d0);
                const double c0 = std::max(contrast[static_cast<std::size_t>(x)], 1e-9);
                const double c1 = std::max(contrast[static_cast<std::size_t>(x + 1)], 1e-9);
                r.contrast_at_v = std::exp((1.0 - u) * std::log(c0) + u * std::log(c1));
            }
        }
        return r;
    }

    static SkySystem* sky_;
    static test::HostFrame* frame_;
};
SkySystem* MetarFramesTest::sky_ = nullptr;
test::HostFrame* MetarFramesTest::frame_ = nullptr;

TEST_F(MetarFramesTest, ABlackTargetAtTheVisibilityHasFivePercentContrast) {
    // North: the Sun ~100 deg to the right, neither behind nor in front.
    sky_->SetAttitude(0.0, 0.0, 0.0);
    sky_->SetProjection(kVerticalFov, static_cast<double>(kWidth) / kHeight);
    sky_->Update();
    const double sun = glm::degrees(sky_->lighting().sun_elevation);
    ASSERT_GT(sun, 30.0);
    ASSERT_LT(sun, 60.0);
    std::printf("visual range, Sun %.1f deg up, from %.0f m, looking north at the horizon\n", sun,
                kEyeHeight);
    std::printf(
        "| visibility V | expected: C = 5 %% at | measured: C = 5 %% at | ratio | C at V |\n");
    for (const double v : {200.0, 1000.0, 5000.0, 20000.0}) {
        sky_->SetVisibility(v);
        sky_->Update();
        const VisualRange r = MeasureVisualRange(v);
        std::printf("| %.0f m | %.0f m | %.0f m | %.3f | %.4f |\n", v, v, r.measured_m,
                    r.measured_m / v, r.contrast_at_v);
        EXPECT_GT(r.measured_m, 0.85 * v) << "V = " << v;
        EXPECT_LT(r.measured_m, 1.15 * v) << "V = " << v;
    }
    sky_->SetVisibility(std::nullopt);
    sky_->Update();
}

// The same in fog (METAR FG with a vertical visibility): the ground fog's extinction and the
// air's make ln 20 / V (weather::CloudWeatherFromMetar), and the clouds' share in front of each
// target comes from its trace cell's transmittance profile (CloudOpacityShareInFront). Each
// frame is the first of its history (a cut), so the clouds are this frame's trace.
TEST_F(MetarFramesTest, InFogABlackTargetAtTheVisibilityHasFivePercentContrast) {
    sky_->SetAttitude(0.0, 0.0, 0.0);
    sky_->SetProjection(kVerticalFov, static_cast<double>(kWidth) / kHeight);
    std::printf("visual range in fog 91 m deep (VV003), from %.0f m, looking north\n", kEyeHeight);
    std::printf("| visibility V | measured: C = 5 %% at | ratio | C at V |\n");
    for (const double v : {100.0, 200.0, 500.0}) {
        char text[96];
        std::snprintf(text, sizeof(text), "LSZH 210900Z 00000KT %04.0f FG VV003 12/12 Q1020", v);
        sky_->SetMetar(weather::DecodeMetar(text), 0.0);
        sky_->ResetCloudHistory();
        sky_->Update();
        const VisualRange r = MeasureVisualRange(v);
        std::printf("| %.0f m | %.0f m | %.3f | %.4f |\n", v, r.measured_m, r.measured_m / v,
                    r.contrast_at_v);
        EXPECT_GT(r.measured_m, 0.85 * v) << "V = " << v;
        EXPECT_LT(r.measured_m, 1.15 * v) << "V = " << v;
    }
    sky_->SetWeather({});
    sky_->SetVisibility(std::nullopt);
    sky_->Update();
}

// CAVOK and SKC (and CLR, NSC, NCD) are the clear sky of the same time and place, bit for bit:
// no layer, and the preset's own air (a visibility of 10 km or more sets none). The frame looks
// from the ground at the horizon and up to 60 deg, the Sun in it.
TEST_F(MetarFramesTest, ClearReportsRenderTheClearSkyBitForBit) {
    constexpr int kSize = 32;
    const auto frame = [&] {
        sky_->SetAttitude(glm::radians(110.0), glm::radians(25.0), 0.0);
        sky_->SetProjection(1.2, 1.0);
        sky_->ResetCloudHistory();
        sky_->Update();
        return sky_->RenderOffscreen({kSize, kSize});
    };
    // The clear sky seen through the report's air: its QNH and temperature refract the stars
    // and the disks (SetMetar sets them too), and nothing else of a clear report may show.
    const auto clear_frame = [&](const weather::Metar& report) {
        sky_->SetWeather(sky::clouds::Weather{});
        sky_->SetVisibility(std::nullopt);
        sky_->SetRefraction(weather::RefractionAirOf(weather::StationAirOf(report, 0.0)));
        return frame();
    };
    for (const char* report :
         {"EGLL 210900Z 24012KT CAVOK 18/09 Q1018", "KJFK 210851Z 18010KT 10SM SKC 22/12 A3001",
          "EDDF 210850Z 27005KT 9999 NSC 17/08 Q1020", "KSFO 210856Z 30012KT 10SM CLR 16/10 A2995",
          "LFPG 210900Z AUTO 22008KT 9999 NCD 16/09 Q1019"}) {
        const weather::Metar decoded = weather::DecodeMetar(report);
        const sky::LutImage clear = clear_frame(decoded);
        ASSERT_EQ(clear.texels.size(), static_cast<std::size_t>(kSize * kSize));
        sky_->SetMetar(decoded, 0.0);
        EXPECT_FALSE(sky_->has_clouds()) << report;
        const sky::LutImage metar = frame();
        ASSERT_EQ(metar.texels.size(), clear.texels.size());
        std::size_t differing = 0;
        for (std::size_t i = 0; i < clear.texels.size(); ++i) {
            if (std::memcmp(&metar.texels[i], &clear.texels[i], sizeof(glm::vec4)) != 0) {
                ++differing;
            }
        }
        std::printf("%s: %zu of %zu pixels differ from the clear sky\n", report, differing,
                    clear.texels.size());
        EXPECT_EQ(differing, 0u) << report;
    }
    // The comparison sees a change: haze at 5 km is not the clear sky.
    const weather::Metar hazy =
        weather::DecodeMetar("EDDF 210850Z 27005KT 5000 HZ NSC 17/08 Q1020");
    const sky::LutImage clear = clear_frame(hazy);
    sky_->SetMetar(hazy, 0.0);
    const sky::LutImage haze = frame();
    EXPECT_NE(std::memcmp(haze.texels.data(), clear.texels.data(),
                          clear.texels.size() * sizeof(glm::vec4)),
              0);
    sky_->SetWeather(sky::clouds::Weather{});
    sky_->SetVisibility(std::nullopt);
    sky_->SetRefraction(geo::RefractionAir{});
}

}  // namespace
}  // namespace zenith::sim
