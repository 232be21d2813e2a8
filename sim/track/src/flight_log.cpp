// Flight logs: what every reader shares (summary, time-order checks, format dispatch).
#include "zenith/track/flight_log.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <glm/glm.hpp>
#include <limits>

#include "flight_log_internal.h"
#include "zenith/base/error.h"
#include "zenith/base/units.h"

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

std::optional<double> ParseDouble(std::string_view text) {
    text = Trim(text);
    if (text.empty()) return std::nullopt;
    std::string_view digits = text;
    if (digits.front() == '+') digits.remove_prefix(1);
    double value = 0.0;
    const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
    if (ec != std::errc() || end != digits.data() + digits.size() || !std::isfinite(value)) {
        constexpr std::size_t kShown = 40;  // a fuzzed field can be megabytes long
        throw ArgumentError(fmt::format("'{}{}' is not a finite number", text.substr(0, kShown),
                                        text.size() > kShown ? "..." : ""));
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

namespace {

std::string FormatDateTime(double time_s) {
    const geo::CivilTime t = geo::CivilFromUnixSeconds(time_s);
    return fmt::format("{:04}-{:02}-{:02} {:02}:{:02}:{:02.0f}", t.year, t.month, t.day, t.hour,
                       t.minute, std::floor(t.second));
}

std::string FormatDuration(double seconds) {
    if (seconds >= 2.0 * 86400.0) return fmt::format("{:.0f} days", seconds / 86400.0);
    if (seconds >= 2.0 * 3600.0) return fmt::format("{:.1f} h", seconds / 3600.0);
    return fmt::format("{:.0f} s", seconds);
}

// The fix's altitude for distances: any kind it has (they differ by at most a few hundred
// metres, nothing next to kMaxSpeed), else 0.
double AnyAltitude(const FlightSample& s) {
    if (s.ellipsoid_height) return *s.ellipsoid_height;
    if (s.msl_altitude) return *s.msl_altitude;
    if (s.pressure_altitude) return *s.pressure_altitude;
    return 0.0;
}

// Straight-line distance between two fixes (m) on a sphere of the Earth's mean radius: within
// 0.5 % of the ellipsoid's, ample to tell a jet from a teleport.
double Distance(const FlightSample& a, const FlightSample& b) {
    constexpr double kMeanRadius = 6371008.8;  // m, IUGG
    const auto point = [](const FlightSample& s) {
        const double r = kMeanRadius + AnyAltitude(s);
        const double lat = Radians(s.lat_deg), lon = Radians(s.lon_deg);
        return r * glm::dvec3(std::cos(lat) * std::cos(lon), std::cos(lat) * std::sin(lon),
                              std::sin(lat));
    };
    return glm::length(point(a) - point(b));
}

double Speed(const FlightSample& a, const FlightSample& b) {
    const double dt = std::abs(b.time_s - a.time_s);
    return dt > 0.0 ? Distance(a, b) / dt : std::numeric_limits<double>::infinity();
}

std::string JumpText(const FlightSample& from, const FlightSample& to) {
    return fmt::format(
        "position jumps {:.1f} km in {:.3g} s from line {} ({:.3g} km/s; no "
        "aircraft flies faster than {:.0f} km/s)",
        Distance(from, to) / 1000.0, to.time_s - from.time_s, from.line, Speed(from, to) / 1000.0,
        kMaxSpeed / 1000.0);
}

}  // namespace

LogBuilder::LogBuilder(std::string source, LogFormat format, const ReadOptions& options)
    : max_samples_(options.max_samples) {
    log_.source = std::move(source);
    log_.format = format;
    if (!(max_samples_ >= 2)) {
        throw ArgumentError(
            fmt::format("max_samples = {} is out of range (expected >= 2)", max_samples_));
    }
}

void LogBuilder::Add(FlightSample s) {
    if (!(s.time_s >= kMinLogTime && s.time_s < kMaxLogTime)) {
        Skip(s.line, fmt::format("time {} s since 1970 is out of range (expected 1900-01-01 to "
                                 "2200-01-01)",
                                 s.time_s));
        return;
    }
    if (!(std::abs(s.lat_deg) <= 90.0) || !(std::abs(s.lon_deg) <= 180.0)) {
        Skip(s.line, fmt::format("position out of range: lat {}, lon {} deg (expected [-90, 90], "
                                 "[-180, 180])",
                                 s.lat_deg, s.lon_deg));
        return;
    }
    for (const AltitudeKind kind :
         {AltitudeKind::kPressure, AltitudeKind::kMsl, AltitudeKind::kEllipsoid}) {
        const std::optional<double> altitude = s.Altitude(kind);
        if (altitude && !(*altitude >= kMinLogAltitude && *altitude <= kMaxLogAltitude)) {
            Skip(s.line,
                 fmt::format("{} {} m is out of range (expected [{}, {}] m)",
                             AltitudeKindName(kind), *altitude, kMinLogAltitude, kMaxLogAltitude));
            return;
        }
    }
    if (s.lon_deg >= 180.0) s.lon_deg -= 360.0;
    if (offered_++ % thinning_ != 0) return;
    std::vector<FlightSample>& samples = log_.samples;
    samples.push_back(std::move(s));
    if (samples.size() > max_samples_) {
        // Keep the samples at even positions: offered indices that are multiples of 2 thinning_.
        std::size_t kept = 0;
        for (std::size_t i = 0; i < samples.size(); i += 2) samples[kept++] = std::move(samples[i]);
        samples.resize(kept);
        thinning_ *= 2;
    }
}

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

// A run of at most kIsolatedRun fixes, more than kIsolatedFixGap away from every other fix, is
// dropped while a longer run exists: a receiver's default date before its first fix, a clock
// that jumped. Separate flights on different days (longer runs) stay, as gaps.
void LogBuilder::DropIsolatedFixes() {
    constexpr std::size_t kIsolatedRun = 3;
    std::vector<FlightSample>& in = log_.samples;
    std::vector<std::pair<std::size_t, std::size_t>> runs;  // [begin, end)
    for (std::size_t i = 0; i < in.size(); ++i) {
        if (i == 0 || in[i].time_s - in[i - 1].time_s > kIsolatedFixGap) {
            runs.emplace_back(i, i + 1);
        } else {
            runs.back().second = i + 1;
        }
    }
    std::size_t longest = 0;
    for (const auto& [b, e] : runs) longest = std::max(longest, e - b);
    if (runs.size() < 2 || longest <= kIsolatedRun) return;
    std::vector<FlightSample> kept;
    kept.reserve(in.size());
    for (std::size_t r = 0; r < runs.size(); ++r) {
        const auto [b, e] = runs[r];
        if (e - b > kIsolatedRun) {
            for (std::size_t i = b; i < e; ++i) kept.push_back(std::move(in[i]));
            continue;
        }
        // The nearest fix of a neighbouring run, to say how far away the rest is.
        const FlightSample& other = r + 1 < runs.size() ? in[runs[r + 1].first] : in[b - 1];
        for (std::size_t i = b; i < e; ++i) {
            Skip(in[i].line,
                 fmt::format("fix at {} is isolated: {} from the rest of the log (line {}, {}); "
                             "a receiver's cold-start date or a clock jump?",
                             FormatDateTime(in[i].time_s),
                             FormatDuration(std::abs(other.time_s - in[i].time_s)), other.line,
                             FormatDateTime(other.time_s)));
        }
    }
    in = std::move(kept);
}

// A fix reached faster than kMaxSpeed from the previous one: when the track comes back at the
// next fix it is a spike and is dropped; when the first fix is the odd one out it is dropped;
// otherwise the jump is real data of another place (spoofing, a spliced log) and the track is
// not interpolated across it.
void LogBuilder::CheckSpeeds() {
    std::vector<FlightSample>& in = log_.samples;
    std::vector<FlightSample> kept;
    kept.reserve(in.size());
    for (std::size_t i = 0; i < in.size(); ++i) {
        FlightSample& s = in[i];
        if (kept.empty() || Speed(kept.back(), s) <= kMaxSpeed) {
            kept.push_back(std::move(s));
            continue;
        }
        const FlightSample* next = i + 1 < in.size() ? &in[i + 1] : nullptr;
        if (next && Speed(kept.back(), *next) <= kMaxSpeed) {
            Skip(s.line, JumpText(kept.back(), s) + " and comes back at the next fix: dropped");
            continue;
        }
        if (kept.size() == 1 && next && Speed(s, *next) <= kMaxSpeed) {
            Skip(kept.back().line, fmt::format("first fix is {:.1f} km from the rest of the track "
                                               "(line {}): dropped",
                                               Distance(kept.back(), s) / 1000.0, s.line));
            kept.back() = std::move(s);
            continue;
        }
        Note(Where(log_.source, s.line) + JumpText(kept.back(), s) +
             ": the track is not interpolated across it (GNSS spoofing or a spliced log?)");
        s.discontinuity = true;
        kept.push_back(std::move(s));
    }
    in = std::move(kept);
}

FlightLog LogBuilder::Finish() {
    std::vector<FlightSample>& in = log_.samples;
    // Time order: a sample whose time does not increase is dropped (of equal times, the first
    // stays). When one sample jumps ahead and the next comes back in order, the jump is the bad
    // one, not everything after it.
    std::vector<FlightSample> kept;
    kept.reserve(in.size());
    for (std::size_t i = 0; i < in.size(); ++i) {
        const FlightSample& s = in[i];
        if (!kept.empty() && !(s.time_s > kept.back().time_s)) {
            Skip(s.line, s.time_s == kept.back().time_s
                             ? fmt::format("duplicate time {} (also at line {}; the first is kept)",
                                           FormatClock(s.time_s), kept.back().line)
                             : fmt::format("time goes backwards: {} after {} at line {}",
                                           FormatClock(s.time_s), FormatClock(kept.back().time_s),
                                           kept.back().line));
            continue;
        }
        if (i + 1 < in.size() && in[i + 1].time_s < s.time_s &&
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
    if (!in.empty()) {
        DropIsolatedFixes();
        CheckSpeeds();
    }
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
    if (in.back().time_s - in.front().time_s > kMaxLogSpan) {
        throw FlightLogError(fmt::format(
            "{}: the log spans {} (line {} at {} to line {} at {}); at most {} are replayed",
            log_.source, FormatDuration(in.back().time_s - in.front().time_s), in.front().line,
            FormatDateTime(in.front().time_s), in.back().line, FormatDateTime(in.back().time_s),
            FormatDuration(kMaxLogSpan)));
    }
    if (thinning_ > 1) {
        Note(fmt::format("{} valid fixes: 1 in {} kept, evenly (at most {} are read)", offered_,
                         thinning_, max_samples_));
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
                Note(fmt::format("{}gap of {} (lines {}-{}, usual interval {:.3g} s)",
                                 Where(log_.source, in[i].line), FormatDuration(intervals[i - 1]),
                                 in[i - 1].line, in[i].line, median));
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

FlightLog ParseFlightLog(std::string_view text, LogFormat format, std::string source,
                         const ReadOptions& options) {
    switch (format) {
        case LogFormat::kIgc:
            return ParseIgc(text, std::move(source), options);
        case LogFormat::kGpx:
            return ParseGpx(text, std::move(source), options);
        case LogFormat::kKml:
            return ParseKml(text, std::move(source), options);
        case LogFormat::kCsv:
            return ParseCsv(text, std::move(source), options);
    }
    throw FlightLogError(source + ": unknown log format");
}

namespace {

// A file mapped read-only: the readers see all of it as one string_view, and the kernel pages
// it in and out, so a log of any size costs no heap of its own.
class MappedFile {
  public:
    explicit MappedFile(const std::filesystem::path& path) {
        const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
        if (fd < 0) {
            throw FlightLogError(
                fmt::format("{}: cannot open flight log: {}", path.string(), std::strerror(errno)));
        }
        struct stat info {};
        if (::fstat(fd, &info) != 0 || !S_ISREG(info.st_mode)) {
            ::close(fd);
            throw FlightLogError(fmt::format("{}: not a regular file", path.string()));
        }
        size_ = static_cast<std::size_t>(info.st_size);
        if (size_ > 0) {
            void* data = ::mmap(nullptr, size_, PROT_READ, MAP_PRIVATE, fd, 0);
            if (data == MAP_FAILED) {
                const int error = errno;
                ::close(fd);
                throw FlightLogError(fmt::format("{}: cannot map {} bytes: {}", path.string(),
                                                 size_, std::strerror(error)));
            }
            data_ = static_cast<const char*>(data);
            ::madvise(data, size_, MADV_SEQUENTIAL);
        }
        ::close(fd);  // the mapping stays valid
    }
    ~MappedFile() {
        if (data_ != nullptr) ::munmap(const_cast<char*>(data_), size_);
    }
    MappedFile(const MappedFile&) = delete;
    MappedFile& operator=(const MappedFile&) = delete;
    std::string_view text() const { return {data_, size_}; }

  private:
    const char* data_ = nullptr;
    std::size_t size_ = 0;
};

}  // namespace

FlightLog ReadFlightLog(const std::filesystem::path& path, const ReadOptions& options) {
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
    const MappedFile file(path);
    // tinyxml2 builds a whole document in memory, several times the file's size.
    if ((format == LogFormat::kGpx || format == LogFormat::kKml) &&
        file.text().size() > kMaxXmlBytes) {
        throw FlightLogError(
            fmt::format("{}: {} MB of XML (at most {} MB are read; split the "
                        "track or convert it to CSV)",
                        path.string(), file.text().size() >> 20, kMaxXmlBytes >> 20));
    }
    return ParseFlightLog(file.text(), format, path.string(), options);
}

}  // namespace zenith::track
