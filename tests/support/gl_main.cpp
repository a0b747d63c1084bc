// The main of every GL test program: registers the environment that owns the
// GL context, so it is destroyed after the last test and before main returns.
#include <gtest/gtest.h>

#include "gl_fixture.h"

int main(int argc, char** argv) {
    ::testing::InitGoogleTest(&argc, argv);
    ::testing::AddGlobalTestEnvironment(new vds::test::GlEnvironment); // owned by GoogleTest
    return RUN_ALL_TESTS();
}
