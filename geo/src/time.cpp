#include "zenith/geo/time.h"

#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace zenith::geo {
namespace {

// IERS Bulletin C: TAI - UTC from the given UTC date on (Julian date of 0h UTC).
struct LeapSecond {
    int year, month;
    double tai_minus_utc;
};
constexpr std::array<LeapSecond, 28> kLeapSeconds{{
    {1972, 1, 10}, {1972, 7, 11}, {1973, 1, 12}, {1974, 1, 13}, {1975, 1, 14}, {1976, 1, 15},
    {1977, 1, 16}, {1978, 1, 17}, {1979, 1, 18}, {1980, 1, 19}, {1981, 7, 20}, {1982, 7, 21},
    {1983, 7, 22}, {1985, 7, 23}, {1988, 1, 24}, {1990, 1, 25}, {1991, 1, 26}, {1992, 7, 27},
    {1993, 7, 28}, {1994, 7, 29}, {1996, 1, 30}, {1997, 7, 31}, {1999, 1, 32}, {2006, 1, 33},
    {2009, 1, 34}, {2012, 7, 35}, {2015, 7, 36}, {2017, 1, 37},
}};

constexpr int kMinYear = 1000;  // the series and the DeltaT model are used well inside their range
constexpr int kMaxYear = 3000;

bool IsLeapYear(int y) { return (y % 4 == 0 && y % 100 != 0) || y % 400 == 0; }

int DaysInMonth(int y, int m) {
    constexpr std::array<int, 12> kDays{31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
    return m == 2 && IsLeapYear(y) ? 29 : kDays[static_cast<std::size_t>(m - 1)];
}

// True if a leap second is inserted at the end of this UTC day (23:59:60 exists).
bool EndsWithLeapSecond(int year, int month, int day) {
    if (day != DaysInMonth(year, month)) return false;
    const int next_year = month == 12 ? year + 1 : year;
    const int next_month = month == 12 ? 1 : month + 1;
    for (std::size_t i = 1; i < kLeapSeconds.size(); ++i) {
        if (kLeapSeconds[i].year == next_year && kLeapSeconds[i].month == next_month) return true;
    }
    return false;
}

// Days since 1970-01-01 of a proleptic Gregorian date (H. Hinnant's days_from_civil).
long long DaysFromCivil(long long y, long long m, long long d) {
    y -= m <= 2;
    const long long era = (y >= 0 ? y : y - 399) / 400;
    const long long yoe = y - era * 400;
    const long long doy = (153 * (m + (m > 2 ? -3 : 9)) + 2) / 5 + d - 1;
    const long long doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
    return era * 146097 + doe - 719468;
}

void CivilFromDays(long long z, int& y, int& m, int& d) {
    z += 719468;
    const long long era = (z >= 0 ? z : z - 146096) / 146097;
    const long long doe = z - era * 146097;
    const long long yoe = (doe - doe / 1460 + doe / 36524 - doe / 146096) / 365;
    const long long doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    const long long mp = (5 * doy + 2) / 153;
    d = static_cast<int>(doy - (153 * mp + 2) / 5 + 1);
    m = static_cast<int>(mp < 10 ? mp + 3 : mp - 9);
    y = static_cast<int>(yoe + era * 400 + (m <= 2));
}

std::string Quote(std::string_view s) { return "'" + std::string(s) + "'"; }

[[noreturn]] void Fail(std::string_view text, const std::string& what) {
    throw TimeError(
        "utc " + Quote(text) + ": " + what +
        " (expected ISO 8601 like 2024-04-08T18:18:00.250Z or 2003-10-17T12:30:30-07:00)");
}

// Reads exactly `digits` decimal digits at `pos`.
int ReadDigits(std::string_view text, std::size_t& pos, int digits, const char* field) {
    int value = 0;
    for (int i = 0; i < digits; ++i, ++pos) {
        if (pos >= text.size() || text[pos] < '0' || text[pos] > '9') {
            Fail(text, std::string("expected ") + std::to_string(digits) + " digits for " + field);
        }
        value = value * 10 + (text[pos] - '0');
    }
    return value;
}

void Expect(std::string_view text, std::size_t& pos, char c, const char* where) {
    if (pos >= text.size() || text[pos] != c) {
        Fail(text, std::string("expected '") + c + "' " + where);
    }
    ++pos;
}

}  // namespace

void ValidateCivilTime(const CivilTime& t) {
    auto fail = [&](const std::string& field, const std::string& value, const std::string& range) {
        throw TimeError("utc " + field + " = " + value + " is out of range (expected " + range +
                        ")");
    };
    if (t.year < kMinYear || t.year > kMaxYear) {
        fail("year", std::to_string(t.year),
             std::to_string(kMinYear) + ".." + std::to_string(kMaxYear));
    }
    if (t.month < 1 || t.month > 12) fail("month", std::to_string(t.month), "1..12");
    const int dim = DaysInMonth(t.year, t.month);
    if (t.day < 1 || t.day > dim) {
        fail("day", std::to_string(t.day),
             "1.." + std::to_string(dim) + " for " + std::to_string(t.year) + "-" +
                 std::to_string(t.month));
    }
    if (t.hour < 0 || t.hour > 23) fail("hour", std::to_string(t.hour), "0..23");
    if (t.minute < 0 || t.minute > 59) fail("minute", std::to_string(t.minute), "0..59");
    const bool leap_second_allowed =
        t.hour == 23 && t.minute == 59 && EndsWithLeapSecond(t.year, t.month, t.day);
    const double max_second = leap_second_allowed ? 61.0 : 60.0;
    if (!(t.second >= 0.0 && t.second < max_second)) {
        char buf[64];
        std::snprintf(buf, sizeof buf, "%.6g", t.second);
        fail("second", buf,
             leap_second_allowed ? "0 <= s < 61 on a leap-second day"
                                 : "0 <= s < 60; 60 only in a leap second");
    }
}

CivilTime ParseIso8601(std::string_view text) {
    std::size_t pos = 0;
    while (pos < text.size() && text[pos] == ' ') ++pos;
    while (!text.empty() && text.back() == ' ') text.remove_suffix(1);
    CivilTime t;
    t.year = ReadDigits(text, pos, 4, "the year");
    Expect(text, pos, '-', "after the year");
    t.month = ReadDigits(text, pos, 2, "the month");
    Expect(text, pos, '-', "after the month");
    t.day = ReadDigits(text, pos, 2, "the day");
    t.hour = t.minute = 0;
    t.second = 0.0;
    int offset_minutes = 0;
    if (pos < text.size()) {
        if (text[pos] != 'T' && text[pos] != 't' && text[pos] != ' ') {
            Fail(text, "expected 'T' between date and time");
        }
        ++pos;
        t.hour = ReadDigits(text, pos, 2, "the hour");
        Expect(text, pos, ':', "after the hour");
        t.minute = ReadDigits(text, pos, 2, "the minute");
        if (pos < text.size() && text[pos] == ':') {
            ++pos;
            t.second = ReadDigits(text, pos, 2, "the second");
            if (pos < text.size() && (text[pos] == '.' || text[pos] == ',')) {
                ++pos;
                double scale = 0.1;
                const std::size_t start = pos;
                while (pos < text.size() && text[pos] >= '0' && text[pos] <= '9') {
                    t.second += (text[pos] - '0') * scale;
                    scale *= 0.1;
                    ++pos;
                }
                if (pos == start) Fail(text, "expected digits after the decimal point");
            }
        }
        if (pos < text.size()) {
            const char c = text[pos];
            if (c == 'Z' || c == 'z') {
                ++pos;
            } else if (c == '+' || c == '-') {
                ++pos;
                const int oh = ReadDigits(text, pos, 2, "the offset hours");
                if (pos < text.size() && text[pos] == ':') ++pos;
                const int om =
                    pos < text.size() ? ReadDigits(text, pos, 2, "the offset minutes") : 0;
                if (oh > 14 || om > 59) Fail(text, "UTC offset beyond +-14:00");
                offset_minutes = (c == '+' ? 1 : -1) * (oh * 60 + om);
            } else {
                Fail(text, std::string("unexpected '") + c + "' after the time");
            }
        }
        if (pos != text.size()) Fail(text, "unexpected trailing characters");
    }
    // Validate the local reading first (so 2024-02-30 is rejected whatever the offset), then
    // shift to UTC with exact integer arithmetic.
    try {
        ValidateCivilTime(t);
    } catch (const TimeError& e) {
        Fail(text, e.what());
    }
    if (offset_minutes != 0) {
        long long minutes = DaysFromCivil(t.year, t.month, t.day) * 1440LL + t.hour * 60LL +
                            t.minute - offset_minutes;
        long long days = minutes >= 0 ? minutes / 1440 : -((-minutes + 1439) / 1440);
        const long long minute_of_day = minutes - days * 1440;
        CivilFromDays(days, t.year, t.month, t.day);
        t.hour = static_cast<int>(minute_of_day / 60);
        t.minute = static_cast<int>(minute_of_day % 60);
        ValidateCivilTime(t);
    }
    return t;
}

std::string FormatIso8601(const CivilTime& t) {
    // Round to milliseconds without ever printing 60.000 for a normal second.
    double ms = std::floor(t.second * 1000.0 + 0.5);
    if (ms >= 60000.0 && t.second < 60.0) ms = 59999.0;
    char buf[48];
    std::snprintf(buf, sizeof buf, "%04d-%02d-%02dT%02d:%02d:%06.3fZ", t.year, t.month, t.day,
                  t.hour, t.minute, ms / 1000.0);
    return buf;
}

double JulianDate(int year, int month, int day, int hour, int minute, double second) {
    // 1970-01-01T00:00 is JD 2440587.5.
    return 2440587.5 + static_cast<double>(DaysFromCivil(year, month, day)) +
           (hour * 3600.0 + minute * 60.0 + second) / kSecondsPerDay;
}

CivilTime CivilFromJulianDate(double jd) {
    const double days_since_1970 = jd - 2440587.5;
    const double whole = std::floor(days_since_1970);
    CivilTime t;
    CivilFromDays(static_cast<long long>(whole), t.year, t.month, t.day);
    double seconds = (days_since_1970 - whole) * kSecondsPerDay;
    seconds = std::floor(seconds * 1e6 + 0.5) / 1e6;  // microsecond rounding of JD noise
    if (seconds >= kSecondsPerDay) seconds = kSecondsPerDay - 1e-6;
    t.hour = static_cast<int>(seconds / 3600.0);
    t.minute = static_cast<int>((seconds - t.hour * 3600.0) / 60.0);
    t.second = seconds - t.hour * 3600.0 - t.minute * 60.0;
    return t;
}

double TaiMinusUtc(double jd_utc) {
    double value = 0.0;
    for (const LeapSecond& ls : kLeapSeconds) {
        if (jd_utc >= JulianDate(ls.year, ls.month, 1, 0, 0, 0.0)) value = ls.tai_minus_utc;
    }
    return value;
}

double DeltaTModel(double y) {
    // Espenak & Meeus (2006), "Five Millennium Canon of Solar Eclipses", NASA/TP-2006-214141,
    // polynomial expressions for DeltaT, seconds.
    double t;
    if (y < -500.0 || y >= 2150.0) {
        const double u = (y - 1820.0) / 100.0;
        return -20.0 + 32.0 * u * u;
    }
    if (y < 500.0) {
        const double u = y / 100.0;
        return 10583.6 +
               u * (-1014.41 +
                    u * (33.78311 + u * (-5.952053 +
                                         u * (-0.1798452 + u * (0.022174192 + u * 0.0090316521)))));
    }
    if (y < 1600.0) {
        const double u = (y - 1000.0) / 100.0;
        return 1574.2 +
               u * (-556.01 +
                    u * (71.23472 + u * (0.319781 + u * (-0.8503463 +
                                                         u * (-0.005050998 + u * 0.0083572073)))));
    }
    if (y < 1700.0) {
        t = y - 1600.0;
        return 120.0 + t * (-0.9808 + t * (-0.01532 + t / 7129.0));
    }
    if (y < 1800.0) {
        t = y - 1700.0;
        return 8.83 + t * (0.1603 + t * (-0.0059285 + t * (0.00013336 - t / 1174000.0)));
    }
    if (y < 1860.0) {
        t = y - 1800.0;
        return 13.72 +
               t * (-0.332447 +
                    t * (0.0068612 +
                         t * (0.0041116 +
                              t * (-0.00037436 + t * (0.0000121272 +
                                                      t * (-0.0000001699 + t * 0.000000000875))))));
    }
    if (y < 1900.0) {
        t = y - 1860.0;
        return 7.62 + t * (0.5737 +
                           t * (-0.251754 + t * (0.01680668 + t * (-0.0004473624 + t / 233174.0))));
    }
    if (y < 1920.0) {
        t = y - 1900.0;
        return -2.79 + t * (1.494119 + t * (-0.0598939 + t * (0.0061966 - t * 0.000197)));
    }
    if (y < 1941.0) {
        t = y - 1920.0;
        return 21.20 + t * (0.84493 + t * (-0.076100 + t * 0.0020936));
    }
    if (y < 1961.0) {
        t = y - 1950.0;
        return 29.07 + t * (0.407 + t * (-1.0 / 233.0 + t / 2547.0));
    }
    if (y < 1986.0) {
        t = y - 1975.0;
        return 45.45 + t * (1.067 + t * (-1.0 / 260.0 - t / 718.0));
    }
    if (y < 2005.0) {
        t = y - 2000.0;
        return 63.86 + t * (0.3345 + t * (-0.060374 +
                                          t * (0.0017275 + t * (0.000651814 + t * 0.00002373599))));
    }
    if (y < 2050.0) {
        t = y - 2000.0;
        return 62.92 + t * (0.32217 + t * 0.005589);
    }
    const double u = (y - 1820.0) / 100.0;
    return -20.0 + 32.0 * u * u - 0.5628 * (2150.0 - y);
}

Time TimeFromUtc(const CivilTime& utc, const TimeOptions& options) {
    ValidateCivilTime(utc);
    if (options.dut1_s && !(std::abs(*options.dut1_s) <= 1.0)) {
        throw TimeError("dut1 = " + std::to_string(*options.dut1_s) +
                        " s is out of range (expected |UT1 - UTC| <= 1 s)");
    }
    if (options.delta_t_s && !(std::abs(*options.delta_t_s) < 1e5)) {
        throw TimeError("delta_t = " + std::to_string(*options.delta_t_s) +
                        " s is not a plausible TT - UT1 (expected a finite value, |dT| < 1e5 s)");
    }
    Time t;
    t.jd_utc = JulianDate(utc.year, utc.month, utc.day, utc.hour, utc.minute, utc.second);
    // During a leap second the calendar reading runs one second ahead of UT1.
    const double in_leap_second = utc.second >= 60.0 ? 1.0 : 0.0;
    t.jd_ut1 = t.jd_utc + (options.dut1_s.value_or(0.0) - in_leap_second) / kSecondsPerDay;
    const double day_start = JulianDate(utc.year, utc.month, utc.day, 0, 0, 0.0);
    if (options.delta_t_s) {
        t.jd_tt = t.jd_ut1 + *options.delta_t_s / kSecondsPerDay;
    } else if (utc.year >= 1972) {
        t.jd_tt = t.jd_utc + (TaiMinusUtc(day_start) + 32.184) / kSecondsPerDay;
    } else {
        const double decimal_year = 2000.0 + (t.jd_ut1 - kJ2000) / 365.2425;
        t.jd_tt = t.jd_ut1 + DeltaTModel(decimal_year) / kSecondsPerDay;
    }
    return t;
}

Time TimeFromIso8601(std::string_view text, const TimeOptions& options) {
    return TimeFromUtc(ParseIso8601(text), options);
}

Time TimeNow(const TimeOptions& options) {
    const auto now = std::chrono::system_clock::now().time_since_epoch();
    return TimeFromUnixSeconds(std::chrono::duration<double>(now).count(), options);
}

namespace {
constexpr double kUnixEpochJd = 2440587.5;
// JulianDate's proleptic Gregorian range: -4712-01-01 to 9999-12-31.
constexpr double kMinUnixSeconds = (0.0 - kUnixEpochJd) * kSecondsPerDay;
constexpr double kMaxUnixSeconds = (5373484.5 - kUnixEpochJd) * kSecondsPerDay;
}  // namespace

double UnixSecondsFromCivil(const CivilTime& utc) {
    // Whole days and the time of day apart, so the result keeps microseconds.
    const double jd_midnight = JulianDate(utc.year, utc.month, utc.day, 0, 0, 0.0);
    return std::round((jd_midnight - kUnixEpochJd) * kSecondsPerDay) + utc.hour * 3600.0 +
           utc.minute * 60.0 + utc.second;
}

CivilTime CivilFromUnixSeconds(double unix_s) {
    const double days = std::floor(unix_s / kSecondsPerDay);
    const double second_of_day = unix_s - days * kSecondsPerDay;
    CivilTime t = CivilFromJulianDate(kUnixEpochJd + days);
    t.hour = static_cast<int>(second_of_day / 3600.0);
    t.minute = static_cast<int>((second_of_day - t.hour * 3600.0) / 60.0);
    t.second = second_of_day - t.hour * 3600.0 - t.minute * 60.0;
    return t;
}

Time TimeFromUnixSeconds(double unix_s, const TimeOptions& options) {
    if (!(unix_s >= kMinUnixSeconds && unix_s < kMaxUnixSeconds)) {
        throw TimeError("unix_s = " + std::to_string(unix_s) +
                        " s is out of range (expected a time between the years -4712 and 9999)");
    }
    return TimeFromUtc(CivilFromUnixSeconds(unix_s), options);
}

}  // namespace zenith::geo

namespace zenith::geo {
namespace {

// Knuth's TwoSum: a + b = s + err exactly, for any magnitudes.
void TwoSum(double a, double b, double& s, double& err) {
    s = a + b;
    const double bb = s - a;
    err = (a - (s - bb)) + (b - bb);
}

double RoundToMicroseconds(double seconds) { return std::round(seconds * 1e6) / 1e6; }

// x rounded to whole seconds, milliseconds, 10 us and microseconds, then x itself: a Julian
// date resolves only 40 us, so the instant (or offset) it was made from is taken to be the
// coarsest of these that gives the same date, and instants the clock forms from it are then
// the same bits as the calendar's.
std::array<double, 5> Roundings(double x) {
    return {std::round(x), std::round(x * 1e3) / 1e3, std::round(x * 1e5) / 1e5,
            RoundToMicroseconds(x), x};
}

// The calendar reading of a POSIX day and a second of that day (0 <= second_of_day < 86400).
CivilTime CivilFromDaySecond(std::int64_t day, double second_of_day) {
    CivilTime t;
    CivilFromDays(day, t.year, t.month, t.day);
    t.hour = static_cast<int>(second_of_day / 3600.0);
    if (t.hour * 3600.0 > second_of_day) --t.hour;  // a quotient rounded up to the next hour
    double rest = second_of_day - t.hour * 3600.0;
    t.minute = static_cast<int>(rest / 60.0);
    if (t.minute * 60.0 > rest) --t.minute;
    t.second = rest - t.minute * 60.0;
    return t;
}

bool Identical(const Time& a, const Time& b) {
    return a.jd_utc == b.jd_utc && a.jd_ut1 == b.jd_ut1 && a.jd_tt == b.jd_tt;
}

bool SameInstant(const Time& a, const Time& b) {
    // Within the resolution of a Julian date in a double (40 us) and the microsecond rounding
    // of the offsets.
    constexpr double kTolerance = 1e-4 / kSecondsPerDay;
    return std::abs(a.jd_utc - b.jd_utc) <= kTolerance &&
           std::abs(a.jd_ut1 - b.jd_ut1) <= kTolerance && std::abs(a.jd_tt - b.jd_tt) <= kTolerance;
}

}  // namespace

void SimulationClock::Set(const Time& start) {
    if (!(std::isfinite(start.jd_utc) && std::isfinite(start.jd_ut1) &&
          std::isfinite(start.jd_tt))) {
        throw TimeError("SimulationClock: the start instant has a non-finite Julian date");
    }
    // jd_utc - kUnixEpochJd is exact (both near 2.4e6, the difference smaller).
    const double days_since_1970 = start.jd_utc - kUnixEpochJd;
    const double day = std::floor(days_since_1970);
    const auto start_day = static_cast<std::int64_t>(day);
    const double raw_second = (days_since_1970 - day) * kSecondsPerDay;
    double second_of_day = raw_second;
    for (const double candidate : Roundings(raw_second)) {
        if (!(candidate >= 0.0 && candidate < kSecondsPerDay)) continue;
        const CivilTime c = CivilFromDaySecond(start_day, candidate);
        if (JulianDate(c.year, c.month, c.day, c.hour, c.minute, c.second) == start.jd_utc) {
            second_of_day = candidate;
            break;
        }
    }
    const double ut1_minus_utc = (start.jd_ut1 - start.jd_utc) * kSecondsPerDay;
    const double tt_minus_utc = (start.jd_tt - start.jd_utc) * kSecondsPerDay;
    const double tt_minus_ut1 = (start.jd_tt - start.jd_ut1) * kSecondsPerDay;

    // How UT1 and TT follow from UTC: the leap-second table (TT - UTC then steps with it), or
    // else an explicit TT - UT1, with the coarsest rounding of the offsets that reproduces the
    // start bit for bit; else the same within 0.1 ms; else constant offsets for a start
    // TimeFromUtc cannot make.
    const CivilTime civil = CivilFromDaySecond(start_day, second_of_day);
    std::vector<TimeOptions> candidates;
    for (const double dut1 : Roundings(ut1_minus_utc)) {
        candidates.push_back(TimeOptions{dut1, std::nullopt});
    }
    for (const double dut1 : Roundings(ut1_minus_utc)) {
        for (const double delta_t : Roundings(tt_minus_ut1)) {
            candidates.push_back(TimeOptions{dut1, delta_t});
        }
    }
    std::optional<TimeOptions> exact, close;
    for (const TimeOptions& candidate : candidates) {
        try {
            const Time t = TimeFromUtc(civil, candidate);
            if (Identical(t, start)) {
                exact = candidate;
                break;
            }
            if (!close && SameInstant(t, start)) close = candidate;
        } catch (const TimeError&) {
            // Out of TimeFromUtc's range (a year, |DUT1| > 1 s): constant offsets below.
        }
    }
    start_ = start;
    time_ = start;
    start_day_ = start_day;
    start_second_of_day_ = second_of_day;
    from_table_ = exact || close;
    options_ = exact ? *exact : close.value_or(TimeOptions{});
    ut1_minus_utc_s_ = ut1_minus_utc;
    tt_minus_utc_s_ = tt_minus_utc;
    elapsed_hi_ = 0.0;
    elapsed_lo_ = 0.0;
    stale_ = false;
}

void SimulationClock::Advance(double seconds, double factor) {
    const double step = seconds * factor;
    if (!(std::isfinite(seconds) && std::isfinite(factor) && std::isfinite(step))) {
        throw TimeError("SimulationClock::Advance: seconds = " + std::to_string(seconds) +
                        " and factor = " + std::to_string(factor) + " must be finite");
    }
    const double step_error = std::fma(seconds, factor, -step);  // seconds * factor - step
    double hi = 0.0, err = 0.0;
    TwoSum(elapsed_hi_, step, hi, err);
    elapsed_hi_ = hi;
    elapsed_lo_ += err + step_error;
    stale_ = true;
}

void SimulationClock::SetElapsed(double seconds) {
    if (!std::isfinite(seconds)) {
        throw TimeError("SimulationClock::SetElapsed: seconds = " + std::to_string(seconds) +
                        " must be finite");
    }
    elapsed_hi_ = seconds;
    elapsed_lo_ = 0.0;
    stale_ = true;
}

const Time& SimulationClock::time() const {
    if (stale_) Refresh();
    return time_;
}

void SimulationClock::Refresh() const {
    if (elapsed_hi_ == 0.0 && elapsed_lo_ == 0.0) {
        time_ = start_;
        stale_ = false;
        return;
    }
    // Seconds since the start day's midnight as a + b, then whole days and the second of the
    // day, rounded once.
    double a = 0.0, b = 0.0;
    TwoSum(start_second_of_day_, elapsed_hi_, a, b);
    b += elapsed_lo_;
    double days = std::floor((a + b) / kSecondsPerDay);
    double second_of_day = (a - days * kSecondsPerDay) + b;  // the subtraction is exact
    if (second_of_day < 0.0) {
        second_of_day += kSecondsPerDay;
        days -= 1.0;
        if (second_of_day >= kSecondsPerDay) {  // -1e-12 s + 86400 s rounds to 86400 s
            second_of_day = 0.0;
            days += 1.0;
        }
    } else if (second_of_day >= kSecondsPerDay) {
        second_of_day -= kSecondsPerDay;
        days += 1.0;
    }
    if (!(std::abs(days) < 1e8)) {
        throw TimeError("SimulationClock: " + std::to_string(elapsed_s()) +
                        " s from the start is beyond the calendar's range");
    }
    const CivilTime civil =
        CivilFromDaySecond(start_day_ + static_cast<std::int64_t>(days), second_of_day);
    if (from_table_) {
        time_ = TimeFromUtc(civil, options_);
        stale_ = false;
        return;
    }
    Time t;
    t.jd_utc =
        JulianDate(civil.year, civil.month, civil.day, civil.hour, civil.minute, civil.second);
    t.jd_ut1 = t.jd_utc + ut1_minus_utc_s_ / kSecondsPerDay;
    t.jd_tt = t.jd_utc + tt_minus_utc_s_ / kSecondsPerDay;
    time_ = t;
    stale_ = false;
}

}  // namespace zenith::geo
