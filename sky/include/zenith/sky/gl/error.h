// Exceptions thrown by the GL layer. Every message says what was tried and what would fix it.
#pragma once

#include <stdexcept>

#include "zenith/base/error.h"

namespace zenith::sky::gl {

// A GL call or object (shader, program, loader) failed in a context that exists.
class GlError : public Error {
  public:
    using Error::Error;
};

// No usable context could be had: library missing, no display/device, GL version too low.
class ContextError : public GlError {
  public:
    using GlError::GlError;
};

}  // namespace zenith::sky::gl
