// Test support: one real headless GL context per test program, owned by a
// GoogleTest environment (gl_main.cpp) that destroys it in TearDown, before
// main returns: no GL call happens during static destruction. Tests skip with
// the reason when no GL can be had, unless VDS_REQUIRE_GL=1 (as CI sets),
// where a missing GL is a failure.
#pragma once

#include <cstdlib>
#include <memory>
#include <string>

#include <GL/gl.h>
#include <gtest/gtest.h>

#include <vds/gl/context.h>

namespace vds::test {

class GlEnvironment : public ::testing::Environment {
public:
    void SetUp() override {
        std::string why;
        if (glAvailable(&why)) context() = std::make_unique<GlContext>();
        else reason() = why;
    }
    void TearDown() override { context().reset(); }

    static std::unique_ptr<GlContext>& context() {
        static std::unique_ptr<GlContext> c;
        return c;
    }
    static std::string& reason() {
        static std::string r;
        return r;
    }
};

class GlTest : public ::testing::Test {
protected:
    void SetUp() override {
        if (!GlEnvironment::context()) {
            const char* require = std::getenv("VDS_REQUIRE_GL");
            if (require && std::string(require) == "1")
                FAIL() << "GL required but unavailable: " << GlEnvironment::reason();
            GTEST_SKIP() << "no GL: " << GlEnvironment::reason();
        }
        GlEnvironment::context()->makeCurrent();
        while (glGetError() != GL_NO_ERROR) {}
    }
    void TearDown() override {
        if (GlEnvironment::context()) {
            EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR)) << "a GL error was left behind";
        }
    }
    static GlContext& gl() { return *GlEnvironment::context(); }
};

} // namespace vds::test
