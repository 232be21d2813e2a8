// Flight-log readers for replay: IGC, GPX 1.1 tracks, KML gx:Track and a documented CSV
// (data/flights/README.md), into one list of time-ordered samples.
//
// Readers are forgiving and explicit: a record that cannot be used is skipped with a reason that
// names the source and line number; whatever can be used is used; the summary counts what was
// skipped and keeps the first few reasons. A log with no usable sample at all, or an IGC log with
// no date, throws FlightLogError.
//
// Altitudes are kept apart by what they measure: a sample holds each kind the log gives (an IGC B
// record has both a pressure and a GNSS altitude) and never converts one into another; Trajectory
// (trajectory.h) chooses one kind and converts it to WGS84 ellipsoidal height for rendering.
//
// Times are UTC seconds since 1970-01-01T00:00:00Z on the POSIX scale (every day 86400 s, so a
// leap second has no number of its own, as in every log format read here).
//
// What a log may cost is bounded, whatever it holds (the limits below): a record outside the
// sane ranges of time, position and altitude is skipped with its line; a fix isolated from the
// rest by more than a day (a receiver's cold-start date) is skipped; a position that jumps
// faster than any aircraft flies and comes back is skipped, one that jumps and stays breaks the
// track there; a log longer than kMaxLogSpan is refused; more than kMaxSamples fixes are thinned
// evenly (1 in 2, 1 in 4, ...) while reading, so memory stays bounded for any file size. Line
// formats (IGC, CSV) are read through a memory map, line by line; XML (GPX, KML) is parsed whole
// and refused above kMaxXmlBytes.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "zenith/base/error.h"
#include "zenith/geo/frames.h"
#include "zenith/geo/time.h"

namespace zenith::track {

// Thrown when a log cannot be read at all (unreadable file, unknown format, no usable sample,
// IGC without HFDTE date, CSV without the needed columns). The message names the source and,
// where there is one, the line.
class FlightLogError : public InputError {
  public:
    using InputError::InputError;
};

// Sane limits of a flight log (see the file comment).
inline constexpr double kMinLogTime = -2208988800.0;    // 1900-01-01T00:00:00Z, POSIX s
inline constexpr double kMaxLogTime = 7258118400.0;     // 2200-01-01T00:00:00Z
inline constexpr double kMinLogAltitude = -1000.0;      // m, below the Dead Sea shore
inline constexpr double kMaxLogAltitude = 200000.0;     // m, twice the Karman line
inline constexpr double kIsolatedFixGap = 86400.0;      // s
inline constexpr double kMaxLogSpan = 400.0 * 86400.0;  // s: long-duration balloons fly months
inline constexpr double kMaxSpeed = 2000.0;             // m/s, Mach 6 at altitude
inline constexpr std::size_t kMaxSamples = 4'000'000;
inline constexpr std::uintmax_t kMaxXmlBytes = 256ull << 20;
inline constexpr std::size_t kMaxLineBytes = 1u << 16;  // longer lines are skipped

enum class LogFormat { kIgc, kGpx, kKml, kCsv };
std::string_view LogFormatName(LogFormat format);

// What an altitude measures.
enum class AltitudeKind {
    kPressure,   // pressure altitude: ISA height for the static pressure, 1013.25 hPa datum
    kMsl,        // GNSS/geometric height above mean sea level (the geoid, EGM96-like)
    kEllipsoid,  // GNSS height above the WGS84 ellipsoid
};
std::string_view AltitudeKindName(AltitudeKind kind);

struct FlightSample {
    double time_s = 0.0;  // UTC, POSIX seconds
    double lat_deg = 0.0;
    double lon_deg = 0.0;  // [-180, 180)
    // Each altitude the log gives for this fix, metres; absent when the log has none or it was
    // flagged invalid (an IGC 'V' fix has no GNSS altitude).
    std::optional<double> pressure_altitude;
    std::optional<double> msl_altitude;
    std::optional<double> ellipsoid_height;
    std::optional<geo::Attitude> attitude;  // only when the log records it
    int line = 0;                           // 1-based source line of the record
    // The position jumps here from the previous sample faster than kMaxSpeed and stays: the
    // track is not interpolated across (GNSS spoofing, a spliced log).
    bool discontinuity = false;

    std::optional<double> Altitude(AltitudeKind kind) const;
};

struct SkippedRecord {
    int line = 0;
    std::string reason;
};

// What a reader made of a log. Notes are things worth knowing that skipped nothing (gaps, a
// crossing of the antimeridian, a fix at a pole, GNSS altitudes dropped from 'V' fixes).
struct ReadSummary {
    static constexpr std::size_t kMaxListed = 8;

    int records = 0;  // data records seen (B records, trkpt, when/coord pairs, CSV rows)
    int used = 0;     // samples kept
    int skipped = 0;  // records dropped
    // Up to kMaxListed reasons, sorted by line: the reader's own first, then time-order drops.
    std::vector<SkippedRecord> first_skipped;
    std::vector<std::string> notes;

    // One line per fact: "used 1790 of 1800 records; skipped 10: line 12: ...".
    std::string ToString() const;
};

struct FlightLog {
    std::string source;  // file name or caller-given name, used in messages
    LogFormat format = LogFormat::kCsv;
    std::vector<FlightSample> samples;  // strictly increasing time
    ReadSummary summary;
    std::string description;  // e.g. IGC pilot/glider, GPX/KML track name; may be empty

    // Kinds that at least one sample has, in the enum's order.
    std::vector<AltitudeKind> AltitudeKinds() const;
    bool HasAttitude() const;  // every sample has one
};

struct ReadOptions {
    // Logs of several aircraft (a CSV with an icao24 or callsign column: OpenSky state
    // vectors): the one to read, case-insensitive. Without a choice such a log is refused with
    // a list of the aircraft in it.
    std::optional<std::string> icao24;
    std::optional<std::string> callsign;
    // Fixes kept at most; more are thinned evenly (1 in 2, 1 in 4, ...). >= 2.
    std::size_t max_samples = kMaxSamples;
};

// Reads a file, choosing the reader by extension (.igc .gpx .kml .csv, any case).
FlightLog ReadFlightLog(const std::filesystem::path& path, const ReadOptions& options = {});
// Readers over text already in memory; source names it in messages.
FlightLog ParseIgc(std::string_view text, std::string source = "<igc>",
                   const ReadOptions& options = {});
FlightLog ParseGpx(std::string_view text, std::string source = "<gpx>",
                   const ReadOptions& options = {});
FlightLog ParseKml(std::string_view text, std::string source = "<kml>",
                   const ReadOptions& options = {});
FlightLog ParseCsv(std::string_view text, std::string source = "<csv>",
                   const ReadOptions& options = {});
FlightLog ParseFlightLog(std::string_view text, LogFormat format, std::string source,
                         const ReadOptions& options = {});

}  // namespace zenith::track
