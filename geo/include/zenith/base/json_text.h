// Checks on JSON text before a parser sees it, so that input cannot choose how deep a recursive
// walk goes (a stack overflow) whatever the parser or the code after it does.
#pragma once

#include <cstddef>
#include <optional>
#include <string_view>

namespace zenith {

// The byte offset of the first '[' or '{' that opens level max_depth + 1, outside strings;
// nullopt if the text never nests deeper than max_depth. Linear, no allocation; malformed text
// is scanned all the same (the parser reports it).
std::optional<std::size_t> FindJsonNestingBeyond(std::string_view text, int max_depth);

}  // namespace zenith
