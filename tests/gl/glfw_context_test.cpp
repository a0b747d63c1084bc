// The application's context from a GLFW window (GLX on X11; run under Xvfb):
// adopted by vds, baked into, classified in, and current again after a vds
// context of the library's own came and went and after bake() with none.
#include <cstdio>
#include <vector>

#include <GLFW/glfw3.h>

#include <vds/all.h>
#include <vds/gl/bake.h>
#include <vds/gl/context.h>
#include <vds/gl/sprite.h>
#include <vds/sprite.h>

#include "solids.h"

namespace {

int failures = 0;
void expect(bool ok, const char* what) {
    if (!ok) {
        std::printf("FAILED: %s\n", what);
        ++failures;
    }
}

} // namespace

int main() {
    if (!glfwInit()) {
        std::printf("no display for GLFW: nothing to check\n");
        return 0;
    }
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_VISIBLE, GLFW_FALSE);
    GLFWwindow* window = glfwCreateWindow(64, 64, "vds", nullptr, nullptr);
    if (!window) {
        std::printf("no GL 4.3 core window: nothing to check\n");
        glfwTerminate();
        return 0;
    }
    glfwMakeContextCurrent(window);
    auto windowWorks = [&] {
        glClearColor(0.25f, 0.5f, 0.75f, 1.0f);
        glClear(GL_COLOR_BUFFER_BIT);
        unsigned char pixel[4] = {0, 0, 0, 0};
        glReadPixels(0, 0, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, pixel);
        return glfwGetCurrentContext() == window && pixel[2] > 180 && pixel[2] < 200 && glGetError() == GL_NO_ERROR;
    };
    expect(windowWorks(), "the window's context works to begin with");
    {
        const vds::GlContext gl = vds::GlContext::adoptCurrent();
        std::printf("adopted: %s, %s\n", gl.info().platform.c_str(), gl.info().renderer.c_str());
        expect(!gl.owned() && gl.isCurrent(), "the adopted context is the window's");
        const auto torus = vds::solids::torus({0.5f, 0.5f, 0.5f}, 0.6f, 0.25f, 48);
        vds::BakeOptions o;
        o.resolution = 64;
        const vds::GpuBake baked = vds::bakeToGpu(gl, torus.mesh, o);
        const vds::Sprite host = vds::bakeOnGl(gl, torus.mesh, o);
        std::vector<glm::vec3> points;
        for (int i = 0; i < 4000; ++i)
            points.emplace_back(-0.5f + float(i % 20) * 0.1f, -0.5f + float((i / 20) % 20) * 0.1f,
                                -0.5f + float(i / 400) * 0.2f);
        std::vector<std::uint8_t> cpu(points.size()), gpu(points.size(), 7);
        vds::classify(host, points, cpu.data());
        vds::GpuClassifier classifier(gl);
        classifier.classify(baked.sprite, points, gpu.data());
        expect(cpu == gpu, "GPU labels in the window's context equal the CPU's");
        expect(windowWorks(), "the window's context is current after the GPU calls");
        {
            const vds::CurrentContext keep;
            const vds::GlContext own; // EGL beside the window's GLX
        }
        expect(windowWorks(), "the window's context is current after a vds context came and went");
        vds::BakeOptions cpuLists = o;
        cpuLists.method = vds::BakeMethod::Lists;
        const vds::Sprite privately = vds::bake(torus.mesh, cpuLists); // a private vds context
        expect(privately.depthComplexity == host.depthComplexity, "the private bake agrees");
        expect(windowWorks(), "the window's context is current after bake() with no context");
    }
    expect(windowWorks(), "the window's context works after the adopted handle went");
    glfwDestroyWindow(window);
    glfwTerminate();
    std::printf("%s\n", failures ? "FAILED" : "passed");
    return failures ? 1 : 0;
}
