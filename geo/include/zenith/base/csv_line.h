// One line of comma-separated values (RFC 4180 quoting: a field in double quotes may hold commas,
// and "" inside it is one quote). Shared by the flight-log and METAR-archive readers, which find
// their lines themselves (bounded, any line ending).
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace zenith {

// Replaces `fields` with the line's fields; false when a quoted field is not closed.
bool SplitCsvLine(std::string_view line, std::vector<std::string>& fields);

}  // namespace zenith
