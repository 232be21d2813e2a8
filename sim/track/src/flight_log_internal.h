// Shared by the flight-log readers (flight_log_*.cpp); not installed.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "zenith/base/text_lines.h"
#include "zenith/track/flight_log.h"

namespace zenith::track::detail {

// Collects samples, skipped records and notes while a reader runs, then checks the time order
// and geometry of the whole track (Finish) the same way for every format.
class LogBuilder {
  public:
    LogBuilder(std::string source, LogFormat format, const ReadOptions& options);

    // Checks the sample against the sane ranges (time, position, altitudes; see flight_log.h)
    // and keeps it or skips it with the reason. Longitudes are wrapped to [-180, 180). Past
    // options.max_samples kept samples, every other one is dropped and only every other one is kept
    // from then on (and so on), so the log is thinned evenly and memory stays bounded.
    void Add(FlightSample sample);
    void Skip(int line, std::string reason);
    void Note(std::string note);
    void CountRecord() { ++log_.summary.records; }
    void SetDescription(std::string description) { log_.description = std::move(description); }
    const std::string& source() const { return log_.source; }
    // The samples kept so far, for a reader's fix-ups that need the whole log.
    std::vector<FlightSample>& samples() { return log_.samples; }

    // Drops samples whose time does not increase, fixes isolated in time and positions that
    // jump impossibly fast; notes gaps, pole fixes and antimeridian crossings; throws
    // FlightLogError when nothing usable is left or the log spans more than kMaxLogSpan.
    FlightLog Finish();

  private:
    void DropIsolatedFixes();
    void CheckSpeeds();

    FlightLog log_;
    std::size_t notes_suppressed_ = 0;
    std::size_t max_samples_;
    std::size_t thinning_ = 1;  // keep one offered sample in thinning_
    std::size_t offered_ = 0;   // valid samples offered since thinning last changed
};

// Prefix for messages about a line: "flight.igc:12: ".
std::string Where(std::string_view source, int line);

// Strict numeric parsing of a whole field (no trailing junk, finite). Empty -> nullopt; throws
// zenith::ArgumentError naming the text otherwise.
std::optional<double> ParseDouble(std::string_view text);

// ISO 8601 UTC text -> POSIX seconds; throws geo::TimeError on a bad string.
double UnixSecondsFromIso8601(std::string_view text);

// "hh:mm:ss" of a POSIX time, for messages.
std::string FormatClock(double time_s);

}  // namespace zenith::track::detail
