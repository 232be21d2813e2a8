// A headless OSMesa context shared by every test of a suite (made once: llvmpipe's start-up
// costs more than many of the tests).
#pragma once

#include <gtest/gtest.h>

#include <memory>

#include "zenith/sky/gl/context.h"

namespace zenith::sky::gl::test {

class HeadlessGlTest : public ::testing::Test {
  protected:
    static void SetUpTestSuite() { context_ = CreateHeadlessContext(ContextKind::kOsMesa); }
    static void TearDownTestSuite() { context_.reset(); }
    static inline std::unique_ptr<HeadlessContext> context_;
};

}  // namespace zenith::sky::gl::test
