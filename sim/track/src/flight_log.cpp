// Flight logs: what every reader shares (summary, time-order checks, format dispatch).
#include "zenith/track/flight_log.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include "flight_log_internal.h"

namespace zenith::track {

namespace {

// A fix this close to a pole gets a note: heading and longitude lose meaning there.
constexpr double kPoleNoteLatDeg = 89.99;
// A gap is noted when it is this many times the median interval and at least kMinGapNoteS.
constexpr double kGapNoteFactor = 5.0;
constexpr double kMinGapNoteS = 10.0;
constexpr std::size_t kMaxNotes = 16;

}  // namespace

std::string_view LogFormatName(LogFormat format) {
    switch (format) {
        case LogFormat::kIgc:
            return "IGC";
        case LogFormat::kGpx:
            return "GPX";
        case LogFormat::kKml:
            return "KML";
        case LogFormat::kCsv:
            return "CSV";
    }
    return "?";
}

std::string_view AltitudeKindName(AltitudeKind kind) {
    switch (kind) {
        case AltitudeKind::kPressure:
            return "pressure altitude (ISA, 1013.25 hPa)";
        case AltitudeKind::kMsl:
            return "height above mean sea level (geoid)";
        case AltitudeKind::kEllipsoid:
            return "height above the WGS84 ellipsoid";
    }
    return "?";
}

std::optional<double> FlightSample::Altitude(AltitudeKind kind) const {
    switch (kind) {
        case AltitudeKind::kPressure:
            return pressure_altitude;
        case AltitudeKind::kMsl:
            return msl_altitude;
        case AltitudeKind::kEllipsoid:
            return ellipsoid_height;
    }
    return std::nullopt;
}

std::string ReadSummary::ToString() const {
    std::string out = fmt::format("used {} of {} records", used, records);
    if (skipped > 0) {
        out += fmt::format("; skipped {}", skipped);
        for (const SkippedRecord& s : first_skipped) out += fmt::format("\n  {}", s.reason);
        if (static_cast<std::size_t>(skipped) > first_skipped.size()) {
            out += fmt::format("\n  ... and {} more skipped",
                               static_cast<std::size_t>(skipped) - first_skipped.size());
        }
    }
    for (const std::string& n : notes) out += fmt::format("\nnote: {}", n);
    return out;
}

std::vector<AltitudeKind> FlightLog::AltitudeKinds() const {
    std::vector<AltitudeKind> kinds;
    for (AltitudeKind k : {AltitudeKind::kPressure, AltitudeKind::kMsl, AltitudeKind::kEllipsoid}) {
        if (std::any_of(samples.begin(), samples.end(),
                        [k](const FlightSample& s) { return s.Altitude(k).has_value(); })) {
            kinds.push_back(k);
        }
    }
    return kinds;
}

bool FlightLog::HasAttitude() const {
    return !samples.empty() && std::all_of(samples.begin(), samples.end(),
                                           [](const auto& s) { return s.attitude.has_value(); });
}

namespace detail {

std::string Where(std::string_view source, int line) {
    return fmt::format("{}:{}: ", source, line);
}

std::string_view Trim(std::string_view text) {
    while (!text.empty() && std::isspace(static_cast<unsigned char>(text.front()))) {
        text.remove_prefix(1);
    }
    while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back()))) {
        text.remove_suffix(1);
    }
    return text;
}

std::optional<double> ParseDouble(std::string_view text) {
    text = Trim(text);
    if (text.empty()) return std::nullopt;
    if (text.front() == '+') text.remove_prefix(1);
    double value = 0.0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(value)) {
        throw std::invalid_argument(fmt::format("'{}' is not a number", text));
    }
    return value;
}

double UnixSecondsFromIso8601(std::string_view text) {
    const geo::CivilTime t = geo::ParseIso8601(Trim(text));
    geo::ValidateCivilTime(t);
    // ParseIso8601 folds a "+02:00" offset into the fields, so t is UTC.
    return geo::UnixSecondsFromCivil(t);
}

std::string FormatClock(double time_s) {
    const geo::CivilTime t = geo::CivilFromUnixSeconds(time_s);
    return fmt::format("{:02}:{:02}:{:06.3f}", t.hour, t.minute, t.second);
}

LogBuilder::LogBuilder(std::string source, LogFormat format) {
    log_.source = std::move(source);
    log_.format = format;
}

void LogBuilder::Add(FlightSample sample) { log_.samples.push_back(std::move(sample)); }

void LogBuilder::Skip(int line, std::string reason) {
    ++log_.summary.skipped;
    if (log_.summary.first_skipped.size() < ReadSummary::kMaxListed) {
        log_.summary.first_skipped.push_back({line, Where(log_.source, line) + reason});
    }
}

void LogBuilder::Note(std::string note) {
    if (log_.summary.notes.size() < kMaxNotes) {
        log_.summary.notes.push_back(std::move(note));
    } else {
        ++notes_suppressed_;
    }
}

FlightLog LogBuilder::Finish() {
    std::vector<FlightSample>& in = log_.samples;
    // Time order: a sample whose time does not increase is dropped. When one sample jumps ahead
    // and the next comes back in order, the jump is the bad one, not everything after it.
    std::vector<FlightSample> kept;
    kept.reserve(in.size());
    for (std::size_t i = 0; i < in.size(); ++i) {
        const FlightSample& s = in[i];
        if (!kept.empty() && !(s.time_s > kept.back().time_s)) {
            Skip(s.line, s.time_s == kept.back().time_s
                             ? fmt::format("duplicate time {} (also at line {})",
                                           FormatClock(s.time_s), kept.back().line)
                             : fmt::format("time goes backwards: {} after {} at line {}",
                                           FormatClock(s.time_s), FormatClock(kept.back().time_s),
                                           kept.back().line));
            continue;
        }
        if (i + 1 < in.size() && !(in[i + 1].time_s > s.time_s) &&
            (kept.empty() || in[i + 1].time_s > kept.back().time_s) &&
            (i + 2 >= in.size() || in[i + 2].time_s > in[i + 1].time_s)) {
            Skip(s.line,
                 fmt::format("time jumps ahead to {} and the next record (line {}) "
                             "comes back to {}",
                             FormatClock(s.time_s), in[i + 1].line, FormatClock(in[i + 1].time_s)));
            continue;
        }
        kept.push_back(s);
    }
    in = std::move(kept);
    std::sort(log_.summary.first_skipped.begin(), log_.summary.first_skipped.end(),
              [](const SkippedRecord& a, const SkippedRecord& b) { return a.line < b.line; });
    log_.summary.used = static_cast<int>(in.size());
    if (in.empty()) {
        throw FlightLogError(fmt::format("{}: no usable {} record ({} records, {} skipped){}",
                                         log_.source, LogFormatName(log_.format),
                                         log_.summary.records, log_.summary.skipped,
                                         log_.summary.first_skipped.empty()
                                             ? std::string()
                                             : "; first: " + log_.summary.first_skipped[0].reason));
    }

    // Gaps, relative to the usual interval of this log.
    std::vector<double> intervals;
    for (std::size_t i = 1; i < in.size(); ++i)
        intervals.push_back(in[i].time_s - in[i - 1].time_s);
    if (!intervals.empty()) {
        std::vector<double> sorted = intervals;
        std::nth_element(sorted.begin(), sorted.begin() + static_cast<long>(sorted.size() / 2),
                         sorted.end());
        const double median = sorted[sorted.size() / 2];
        const double gap_limit = std::max(kMinGapNoteS, kGapNoteFactor * median);
        for (std::size_t i = 1; i < in.size(); ++i) {
            if (intervals[i - 1] > gap_limit) {
                Note(fmt::format("{}gap of {:.0f} s (lines {}-{}, usual interval {:.3g} s)",
                                 Where(log_.source, in[i].line), intervals[i - 1], in[i - 1].line,
                                 in[i].line, median));
            }
        }
    }
    bool pole_noted = false;
    int crossings = 0;
    for (std::size_t i = 0; i < in.size(); ++i) {
        if (!pole_noted && std::abs(in[i].lat_deg) >= kPoleNoteLatDeg) {
            pole_noted = true;
            Note(
                fmt::format("{}fix at the pole (lat {:.4f} deg): longitude and heading are "
                            "undefined there; positions are interpolated in ECEF",
                            Where(log_.source, in[i].line), in[i].lat_deg));
        }
        if (i > 0 && std::abs(in[i].lon_deg - in[i - 1].lon_deg) > 180.0) {
            if (++crossings == 1) {
                Note(
                    fmt::format("{}track crosses the 180 deg meridian (lon {:.4f} -> {:.4f}); "
                                "positions are interpolated in ECEF",
                                Where(log_.source, in[i].line), in[i - 1].lon_deg, in[i].lon_deg));
            }
        }
    }
    if (notes_suppressed_ > 0) {
        log_.summary.notes.push_back(fmt::format("... and {} more notes", notes_suppressed_));
    }
    return std::move(log_);
}

}  // namespace detail

FlightLog ParseFlightLog(std::string_view text, LogFormat format, std::string source) {
    switch (format) {
        case LogFormat::kIgc:
            return ParseIgc(text, std::move(source));
        case LogFormat::kGpx:
            return ParseGpx(text, std::move(source));
        case LogFormat::kKml:
            return ParseKml(text, std::move(source));
        case LogFormat::kCsv:
            return ParseCsv(text, std::move(source));
    }
    throw FlightLogError(source + ": unknown log format");
}

FlightLog ReadFlightLog(const std::filesystem::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    LogFormat format;
    if (ext == ".igc") {
        format = LogFormat::kIgc;
    } else if (ext == ".gpx") {
        format = LogFormat::kGpx;
    } else if (ext == ".kml") {
        format = LogFormat::kKml;
    } else if (ext == ".csv") {
        format = LogFormat::kCsv;
    } else {
        throw FlightLogError(
            fmt::format("{}: unknown flight-log extension '{}' (expected .igc, "
                        ".gpx, .kml or .csv)",
                        path.string(), ext));
    }
    std::ifstream in(path, std::ios::binary);
    if (!in) throw FlightLogError(fmt::format("{}: cannot open flight log", path.string()));
    std::ostringstream buffer;
    buffer << in.rdbuf();
    if (in.bad()) throw FlightLogError(fmt::format("{}: read error", path.string()));
    return ParseFlightLog(buffer.str(), format, path.string());
}

}  // namespace zenith::track
