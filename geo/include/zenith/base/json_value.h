// How an error message shows a JSON value (header-only; needs nlohmann-json, which the readers
// that include it already use).
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace zenith {

// A scalar's type and text, cut at 40 characters; an array's or object's type and size (never
// a recursive dump of what may be a huge or deeply nested value).
inline std::string DescribeJsonValue(const nlohmann::json& value) {
    if (value.is_structured()) {
        return std::string(value.type_name()) + " of " + std::to_string(value.size()) +
               (value.size() == 1 ? " element" : " elements");
    }
    std::string text = value.dump();
    if (text.size() > 40) text = text.substr(0, 37) + "...";
    return std::string(value.type_name()) + " " + text;
}

}  // namespace zenith
