// Shared by the flight-log readers (flight_log_*.cpp); not installed.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "zenith/track/flight_log.h"

namespace zenith::track::detail {

// Collects samples, skipped records and notes while a reader runs, then checks the time order
// and geometry of the whole track (Finish) the same way for every format.
class LogBuilder {
  public:
    LogBuilder(std::string source, LogFormat format);

    void Add(FlightSample sample);
    void Skip(int line, std::string reason);
    void Note(std::string note);
    void CountRecord() { ++log_.summary.records; }
    void SetDescription(std::string description) { log_.description = std::move(description); }
    const std::string& source() const { return log_.source; }

    // Drops samples whose time does not increase, notes gaps, pole fixes and antimeridian
    // crossings, and throws FlightLogError when nothing usable is left.
    FlightLog Finish();

  private:
    FlightLog log_;
    std::size_t notes_suppressed_ = 0;
};

// Prefix for messages about a line: "flight.igc:12: ".
std::string Where(std::string_view source, int line);

// Strict numeric parsing of a whole field (no trailing junk, finite). Empty -> nullopt.
std::optional<double> ParseDouble(std::string_view text);

// ISO 8601 UTC text -> POSIX seconds; throws geo::TimeError on a bad string.
double UnixSecondsFromIso8601(std::string_view text);

// "hh:mm:ss" of a POSIX time, for messages.
std::string FormatClock(double time_s);

std::string_view Trim(std::string_view text);

}  // namespace zenith::track::detail
