// The GL foundation: context, RAII objects, embedded shaders and includes.
#include <gtest/gtest.h>

#include <optional>

#include <vds/all.h>
#include <vds/bake.h>
#include <vds/error.h>
#include <vds/gl/objects.h>
#include <vds/gl/shader.h>

#include "../support/gl_fixture.h"
#include "solids.h"

namespace vds {
namespace {

class GlFoundationTest : public test::GlTest {};

TEST_F(GlFoundationTest, ContextIsDesktopCore43OrLater) {
    const GlInfo& info = gl().info();
    EXPECT_TRUE(info.major > 4 || (info.major == 4 && info.minor >= 3)) << info.version;
    EXPECT_FALSE(info.renderer.empty());
    std::printf("GL: %s | %s | %s | platform %s\n", info.vendor.c_str(), info.renderer.c_str(),
                info.version.c_str(), info.platform.c_str());
}

// Lifetime rules of <vds/gl/context.h>: scopes restore the caller's context;
// destroying or moving a context never changes which other one is current.
TEST_F(GlFoundationTest, ScopesAndDestructionKeepTheCallersCurrentContext) {
    ASSERT_TRUE(gl().isCurrent());
    {
        GlContext second; // current on creation
        EXPECT_TRUE(second.isCurrent());
        EXPECT_FALSE(gl().isCurrent());
        {
            const CurrentContext scope(gl());
            EXPECT_TRUE(gl().isCurrent());
        }
        EXPECT_TRUE(second.isCurrent()) << "the scope restores the context current before it";
        // Programs cached on `second` are freed on `second` when it goes, without
        // disturbing the caller's context.
        second.program("test.empty", [] {
            return buildProgram({{GL_COMPUTE_SHADER, "c", "layout(local_size_x = 1) in; void main() {}\n"}});
        });
        gl().makeCurrent();
        EXPECT_THROW(second.program("test.other", [] { return Program(); }), GlError)
            << "a context builds programs only while it is current";
    }
    EXPECT_TRUE(gl().isCurrent()) << "destroying a context that is not current leaves the current one alone";

    std::optional<GlContext> moved;
    {
        GlContext source;
        moved.emplace(std::move(source));
        EXPECT_TRUE(moved->isCurrent()) << "a move does not change the current context";
        EXPECT_THROW(source.makeCurrent(), GlError); // NOLINT: use after move is the point
        EXPECT_FALSE(source.isCurrent());
    }
    EXPECT_TRUE(moved->isCurrent()) << "destroying a moved-from context changes nothing";
    moved.reset();
    EXPECT_FALSE(gl().isCurrent()) << "destroying the current context leaves none current";
    gl().makeCurrent();
}

TEST_F(GlFoundationTest, ABakeWithAPrivateContextRestoresTheCallersContext) {
    const auto box = solids::box({0, 0, 0}, {1, 1, 1});
    BakeOptions o;
    o.resolution = 16;
    o.method = BakeMethod::Lists;
    const Sprite s = bake(box.mesh, o); // no context given: a private one
    EXPECT_EQ(s.depthComplexity, 2u);
    EXPECT_TRUE(gl().isCurrent());
}

// Every code surfaces by name (not only out-of-memory), and the queue is
// drained: GL may keep one flag per code, so checkGl reads until it is empty.
TEST_F(GlFoundationTest, CheckGlNamesTheErrorAndDrainsTheQueue) {
    glEnable(GL_TEXTURE_2D + 12345);            // GL_INVALID_ENUM
    glBindBuffer(GL_ARRAY_BUFFER, 0xfffffff0u); // GL_INVALID_OPERATION where GL keeps a flag per code
    try {
        checkGl("two mistakes");
        ADD_FAILURE() << "checkGl did not throw";
    } catch (const OutOfMemory&) {
        ADD_FAILURE() << "only GL_OUT_OF_MEMORY is an OutOfMemory";
    } catch (const GlError& e) {
        const std::string what = e.what();
        EXPECT_EQ(what.rfind("two mistakes: GL_INVALID_ENUM", 0), 0u) << what;
    }
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR)) << "checkGl drains the error queue";
    EXPECT_NO_THROW(checkGl("nothing pending"));
}

TEST_F(GlFoundationTest, ObjectsAreMoveOnlyAndReleaseTheirName) {
    static_assert(!std::is_copy_constructible<Buffer>::value, "GL objects must not be copyable");
    static_assert(std::is_nothrow_move_constructible<Texture>::value, "moves must not throw");
    Buffer a = Buffer::create();
    const GLuint id = a.id();
    EXPECT_TRUE(glIsBuffer(id));
    Buffer b = std::move(a);
    EXPECT_EQ(a.id(), 0u);
    EXPECT_EQ(b.id(), id);
    b.reset();
    EXPECT_FALSE(glIsBuffer(id));
    Texture t = Texture::create(GL_TEXTURE_3D);
    const GLuint raw = t.release();
    EXPECT_TRUE(glIsTexture(raw));
    Texture adopted = Texture::wrap(raw);
    EXPECT_EQ(adopted.id(), raw);
}

TEST_F(GlFoundationTest, EveryEmbeddedShaderIsPresentAndTheIncludeStandsAlone) {
    const auto paths = embeddedShaderPaths();
    EXPECT_NE(std::find(paths.begin(), paths.end(), "vds/vpt.glsl"), paths.end());
    // The include compiles in every stage on its own.
    const std::string use = "#include \"vds/vpt.glsl\"\nuniform sampler3D u_ldi;\nuniform VdsPlacement u_p;\n";
    EXPECT_NO_THROW(buildProgram({{GL_VERTEX_SHADER, "v", use + "void main() { gl_Position = vec4(vdsContains(u_ldi, u_p, vec3(0), 0) ? 1.0 : 0.0); }\n"},
                                  {GL_FRAGMENT_SHADER, "f", use + "out vec4 c; void main() { c = vec4(vdsContains(u_ldi, u_p, vec3(1), 1) ? 1.0 : 0.0); }\n"}}));
    EXPECT_NO_THROW(buildProgram({{GL_COMPUTE_SHADER, "c", use + "layout(local_size_x = 1) in; void main() { vdsContains(u_ldi, u_p, vec3(0), 0); }\n"}}));
}

TEST_F(GlFoundationTest, IncludesAreResolvedOnceWithLineDirectives) {
    std::vector<std::string> files;
    const std::string text = assembleShader(
        {GL_FRAGMENT_SHADER, "mine.frag", "#include \"vds/vpt.glsl\"\n#include \"vds/vpt.glsl\"\nvoid main() {}\n"},
        "#version 450 core", "#define X 1\n", &files);
    ASSERT_EQ(files.size(), 2u);
    EXPECT_EQ(files[0], "mine.frag");
    EXPECT_EQ(files[1], "vds/vpt.glsl");
    EXPECT_EQ(text.rfind("#version 450 core\n#define X 1\n#line 1 0\n", 0), 0u);
    EXPECT_NE(text.find("#line 1 1\n"), std::string::npos);
    EXPECT_NE(text.find("#line 2 0\n"), std::string::npos);
    EXPECT_EQ(text.find("int vdsWinding("), text.rfind("int vdsWinding(")) << "included twice";
    EXPECT_THROW(embeddedShader("vds/missing.glsl"), InvalidArgument);
}

TEST_F(GlFoundationTest, CompileErrorsNameTheRealFileAndLine) {
    try {
        buildProgram({{GL_FRAGMENT_SHADER, "broken.frag",
                       "#include \"vds/vpt.glsl\"\nout vec4 c;\nvoid main() {\n  c = undefinedThing;\n}\n"}});
        FAIL() << "a broken shader compiled";
    } catch (const GlError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("broken.frag:4"), std::string::npos) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << "error must be one line";
    }
}

} // namespace
} // namespace vds
