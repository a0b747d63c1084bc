// Test support: a real headless GL context per test suite. Tests skip with
// the reason when no GL can be had, unless VDS_REQUIRE_GL=1 (as CI sets),
// where a missing GL is a failure.
#pragma once

#include <cstdlib>
#include <memory>
#include <string>

#include <GL/gl.h>
#include <gtest/gtest.h>

#include <vds/gl_context.h>

namespace vds::test {

class GlTest : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        if (!context()) {
            std::string why;
            if (glAvailable(&why)) context() = std::make_unique<GlContext>();
            else reason() = why;
        }
    }
    void SetUp() override {
        if (!context()) {
            const char* require = std::getenv("VDS_REQUIRE_GL");
            if (require && std::string(require) == "1") FAIL() << "GL required but unavailable: " << reason();
            GTEST_SKIP() << "no GL: " << reason();
        }
        context()->makeCurrent();
        while (glGetError() != GL_NO_ERROR) {}
    }
    void TearDown() override {
        if (context()) {
            EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR)) << "a GL error was left behind";
        }
    }
    static GlContext& gl() { return *context(); }

private:
    static std::unique_ptr<GlContext>& context() {
        static std::unique_ptr<GlContext> c;
        return c;
    }
    static std::string& reason() {
        static std::string r;
        return r;
    }
};

} // namespace vds::test
