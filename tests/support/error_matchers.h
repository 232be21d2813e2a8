// gmock matchers for zenith's errors (geo/include/zenith/base/error.h): the exception's type, the
// API field an ArgumentError names and what its message says, e.g.
//   EXPECT_THAT([&] { Call(); }, ThrowsArgumentError("fov_deg", HasSubstr("(0, 180) deg")));
#pragma once

#include <gmock/gmock.h>

#include <string>

#include "zenith/base/error.h"

namespace zenith::test {

// The message of any exception, as a std::string (what() is a C string).
template <class Matcher>
auto MessageIs(Matcher message) {
    return ::testing::ResultOf(
        "what()", [](const std::exception& e) { return std::string(e.what()); }, message);
}

// Throws zenith::ArgumentError naming `field`, with a message `message` matches.
template <class Matcher>
auto ThrowsArgumentError(const std::string& field, Matcher message) {
    return ::testing::Throws<ArgumentError>(::testing::AllOf(
        ::testing::Property("field", &ArgumentError::field, field), MessageIs(message)));
}

}  // namespace zenith::test
