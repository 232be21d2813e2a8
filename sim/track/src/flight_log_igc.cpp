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
                                           : std::string(detail::Trim(line.substr(colon + 1)));
}

struct Line {
    std::string_view text;
    int number;
};

std::vector<Line> SplitLines(std::string_view text) {
    std::vector<Line> lines;
    int number = 0;
    while (!text.empty()) {
        const auto end = text.find('\n');
        std::string_view line = text.substr(0, end);
        while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.remove_suffix(1);
        lines.push_back({line, ++number});
        if (end == std::string_view::npos) break;
        text.remove_prefix(end + 1);
    }
    return lines;
}

}  // namespace

FlightLog ParseIgc(std::string_view text, std::string source) {
    LogBuilder out(std::move(source), LogFormat::kIgc);
    const std::vector<Line> lines = SplitLines(text);

    // Headers first: some recorders write HFDTE after the first fixes.
    std::optional<double> midnight_s;
    int date_line = 0;
    AltitudeKind gnss_kind = AltitudeKind::kMsl;
    bool gnss_datum_given = false;
    std::size_t b_length = kBRecordLength;
    std::string pilot, glider;
    for (const Line& l : lines) {
        const std::string upper = Upper(l.text.substr(0, std::min<std::size_t>(l.text.size(), 24)));
        if (StartsWith(upper, "HFDTE") || StartsWith(upper, "HODTE")) {
            std::size_t pos = 5;
            if (StartsWith(upper.substr(5), "DATE:")) pos = 10;
            const auto dd = Digits(l.text, pos, 2);
            const auto mm = Digits(l.text, pos + 2, 2);
            const auto yy = Digits(l.text, pos + 4, 2);
            if (!dd || !mm || !yy) {
                out.Skip(l.number, fmt::format("HFDTE date '{}' is not ddmmyy", l.text));
                continue;
            }
            // IGC files exist from 1990 on.
            const geo::CivilTime date{*yy < 80 ? 2000 + *yy : 1900 + *yy, *mm, *dd, 0, 0, 0.0};
            try {
                geo::ValidateCivilTime(date);
            } catch (const geo::TimeError& e) {
                out.Skip(l.number,
                         fmt::format("HFDTE date '{}' does not exist: {}", l.text, e.what()));
                continue;
            }
            if (midnight_s) {
                out.Note(fmt::format("{}second HFDTE record ignored (date taken from line {})",
                                     detail::Where(out.source(), l.number), date_line));
                continue;
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
                continue;
            }
            for (int i = 0; i < *count; ++i) {
                const auto finish = Digits(l.text, 3 + 7 * static_cast<std::size_t>(i) + 2, 2);
                if (finish) b_length = std::max(b_length, static_cast<std::size_t>(*finish));
            }
        }
    }
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
    bool any_pressure = false, any_gnss = false;
    std::vector<FlightSample> samples;
    for (const Line& l : lines) {
        if (l.text.empty()) continue;
        const char type = l.text[0];
        if (type != 'B') {
            if (!std::isupper(static_cast<unsigned char>(type))) {
                out.CountRecord();
                out.Skip(l.number,
                         fmt::format("not an IGC record (starts with '{}')", l.text.substr(0, 12)));
            }
            continue;
        }
        out.CountRecord();
        const std::string_view b = l.text;
        if (b.size() < kBRecordLength) {
            out.Skip(l.number, fmt::format("B record truncated: {} of {} characters", b.size(),
                                           kBRecordLength));
            continue;
        }
        if (b.size() < b_length) ++short_extensions;
        const auto hh = Digits(b, 1, 2), mi = Digits(b, 3, 2), ss = Digits(b, 5, 2);
        if (!hh || !mi || !ss || *hh > 23 || *mi > 59 || *ss > 59) {
            out.Skip(l.number, fmt::format("bad time '{}' (hhmmss)", b.substr(1, 6)));
            continue;
        }
        const auto lat_d = Digits(b, 7, 2), lat_m = Digits(b, 9, 5);
        const auto lon_d = Digits(b, 15, 3), lon_m = Digits(b, 18, 5);
        const char ns = b[14], ew = b[23], validity = b[24];
        if (!lat_d || !lat_m || (ns != 'N' && ns != 'S') || *lat_m >= 60000) {
            out.Skip(l.number,
                     fmt::format("bad latitude '{}' (ddmmmmm then N or S)", b.substr(7, 8)));
            continue;
        }
        if (!lon_d || !lon_m || (ew != 'E' && ew != 'W') || *lon_m >= 60000) {
            out.Skip(l.number,
                     fmt::format("bad longitude '{}' (dddmmmmm then E or W)", b.substr(15, 9)));
            continue;
        }
        double lat_deg = *lat_d + *lat_m / 60000.0;
        double lon_deg = *lon_d + *lon_m / 60000.0;
        if (!(lat_deg <= 90.0) || !(lon_deg <= 180.0)) {
            out.Skip(l.number, fmt::format("position out of range: lat {:.5f}, lon {:.5f} deg",
                                           lat_deg, lon_deg));
            continue;
        }
        if (ns == 'S') lat_deg = -lat_deg;
        if (ew == 'W') lon_deg = -lon_deg;
        if (lon_deg >= 180.0) lon_deg -= 360.0;
        if (validity != 'A' && validity != 'V') {
            out.Skip(l.number, fmt::format("bad fix validity '{}' (A or V)", validity));
            continue;
        }
        const auto pressure = AltitudeField(b, 25), gnss = AltitudeField(b, 30);
        if (!pressure || !gnss) {
            out.Skip(l.number, fmt::format("bad altitude fields '{}' (two 5-digit metres)",
                                           b.substr(25, 10)));
            continue;
        }
        if (validity == 'V' && lat_deg == 0.0 && lon_deg == 0.0) {
            out.Skip(l.number, "V fix with no position (0, 0)");
            continue;
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
        samples.push_back(s);
    }
    // A recorder without a pressure sensor (or without GNSS altitude) writes 00000 throughout.
    if (!any_pressure) {
        if (!samples.empty()) {
            out.Note("pressure altitude is 0 in every fix (no pressure sensor): not used");
        }
        for (FlightSample& s : samples) s.pressure_altitude.reset();
    }
    if (!any_gnss) {
        if (!samples.empty()) out.Note("GNSS altitude is 0 in every fix: not used");
        for (FlightSample& s : samples) {
            s.msl_altitude.reset();
            s.ellipsoid_height.reset();
        }
    }
    if (v_fixes > 0) {
        out.Note(fmt::format("{} fixes flagged V (2D or no GNSS): their GNSS altitude is not used",
                             v_fixes));
    }
    if (short_extensions > 0) {
        out.Note(
            fmt::format("{} B records are shorter than the I record's extensions ({} "
                        "characters); the extensions are not used anyway",
                        short_extensions, b_length));
    }
    for (FlightSample& s : samples) out.Add(std::move(s));
    return out.Finish();
}

}  // namespace zenith::track
