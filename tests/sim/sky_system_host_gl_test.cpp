// What a host relies on beyond the picture: exact simulation time however it is driven, the
// Euler order of SetAttitude, lighting in ECEF, and a notice when the stars are missing.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <glm/gtc/constants.hpp>
#include <string>
#include <vector>

#include "zenith/sim/sky_system.h"

namespace zenith::sim {
namespace {

// One system for the file, made without a star catalogue, its notices recorded.
class SkySystemHostTest : public ::testing::Test {
  protected:
    static void SetUpTestSuite() {
        SkySystemSettings settings;
        settings.star_directory = "/nonexistent/zenith-star-catalogue";
        settings.on_notice = [](const std::string& message) { received_.push_back(message); };
        sky_ = SkySystem::CreateHeadless(settings).release();
        sky_->SetGeodetic(47.45, 8.56, 420.0);
        sky_->SetAttitude(glm::radians(270.0), 0.05, 0.0);
        sky_->SetProjection(1.0, 16.0 / 9.0);
    }
    static void TearDownTestSuite() { delete sky_; }

    static glm::dvec3 SunAfterUpdate() {
        sky_->Update();
        return sky_->lighting().sun_direction_enu;
    }

    static SkySystem* sky_;
    static std::vector<std::string> received_;
};
SkySystem* SkySystemHostTest::sky_ = nullptr;
std::vector<std::string> SkySystemHostTest::received_;

const char* const kStart = "2024-06-21T19:00:00Z";
const char* const kEnd = "2024-06-21T20:00:00Z";

// An hour of AdvanceTime at the host's rate lands where SetTime of the end instant does. Before
// the clock, a Julian date advanced in place drifted +6.5 s at 100 Hz, -2.2 s at 60 Hz and
// -0.74 s at 25 Hz: 1e-4 rad of sun direction.
TEST_F(SkySystemHostTest, AnHourOfStepsIsTheEndInstant) {
    sky_->SetTime(geo::TimeFromIso8601(kEnd));
    const geo::Time end = sky_->time();
    const glm::dvec3 sun_end = SunAfterUpdate();
    struct Run {
        int hz;
        double warp;
    };
    for (const Run run : {Run{100, 1.0}, Run{60, 1.0}, Run{25, 1.0}, Run{60, 60.0}}) {
        sky_->SetTime(geo::TimeFromIso8601(kStart));
        const double dt = 1.0 / run.hz;
        const int steps = static_cast<int>(std::lround(3600.0 / run.warp * run.hz));
        for (int i = 0; i < steps; ++i) sky_->AdvanceTime(dt, run.warp);
        const double error_s = (sky_->time().jd_utc - end.jd_utc) * geo::kSecondsPerDay;
        const glm::dvec3 sun = SunAfterUpdate();
        std::printf("%d Hz x%g: %.3g s from the end instant, sun %.3g rad\n", run.hz, run.warp,
                    error_s, glm::length(sun - sun_end));
        EXPECT_EQ(sky_->time().jd_utc, end.jd_utc) << run.hz << " Hz x" << run.warp;
        EXPECT_EQ(sky_->time().jd_tt, end.jd_tt) << run.hz << " Hz x" << run.warp;
        EXPECT_LE(glm::length(sun - sun_end), 1e-9) << run.hz << " Hz x" << run.warp;
    }
}

TEST_F(SkySystemHostTest, UnixTimeAndTheHostsClock) {
    const geo::Time end = geo::TimeFromIso8601(kEnd);
    sky_->SetTime(end);
    const glm::dvec3 sun_end = SunAfterUpdate();

    // 2024-06-21T20:00:00Z is 1719000000 POSIX seconds (`date -u -d @1719000000`).
    sky_->SetUnixTime(1719000000.0);
    EXPECT_EQ(sky_->time().jd_utc, end.jd_utc);
    EXPECT_LE(glm::length(SunAfterUpdate() - sun_end), 1e-9);

    // A host clock counting seconds since its own epoch, read every frame.
    const geo::Time epoch = geo::TimeFromIso8601(kStart);
    for (double t = 0.0; t < 3600.0; t += 0.37) sky_->SetTime(epoch, t);
    sky_->SetTime(epoch, 3600.0);
    EXPECT_EQ(sky_->time().jd_utc, end.jd_utc);
    EXPECT_LE(glm::length(SunAfterUpdate() - sun_end), 1e-9);
    sky_->SetTime(epoch, 0.0);
    EXPECT_EQ(sky_->time().jd_utc, epoch.jd_utc);

    EXPECT_THROW(sky_->SetUnixTime(NAN), geo::TimeError);
    EXPECT_THROW(sky_->SetTime(epoch, INFINITY), ArgumentError);
    EXPECT_THROW(sky_->AdvanceTime(1.0, NAN), ArgumentError);
    EXPECT_THROW(sky_->AdvanceTime(1e300, 1e300), ArgumentError);
}

// Pins the order documented at SetAttitude: heading about down, then pitch about the new right
// wing, then roll about the new nose (aerospace 3-2-1 in NED).
TEST_F(SkySystemHostTest, AttitudeIsHeadingThenPitchThenRoll) {
    const auto forward = [](const glm::dmat3& m) { return -m[2]; };
    const auto expect_near = [](const glm::dvec3& a, const glm::dvec3& b, const char* what) {
        EXPECT_LT(glm::length(a - b), 1e-12)
            << what << ": (" << a.x << ", " << a.y << ", " << a.z << ") vs (" << b.x << ", " << b.y
            << ", " << b.z << ")";
    };
    const double s30 = 0.5, c30 = std::sqrt(3.0) / 2.0;
    sky_->SetAttitude(glm::radians(90.0), 0.0, 0.0);
    expect_near(forward(sky_->enu_from_view()), {1.0, 0.0, 0.0}, "heading 90 looks east");
    sky_->SetAttitude(0.0, glm::radians(30.0), 0.0);
    expect_near(forward(sky_->enu_from_view()), {0.0, c30, s30}, "pitch 30 looks up");
    sky_->SetAttitude(0.0, 0.0, glm::radians(90.0));
    expect_near(sky_->enu_from_view()[0], {0.0, 0.0, -1.0}, "roll 90: right wing down");
    expect_near(sky_->enu_from_view()[1], {1.0, 0.0, 0.0}, "roll 90: the roof to the east");
    // All three: the nose east and 30 deg up, then rolled so the right wing points along the
    // pitched belly. Another order (roll first, or pitch about the unrotated east axis) differs.
    sky_->SetAttitude(glm::radians(90.0), glm::radians(30.0), glm::radians(90.0));
    expect_near(forward(sky_->enu_from_view()), {c30, 0.0, s30}, "3-2-1 forward");
    expect_near(sky_->enu_from_view()[0], {s30, 0.0, -c30}, "3-2-1 right wing");
    sky_->SetAttitude(glm::radians(270.0), 0.05, 0.0);
}

TEST_F(SkySystemHostTest, LightingInEcef) {
    sky_->SetTime(geo::TimeFromIso8601("2024-06-21T11:30:00Z"));
    sky_->Update();
    const SkyLighting& l = sky_->lighting();
    const glm::dmat3 ecef_from_enu = geo::Observer(47.45, 8.56, 420.0).ecef_from_enu();
    for (int c = 0; c < 3; ++c) {
        EXPECT_LT(glm::length(l.ecef_from_enu[c] - ecef_from_enu[c]), 1e-15);
    }
    EXPECT_LT(glm::length(l.sun_direction_ecef - ecef_from_enu * l.sun_direction_enu), 1e-15);
    EXPECT_LT(glm::length(l.moon_direction_ecef - ecef_from_enu * l.moon_direction_enu), 1e-15);
    // The ECEF up at the aircraft is the ellipsoid normal:
    // (cos lat cos lon, cos lat sin lon, sin lat).
    const double lat = glm::radians(47.45), lon = glm::radians(8.56);
    EXPECT_LT(
        glm::length(l.ecef_from_enu[2] - glm::dvec3(std::cos(lat) * std::cos(lon),
                                                    std::cos(lat) * std::sin(lon), std::sin(lat))),
        1e-12);
}

TEST_F(SkySystemHostTest, AMissingStarCatalogueIsNoticedOnce) {
    ASSERT_EQ(received_.size(), 1u);
    EXPECT_EQ(sky_->notices(), received_);
    const std::string& notice = received_.front();
    EXPECT_NE(notice.find("no stars"), std::string::npos) << notice;
    EXPECT_NE(notice.find("/nonexistent/zenith-star-catalogue"), std::string::npos) << notice;
    EXPECT_NE(notice.find("kstars-data"), std::string::npos) << notice;
    sky_->Update();
    EXPECT_EQ(sky_->notices().size(), 1u);  // once, not every frame
    EXPECT_TRUE(sky_->ephemeris().stars.empty());
}

// Prepare is a warm-up, not a state change: the frame after it is the frame without it.
TEST_F(SkySystemHostTest, PrepareLeavesTheNextFrameAsItWas) {
    sky_->SetTime(geo::TimeFromIso8601("2024-06-21T17:00:00Z"));
    sky_->SetAttitude(glm::radians(270.0), 0.05, 0.0);
    sky_->Update();
    const sky::LutImage before = sky_->RenderOffscreen({48, 32});
    const glm::dvec3 sun_before = sky_->lighting().sun_illuminance;
    sky_->Prepare({48, 32});
    EXPECT_EQ(sky_->lighting().sun_illuminance, sun_before);
    sky_->Update();
    const sky::LutImage after = sky_->RenderOffscreen({48, 32});
    ASSERT_EQ(after.texels.size(), before.texels.size());
    for (std::size_t i = 0; i < before.texels.size(); ++i) {
        ASSERT_EQ(after.texels[i], before.texels[i]) << "texel " << i;
    }
    EXPECT_THROW(sky_->Prepare({0, 32}), ArgumentError);
}

}  // namespace
}  // namespace zenith::sim
