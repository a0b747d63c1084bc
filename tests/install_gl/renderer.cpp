// A renderer with its own EGL context (no vds context is ever made): adopts
// it, bakes a sphere into it, renders a plane clipped by the sphere and
// styled by a lens (vds/styles.glsl) and the same plane through a voxel
// lookup (voxel/solid.glsl), and checks every pixel against the analytic
// solids (away from their borders) and the host voxel grid (everywhere).
// Exit 0 when all agree and its own context is still current and usable.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/gl.h>
#include <GL/glext.h>

#include <vds/gl/bake.h>
#include <vds/gl/context.h>
#include <vds/gl/shader.h>
#include <vds/gl/styles.h>
#include <vds/voxel/gpu_grid.h>
#include <vds/voxel/solid.h>

namespace {

int failures = 0;
void expect(bool ok, const std::string& what) {
    if (!ok) {
        std::printf("FAILED: %s\n", what.c_str());
        ++failures;
    }
}

// A UV sphere: a pole vertex at each end, n - 1 rings of 2n vertices,
// triangles wound counter-clockwise seen from outside.
vds::TriangleMesh sphere(glm::vec3 c, float r, int n) {
    vds::TriangleMesh m;
    const float pi = 3.14159265f;
    m.positions.push_back(c + glm::vec3(0, 0, r));
    for (int i = 1; i < n; ++i)
        for (int j = 0; j < 2 * n; ++j) {
            const float t = pi * float(i) / float(n), p = pi * float(j) / float(n);
            m.positions.push_back(c + r * glm::vec3(std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t)));
        }
    const auto south = std::uint32_t(m.positions.size());
    m.positions.push_back(c - glm::vec3(0, 0, r));
    auto ring = [n](int i, int j) { return std::uint32_t(1 + (i - 1) * 2 * n + (j % (2 * n))); };
    for (int j = 0; j < 2 * n; ++j) {
        m.triangles.push_back({0u, ring(1, j), ring(1, j + 1)});
        for (int i = 1; i < n - 1; ++i) {
            m.triangles.push_back({ring(i, j), ring(i + 1, j), ring(i + 1, j + 1)});
            m.triangles.push_back({ring(i, j), ring(i + 1, j + 1), ring(i, j + 1)});
        }
        m.triangles.push_back({south, ring(n - 1, j + 1), ring(n - 1, j)});
    }
    return m;
}

// An axis-aligned box, corner k at (k & 1 ? hi.x : lo.x, k & 2 ? ..., k & 4 ? ...).
vds::TriangleMesh box(glm::vec3 lo, glm::vec3 hi) {
    vds::TriangleMesh m;
    for (int k = 0; k < 8; ++k) m.positions.push_back({k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z});
    m.triangles = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                   {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
    return m;
}

const char* kVertex = "#version 430 core\nout vec2 v_uv;\n"
                      "void main() { vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);\n"
                      "  v_uv = p; gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0); }\n";

// Renders the plane z = 0.5 over [0, 1]^2 at n x n into an R32I target.
std::vector<int> render(GLuint program, int n) {
    GLuint texture = 0, fbo = 0, vao = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &texture);
    glTextureStorage2D(texture, 1, GL_R32I, n, n);
    glCreateFramebuffers(1, &fbo);
    glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, texture, 0);
    glCreateVertexArrays(1, &vao);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    const GLint clear[4] = {-1, 0, 0, 0};
    glClearBufferiv(GL_COLOR, 0, clear);
    glViewport(0, 0, n, n);
    glUseProgram(program);
    glBindVertexArray(vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    std::vector<int> pixels(std::size_t(n) * std::size_t(n));
    glGetTextureImage(texture, 0, GL_RED_INTEGER, GL_INT, GLsizei(pixels.size() * 4), pixels.data());
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glUseProgram(0);
    glBindVertexArray(0);
    glDeleteVertexArrays(1, &vao);
    glDeleteFramebuffers(1, &fbo);
    glDeleteTextures(1, &texture);
    return pixels;
}

} // namespace

int main() {
    // The renderer's own context.
    auto getDisplay = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
    EGLDisplay display = getDisplay ? getDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr) : EGL_NO_DISPLAY;
    if (getDisplay && (display == EGL_NO_DISPLAY || !eglInitialize(display, nullptr, nullptr))) {
        // No Mesa surfaceless platform (NVIDIA's EGL): the first EGL device.
        auto queryDevices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
        EGLDeviceEXT device = nullptr;
        EGLint count = 0;
        display = queryDevices && queryDevices(1, &device, &count) && count > 0
                      ? getDisplay(EGL_PLATFORM_DEVICE_EXT, device, nullptr)
                      : EGL_NO_DISPLAY;
        if (display != EGL_NO_DISPLAY && !eglInitialize(display, nullptr, nullptr)) display = EGL_NO_DISPLAY;
    }
    if (display == EGL_NO_DISPLAY || !eglBindAPI(EGL_OPENGL_API)) {
        std::printf("no EGL display: nothing to check\n");
        return 0;
    }
    const EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 3,
                              EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    const EGLContext mine = eglCreateContext(display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attribs);
    if (mine == EGL_NO_CONTEXT || !eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, mine)) {
        std::printf("no GL 4.3 core context: nothing to check\n");
        return 0;
    }
    {
        const vds::GlContext gl = vds::GlContext::adoptCurrent();
        const glm::vec3 centre(0.5f, 0.5f, 0.5f);
        const float radius = 0.3f;
        vds::BakeOptions options;
        options.resolution = 128;
        const vds::GpuBake clip = vds::bakeToGpu(gl, sphere(centre, radius, 48), options);
        const glm::vec3 lensLo(0.6f, 0.1f, 0.0f), lensHi(0.95f, 0.4f, 1.0f);
        const vds::GpuBake lens = vds::bakeToGpu(gl, box(lensLo, lensHi), options);

        // Clip and lens through styles.glsl, in the renderer's own shader.
        const int n = 128;
        const std::string frag = "#version 430 core\n#include \"vds/styles.glsl\"\nin vec2 v_uv;\nout int o_style;\n"
                                 "void main() { VdsStyle s = vdsStyleAt(vec3(v_uv, 0.5));\n"
                                 "  o_style = s.discarded ? 9 : s.style; }\n";
        const vds::Program styles = vds::buildProgram({{GL_VERTEX_SHADER, "plane.vert", kVertex},
                                                        {GL_FRAGMENT_SHADER, "styles.frag", frag}});
        vds::StyleOptions units;
        units.baseUnit = 2;
        vds::setStyleUniforms(styles.id(),
                              {{&clip.sprite, vds::StyleRole::ClipAway, 0, vds::Rule::Parity},
                               {&lens.sprite, vds::StyleRole::Lens, 3, vds::Rule::Parity}},
                              units);
        const std::vector<int> pixels = render(styles.id(), n);
        int checked = 0, wrong = 0;
        const float margin = 2.0f / float(options.resolution);
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                const glm::vec2 p((float(x) + 0.5f) / float(n), (float(y) + 0.5f) / float(n));
                const float dSphere = glm::length(glm::vec2(p) - glm::vec2(centre)) - radius; // the plane z = 0.5 cuts the sphere through its centre
                const float dLens = std::max(std::max(lensLo.x - p.x, p.x - lensHi.x), std::max(lensLo.y - p.y, p.y - lensHi.y));
                if (std::abs(dSphere) < margin || std::abs(dLens) < margin) continue;
                const int expected = dSphere < 0 ? 9 : dLens < 0 ? 3 : 0;
                ++checked;
                wrong += pixels[std::size_t(y * n + x)] != expected;
            }
        std::printf("styles: %d of %d pixels away from the borders differ from the analytic answer\n", wrong, checked);
        expect(wrong == 0 && checked > n * n / 2, "clip and lens match the analytic solids");

        // A voxel lookup in the renderer's own shader.
        const vds::voxel::BitGrid bits = vds::voxel::voxelizeSolid(
            gl, sphere(centre, radius, 48), vds::voxel::makeVoxelGrid({{0, 0, 0}, {1, 1, 1}}, 64),
            vds::voxel::SolidMethod::Compute);
        const vds::voxel::GpuBitGrid voxels(gl, bits);
        const vds::Program lookup = vds::buildProgram(
            {{GL_VERTEX_SHADER, "plane.vert", kVertex},
             {GL_FRAGMENT_SHADER, "voxels.frag",
              "#version 430 core\n#include \"voxel/solid.glsl\"\nuniform usamplerBuffer u_voxels;\n"
              "uniform VdsVoxelGrid u_grid;\nin vec2 v_uv;\nout int o_inside;\n"
              "void main() { o_inside = vdsBitGridContains(u_voxels, u_grid, vec3(v_uv, 0.5)) ? 1 : 0; }\n"}});
        voxels.setUniforms(lookup.id(), "u_voxels", "u_grid", 5);
        const std::vector<int> inside = render(lookup.id(), n);
        int voxelWrong = 0;
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                const glm::vec3 p((float(x) + 0.5f) / float(n), (float(y) + 0.5f) / float(n), 0.5f);
                voxelWrong += inside[std::size_t(y * n + x)] != int(bits.contains(p));
            }
        std::printf("voxels: %d of %d pixels differ from BitGrid::contains\n", voxelWrong, n * n);
        expect(voxelWrong == 0, "the voxel lookup matches the host grid");

        // The installed files are the embedded ones.
        std::ifstream file(std::string(VDS_SHADER_DIR) + "/vds/styles.glsl");
        std::stringstream text;
        text << file.rdbuf();
        expect(file.good() && text.str() == vds::embeddedShader("vds/styles.glsl"),
               std::string("vds_SHADER_DIR (") + VDS_SHADER_DIR + ") holds vds/styles.glsl as embedded");
        for (GLuint unit = 0; unit < 6; ++unit) glBindTextureUnit(unit, 0);
        expect(glGetError() == GL_NO_ERROR, "no GL error left behind");
    }
    expect(eglGetCurrentContext() == mine, "the renderer's context is still current");
    expect(eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT) &&
               eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, mine),
           "and can be made current again");
    eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(display, mine);
    std::printf("%s\n", failures ? "FAILED" : "passed");
    return failures ? 1 : 0;
}
