// The application's own GL context (<vds/gl/context.h>, the GL rule): a
// program that makes its own raw EGL context, as a renderer does, and lets
// the library work in it (adopted) and beside it (a vds-owned context that
// comes and goes). No vds context is made by the test's main, so the
// library's last own context really goes while the application's lives.
// Also the one-line errors on misuse: no context, another context, another thread.
#include <cstdint>
#include <string>
#include <thread>
#include <vector>

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/gl.h>
#include <GL/glext.h>
#include <gtest/gtest.h>

#include <vds/all.h>
#include <vds/error.h>
#include <vds/gl/bake.h>
#include <vds/gl/context.h>
#include <vds/gl/occupancy.h>
#include <vds/gl/shader.h>
#include <vds/distance.h>
#include <vds/gl/sprite.h>
#include <vds/sprite.h>

#include "solids.h"

namespace {

using namespace vds;

// A plain EGL 4.3 core context on Mesa's surfaceless platform (the display
// vds's own headless context uses too: the case that once broke), else on
// the first EGL device.
class RawEgl {
public:
    RawEgl() {
        auto getDisplay = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
        if (!getDisplay) return;
        display_ = getDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        if (display_ == EGL_NO_DISPLAY || !eglInitialize(display_, nullptr, nullptr)) {
            // No Mesa surfaceless platform (NVIDIA's EGL): the first EGL device.
            auto queryDevices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
            EGLDeviceEXT device = nullptr;
            EGLint count = 0;
            if (!queryDevices || !queryDevices(1, &device, &count) || count < 1) return;
            display_ = getDisplay(EGL_PLATFORM_DEVICE_EXT, device, nullptr);
            if (display_ == EGL_NO_DISPLAY || !eglInitialize(display_, nullptr, nullptr)) return;
        }
        if (!eglBindAPI(EGL_OPENGL_API)) return;
        const EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 3,
                                  EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
        context_ = eglCreateContext(display_, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attribs);
    }
    ~RawEgl() {
        if (context_ == EGL_NO_CONTEXT) return;
        if (eglGetCurrentContext() == context_)
            eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        eglDestroyContext(display_, context_);
    }
    RawEgl(const RawEgl&) = delete;
    RawEgl& operator=(const RawEgl&) = delete;
    bool ok() const { return context_ != EGL_NO_CONTEXT; }
    bool makeCurrent() const { return eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_) == EGL_TRUE; }
    bool isCurrent() const { return eglGetCurrentContext() == context_; }
    static void release() {
        if (EGLDisplay d = eglGetCurrentDisplay(); d != EGL_NO_DISPLAY)
            eglMakeCurrent(d, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    }

private:
    EGLDisplay display_ = EGL_NO_DISPLAY;
    EGLContext context_ = EGL_NO_CONTEXT;
};

// The application's context works: it compiles and runs a compute shader
// that writes a known value, read back.
bool contextWorks() {
    const GLuint shader = glCreateShader(GL_COMPUTE_SHADER);
    const char* src = "#version 430 core\nlayout(local_size_x = 1) in;\n"
                      "layout(std430, binding = 0) buffer B { uint v; };\nvoid main() { v = 1234u; }\n";
    glShaderSource(shader, 1, &src, nullptr);
    glCompileShader(shader);
    const GLuint program = glCreateProgram();
    glAttachShader(program, shader);
    glLinkProgram(program);
    GLuint buffer = 0;
    glCreateBuffers(1, &buffer);
    const GLuint zero = 0;
    glNamedBufferData(buffer, 4, &zero, GL_DYNAMIC_READ);
    glUseProgram(program);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buffer);
    glDispatchCompute(1, 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    GLuint value = 0;
    glGetNamedBufferSubData(buffer, 0, 4, &value);
    glUseProgram(0);
    glDeleteBuffers(1, &buffer);
    glDeleteProgram(program);
    glDeleteShader(shader);
    return value == 1234u && glGetError() == GL_NO_ERROR;
}

class ForeignContext : public ::testing::Test {
protected:
    void SetUp() override {
        if (!egl.ok() || !egl.makeCurrent()) GTEST_SKIP() << "no surfaceless EGL 4.3 core context here";
    }
    void TearDown() override { RawEgl::release(); }
    RawEgl egl;
};

std::vector<glm::vec3> gridPoints(int n) {
    std::vector<glm::vec3> p;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            for (int k = 0; k < n; ++k)
                p.emplace_back(-0.5f + 2.0f * (float(i) + 0.37f) / float(n), -0.5f + 2.0f * (float(j) + 0.21f) / float(n),
                               -0.5f + 2.0f * (float(k) + 0.53f) / float(n));
    return p;
}

TEST_F(ForeignContext, AVdsContextThatComesAndGoesLeavesTheApplicationsContextUsable) {
    ASSERT_TRUE(contextWorks());
    {
        const CurrentContext keep; // the application's context comes back after the vds one
        const GlContext own;       // on the same surfaceless display
        ASSERT_TRUE(own.isCurrent());
    } // the library's last own context goes: the display must stay alive
    EXPECT_TRUE(egl.isCurrent()) << "the application's context is current again";
    EXPECT_TRUE(contextWorks()) << "and works";
    RawEgl::release();
    EXPECT_TRUE(egl.makeCurrent()) << "and can be made current again (the display was not terminated)";
    EXPECT_TRUE(contextWorks());

    // bake() with no context makes a private one and gives it back.
    BakeOptions o;
    o.resolution = 16;
    o.method = BakeMethod::Lists;
    const Sprite s = bake(solids::box({0, 0, 0}, {1, 1, 1}).mesh, o);
    EXPECT_EQ(s.depthComplexity, 2u);
    EXPECT_TRUE(egl.isCurrent());
    EXPECT_TRUE(contextWorks());
    // The probe, too.
    EXPECT_TRUE(glAvailable());
    EXPECT_TRUE(egl.isCurrent());
    EXPECT_TRUE(contextWorks());
}

TEST_F(ForeignContext, AnAdoptedContextBakesUploadsAndClassifiesLikeTheCpu) {
    const GlContext gl = GlContext::adoptCurrent();
    EXPECT_FALSE(gl.owned());
    EXPECT_TRUE(gl.isCurrent());
    EXPECT_EQ(gl.info().platform, "adopted EGL");
    // Read from the renderer's own name when adopted, as when made.
    const std::string& renderer = gl.info().renderer;
    EXPECT_EQ(gl.info().software, renderer.find("llvmpipe") != std::string::npos ||
                                      renderer.find("softpipe") != std::string::npos)
        << renderer;
    const auto torus = solids::torus({0.5f, 0.5f, 0.5f}, 0.6f, 0.25f, 48);
    BakeOptions o;
    o.resolution = 64;
    const Sprite host = bakeOnGl(gl, torus.mesh, o);
    EXPECT_TRUE(egl.isCurrent());
    const GpuBake baked = bakeToGpu(gl, torus.mesh, o);
    EXPECT_TRUE(egl.isCurrent());
    EXPECT_EQ(baked.depthComplexity, host.depthComplexity);
    const GpuSprite uploaded(host); // the application's current context, with no vds handle at all

    const std::vector<glm::vec3> points = gridPoints(24);
    std::vector<std::uint8_t> cpu(points.size()), fromBake(points.size()), fromUpload(points.size());
    classify(host, points, cpu.data());
    GpuClassifier classifier(gl);
    classifier.classify(baked.sprite, points, fromBake.data());
    classifier.classify(uploaded, points, fromUpload.data());
    EXPECT_EQ(fromBake, cpu);
    EXPECT_EQ(fromUpload, cpu);
    std::size_t inside = 0;
    for (auto l : cpu) inside += l;
    EXPECT_GT(inside, 0u);
    EXPECT_LT(inside, cpu.size());
    EXPECT_TRUE(egl.isCurrent());
    EXPECT_TRUE(contextWorks());
}

// makeClassifier with no context makes a private one for a GPU method: the
// application's context is current again when it returns (rule 3), and
// after the classifier answers and goes.
TEST_F(ForeignContext, MakeClassifierOnAPrivateContextGivesTheApplicationsContextBack) {
    const auto torus = solids::torus({0.5f, 0.5f, 0.5f}, 0.6f, 0.25f, 32);
    MethodOptions o;
    o.resolution = 32;
    std::unique_ptr<Classifier> gpu = makeClassifier(torus.mesh, Method::SpriteGpu, o);
    EXPECT_TRUE(egl.isCurrent()) << "makeClassifier left the library's own context current";
    const std::unique_ptr<Classifier> cpu = makeClassifier(torus.mesh, Method::Sprite, o);
    const std::vector<glm::vec3> points = gridPoints(12);
    std::vector<std::uint8_t> fromGpu(points.size()), fromCpu(points.size());
    gpu->classify(points, fromGpu.data());
    EXPECT_TRUE(egl.isCurrent());
    cpu->classify(points, fromCpu.data());
    EXPECT_EQ(fromGpu, fromCpu);
    gpu.reset();
    EXPECT_TRUE(egl.isCurrent());
    EXPECT_TRUE(contextWorks());
}

TEST_F(ForeignContext, MisuseGivesOneLineErrorsNamingTheMistake) {
    const auto box = solids::box({0, 0, 0}, {1, 1, 1});
    BakeOptions o;
    o.resolution = 8;
    o.method = BakeMethod::Cpu;
    const Sprite host = bakeCpu(box.mesh, o);
    auto message = [](auto&& f) -> std::string {
        try {
            f();
        } catch (const GlError& e) {
            return e.what();
        }
        return "no GlError";
    };
    const GpuSprite sprite(host); // belongs to the application's context
    Sprite withDistance = host;
    withDistance.distance = bakeDistance(box.mesh, host.grid.box, 8, Rule::Parity);
    const GpuSprite distanced(withDistance); // its boundary and distance grid too

    // No context current.
    RawEgl::release();
    const std::string none = message([&] { GpuSprite s(host); });
    EXPECT_NE(none.find("no GL context current"), std::string::npos) << none;
    EXPECT_EQ(none.find("3D texture limit"), std::string::npos) << none;
    EXPECT_NE(message([] { GlContext::adoptCurrent(); }).find("no GL context current"), std::string::npos);
    EXPECT_NE(message([&] { sprite.bind(0); }).find("no GL context current"), std::string::npos);

    // Another context current.
    {
        const GlContext other;
        const std::string wrong = message([&] { sprite.bind(0); });
        EXPECT_NE(wrong.find("another GL context"), std::string::npos) << wrong;
        const std::string boundary = message([&] { distanced.boundary().setUniforms(0, "u_boundary", 5); });
        EXPECT_NE(boundary.find("another GL context"), std::string::npos) << boundary;
        const std::string field = message([&] { distanced.distanceGrid().setUniforms(0, "u_d", "u_lo", "u_hi", 1); });
        EXPECT_NE(field.find("another GL context"), std::string::npos) << field;
        GpuClassifier classifier(other);
        std::vector<glm::vec3> points{{0.5f, 0.5f, 0.5f}};
        std::uint8_t label = 7;
        const std::string classify = message([&] { classifier.classify(sprite, points, &label); });
        EXPECT_NE(classify.find("the sprite: made in another GL context"), std::string::npos) << classify;
        ASSERT_TRUE(egl.makeCurrent());
        const std::string program = message([&] { other.program("y", [] { return Program(); }); });
        EXPECT_NE(program.find("another GL context is current"), std::string::npos) << program;
    }

    // Another thread (with its own context current, and with none).
    ASSERT_TRUE(egl.makeCurrent());
    std::string fromThread;
    std::thread([&] { fromThread = message([&] { sprite.bind(0); }); }).join();
    EXPECT_NE(fromThread.find("another thread"), std::string::npos) << fromThread;
    // Handing the context over to the thread (current there) is allowed: one thread at a time.
    RawEgl::release();
    std::string handedOver;
    std::thread([&] {
        handedOver = egl.makeCurrent() ? message([&] { sprite.bind(0); }) : "cannot make the context current";
        RawEgl::release();
    }).join();
    EXPECT_EQ(handedOver, "no GlError");
    ASSERT_TRUE(egl.makeCurrent());
    for (const std::string& m : {none, fromThread}) EXPECT_EQ(m.find('\n'), std::string::npos) << m;
    EXPECT_TRUE(contextWorks());
}

TEST_F(ForeignContext, SetUniformsNeedsNoProgramInUseAndLeavesNoError) {
    const GlContext gl = GlContext::adoptCurrent();
    const auto box = solids::box({0, 0, 0}, {1, 1, 1});
    BakeOptions o;
    o.resolution = 8;
    o.method = BakeMethod::Cpu;
    const GpuSprite sprite(gl, bakeCpu(box.mesh, o));
    const Program program = buildProgram({{GL_COMPUTE_SHADER, "user.comp",
                                           "#version 430 core\n#include \"vds/vpt.glsl\"\n"
                                           "layout(local_size_x = 1) in;\nuniform sampler3D u_ldi;\n"
                                           "uniform VdsPlacement u_placement;\n"
                                           "layout(std430, binding = 0) buffer B { float v; };\n"
                                           "void main() { v = u_placement.position.x + texture(u_ldi, vec3(0.5)).r; }\n"}});
    glUseProgram(0);
    while (glGetError() != GL_NO_ERROR) {
    }
    sprite.setUniforms(program.id(), "u_ldi", "u_placement", 3);
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
    GLint unit = -1;
    glGetUniformiv(program.id(), glGetUniformLocation(program.id(), "u_ldi"), &unit);
    EXPECT_EQ(unit, 3);
    glBindTextureUnit(3, 0);
}

} // namespace
