// Files of METAR reports: one report per line, or the CSV that airport weather archives export
// (Iowa Environmental Mesonet, "ASOS/AWOS download": station,valid,lon,lat,metar).
//
// Readers are forgiving and explicit, like the flight-log readers (zenith/track/flight_log.h): a
// line that cannot be used (no station, too long, wrong number of CSV fields, bad valid time) is
// skipped and the first reasons are kept, each naming file:line; decode warnings stay with their
// record (MetarRecord::metar.warnings). A file that cannot be read at all throws MetarError naming
// the file (and the line where there is one): unreadable, larger than kMaxMetarFileBytes, more
// than kMaxMetarRecords reports, a CSV without a metar column, or no usable report.
//
// Lines end in "\n", "\r\n" or "\r"; blank lines and lines starting with '#' are skipped; a line
// is at most kMaxMetarLineBytes long (longer ones are skipped). In a lines file, a line
// "YYYY/MM/DD hh:mm" (NOAA's per-station files) gives the UTC time of the report on the next
// line.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "zenith/weather/metar.h"

namespace zenith::weather {

inline constexpr std::size_t kMaxMetarLineBytes = 1u << 16;
inline constexpr std::uintmax_t kMaxMetarFileBytes = 256ull << 20;
inline constexpr std::size_t kMaxMetarRecords = 2'000'000;  // 60 years of half-hourly reports
inline constexpr std::size_t kMaxListedSkips = 10;

struct MetarRecord {
    Metar metar;
    std::size_t line = 0;  // 1-based
    // From the CSV: the valid time (UTC, POSIX seconds), the station's position and its name in
    // the archive (IEM: "DSM" for KDSM). Lines files have only the time, and only after a NOAA
    // time line.
    std::optional<double> time_s;
    std::optional<double> lat_deg;
    std::optional<double> lon_deg;
    std::string archive_station;
};

struct MetarFile {
    std::string source;  // the path, or the name given to Parse*
    std::vector<MetarRecord> records;
    std::size_t skipped = 0;
    std::vector<std::string> first_skipped;  // "file:line: reason", at most kMaxListedSkips
    std::size_t warnings = 0;                // decode warnings over all records
    std::string Summary() const;             // "12 reports, 1 skipped, 3 warnings; first: ..."
};

MetarFile ReadMetarLines(const std::filesystem::path& path);
MetarFile ParseMetarLines(std::string_view text, std::string source);

// Header row required; columns are found by name (case-insensitive, any order): metar (the
// report, required), valid ("YYYY-MM-DD HH:MM" UTC, or ISO 8601), station, lat, lon (degrees;
// "M" or empty: missing). Other columns are ignored. Fields may be quoted ("" for a quote).
MetarFile ReadMetarCsv(const std::filesystem::path& path);
MetarFile ParseMetarCsv(std::string_view text, std::string source);

}  // namespace zenith::weather
