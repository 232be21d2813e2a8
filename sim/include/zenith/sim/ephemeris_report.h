// The `zenith ephemeris` command's work, as a library so it is testable and reusable: one
// instant to a table or JSON, and the JSON-lines batch mode.
#pragma once

#include <iosfwd>
#include <nlohmann/json_fwd.hpp>
#include <string>

#include "zenith/geo/ephemeris.h"

namespace zenith::sim {

// The batch record: the keys documented in the README (degrees, km), elevations geometric.
nlohmann::json EphemerisRecord(const geo::SkyEphemeris& e);

// Human-readable table with the `max_stars` brightest stars above the horizon.
std::string EphemerisTable(const geo::SkyEphemeris& e, const geo::Observer& observer,
                           std::size_t max_stars);

struct BatchSummary {
    std::size_t lines = 0;
    std::size_t failed = 0;
    std::string first_error;  // "line N: message" of the first failure, empty if none
};

// Reads JSON objects one per line (keys utc, lat_deg, lon_deg, height_m; optional dut1_s,
// delta_t_s; other keys ignored) and writes one record per line in the same order. A line that
// cannot be computed yields {"line": N, "error": "..."} in its place; the rest go on.
BatchSummary RunEphemerisBatch(std::istream& in, std::ostream& out);

}  // namespace zenith::sim
