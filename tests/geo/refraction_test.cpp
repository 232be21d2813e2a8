// The traced refraction (zenith/geo/refraction.h) against closed forms and published figures.
#include "zenith/geo/refraction.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/gtc/constants.hpp>
#include <vector>

#include "zenith/base/error.h"
#include "zenith/geo/observer.h"

namespace zenith::geo {
namespace {

constexpr double kArcsec = 4.84813681109536e-6;  // rad
constexpr double kArcmin = 60.0 * kArcsec;

double Rad(double deg) { return glm::radians(deg); }

// A planet so large that its air is plane-parallel: Snell's law n sin z stays constant, so a
// body at zenith angle z_t outside the air is seen at z0 with sin z_t = n0 sin z0, whatever the
// profile between.
TEST(Refraction, PlaneParallelLimitIsSnellsLaw) {
    const RefractionAir air;
    const double n0 = 1.0 + kAirRefractivity;  // ISA at sea level
    for (const double e : {10.0, 30.0, 60.0, 85.0}) {
        const double z0 = Rad(90.0 - e);
        const double expected = std::asin(n0 * std::sin(z0)) - z0;
        const std::optional<double> bend = TraceRefraction(air, 0.0, Rad(e), 1e13);
        ASSERT_TRUE(bend);
        EXPECT_NEAR(*bend, expected, 0.01 * kArcsec) << e << " deg";
    }
}

// Near the horizon, where refraction depends on the whole profile: Bennett (1982), the fit to
// the Pulkovo tables of the real atmosphere that the NREL SPA uses, at its own conditions
// (1010 hPa, 10 deg C) at sea level. Real horizons vary by arcminutes with the air near the
// ground; the lapse rate here is ISA's.
TEST(Refraction, NearTheHorizonMatchesBennett) {
    RefractionAir air;
    air.sea_level_pressure_hpa = 1010.0;
    air.sea_level_temperature_c = 10.0;
    for (const double e : {0.0, 0.5, 1.0, 2.0, 3.0, 5.0}) {
        const double traced = *TraceRefraction(air, 0.0, Rad(e));
        // Bennett's formula takes the geometric elevation.
        const double bennett = RefractionBennett(Rad(e) - traced, 1010.0, 10.0);
        EXPECT_NEAR(traced, bennett, (e < 2.0 ? 0.5 : 0.15) * kArcmin)
            << e << " deg: traced " << traced / kArcmin << "', Bennett " << bennett / kArcmin
            << "'";
    }
}

// Away from the horizon, Laplace's theorem: to third order in tan z the refraction depends
// only on the air at the observer, R = a (1 - b) tan z - a (b - a/2) tan^3 z with a = n0 - 1
// and b = (R_d T0 / g) / r0 (Smart, Spherical Astronomy, Sect. 36). Bennett's formula is 3 %
// higher up here (60" at 45 deg against 58"): it is fitted near the horizon.
TEST(Refraction, AwayFromTheHorizonMatchesLaplacesTheorem) {
    RefractionAir air;
    air.sea_level_temperature_c = 10.0;
    const double t0 = 283.15;
    const double a = kAirRefractivity * (kIsaTemperatureK / t0);
    for (const double height : {0.0}) {
        const double b = kDryAirGasConstant * t0 / kStandardGravity / (6371000.0 + height);
        for (const double e : {20.0, 30.0, 45.0, 60.0, 80.0}) {
            const double tz = std::tan(Rad(90.0 - e));
            const double laplace = a * (1.0 - b) * tz - a * (b - 0.5 * a) * tz * tz * tz;
            EXPECT_NEAR(*TraceRefraction(air, height, Rad(e)), laplace, 0.05 * kArcsec) << e;
        }
    }
}

// The sea horizon's dip seen from height h with refraction, the nautical almanac's
// 1.76' sqrt(h / m) (geometric 1.93' sqrt(h)).
TEST(Refraction, HorizonDipMatchesTheNauticalAlmanac) {
    for (const double h : {10.0, 100.0, 1000.0}) {
        const RefractionTable table(RefractionAir{}, h);
        EXPECT_NEAR(-table.horizon() / kArcmin, 1.76 * std::sqrt(h), 0.02 * 1.76 * std::sqrt(h))
            << h << " m";
    }
    EXPECT_NEAR(RefractionTable(RefractionAir{}, 0.0).horizon(), 0.0, 1e-8);
}

// A ray that grazes the ground, seen from above the air, is bent twice as much as the
// horizontal ray seen on the ground (its two halves).
TEST(Refraction, GrazingRayFromAboveTheAirIsTwiceTheHorizontalOne) {
    const RefractionAir air;
    const double radius = 6371000.0;
    const double height = 100000.0;
    const double grazing = -std::acos((1.0 + kAirRefractivity) * radius / (radius + height));
    const double from_space = *TraceRefraction(air, height, grazing + 1e-9);
    const double on_ground = *TraceRefraction(air, 0.0, 0.0);
    EXPECT_NEAR(from_space, 2.0 * on_ground, 0.5 * kArcsec);
    EXPECT_FALSE(TraceRefraction(air, height, grazing - 1e-4));  // from the ground
}

// Bending by the density: twice the pressure, twice the refraction away from the horizon.
TEST(Refraction, ScalesWithThePressure) {
    RefractionAir low;
    low.sea_level_pressure_hpa = 900.0;
    RefractionAir high;
    high.sea_level_pressure_hpa = 1080.0;
    const double ratio =
        *TraceRefraction(high, 0.0, Rad(30.0)) / *TraceRefraction(low, 0.0, Rad(30.0));
    EXPECT_NEAR(ratio, 1080.0 / 900.0, 1e-3);
}

// The table places bodies within 2" of the traced value, except near the kinks of ISA's
// profile (the temperature gradient jumps at 11, 20, 32 km...: a ray whose lowest point, or an
// observer, crosses one bends with a kink the linear interpolation rounds off, < 40", an
// eighth of a pixel at 60 deg over 720 lines).
TEST(Refraction, TableInterpolatesWithinTwoArcseconds) {
    for (const double h : {0.0, 1500.0, 8000.0, 11000.0, 40000.0}) {
        const RefractionTable table(RefractionAir{}, h);
        std::vector<double> errors;
        for (int i = 0; i <= 400; ++i) {
            const double apparent =
                table.horizon() + 1e-7 + (Rad(89.9) - table.horizon()) * (i / 400.0) * (i / 400.0);
            const double geometric = apparent - *TraceRefraction(RefractionAir{}, h, apparent);
            const std::optional<double> placed = table.Apparent(geometric);
            ASSERT_TRUE(placed) << h << " m, " << geometric;
            errors.push_back(std::abs(*placed - apparent));
        }
        std::sort(errors.begin(), errors.end());
        const bool kinks = h >= 11000.0;
        EXPECT_LT(errors.back(), (kinks ? 40.0 : 2.0) * kArcsec) << h << " m";
        EXPECT_LT(errors[errors.size() / 2], 0.1 * kArcsec) << h << " m";
    }
}

TEST(Refraction, TableHidesBodiesBehindTheGroundAndFlattensTheSettingSun) {
    const RefractionTable cruise(RefractionAir{}, 10000.0);
    EXPECT_NEAR(cruise.horizon(), -Rad(3.0), Rad(0.2));  // the dip, 3.2 deg geometric
    EXPECT_FALSE(cruise.Apparent(-Rad(4.5)));
    ASSERT_TRUE(cruise.Apparent(-Rad(3.2)));  // just below the geometric dip: refracted into view
    EXPECT_GT(*cruise.Apparent(-Rad(3.2)), cruise.horizon());
    // The setting Sun on the sea-level horizon: its vertical diameter shrinks by the change of
    // refraction across it, Bennett's slope there (about 0.8).
    const RefractionTable ground(RefractionAir{}, 0.0);
    const double g = -*TraceRefraction(RefractionAir{}, 0.0, Rad(0.25)) + Rad(0.25);
    const double step = Rad(0.1);
    const double bennett_scale = 1.0 + (RefractionBennett(g + step, 1013.25, 15.0) -
                                        RefractionBennett(g - step, 1013.25, 15.0)) /
                                           (2.0 * step);
    EXPECT_NEAR(ground.VerticalScale(g), bennett_scale, 0.03);
    EXPECT_NEAR(ground.VerticalScale(Rad(60.0)), 1.0, 1e-3);
}

TEST(Refraction, RejectsAirOutsideWhatAReportHolds) {
    RefractionAir air;
    air.sea_level_pressure_hpa = 500.0;
    try {
        TraceRefraction(air, 0.0, 0.1);
        FAIL();
    } catch (const ArgumentError& e) {
        EXPECT_NE(std::string(e.what()).find("pressure"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("500"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace zenith::geo
