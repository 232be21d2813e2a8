// CSV reader; the format is documented in data/flights/README.md.
//
// Comma-separated, a header row naming the columns (any order, case-insensitive), '#' comment
// lines and blank lines allowed, fields optionally in double quotes ("" for a quote inside).
// Columns: time (ISO 8601, or Unix seconds when the value is a number), lat/lon (degrees),
// altitudes named alt_<datum>_<unit> (datum msl|wgs84|pressure, unit m|ft), optional
// heading_deg/pitch_deg/roll_deg attitude; OpenSky state vectors (time, lat, lon, baroaltitude,
// geoaltitude, heading = track, velocity, vertrate, ...) read as they are.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <map>
#include <numbers>

#include "flight_log_internal.h"
#include "zenith/base/error.h"
#include "zenith/base/text_lines.h"

namespace zenith::track {

namespace {

using detail::LogBuilder;

constexpr double kMetresPerFoot = 0.3048;
constexpr double kRadPerDeg = std::numbers::pi / 180.0;

struct AltitudeColumn {
    std::size_t index;
    AltitudeKind kind;
    double metres_per_unit;
};

std::string Lower(std::string_view s) {
    std::string out(Trim(s));
    std::transform(out.begin(), out.end(), out.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return out;
}

std::optional<AltitudeColumn> AltitudeColumnFromName(const std::string& name, std::size_t index) {
    // OpenSky: baroaltitude is the ADS-B barometric (pressure) altitude in metres; geoaltitude
    // is the ADS-B GNSS height, which DO-260B defines above the WGS84 ellipsoid (HAE).
    if (name == "baroaltitude") return AltitudeColumn{index, AltitudeKind::kPressure, 1.0};
    if (name == "geoaltitude") return AltitudeColumn{index, AltitudeKind::kEllipsoid, 1.0};
    if (name.rfind("alt_", 0) != 0) return std::nullopt;
    const auto last = name.rfind('_');
    const std::string datum = name.substr(4, last - 4);
    const std::string unit = name.substr(last + 1);
    double scale = 0.0;
    if (unit == "m") {
        scale = 1.0;
    } else if (unit == "ft") {
        scale = kMetresPerFoot;
    } else {
        return std::nullopt;
    }
    if (datum == "msl" || datum == "geoid") return AltitudeColumn{index, AltitudeKind::kMsl, scale};
    if (datum == "wgs84" || datum == "ellipsoid" || datum == "hae") {
        return AltitudeColumn{index, AltitudeKind::kEllipsoid, scale};
    }
    if (datum == "pressure" || datum == "baro") {
        return AltitudeColumn{index, AltitudeKind::kPressure, scale};
    }
    return std::nullopt;
}

// Which aircraft rows belong to, in a log of several (OpenSky: icao24 and callsign columns).
class AircraftFilter {
  public:
    AircraftFilter(const ReadOptions& options)
        : icao24_(Lower(options.icao24.value_or(""))),
          callsign_(Lower(options.callsign.value_or(""))) {}

    void SetColumns(std::optional<std::size_t> icao24, std::optional<std::size_t> callsign) {
        icao24_col_ = icao24;
        callsign_col_ = callsign;
    }
    bool has_columns() const { return icao24_col_ || callsign_col_; }
    bool chosen() const { return !icao24_.empty() || !callsign_.empty(); }

    // Whether the row is of the chosen aircraft (every row when none is chosen); counts rows
    // per aircraft either way, up to kMaxListedAircraft distinct ones.
    bool Accept(const std::vector<std::string>& fields) {
        const std::string icao24 = icao24_col_ ? Lower(fields[*icao24_col_]) : std::string();
        const std::string callsign = callsign_col_ ? Lower(fields[*callsign_col_]) : std::string();
        const std::string key = icao24_col_ ? icao24 : callsign;
        if (auto it = counts_.find(key); it != counts_.end()) {
            ++it->second.rows;
            if (it->second.callsign.empty()) it->second.callsign = callsign;
        } else if (counts_.size() < kMaxCountedAircraft) {
            counts_.emplace(key, Count{callsign, 1});
        } else {
            ++uncounted_rows_;
        }
        if (!chosen()) return true;
        return (icao24_.empty() || icao24 == icao24_) &&
               (callsign_.empty() || callsign == callsign_);
    }

    std::size_t aircraft() const { return counts_.size(); }

    // "3c6444 (DLH9U, 120 rows), ..." the aircraft with most rows first.
    std::string List(std::size_t at_most) const {
        std::vector<std::pair<std::string, Count>> sorted(counts_.begin(), counts_.end());
        std::sort(sorted.begin(), sorted.end(),
                  [](const auto& a, const auto& b) { return a.second.rows > b.second.rows; });
        std::string out;
        for (std::size_t i = 0; i < sorted.size() && i < at_most; ++i) {
            const auto& [key, count] = sorted[i];
            out += fmt::format("{}{}{} ({} rows)", i > 0 ? ", " : "", key.empty() ? "(none)" : key,
                               count.callsign.empty() || !icao24_col_ ? "" : " " + count.callsign,
                               count.rows);
        }
        if (sorted.size() > at_most) out += fmt::format(", ... {} more", sorted.size() - at_most);
        return out;
    }

    std::string Chosen() const {
        if (!icao24_.empty() && !callsign_.empty())
            return "icao24 " + icao24_ + " callsign " + callsign_;
        return !icao24_.empty() ? "icao24 " + icao24_ : "callsign " + callsign_;
    }

  private:
    static constexpr std::size_t kMaxCountedAircraft = 100000;
    struct Count {
        std::string callsign;
        std::size_t rows;
    };
    std::string icao24_, callsign_;
    std::optional<std::size_t> icao24_col_, callsign_col_;
    std::map<std::string, Count> counts_;
    std::size_t uncounted_rows_ = 0;
};

}  // namespace

FlightLog ParseCsv(std::string_view text, std::string source, const ReadOptions& options) {
    LogBuilder out(std::move(source), LogFormat::kCsv, options);
    AircraftFilter aircraft(options);
    // A UTF-8 byte-order mark (spreadsheet exports) is not part of the first column's name.
    if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
    std::vector<std::string> header;
    std::vector<std::string> fields;
    std::optional<std::size_t> time_col, lat_col, lon_col;
    std::array<std::optional<std::size_t>, 3> attitude_cols;  // heading, pitch, roll
    std::vector<AltitudeColumn> altitude_cols;
    int line_number = 0;
    bool have_header = false;
    std::optional<std::size_t> icao24_col, callsign_col;
    std::size_t rows = 0;  // of the chosen aircraft
    std::string_view line, trimmed;
    while (NextContentLine(text, line_number, line, trimmed)) {
        if (line.size() > kMaxLineBytes) {
            if (!have_header) {
                throw FlightLogError(fmt::format("{}header of {} characters (at most {})",
                                                 detail::Where(out.source(), line_number),
                                                 line.size(), kMaxLineBytes));
            }
            out.CountRecord();
            out.Skip(line_number,
                     fmt::format("row of {} characters (at most {})", line.size(), kMaxLineBytes));
            continue;
        }

        if (!SplitCsvLine(line, fields)) {
            if (!have_header) {
                throw FlightLogError(fmt::format("{}unclosed quote in the header",
                                                 detail::Where(out.source(), line_number)));
            }
            out.CountRecord();
            out.Skip(line_number, "unclosed quote (truncated row?)");
            continue;
        }
        if (!have_header) {
            have_header = true;
            std::vector<std::string> ignored;
            for (std::size_t i = 0; i < fields.size(); ++i) {
                const std::string name = Lower(fields[i]);
                header.push_back(name);
                if (name == "time" || name == "timestamp") {
                    time_col = i;
                } else if (name == "lat" || name == "lat_deg" || name == "latitude") {
                    lat_col = i;
                } else if (name == "lon" || name == "lon_deg" || name == "longitude") {
                    lon_col = i;
                } else if (name == "heading_deg") {
                    attitude_cols[0] = i;
                } else if (name == "pitch_deg") {
                    attitude_cols[1] = i;
                } else if (name == "roll_deg") {
                    attitude_cols[2] = i;
                } else if (name == "icao24") {
                    icao24_col = i;
                } else if (name == "callsign") {
                    callsign_col = i;
                } else if (auto alt = AltitudeColumnFromName(name, i)) {
                    altitude_cols.push_back(*alt);
                } else if (name == "alt" || name == "altitude" || name == "ele" ||
                           name == "elevation" || name == "height" || name.rfind("alt_", 0) == 0) {
                    throw FlightLogError(fmt::format(
                        "{}altitude column '{}' does not say its datum and unit: name it "
                        "alt_<datum>_<unit> with datum msl, wgs84 or pressure and unit m or ft "
                        "(e.g. alt_msl_m, alt_pressure_ft)",
                        detail::Where(out.source(), line_number), fields[i]));
                } else {
                    ignored.push_back(name);
                }
            }
            if (!time_col || !lat_col || !lon_col) {
                throw FlightLogError(
                    fmt::format("{}header needs columns time, lat and lon (found: {})",
                                detail::Where(out.source(), line_number), fmt::join(header, ", ")));
            }
            const auto n_attitude = std::count_if(attitude_cols.begin(), attitude_cols.end(),
                                                  [](const auto& c) { return c.has_value(); });
            if (n_attitude != 0 && n_attitude != 3) {
                throw FlightLogError(
                    fmt::format("{}attitude needs all three of heading_deg, pitch_deg and roll_deg",
                                detail::Where(out.source(), line_number)));
            }
            if (altitude_cols.empty()) {
                out.Note(
                    "no altitude column (alt_msl_m, alt_wgs84_m, alt_pressure_ft, "
                    "baroaltitude, ...): samples have no altitude");
            }
            if (std::find(header.begin(), header.end(), "heading") != header.end()) {
                out.Note(
                    "column 'heading' (OpenSky: direction of movement, i.e. track) is not an "
                    "attitude; attitude is derived from the track");
            }
            if (!ignored.empty()) {
                out.Note(fmt::format("columns not used: {}", fmt::join(ignored, ", ")));
            }
            aircraft.SetColumns(icao24_col, callsign_col);
            if (aircraft.chosen() && !aircraft.has_columns()) {
                throw FlightLogError(
                    fmt::format("{}an aircraft was chosen ({}) but the header "
                                "has no icao24 or callsign column",
                                detail::Where(out.source(), line_number), aircraft.Chosen()));
            }
            continue;
        }

        if (fields.size() != header.size()) {
            out.CountRecord();
            out.Skip(line_number,
                     fmt::format("{} fields for {} columns{}", fields.size(), header.size(),
                                 fields.size() < header.size() ? " (truncated row?)" : ""));
            continue;
        }
        // Rows of other aircraft are not this log's records.
        if (aircraft.has_columns() && !aircraft.Accept(fields)) continue;
        out.CountRecord();
        ++rows;
        FlightSample s;
        s.line = line_number;
        const std::string_view time_text = Trim(fields[*time_col]);
        if (time_text.empty()) {
            out.Skip(line_number, "empty time");
            continue;
        }
        try {
            std::optional<double> unix_s;
            try {
                unix_s = detail::ParseDouble(time_text);
            } catch (const ArgumentError&) {
                // not a number: ISO 8601 below
            }
            s.time_s = unix_s ? *unix_s : detail::UnixSecondsFromIso8601(time_text);
        } catch (const std::exception& e) {
            out.Skip(line_number, fmt::format("bad time '{}': {}", time_text, e.what()));
            continue;
        }
        try {
            const auto lat = detail::ParseDouble(fields[*lat_col]);
            const auto lon = detail::ParseDouble(fields[*lon_col]);
            if (!lat || !lon) {
                out.Skip(line_number, "no position (empty lat or lon)");
                continue;
            }
            s.lat_deg = *lat;
            s.lon_deg = *lon;
        } catch (const std::exception& e) {
            out.Skip(line_number, fmt::format("bad lat/lon: {}", e.what()));
            continue;
        }
        bool bad = false;
        for (const AltitudeColumn& c : altitude_cols) {
            try {
                const auto v = detail::ParseDouble(fields[c.index]);
                if (!v) continue;
                const double metres = *v * c.metres_per_unit;
                switch (c.kind) {
                    case AltitudeKind::kPressure:
                        s.pressure_altitude = metres;
                        break;
                    case AltitudeKind::kMsl:
                        s.msl_altitude = metres;
                        break;
                    case AltitudeKind::kEllipsoid:
                        s.ellipsoid_height = metres;
                        break;
                }
            } catch (const std::exception& e) {
                out.Skip(line_number, fmt::format("bad {}: {}", header[c.index], e.what()));
                bad = true;
                break;
            }
        }
        if (bad) continue;
        if (attitude_cols[0]) {
            try {
                const auto h = detail::ParseDouble(fields[*attitude_cols[0]]);
                const auto p = detail::ParseDouble(fields[*attitude_cols[1]]);
                const auto r = detail::ParseDouble(fields[*attitude_cols[2]]);
                if (h && p && r) {
                    s.attitude = geo::Attitude{*h * kRadPerDeg, *p * kRadPerDeg, *r * kRadPerDeg};
                }
            } catch (const std::exception& e) {
                out.Skip(line_number, fmt::format("bad attitude: {}", e.what()));
                continue;
            }
        }
        out.Add(std::move(s));
    }
    if (!have_header) throw FlightLogError(out.source() + ": empty CSV (no header row)");
    if (!aircraft.chosen() && aircraft.aircraft() > 1) {
        throw FlightLogError(fmt::format(
            "{}: {} aircraft in one log; choose one by icao24 or callsign (zenith replay "
            "--icao24/--callsign): {}",
            out.source(), aircraft.aircraft(), aircraft.List(10)));
    }
    if (aircraft.chosen() && rows == 0) {
        throw FlightLogError(fmt::format("{}: no row of {} (aircraft in the log: {})", out.source(),
                                         aircraft.Chosen(), aircraft.List(10)));
    }
    return out.Finish();
}

}  // namespace zenith::track
