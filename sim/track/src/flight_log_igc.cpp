// IGC reader (FAI Technical Specification for IGC-approved GNSS flight recorders, Appendix A).
//
// Read: A (recorder), H (HFDTE date in both the old "HFDTEddmmyy" and the 2015+ "HFDTEDATE:
// ddmmyy,nn" forms; HFALG/HFALP altitude datums; pilot and glider for the description), I (fix
// extensions, to know the full B-record length) and B records. Ignored: C, D, E, F, J, K, L and
// G (the security signature is recorder-specific and cannot be checked without the vendor's key;
// IGC lines carry no checksum of their own).
//
// B record, byte offsets (0-based): 1-6 hhmmss UTC, 7-13 ddmmmmm + 14 N/S, 15-22 dddmmmmm + 23
// E/W, 24 fix validity (A = 3D, V = 2D or no GNSS), 25-29 pressure altitude (m, ISA 1013.25 hPa),
// 30-34 GNSS altitude (m); extensions from byte 35 as the I record says.
#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>

#include "flight_log_internal.h"

namespace zenith::track {

namespace {

using detail::LogBuilder;

constexpr std::size_t kBRecordLength = 35;
constexpr double kSecondsPerDay = 86400.0;
// A B-record clock that drops by more than this is a flight across 00:00 UTC, not a step back.
constexpr double kMidnightRolloverS = 12.0 * 3600.0;

std::optional<int> Digits(std::string_view line, std::size_t pos, std::size_t count) {
    if (pos + count > line.size()) return std::nullopt;
    int value = 0;
    for (std::size_t i = pos; i < pos + count; ++i) {
        if (!std::isdigit(static_cast<unsigned char>(line[i]))) return std::nullopt;
        value = value * 10 + (line[i] - '0');
    }
    return value;
}

// Altitude field of 5 characters: digits, or '-' then 4 digits.
std::optional<int> AltitudeField(std::string_view line, std::size_t pos) {
    if (pos + 5 > line.size()) return std::nullopt;
    if (line[pos] == '-') {
        const auto v = Digits(line, pos + 1, 4);
        return v ? std::optional<int>(-*v) : std::nullopt;
    }
    return Digits(line, pos, 5);
}

bool StartsWith(std::string_view s, std::string_view prefix) {
    return s.size() >= prefix.size() && s.substr(0, prefix.size()) == prefix;
}

std::string Upper(std::string_view s) {
    std::string out(s);
    std::transform(out.begin(), out.end(), out.begin(),
                   [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
    return out;
}

// Value after the first ':' of an H record ("HFPLTPILOTINCHARGE:Jane Doe"), trimmed.
std::string HeaderValue(std::string_view line) {
    const auto colon = line.find(':');
    return colon == std::string_view::npos ? std::string()
                                           : std::string(Trim(line.substr(colon + 1)));
}

struct Line {
    std::string_view text;
    int number;
};

// Calls f(Line) for each line of the text, without storing them: a log of millions of B records
// is read through once per pass. Lines end in LF, CRLF or a lone CR; trailing blanks go.
template <class F>
void ForEachLine(std::string_view text, F&& f) {
    int number = 0;
    while (!text.empty()) {
        std::string_view line = NextLine(text);
        while (!line.empty() && line.back() == ' ') line.remove_suffix(1);
        f(Line{line, ++number});
    }
}

}  // namespace

FlightLog ParseIgc(std::string_view text, std::string source, const ReadOptions& options) {
    LogBuilder out(std::move(source), LogFormat::kIgc, options);

    // Headers first: some recorders write HFDTE after the first fixes.
    std::optional<double> midnight_s;
    int date_line = 0;
    AltitudeKind gnss_kind = AltitudeKind::kMsl;
    bool gnss_datum_given = false;
    std::size_t b_length = kBRecordLength;
    std::string pilot, glider;
    ForEachLine(text, [&](const Line& l) {
        const std::string upper = Upper(l.text.substr(0, std::min<std::size_t>(l.text.size(), 24)));
        if (StartsWith(upper, "HFDTE") || StartsWith(upper, "HODTE")) {
            std::size_t pos = 5;
            if (StartsWith(upper.substr(5), "DATE:")) pos = 10;
            const auto dd = Digits(l.text, pos, 2);
            const auto mm = Digits(l.text, pos + 2, 2);
            const auto yy = Digits(l.text, pos + 4, 2);
            if (!dd || !mm || !yy) {
                out.Skip(l.number, fmt::format("HFDTE date '{}' is not ddmmyy", l.text));
                return;
            }
            // IGC files exist from 1990 on.
            const geo::CivilTime date{*yy < 80 ? 2000 + *yy : 1900 + *yy, *mm, *dd, 0, 0, 0.0};
            try {
                geo::ValidateCivilTime(date);
            } catch (const geo::TimeError& e) {
                out.Skip(l.number,
                         fmt::format("HFDTE date '{}' does not exist: {}", l.text, e.what()));
                return;
            }
            if (midnight_s) {
                out.Note(fmt::format("{}second HFDTE record ignored (date taken from line {})",
                                     detail::Where(out.source(), l.number), date_line));
                return;
            }
            midnight_s = geo::UnixSecondsFromCivil(date);
            date_line = l.number;
        } else if (StartsWith(upper, "HFALG") || StartsWith(upper, "HOALG")) {
            const std::string v = Upper(HeaderValue(l.text));
            if (StartsWith(v, "ELL")) {
                gnss_kind = AltitudeKind::kEllipsoid;
                gnss_datum_given = true;
            } else if (StartsWith(v, "GEO")) {
                gnss_kind = AltitudeKind::kMsl;
                gnss_datum_given = true;
            }
        } else if (StartsWith(upper, "HFPLT")) {
            pilot = HeaderValue(l.text);
        } else if (StartsWith(upper, "HFGTY")) {
            glider = HeaderValue(l.text);
        } else if (!l.text.empty() && l.text[0] == 'I') {
            const auto count = Digits(l.text, 1, 2);
            if (!count || l.text.size() < 3 + 7 * static_cast<std::size_t>(*count)) {
                out.Skip(l.number,
                         "I record truncated or malformed; B-record extensions "
                         "are not checked");
                return;
            }
            for (int i = 0; i < *count; ++i) {
                const auto finish = Digits(l.text, 3 + 7 * static_cast<std::size_t>(i) + 2, 2);
                if (finish) b_length = std::max(b_length, static_cast<std::size_t>(*finish));
            }
        }
    });
    if (!midnight_s) {
        throw FlightLogError(
            fmt::format("{}: no valid HFDTE date record (expected 'HFDTEddmmyy' "
                        "or 'HFDTEDATE:ddmmyy,nn'); B records carry only the "
                        "time of day",
                        out.source()));
    }
    if (!gnss_datum_given) {
        out.Note(
            "no HFALG record: GNSS altitude taken as height above the geoid (what most "
            "recorders write)");
    }
    {
        std::string description = pilot;
        if (!glider.empty()) description += (description.empty() ? "" : ", ") + glider;
        out.SetDescription(description);
    }

    double day_offset_s = 0.0;
    std::optional<double> previous_clock_s;
    int v_fixes = 0;
    int short_extensions = 0;
    int fixes = 0;
    bool any_pressure = false, any_gnss = false;
    ForEachLine(text, [&](const Line& l) {
        if (l.text.empty()) return;
        const char type = l.text[0];
        if (type != 'B') {
            if (!std::isupper(static_cast<unsigned char>(type))) {
                out.CountRecord();
                out.Skip(l.number,
                         fmt::format("not an IGC record (starts with '{}')", l.text.substr(0, 12)));
            }
            return;
        }
        out.CountRecord();
        const std::string_view b = l.text;
        if (b.size() < kBRecordLength) {
            out.Skip(l.number, fmt::format("B record truncated: {} of {} characters", b.size(),
                                           kBRecordLength));
            return;
        }
        if (b.size() > kMaxLineBytes) {
            out.Skip(l.number, fmt::format("B record of {} characters (at most {})", b.size(),
                                           kMaxLineBytes));
            return;
        }
        if (b.size() < b_length) ++short_extensions;
        const auto hh = Digits(b, 1, 2), mi = Digits(b, 3, 2), ss = Digits(b, 5, 2);
        if (!hh || !mi || !ss || *hh > 23 || *mi > 59 || *ss > 59) {
            out.Skip(l.number, fmt::format("bad time '{}' (hhmmss)", b.substr(1, 6)));
            return;
        }
        const auto lat_d = Digits(b, 7, 2), lat_m = Digits(b, 9, 5);
        const auto lon_d = Digits(b, 15, 3), lon_m = Digits(b, 18, 5);
        const char ns = b[14], ew = b[23], validity = b[24];
        if (!lat_d || !lat_m || (ns != 'N' && ns != 'S') || *lat_m >= 60000) {
            out.Skip(l.number,
                     fmt::format("bad latitude '{}' (ddmmmmm then N or S)", b.substr(7, 8)));
            return;
        }
        if (!lon_d || !lon_m || (ew != 'E' && ew != 'W') || *lon_m >= 60000) {
            out.Skip(l.number,
                     fmt::format("bad longitude '{}' (dddmmmmm then E or W)", b.substr(15, 9)));
            return;
        }
        double lat_deg = *lat_d + *lat_m / 60000.0;
        double lon_deg = *lon_d + *lon_m / 60000.0;
        if (!(lat_deg <= 90.0) || !(lon_deg <= 180.0)) {
            out.Skip(l.number, fmt::format("position out of range: lat {:.5f}, lon {:.5f} deg",
                                           lat_deg, lon_deg));
            return;
        }
        if (ns == 'S') lat_deg = -lat_deg;
        if (ew == 'W') lon_deg = -lon_deg;
        if (lon_deg >= 180.0) lon_deg -= 360.0;
        if (validity != 'A' && validity != 'V') {
            out.Skip(l.number, fmt::format("bad fix validity '{}' (A or V)", validity));
            return;
        }
        const auto pressure = AltitudeField(b, 25), gnss = AltitudeField(b, 30);
        if (!pressure || !gnss) {
            out.Skip(l.number, fmt::format("bad altitude fields '{}' (two 5-digit metres)",
                                           b.substr(25, 10)));
            return;
        }
        if (validity == 'V' && lat_deg == 0.0 && lon_deg == 0.0) {
            out.Skip(l.number, "V fix with no position (0, 0)");
            return;
        }

        const double clock_s = *hh * 3600.0 + *mi * 60.0 + *ss;
        if (previous_clock_s && clock_s < *previous_clock_s - kMidnightRolloverS) {
            day_offset_s += kSecondsPerDay;
        }
        previous_clock_s = clock_s;

        FlightSample s;
        s.time_s = *midnight_s + day_offset_s + clock_s;
        s.lat_deg = lat_deg;
        s.lon_deg = lon_deg;
        s.line = l.number;
        s.pressure_altitude = *pressure;
        any_pressure = any_pressure || *pressure != 0;
        if (validity == 'A') {
            if (gnss_kind == AltitudeKind::kEllipsoid) {
                s.ellipsoid_height = *gnss;
            } else {
                s.msl_altitude = *gnss;
            }
            any_gnss = any_gnss || *gnss != 0;
        } else {
            ++v_fixes;
        }
        ++fixes;
        out.Add(std::move(s));
    });
    // A recorder without a pressure sensor (or without GNSS altitude) writes 00000 throughout.
    if (!any_pressure) {
        if (fixes > 0) {
            out.Note("pressure altitude is 0 in every fix (no pressure sensor): not used");
        }
        for (FlightSample& s : out.samples()) s.pressure_altitude.reset();
    }
    if (!any_gnss) {
        if (fixes > 0 && v_fixes == fixes) {
            out.Note(
                fmt::format("all {} fixes are flagged V (2-D or no GNSS fix): no GNSS "
                            "altitude",
                            fixes));
        } else if (fixes > 0) {
            out.Note("GNSS altitude is 0 in every fix: not used");
        }
        for (FlightSample& s : out.samples()) {
            s.msl_altitude.reset();
            s.ellipsoid_height.reset();
        }
    } else if (v_fixes > 0) {
        out.Note(
            fmt::format("{} fixes flagged V (2-D or no GNSS fix): their GNSS altitude is not "
                        "used",
                        v_fixes));
    }
    if (short_extensions > 0) {
        out.Note(
            fmt::format("{} B records are shorter than the I record's extensions ({} "
                        "characters); the extensions are not used anyway",
                        short_extensions, b_length));
    }
    return out.Finish();
}

}  // namespace zenith::track
