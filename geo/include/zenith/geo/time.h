// Time scales for the ephemeris: UTC in, UT1 (Earth rotation) and TT (dynamical time) out.
//
// TT - UTC comes from the IERS leap-second table (TAI - UTC) + 32.184 s for instants from
// 1972-01-01, which is exact. Before 1972, TT = UT1 + DeltaT with the Espenak & Meeus (2006)
// polynomial model of DeltaT (NASA Five Millennium Canon of Solar Eclipses). After the last
// entry in the table, TAI - UTC is held at its last value (37 s since 2017-01-01; no leap second
// has been announced since, and the CGPM decided in 2022 to stop them by 2035).
// UT1 = UTC + DUT1, with DUT1 = 0 unless the caller gives it (|DUT1| < 0.9 s by definition of
// UTC; 1 s of UT1 error moves everything in the sky by up to 15 arcseconds).
#pragma once

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

#include "zenith/base/error.h"

namespace zenith::geo {

// Thrown for any input that cannot be a valid instant; the message names the parameter, the
// value and the accepted range or format.
class TimeError : public ArgumentError {
  public:
    using ArgumentError::ArgumentError;
};

// A UTC calendar instant. second may reach 60.999... only on a day that ends with a leap second.
struct CivilTime {
    int year = 2000;
    int month = 1;
    int day = 1;
    int hour = 12;
    int minute = 0;
    double second = 0.0;
};

struct TimeOptions {
    std::optional<double> dut1_s;     // UT1 - UTC, seconds; default 0
    std::optional<double> delta_t_s;  // TT - UT1 override, seconds (e.g. to match NREL SPA)
};

// One instant on the scales the ephemeris needs. Julian dates are single doubles: at JD 2.46e6 the
// resolution is ~40 us, i.e. 20 micro-arcseconds of lunar motion.
struct Time {
    double jd_utc = 2451545.0;  // quasi Julian date of the UTC calendar instant
    double jd_ut1 = 2451545.0;  // UT1 Julian date (Earth rotation angle, sidereal time)
    double jd_tt = 2451545.0;   // TT Julian date (ephemeris arguments)

    double DeltaT() const { return (jd_tt - jd_ut1) * 86400.0; }  // TT - UT1, seconds
    // Julian centuries of TT since J2000.0 (JD 2451545.0 TT).
    double CenturiesTT() const { return (jd_tt - 2451545.0) / 36525.0; }
};

inline constexpr double kJ2000 = 2451545.0;
inline constexpr double kDaysPerCentury = 36525.0;
inline constexpr double kSecondsPerDay = 86400.0;

// Parse ISO 8601: "2024-04-08T18:18:00Z", fractional seconds, "+02:00"/"-0700" offsets,
// a space instead of 'T', or a date alone (midnight). No offset means UTC.
CivilTime ParseIso8601(std::string_view text);
// Format as "YYYY-MM-DDThh:mm:ss.sssZ".
std::string FormatIso8601(const CivilTime& utc);

// Throws TimeError naming the field when the calendar instant does not exist.
void ValidateCivilTime(const CivilTime& utc);

// Julian date of a proleptic Gregorian calendar instant (Meeus, Astronomical Algorithms, ch. 7).
double JulianDate(int year, int month, int day, int hour, int minute, double second);
CivilTime CivilFromJulianDate(double jd);

// TAI - UTC in seconds for the UTC day containing jd_utc; 0 before 1972 (see file comment).
double TaiMinusUtc(double jd_utc);
// TT - UT1 in seconds, Espenak & Meeus (2006) polynomials, valid -1999..3000.
double DeltaTModel(double decimal_year);

Time TimeFromUtc(const CivilTime& utc, const TimeOptions& options = {});
Time TimeFromIso8601(std::string_view text, const TimeOptions& options = {});
// UTC now from the system clock.
Time TimeNow(const TimeOptions& options = {});

// POSIX ("Unix") time: seconds since 1970-01-01T00:00:00Z with every day 86400 s long, so a leap
// second has no number of its own (as in flight logs, simulators and operating systems).
double UnixSecondsFromCivil(const CivilTime& utc);
CivilTime CivilFromUnixSeconds(double unix_s);
// Throws TimeError for a non-finite value or one outside the years -4712..9999.
Time TimeFromUnixSeconds(double unix_s, const TimeOptions& options = {});

// Simulation time that moves by many small steps without drifting.
//
// Adding a 10 ms step to a Julian date near 2.46e6 held in a double rounds it to the date's
// resolution (2^-31 day, 40 us) on every step, and the rounding has the same sign step after step:
// +6.5 s per hour at 100 Hz. The clock keeps instead the instant it was set to and the seconds
// elapsed since then as an unevaluated sum (Knuth's TwoSum, so 360,000 steps of 0.01 s make
// 3600 s to ~1e-12 s), and forms time() from them with a single rounding: the calendar instant
// start + elapsed (days of 86400 s, as POSIX time: a leap second is not counted) converted as
// TimeFromUtc converts it, with the start's DUT1 and, where the start came from the leap-second
// table, that table (so TT - UTC steps at a leap second). A clock advanced to an instant and
// TimeFromUtc of that instant are the same Time to the last bit.
class SimulationClock {
  public:
    SimulationClock() : SimulationClock(Time{}) {}
    explicit SimulationClock(const Time& start) { Set(start); }

    // time() is `start`, exactly, until the clock moves.
    void Set(const Time& start);
    // Moves on by seconds x factor (factor: a time warp); the product is taken exactly.
    // Throws TimeError for a non-finite value.
    void Advance(double seconds, double factor = 1.0);
    // Sets the seconds since the start instant (a host's own simulation clock).
    void SetElapsed(double seconds);

    // Formed on demand (Advance is a few additions, so a 1 kHz physics loop pays nothing for
    // the calendar). Throws TimeError once the clock has left TimeFromUtc's years.
    const Time& time() const;
    const Time& start() const { return start_; }
    // Seconds since the start instant (hi + lo of the compensated sum, rounded once).
    double elapsed_s() const { return elapsed_hi_ + elapsed_lo_; }

  private:
    void Refresh() const;

    Time start_;
    mutable Time time_;
    mutable bool stale_ = false;
    // The start as POSIX days since 1970-01-01 and the second of that day (to the microsecond).
    std::int64_t start_day_ = 0;
    double start_second_of_day_ = 0.0;
    // How the start's UT1 and TT follow from its UTC: TimeFromUtc with these options, or, when
    // that cannot reproduce the start (a Time built by hand), constant offsets in seconds.
    bool from_table_ = true;
    TimeOptions options_;
    double ut1_minus_utc_s_ = 0.0;
    double tt_minus_utc_s_ = 0.0;
    double elapsed_hi_ = 0.0;
    double elapsed_lo_ = 0.0;
};

}  // namespace zenith::geo
