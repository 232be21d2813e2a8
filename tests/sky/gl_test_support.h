// A headless context shared by every test of a suite (made once: llvmpipe's start-up costs more
// than many of the tests). ZENITH_GL chooses it (OSMesa by default; ZENITH_GL=egl runs the GL
// tests on a GPU through EGL, e.g. ZENITH_EGL_PLATFORM=device on a headless NVIDIA machine).
#pragma once

#include <gtest/gtest.h>

#include <memory>

#include "zenith/sky/gl/context.h"

namespace zenith::sky::gl::test {

class HeadlessGlTest : public ::testing::Test {
  protected:
    static void SetUpTestSuite() { context_ = CreateHeadlessContextFromEnvironment(); }
    static void TearDownTestSuite() { context_.reset(); }
    static inline std::unique_ptr<HeadlessContext> context_;
};

}  // namespace zenith::sky::gl::test
