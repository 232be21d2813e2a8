#include "zenith/base/error.h"

#include <fmt/format.h>

#include <cmath>

namespace zenith {

bool Range::Contains(double value) const {
    const bool above = lo_open ? value > lo : value >= lo;
    const bool below = hi_open ? value < hi : value <= hi;
    return above && below;  // false for NaN
}

std::string Range::ToString() const {
    return fmt::format("{}{}, {}{}", lo_open ? '(' : '[', FormatValue(lo), FormatValue(hi),
                       hi_open ? ')' : ']');
}

std::string FormatValue(double value) { return fmt::format("{}", value); }

std::string RangeMessage(std::string_view field, double value, std::string_view unit,
                         const Range& range) {
    const std::string_view space = unit.empty() ? "" : " ";
    return fmt::format("{} = {}{}{} is out of range (expected {}{}{})", field, FormatValue(value),
                       space, unit, range.ToString(), space, unit);
}

std::string AtLocation(const std::filesystem::path& file, std::optional<std::size_t> line,
                       std::string_view message) {
    if (line) return fmt::format("{}:{}: {}", file.string(), *line, message);
    return fmt::format("{}: {}", file.string(), message);
}

}  // namespace zenith
