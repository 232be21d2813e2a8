// Exceptions thrown by the GL layer. Every message says what was tried and what would fix it.
#pragma once

#include <stdexcept>

namespace zenith::sky::gl {

// A GL call or object (shader, program, loader) failed in a context that exists.
class GlError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

// No usable context could be had: library missing, no display/device, GL version too low.
class ContextError : public GlError {
  public:
    using GlError::GlError;
};

}  // namespace zenith::sky::gl
