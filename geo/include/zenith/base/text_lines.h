// Lines of text as the bounded readers (flight logs, METAR files) see them: any line ending, no
// surrounding blanks, and one line of comma-separated values (RFC 4180 quoting: a field in
// double quotes may hold commas, and "" inside it is one quote).
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace zenith {

// The next line of text, which it removes from `text`: lines end in "\n", "\r\n" or a lone "\r"
// (old Mac files), none of which is part of the line.
std::string_view NextLine(std::string_view& text);

// `text` without leading and trailing white space.
std::string_view Trim(std::string_view text);

// The next line that is neither blank nor a '#' comment, removed from `text` with the lines
// skipped before it, as `line` and `trimmed` (Trim(line)); `line_number` counts every line
// read, so it is the 1-based number of the one returned. False at the end of `text`.
template <typename LineNumber>
bool NextContentLine(std::string_view& text, LineNumber& line_number, std::string_view& line,
                     std::string_view& trimmed) {
    while (!text.empty()) {
        line = NextLine(text);
        ++line_number;
        trimmed = Trim(line);
        if (!trimmed.empty() && trimmed.front() != '#') return true;
    }
    return false;
}

// Replaces `fields` with the line's fields; false when a quoted field is not closed.
bool SplitCsvLine(std::string_view line, std::vector<std::string>& fields);

}  // namespace zenith
