// One error family for the whole library: every exception zenith throws derives from
// zenith::Error, so a host can catch one type. Messages name the field (a library never names a
// CLI flag: the CLI maps fields to its flags), the value with its unit, and what was expected;
// errors about input files name the file and the line.
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>

namespace zenith {

class Error : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

// A value given through the API is outside what it may be. field() names it as the API does
// ("fov_deg", "size"), so that a front end can say which of its own options it was.
class ArgumentError : public Error {
  public:
    explicit ArgumentError(const std::string& message) : Error(message) {}
    ArgumentError(std::string field, const std::string& message)
        : Error(message), field_(std::move(field)) {}
    const std::string& field() const { return field_; }

  private:
    std::string field_;
};

// An input file or record is malformed; the message starts with "file:line: " where known.
class InputError : public Error {
  public:
    using Error::Error;
};

// A closed, open or half-open interval of allowed values, printed as in mathematics:
// "[0, 1]", "(0, 180)", "[1, 16384]".
struct Range {
    double lo;
    double hi;
    bool lo_open = false;
    bool hi_open = false;

    static Range Closed(double lo, double hi) { return {lo, hi, false, false}; }
    static Range Open(double lo, double hi) { return {lo, hi, true, true}; }
    static Range LeftOpen(double lo, double hi) { return {lo, hi, true, false}; }
    static Range RightOpen(double lo, double hi) { return {lo, hi, false, true}; }
    // NaN is in no range.
    bool Contains(double value) const;
    std::string ToString() const;
};

// Shortest round-trip text of a number ("0.1", "1e+300", "nan", "inf").
std::string FormatValue(double value);

// "<field> = <value> <unit> is out of range (expected <range> <unit>)"; unit may be empty.
std::string RangeMessage(std::string_view field, double value, std::string_view unit,
                         const Range& range);

// Returns value if range contains it, else throws E with RangeMessage (and the field, for an
// ArgumentError). NaN always throws.
template <class E = ArgumentError>
double Require(std::string_view field, double value, std::string_view unit, const Range& range) {
    if (!range.Contains(value)) {
        if constexpr (std::is_constructible_v<E, std::string, std::string>) {
            throw E(std::string(field), RangeMessage(field, value, unit, range));
        } else {
            throw E(RangeMessage(field, value, unit, range));
        }
    }
    return value;
}

// "file:line: message", or "file: message" without a line.
std::string AtLocation(const std::filesystem::path& file, std::optional<std::size_t> line,
                       std::string_view message);

}  // namespace zenith
