#include "zenith/geo/time.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

namespace zenith::geo {
namespace {

constexpr double kJdTolerance = 1e-9;      // days: ~86 us, the double's resolution near 2.45e6
constexpr double kSecondTolerance = 1e-4;  // s, after JD round trips (JD resolution ~40 us)

TEST(JulianDate, MeeusExamples) {
    // Meeus, Astronomical Algorithms (2nd ed.), Example 7.a and the table after Eq. 7.1.
    EXPECT_NEAR(JulianDate(2000, 1, 1, 12, 0, 0.0), 2451545.0, kJdTolerance);
    EXPECT_NEAR(JulianDate(1957, 10, 4, 19, 26, 24.0), 2436116.31, kJdTolerance);
    EXPECT_NEAR(JulianDate(1987, 6, 19, 12, 0, 0.0), 2446966.0, kJdTolerance);
    EXPECT_NEAR(JulianDate(1988, 1, 27, 0, 0, 0.0), 2447187.5, kJdTolerance);
    EXPECT_NEAR(JulianDate(1999, 1, 1, 0, 0, 0.0), 2451179.5, kJdTolerance);
    EXPECT_NEAR(JulianDate(1600, 1, 1, 0, 0, 0.0), 2305447.5, kJdTolerance);
    EXPECT_NEAR(JulianDate(1600, 12, 31, 0, 0, 0.0), 2305812.5, kJdTolerance);
}

TEST(JulianDate, RoundTripsOverTheEphemerisRange) {
    std::mt19937_64 rng(42);
    std::uniform_real_distribution<double> jd(JulianDate(1950, 1, 1, 0, 0, 0.0),
                                              JulianDate(2100, 12, 31, 0, 0, 0.0));
    for (int i = 0; i < 10000; ++i) {
        const double j = jd(rng);
        const CivilTime c = CivilFromJulianDate(j);
        ValidateCivilTime(c);
        const double back = JulianDate(c.year, c.month, c.day, c.hour, c.minute, c.second);
        ASSERT_NEAR((back - j) * kSecondsPerDay, 0.0, kSecondTolerance) << FormatIso8601(c);
    }
}

TEST(Iso8601, ParsesZuluFractionsAndOffsets) {
    CivilTime t = ParseIso8601("2024-04-08T18:18:00Z");
    EXPECT_EQ(t.year, 2024);
    EXPECT_EQ(t.month, 4);
    EXPECT_EQ(t.day, 8);
    EXPECT_EQ(t.hour, 18);
    EXPECT_EQ(t.minute, 18);
    EXPECT_EQ(t.second, 0.0);

    t = ParseIso8601("2024-04-08T18:18:07.125Z");
    EXPECT_DOUBLE_EQ(t.second, 7.125);

    // NREL SPA's example: 12:30:30 at UTC-7 is 19:30:30 UTC.
    t = ParseIso8601("2003-10-17T12:30:30-07:00");
    EXPECT_EQ(t.day, 17);
    EXPECT_EQ(t.hour, 19);
    EXPECT_EQ(t.minute, 30);
    EXPECT_EQ(t.second, 30.0);

    // An offset that crosses a year boundary.
    t = ParseIso8601("2024-01-01T00:30:00+01:00");
    EXPECT_EQ(t.year, 2023);
    EXPECT_EQ(t.month, 12);
    EXPECT_EQ(t.day, 31);
    EXPECT_EQ(t.hour, 23);
    EXPECT_EQ(t.minute, 30);

    t = ParseIso8601("2024-02-29 06:07");
    EXPECT_EQ(t.hour, 6);
    EXPECT_EQ(t.minute, 7);
    t = ParseIso8601("2024-02-29");
    EXPECT_EQ(t.hour, 0);
    t = ParseIso8601("2024-02-29T06:07:08+0530");
    EXPECT_EQ(t.hour, 0);
    EXPECT_EQ(t.minute, 37);
}

void ExpectRejected(const std::string& text, const std::string& mentions) {
    try {
        ParseIso8601(text);
        FAIL() << "accepted '" << text << "'";
    } catch (const TimeError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find(mentions), std::string::npos) << message;
        EXPECT_NE(message.find(text), std::string::npos)
            << "message should quote the input: " << message;
    }
}

TEST(Iso8601, RejectsImpossibleTimesNamingTheField) {
    ExpectRejected("2023-02-29T00:00:00Z", "day");
    ExpectRejected("2024-04-31T00:00:00Z", "day");
    ExpectRejected("2024-13-01T00:00:00Z", "month");
    ExpectRejected("2024-00-10T00:00:00Z", "month");
    ExpectRejected("2024-04-08T24:00:00Z", "hour");
    ExpectRejected("2024-04-08T12:60:00Z", "minute");
    ExpectRejected("2024-04-08T12:00:60Z", "second");
    ExpectRejected("2015-12-31T23:59:60Z", "second");  // no leap second that day
    ExpectRejected("yesterday", "year");
    ExpectRejected("2024-04-08T12:00:00Q", "unexpected");
    ExpectRejected("2024-04-08T12:00:00.Z", "decimal");
    ExpectRejected("2024-04-08T12:00:00+15:00", "offset");
    ExpectRejected("0999-01-01T00:00:00Z", "year");
}

TEST(TimeScales, LeapSecondTable) {
    EXPECT_EQ(TaiMinusUtc(JulianDate(1971, 12, 31, 0, 0, 0.0)), 0.0);
    EXPECT_EQ(TaiMinusUtc(JulianDate(1972, 1, 1, 0, 0, 0.0)), 10.0);
    EXPECT_EQ(TaiMinusUtc(JulianDate(2016, 12, 31, 23, 59, 59.0)), 36.0);
    EXPECT_EQ(TaiMinusUtc(JulianDate(2017, 1, 1, 0, 0, 0.0)), 37.0);
    EXPECT_EQ(TaiMinusUtc(JulianDate(2090, 1, 1, 0, 0, 0.0)), 37.0);
}

TEST(TimeScales, TtMinusUtcIsExactInTheLeapSecondEra) {
    const Time t = TimeFromIso8601("2024-04-08T18:18:00Z");
    EXPECT_NEAR((t.jd_tt - t.jd_utc) * kSecondsPerDay, 69.184, kSecondTolerance);
    EXPECT_NEAR(t.jd_ut1, t.jd_utc, kJdTolerance);
    const Time with_dut1 =
        TimeFromIso8601("2024-04-08T18:18:00Z", {.dut1_s = 0.25, .delta_t_s = {}});
    EXPECT_NEAR((with_dut1.jd_ut1 - with_dut1.jd_utc) * kSecondsPerDay, 0.25, kSecondTolerance);
    EXPECT_NEAR(with_dut1.DeltaT(), 69.184 - 0.25, kSecondTolerance);
}

TEST(TimeScales, LeapSecondIsOneTtSecondLong) {
    const Time before = TimeFromIso8601("2016-12-31T23:59:59.5Z");
    const Time during = TimeFromIso8601("2016-12-31T23:59:60.5Z");
    const Time after = TimeFromIso8601("2017-01-01T00:00:00.5Z");
    EXPECT_NEAR((during.jd_tt - before.jd_tt) * kSecondsPerDay, 1.0, kSecondTolerance);
    EXPECT_NEAR((after.jd_tt - during.jd_tt) * kSecondsPerDay, 1.0, kSecondTolerance);
    // With a constant DUT1, UT1 follows the UTC calendar (1 s over these 2 s of TT): in reality
    // DUT1 jumps by +1 s at a leap second, and the caller passes it.
    EXPECT_NEAR((after.jd_ut1 - before.jd_ut1) * kSecondsPerDay, 1.0, kSecondTolerance);
}

TEST(TimeScales, DeltaTModelMatchesEspenakMeeusTable) {
    // Values of the polynomials at their epochs (Espenak & Meeus 2006, NASA/TP-2006-214141).
    EXPECT_NEAR(DeltaTModel(1900.0), -2.79, 1e-9);
    EXPECT_NEAR(DeltaTModel(1950.0), 29.07, 1e-9);
    EXPECT_NEAR(DeltaTModel(1975.0), 45.45, 1e-9);
    EXPECT_NEAR(DeltaTModel(2000.0), 63.86, 1e-9);
    // The 2005-2050 and 2050-2150 expressions meet at 2050 (93.0 s).
    EXPECT_NEAR(DeltaTModel(2049.999999), DeltaTModel(2050.0), 1e-3);
    EXPECT_NEAR(DeltaTModel(2050.0), 93.0, 0.01);
    // Before 1972 TT comes from the model; at the 1972 switch the two agree to ~0.1 s.
    const Time t1971 = TimeFromIso8601("1971-12-31T23:59:59Z");
    const Time t1972 = TimeFromIso8601("1972-01-01T00:00:00Z");
    EXPECT_NEAR(t1971.DeltaT(), 42.184, 0.3);
    EXPECT_NEAR(t1972.DeltaT(), 42.184, kSecondTolerance);
}

TEST(TimeScales, OverridesAndBadOptions) {
    const Time t = TimeFromIso8601("2003-10-17T12:30:30-07:00", {.dut1_s = 0.0, .delta_t_s = 67.0});
    EXPECT_NEAR(t.DeltaT(), 67.0, kSecondTolerance);
    EXPECT_NEAR(t.jd_ut1, 2452930.312847, 1e-6);  // SPA's printed JD
    EXPECT_THROW(TimeFromIso8601("2024-01-01", {.dut1_s = 1.5, .delta_t_s = {}}), TimeError);
    EXPECT_THROW(TimeFromIso8601("2024-01-01", {.dut1_s = NAN, .delta_t_s = {}}), TimeError);
    EXPECT_THROW(TimeFromIso8601("2024-01-01", {.dut1_s = {}, .delta_t_s = INFINITY}), TimeError);
    try {
        TimeFromIso8601("2024-01-01", {.dut1_s = 2.0, .delta_t_s = {}});
        FAIL();
    } catch (const TimeError& e) {
        EXPECT_NE(std::string(e.what()).find("dut1"), std::string::npos) << e.what();
    }
}

TEST(TimeScales, NowIsRecent) {
    const Time now = TimeNow();
    EXPECT_GT(now.jd_utc, JulianDate(2024, 1, 1, 0, 0, 0.0));
    EXPECT_LT(now.jd_utc, JulianDate(2200, 1, 1, 0, 0, 0.0));
}

TEST(Iso8601, FormatRoundTrips) {
    const CivilTime t = ParseIso8601("2024-04-08T18:18:07.125Z");
    EXPECT_EQ(FormatIso8601(t), "2024-04-08T18:18:07.125Z");
    EXPECT_EQ(FormatIso8601(ParseIso8601("2016-12-31T23:59:60.5Z")), "2016-12-31T23:59:60.500Z");
}

// A JD double advanced by the step rounds to 2^-31 day (40 us) on every step, with the same
// sign each time: +6.5 s per hour at 100 Hz. The clock must land on the end instant itself.
TEST(SimulationClock, AnHourOfHundredthsLandsOnTheHour) {
    SimulationClock clock(TimeFromIso8601("2024-06-21T19:00:00Z"));
    for (int i = 0; i < 360000; ++i) clock.Advance(0.01);
    EXPECT_NEAR(clock.elapsed_s(), 3600.0, 1e-6);
    const Time end = TimeFromIso8601("2024-06-21T20:00:00Z");
    // The same Time, bit for bit, as the end instant made from the calendar.
    EXPECT_EQ(clock.time().jd_utc, end.jd_utc);
    EXPECT_EQ(clock.time().jd_ut1, end.jd_ut1);
    EXPECT_EQ(clock.time().jd_tt, end.jd_tt);
}

TEST(SimulationClock, ADayAtFrameRatesIsWithinAMillisecond) {
    const Time start = TimeFromIso8601("2024-03-20T00:00:00Z");
    const Time end = TimeFromIso8601("2024-03-21T00:00:00Z");
    for (const int hz : {25, 60, 100, 144}) {
        SimulationClock clock(start);
        const double dt = 1.0 / hz;
        for (int i = 0; i < 86400 * hz; ++i) clock.Advance(dt);
        EXPECT_NEAR(clock.elapsed_s(), 86400.0, 1e-6) << hz << " Hz";
        // Within a Julian date's resolution (40 us), far inside the 1 ms asked of a day.
        EXPECT_NEAR((clock.time().jd_utc - end.jd_utc) * kSecondsPerDay, 0.0, 5e-5) << hz;
        EXPECT_NEAR((clock.time().jd_tt - end.jd_tt) * kSecondsPerDay, 0.0, 5e-5) << hz;
    }
}

TEST(SimulationClock, WarpBackwardsElapsedAndMidnight) {
    const Time start = TimeFromIso8601("2024-06-21T23:59:59.5Z");
    SimulationClock clock(start);
    EXPECT_EQ(clock.time().jd_utc, start.jd_utc);  // exactly the start until it moves
    for (int i = 0; i < 6000; ++i) clock.Advance(1.0 / 60.0, 60.0);  // 100 s at 60x: 6000 s
    EXPECT_NEAR(clock.elapsed_s(), 6000.0, 1e-9);
    EXPECT_EQ(clock.time().jd_utc, TimeFromIso8601("2024-06-22T01:39:59.5Z").jd_utc);
    clock.Advance(-6000.5);
    EXPECT_EQ(clock.time().jd_utc, TimeFromIso8601("2024-06-21T23:59:59Z").jd_utc);
    clock.SetElapsed(0.5);  // a host's own clock: seconds since the start
    EXPECT_EQ(clock.time().jd_utc, TimeFromIso8601("2024-06-22T00:00:00Z").jd_utc);
    EXPECT_THROW(clock.Advance(NAN), TimeError);
    EXPECT_THROW(clock.Advance(1.0, INFINITY), TimeError);
    EXPECT_THROW(clock.SetElapsed(INFINITY), TimeError);
}

TEST(SimulationClock, KeepsTheStartsTimeScales) {
    // An explicit DUT1 and TT - UT1 are carried along.
    const TimeOptions options{.dut1_s = 0.25, .delta_t_s = 67.0};
    SimulationClock clock(TimeFromIso8601("2003-10-17T12:30:30Z", options));
    clock.Advance(3600.0);
    const Time end = TimeFromIso8601("2003-10-17T13:30:30Z", options);
    EXPECT_EQ(clock.time().jd_ut1, end.jd_ut1);
    EXPECT_EQ(clock.time().jd_tt, end.jd_tt);
    // From the table, TT - UTC steps by the leap second at the end of 2016 (POSIX seconds:
    // the leap second itself is not counted).
    SimulationClock leap(TimeFromIso8601("2016-12-31T23:59:00Z"));
    leap.Advance(120.0);
    EXPECT_NEAR((leap.time().jd_tt - leap.time().jd_utc) * kSecondsPerDay, 69.184, 1e-4);
    // A Time made by hand (offsets TimeFromUtc cannot make) keeps its offsets.
    Time odd = TimeFromIso8601("2024-01-01T00:00:00Z");
    odd.jd_ut1 = odd.jd_utc + 5.0 / kSecondsPerDay;
    SimulationClock hand(odd);
    hand.Advance(10.0);
    EXPECT_NEAR((hand.time().jd_ut1 - hand.time().jd_utc) * kSecondsPerDay, 5.0, 1e-4);
    EXPECT_NEAR((hand.time().jd_utc - odd.jd_utc) * kSecondsPerDay, 10.0, 1e-4);
}

}  // namespace
}  // namespace zenith::geo
