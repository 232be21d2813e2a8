// Altimetry (altimetry.h): ISA against the standard's table, QNH against the barometric formula
// written the other way round, temperature against ICAO Doc 8168's cold-temperature formula and
// table.
#include "zenith/weather/altimetry.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "error_matchers.h"
#include "zenith/base/error.h"

namespace zenith::weather {
namespace {

constexpr double kFeet = 0.3048;

// ICAO Doc 7488 (the standard atmosphere's table, by geopotential height; the same as the U.S.
// Standard Atmosphere 1976 to 20 km), geopotential height -> pressure.
TEST(Altimetry, IsaPressureMatchesTheStandardsTable) {
    const struct {
        double h, hpa;
    } kTable[] = {{0.0, 1013.25},    {1000.0, 898.75},  {2000.0, 794.95}, {5000.0, 540.20},
                  {11000.0, 226.32}, {15000.0, 120.44}, {20000.0, 54.748}};
    for (const auto& row : kTable) {
        EXPECT_NEAR(IsaPressure(row.h) / row.hpa, 1.0, 2e-4) << row.h;
        EXPECT_NEAR(IsaPressureAltitude(IsaPressure(row.h)), row.h, 1e-6) << row.h;
    }
}

TEST(Altimetry, StandardAirGivesThePressureAltitudeItself) {
    for (const double elevation : {0.0, 400.0, 1600.0}) {
        StationAir air;
        air.elevation_m = elevation;
        air.temperature_c = 15.0 - kIsaLapseRate * elevation;  // ISA's temperature there
        for (const double h : {-300.0, 0.0, 1500.0, 9000.0, 12500.0, 19000.0}) {
            EXPECT_NEAR(HeightFromPressureAltitude(h, air), h, 1e-6) << elevation << " " << h;
            air.temperature_c.reset();
            EXPECT_NEAR(HeightFromPressureAltitude(h, air), h, 1e-6) << elevation << " " << h;
            air.temperature_c = 15.0 - kIsaLapseRate * elevation;
        }
    }
}

// With ISA's temperature, the air is ISA with a sea-level pressure of QNH: the aircraft's
// pressure P_isa(H_p) must be QNH (1 - L z / T0)^(g0 / (R L)) at the height found.
TEST(Altimetry, QnhShiftsTheHeightAsTheBarometricFormulaSays) {
    const double exponent = kStandardGravity / (kDryAirGasConstant * kIsaLapseRate);
    for (const double qnh : {960.0, 1000.0, 1030.0, 1050.0}) {
        for (const double elevation : {0.0, 700.0}) {
            for (const double h : {0.0, 1000.0, 3000.0, 8000.0}) {
                StationAir air;
                air.qnh_hpa = qnh;
                air.elevation_m = elevation;
                const double z = HeightFromPressureAltitude(h, air);
                const double p =
                    qnh * std::pow(1.0 - kIsaLapseRate * z / kIsaTemperatureK, exponent);
                EXPECT_NEAR(p / IsaPressure(h), 1.0, 1e-12) << qnh << " " << elevation << " " << h;
            }
        }
    }
    // The pilots' rule: about 27 ft per hPa near the ground (8.2 m).
    StationAir high;
    high.qnh_hpa = 1023.25;
    EXPECT_NEAR(HeightFromPressureAltitude(0.0, high), 83.2, 1.0);
}

// The correction a pilot adds to an altitude above a sea-level aerodrome with QNH set so that
// the aircraft is really `height` above it, in air at `temperature_c` there: the altimeter's
// indicated height H_ind (ISA with QNH) whose true height is `height`, minus `height`.
double ColdCorrection(double height, double temperature_c) {
    StationAir air;
    air.temperature_c = temperature_c;
    double lo = height, hi = 2.0 * height;
    for (int i = 0; i < 100; ++i) {
        const double indicated = 0.5 * (lo + hi);
        // QNH 1013.25: the indicated height is the pressure altitude.
        (HeightFromPressureAltitude(indicated, air) < height ? lo : hi) = indicated;
    }
    return 0.5 * (lo + hi) - height;
}

// ICAO Doc 8168 (PANS-OPS) Vol. I, the cold-temperature correction for an aerodrome at sea
// level: dH = H (15 - t0) / (273 + t0 - 0.5 L H), its published table built from it (the AIM
// reproduces it as TBL 7-3-1): -30 deg C, 1000 ft above the aerodrome: 190 ft.
TEST(Altimetry, ColdAirMatchesIcaoDoc8168) {
    for (const double t0 : {0.0, -10.0, -20.0, -30.0, -40.0, -50.0}) {
        for (const double feet : {500.0, 1000.0, 3000.0, 5000.0}) {
            const double h = feet * kFeet;
            const double icao = h * (15.0 - t0) / (273.0 + t0 - 0.5 * kIsaLapseRate * h);
            const double ours = ColdCorrection(h, t0);
            EXPECT_NEAR(ours / icao, 1.0, 0.03) << t0 << " deg C, " << feet << " ft";
        }
    }
    EXPECT_NEAR(ColdCorrection(1000.0 * kFeet, -30.0) / kFeet, 190.0, 10.0);
    // Warm air: the aircraft is higher than the pressure altitude says.
    StationAir warm;
    warm.temperature_c = 35.0;
    EXPECT_GT(HeightFromPressureAltitude(3000.0, warm), 3000.0 + 150.0);
}

TEST(Altimetry, OutOfRangeInputIsRefusedByName) {
    StationAir air;
    air.qnh_hpa = 700.0;
    EXPECT_THAT([&] { HeightFromPressureAltitude(1000.0, air); },
                test::ThrowsArgumentError("qnh", ::testing::HasSubstr("qnh = 700 hPa")));
    air.qnh_hpa = 1013.0;
    EXPECT_THROW(HeightFromPressureAltitude(25000.0, air), ArgumentError);
    EXPECT_THROW(HeightFromPressureAltitude(std::nan(""), air), ArgumentError);
    air.temperature_c = -120.0;
    EXPECT_THAT([&] { HeightFromPressureAltitude(1000.0, air); },
                test::ThrowsArgumentError("temperature", ::testing::HasSubstr("-120")));
}

TEST(Altimetry, StationAirFromAReport) {
    const Metar q = DecodeMetar("EGLL 211750Z 24012KT 9999 FEW035 05/M02 Q1023");
    const StationAir a = StationAirOf(q, 25.0);
    EXPECT_DOUBLE_EQ(a.qnh_hpa, 1023.0);
    ASSERT_TRUE(a.temperature_c);
    EXPECT_DOUBLE_EQ(*a.temperature_c, 5.0);
    EXPECT_DOUBLE_EQ(a.elevation_m, 25.0);
    // Inches of mercury (FAA) become hPa; no QNH at all is ISA's.
    EXPECT_NEAR(
        StationAirOf(DecodeMetar("KJFK 211751Z 24012KT 10SM FEW035 18/09 A2992"), 0.0).qnh_hpa,
        1013.2, 0.1);
    EXPECT_DOUBLE_EQ(StationAirOf(DecodeMetar("EGLL 211750Z 24012KT 9999 FEW035"), 0.0).qnh_hpa,
                     kIsaPressureHpa);
}

// Refraction's air: QNH at sea level, the station's temperature carried down ISA's lapse rate.
TEST(Altimetry, RefractionAirFromAReport) {
    const Metar q = DecodeMetar("LSZH 211750Z 24012KT 9999 FEW035 25/12 Q1020");
    const geo::RefractionAir air = RefractionAirOf(StationAirOf(q, 500.0));
    EXPECT_DOUBLE_EQ(air.sea_level_pressure_hpa, 1020.0);
    EXPECT_DOUBLE_EQ(air.sea_level_temperature_c, 25.0 + 0.0065 * 500.0);
    const geo::RefractionAir isa = RefractionAirOf(StationAir{});
    EXPECT_EQ(isa, geo::RefractionAir{});
}

}  // namespace
}  // namespace zenith::weather
