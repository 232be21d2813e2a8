// The context implementations behind CreateHeadlessContext, and loader state they share.
#pragma once

#include <memory>

#include "zenith/sky/gl/context.h"

namespace zenith::sky::gl::internal {

std::unique_ptr<HeadlessContext> CreateOsMesaContext(const ContextOptions& options);
std::unique_ptr<HeadlessContext> CreateEglContext(const ContextOptions& options);

// The getProcAddress the process-wide GL pointers were last loaded through (nullptr: none, or a
// std::function loader). HeadlessContext::MakeCurrent reloads when this is not its own.
GetProcAddressFn LastLoader();

}  // namespace zenith::sky::gl::internal
