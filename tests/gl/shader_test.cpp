// The shader resolver as a renderer uses it (<vds/gl/shader.h>): the user's
// own `#version`, includes inside comments and false `#if` branches left
// out, `#line` kept, every layer's includes known from the start.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <vds/error.h>
#include <vds/gl/objects.h>
#include <vds/gl/shader.h>

#include "../support/gl_fixture.h"

namespace vds {
namespace {

using ShaderTest = test::GlTest;

bool pulls(const std::string& source, const char* what = "int vdsWinding(") {
    const std::string text = assembleShader({GL_FRAGMENT_SHADER, "mine.frag", source}, "#version 430 core", "");
    return text.find(what) != std::string::npos;
}

std::size_t count(const std::string& text, const std::string& word) {
    std::size_t n = 0;
    for (std::size_t p = text.find(word); p != std::string::npos; p = text.find(word, p + 1)) ++n;
    return n;
}

TEST_F(ShaderTest, TheUsersOwnVersionLineIsKeptAndNoOtherAdded) {
    const std::string source = "// my renderer's shader\n#version 450 core\n#include \"vds/vpt.glsl\"\n"
                               "out vec4 c;\nvoid main() { c = vec4(1.0); }\n";
    const std::string text =
        assembleShader({GL_FRAGMENT_SHADER, "mine.frag", source}, "#version 430 core", "#define X 1\n");
    EXPECT_EQ(text.rfind("#version 450 core\n#define X 1\n", 0), 0u) << text.substr(0, 80);
    EXPECT_EQ(count(text, "#version"), 1u);
    EXPECT_NO_THROW(buildProgram({{GL_FRAGMENT_SHADER, "mine.frag", source}}));
    // Without one, the context's is added.
    EXPECT_EQ(assembleShader({GL_FRAGMENT_SHADER, "m", "void main() {}\n"}, "#version 430 core", "").rfind("#version 430 core\n", 0), 0u);
}

TEST_F(ShaderTest, IncludesInCommentsAndSkippedBranchesAreLeftOut) {
    EXPECT_TRUE(pulls("#include \"vds/vpt.glsl\"\n"));
    EXPECT_FALSE(pulls("// #include \"vds/vpt.glsl\"\n"));
    EXPECT_FALSE(pulls("/* a block\n#include \"vds/vpt.glsl\"\n*/\n"));
    EXPECT_FALSE(pulls("/* one line */ // #include \"vds/vpt.glsl\"\n"));
    EXPECT_TRUE(pulls("/* one line */ #include \"vds/vpt.glsl\"\n"));
    EXPECT_FALSE(pulls("#if 0\n#include \"vds/vpt.glsl\"\n#endif\n"));
    EXPECT_TRUE(pulls("#if 1\n#include \"vds/vpt.glsl\"\n#endif\n"));
    EXPECT_FALSE(pulls("#ifdef NOT_DEFINED\n#include \"vds/vpt.glsl\"\n#endif\n"));
    EXPECT_TRUE(pulls("#define USE_VDS\n#ifdef USE_VDS\n#include \"vds/vpt.glsl\"\n#endif\n"));
    EXPECT_FALSE(pulls("#define USE_VDS\n#undef USE_VDS\n#if defined(USE_VDS)\n#include \"vds/vpt.glsl\"\n#endif\n"));
    EXPECT_TRUE(pulls("#ifndef NOT_DEFINED\n#include \"vds/vpt.glsl\"\n#endif\n"));
    EXPECT_TRUE(pulls("#if 0\n#elif !defined(NOT_DEFINED)\n#include \"vds/vpt.glsl\"\n#endif\n"));
    EXPECT_TRUE(pulls("#if 0\n#else\n#include \"vds/vpt.glsl\"\n#endif\n"));
    EXPECT_FALSE(pulls("#if 1\n#else\n#include \"vds/vpt.glsl\"\n#endif\n"));
    EXPECT_FALSE(pulls("#if 0\n#if 1\n#include \"vds/vpt.glsl\"\n#endif\n#endif\n"));
    // The caller's defines count.
    const std::string guarded = "#ifdef WANT\n#include \"vds/vpt.glsl\"\n#endif\n";
    EXPECT_TRUE(assembleShader({GL_FRAGMENT_SHADER, "m", guarded}, "#version 430 core", "#define WANT\n")
                    .find("int vdsWinding(") != std::string::npos);
    // A condition the resolver cannot evaluate keeps the include (the driver decides).
    EXPECT_TRUE(pulls("#define N 3\n#if N > 2\n#include \"vds/vpt.glsl\"\n#endif\n"));
    EXPECT_TRUE(pulls("#if N > 2\n#else\n#include \"vds/vpt.glsl\"\n#endif\n"));
    // And the assembled text compiles, the skipped include gone.
    EXPECT_NO_THROW(buildProgram({{GL_COMPUTE_SHADER, "c",
                                   "#if 0\n#include \"vds/none.glsl\"\n#endif\n// #include \"vds/none.glsl\"\n"
                                   "layout(local_size_x = 1) in; void main() {}\n"}}));
}

TEST_F(ShaderTest, ErrorLinesMapToTheUsersFileAfterIncludesAndSkippedOnes) {
    try {
        buildProgram({{GL_FRAGMENT_SHADER, "mine.frag",
                       "#version 430 core\n/*\n#include \"vds/styles.glsl\"\n*/\n#if 0\n#include \"vds/vpt.glsl\"\n"
                       "#endif\n#include \"vds/styles.glsl\"\nout vec4 c;\nvoid main() {\n  c = undefinedThing;\n}\n"}});
        FAIL() << "a broken shader compiled";
    } catch (const GlError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("mine.frag:11"), std::string::npos) << message;
    }
}

TEST_F(ShaderTest, EveryLayersIncludesResolveBeforeAnyOtherCall) {
    const auto paths = embeddedShaderPaths();
    for (const char* path : {"vds/vpt.glsl", "vds/styles.glsl", "voxel/solid.glsl", "voxel/slicemap.glsl", "voxel/grid.glsl"})
        EXPECT_NE(std::find(paths.begin(), paths.end(), path), paths.end()) << path;
    EXPECT_NO_THROW(buildProgram({{GL_COMPUTE_SHADER, "c",
                                   "#include \"voxel/solid.glsl\"\nuniform usamplerBuffer u_voxels;\nuniform VdsVoxelGrid u_g;\n"
                                   "layout(std430, binding = 0) buffer B { uint v; };\n"
                                   "layout(local_size_x = 1) in; void main() { v = vdsBitGridContains(u_voxels, u_g, vec3(0)) ? 1u : 0u; }\n"}}));
}

// One pi: every program the library builds gets VDS_FOUR_PI from the C++
// constant, and the public include's default, for a user's shader built
// elsewhere, is the same number.
TEST_F(ShaderTest, FourPiReachesEveryProgramAndThePublicIncludesDefaultAgrees) {
    const double fourPi = 4.0 * std::acos(-1.0);
    const std::string source = "#include \"vds/vpt.glsl\"\n"
                               "layout(std430, binding = 0) buffer B { float v; };\n"
                               "layout(local_size_x = 1) in; void main() { v = VDS_FOUR_PI; }\n";
    const Program program = buildProgram({{GL_COMPUTE_SHADER, "pi.comp", source}});
    Buffer out = Buffer::create();
    const float unset = 0.0f;
    glNamedBufferStorage(out.id(), 4, &unset, 0);
    glUseProgram(program.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, out.id());
    glDispatchCompute(1, 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    float v = 0.0f;
    glGetNamedBufferSubData(out.id(), 0, 4, &v);
    glUseProgram(0);
    EXPECT_EQ(v, float(fourPi));

    const std::string text = assembleShader({GL_COMPUTE_SHADER, "pi.comp", source}, "#version 430 core", "");
    const std::string guard = "#ifndef VDS_FOUR_PI\n#define VDS_FOUR_PI ";
    const std::size_t at = text.find(guard);
    ASSERT_NE(at, std::string::npos);
    EXPECT_EQ(std::stod(text.substr(at + guard.size())), fourPi);
}

} // namespace
} // namespace vds
