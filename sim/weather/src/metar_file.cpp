// METAR files; the formats are in metar_file.h.
#include "zenith/weather/metar_file.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <iterator>
#include <system_error>

#include "zenith/base/text_lines.h"
#include "zenith/geo/time.h"

namespace zenith::weather {

namespace {

std::string Lower(std::string_view s) {
    std::string out(Trim(s));
    std::transform(out.begin(), out.end(), out.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return out;
}

std::string ReadWholeFile(const std::filesystem::path& path) {
    std::error_code ec;
    const std::uintmax_t size = std::filesystem::file_size(path, ec);
    if (ec) throw MetarError(AtLocation(path, std::nullopt, "cannot read: " + ec.message()));
    if (size > kMaxMetarFileBytes) {
        throw MetarError(AtLocation(
            path, std::nullopt,
            fmt::format("file of {} MiB (at most {} MiB)", size >> 20, kMaxMetarFileBytes >> 20)));
    }
    std::ifstream in(path, std::ios::binary);
    if (!in) throw MetarError(AtLocation(path, std::nullopt, "cannot open"));
    std::string text(static_cast<std::size_t>(size), '\0');
    in.read(text.data(), static_cast<std::streamsize>(size));
    text.resize(static_cast<std::size_t>(in.gcount()));
    return text;
}

class Collector {
  public:
    explicit Collector(std::string source) { file_.source = std::move(source); }

    void Skip(std::size_t line, std::string_view reason) {
        ++file_.skipped;
        if (file_.first_skipped.size() < kMaxListedSkips) {
            file_.first_skipped.push_back(AtLocation(file_.source, line, reason));
        }
    }

    // Decodes the report; a fatal decode error skips the line.
    std::optional<MetarRecord> Decode(std::string_view report, std::size_t line) {
        if (file_.records.size() >= kMaxMetarRecords) {
            throw MetarError(AtLocation(file_.source, line,
                                        fmt::format("more than {} reports", kMaxMetarRecords)));
        }
        try {
            MetarRecord r;
            r.metar = DecodeMetar(report);
            r.line = line;
            return r;
        } catch (const MetarError& e) {
            Skip(line, e.what());
            return std::nullopt;
        }
    }

    void Add(MetarRecord r) {
        file_.warnings += r.metar.warnings.size() + r.metar.warnings_suppressed;
        file_.records.push_back(std::move(r));
    }

    const std::string& source() const { return file_.source; }

    MetarFile Finish() {
        if (file_.records.empty()) {
            std::string message = "no usable METAR report";
            if (!file_.first_skipped.empty())
                message += "; first skipped: " + file_.first_skipped[0];
            throw MetarError(AtLocation(file_.source, std::nullopt, message));
        }
        return std::move(file_);
    }

  private:
    MetarFile file_;
};

std::optional<double> ParseCoordinate(std::string_view text, double limit) {
    text = Trim(text);
    if (text.empty() || text == "M") return std::nullopt;
    double v = 0.0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (ec != std::errc() || end != text.data() + text.size() || !(std::abs(v) <= limit)) {
        throw MetarError(
            fmt::format("'{}' is not a coordinate in [-{}, {}] deg", text, limit, limit));
    }
    return v;
}

}  // namespace

std::string MetarFile::Summary() const {
    std::string out = fmt::format("{}: {} reports, {} skipped, {} decode warnings", source,
                                  records.size(), skipped, warnings);
    if (!first_skipped.empty()) out += "; first skipped: " + first_skipped.front();
    return out;
}

// NOAA's per-station files (tgftp.nws.noaa.gov/data/observations/metar/stations) put the
// observation time on the line before the report: "2024/07/14 12:00".
std::optional<double> NoaaTimeLine(std::string_view s) {
    if (s.size() != 16 || s[4] != '/' || s[7] != '/' || s[10] != ' ' || s[13] != ':') {
        return std::nullopt;
    }
    std::string iso(s);
    iso[4] = '-';
    iso[7] = '-';
    try {
        const geo::CivilTime t = geo::ParseIso8601(iso);
        geo::ValidateCivilTime(t);
        return geo::UnixSecondsFromCivil(t);
    } catch (const std::exception&) {
        return std::nullopt;
    }
}

MetarFile ParseMetarLines(std::string_view text, std::string source) {
    Collector out(std::move(source));
    std::size_t line_number = 0;
    std::optional<double> pending_time;
    std::string_view line, trimmed;
    while (NextContentLine(text, line_number, line, trimmed)) {
        if (line.size() > kMaxMetarLineBytes) {
            out.Skip(line_number, fmt::format("line of {} characters (at most {})", line.size(),
                                              kMaxMetarLineBytes));
            continue;
        }
        if (const auto t = NoaaTimeLine(trimmed)) {
            pending_time = t;
            continue;
        }
        if (auto r = out.Decode(trimmed, line_number)) {
            r->time_s = pending_time;
            out.Add(std::move(*r));
        }
        pending_time.reset();
    }
    return out.Finish();
}

MetarFile ReadMetarLines(const std::filesystem::path& path) {
    return ParseMetarLines(ReadWholeFile(path), path.string());
}

MetarFile ParseMetarCsv(std::string_view text, std::string source) {
    Collector out(std::move(source));
    if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);  // UTF-8 byte-order mark
    std::vector<std::string> fields;
    std::size_t columns = 0;
    std::optional<std::size_t> metar_col, valid_col, station_col, lat_col, lon_col;
    bool have_header = false;
    std::size_t line_number = 0;
    std::string_view line, trimmed;
    while (NextContentLine(text, line_number, line, trimmed)) {
        if (line.size() > kMaxMetarLineBytes) {
            const std::string reason =
                fmt::format("line of {} characters (at most {})", line.size(), kMaxMetarLineBytes);
            if (!have_header) throw MetarError(AtLocation(out.source(), line_number, reason));
            out.Skip(line_number, reason);
            continue;
        }
        if (!SplitCsvLine(line, fields)) {
            if (!have_header) {
                throw MetarError(
                    AtLocation(out.source(), line_number, "unclosed quote in the header"));
            }
            out.Skip(line_number, "unclosed quote (truncated row?)");
            continue;
        }
        if (!have_header) {
            have_header = true;
            columns = fields.size();
            for (std::size_t i = 0; i < fields.size(); ++i) {
                const std::string name = Lower(fields[i]);
                if (name == "metar" || name == "raw_text") {
                    metar_col = i;
                } else if (name == "valid" || name == "time" || name == "observation_time") {
                    valid_col = i;
                } else if (name == "station" || name == "station_id") {
                    station_col = i;
                } else if (name == "lat" || name == "latitude") {
                    lat_col = i;
                } else if (name == "lon" || name == "longitude") {
                    lon_col = i;
                }
            }
            if (!metar_col) {
                throw MetarError(AtLocation(out.source(), line_number,
                                            "CSV header has no 'metar' column (expected e.g. "
                                            "station,valid,lon,lat,metar)"));
            }
            continue;
        }
        if (fields.size() != columns) {
            out.Skip(line_number, fmt::format("{} fields for {} columns", fields.size(), columns));
            continue;
        }
        auto r = out.Decode(Trim(fields[*metar_col]), line_number);
        if (!r) continue;
        try {
            if (valid_col && !Trim(fields[*valid_col]).empty()) {
                const geo::CivilTime t = geo::ParseIso8601(Trim(fields[*valid_col]));
                geo::ValidateCivilTime(t);
                r->time_s = geo::UnixSecondsFromCivil(t);
                const auto& rt = r->metar.time;
                if (rt && (rt->day != t.day || rt->hour != t.hour || rt->minute != t.minute) &&
                    r->metar.warnings.size() < kMaxMetarWarnings) {
                    r->metar.warnings.push_back(
                        {r->metar.station,
                         {0, 0},
                         fmt::format("report time day {} {:02d}:{:02d} differs from the valid time "
                                     "'{}'",
                                     rt->day, rt->hour, rt->minute, Trim(fields[*valid_col]))});
                }
            }
            if (lat_col) r->lat_deg = ParseCoordinate(fields[*lat_col], 90.0);
            if (lon_col) r->lon_deg = ParseCoordinate(fields[*lon_col], 180.0);
        } catch (const std::exception& e) {
            out.Skip(line_number, e.what());
            continue;
        }
        if (station_col) r->archive_station = std::string(Trim(fields[*station_col]));
        out.Add(std::move(*r));
    }
    if (!have_header)
        throw MetarError(AtLocation(out.source(), std::nullopt, "empty CSV (no header row)"));
    return out.Finish();
}

MetarFile ReadMetarCsv(const std::filesystem::path& path) {
    return ParseMetarCsv(ReadWholeFile(path), path.string());
}

}  // namespace zenith::weather
