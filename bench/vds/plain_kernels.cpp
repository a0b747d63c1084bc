#include "plain_kernels.h"

#include <algorithm>
#include <chrono>
#include <string>

#include <GL/gl.h>
#include <GL/glext.h>

#include <vds/error.h>
#include <vds/gl/shader.h>

namespace vds::bench {
// shaders/bench/plain.comp, embedded by vds_embed_shaders.
extern const vds::ShaderFile kBenchShaders[];
extern const std::size_t kBenchShadersCount;

namespace {

constexpr GLuint kBoundaryBinding = 5;
constexpr std::uint32_t kLocal = 256; ///< plain.comp's local_size_x

// One program a rule and form of shaders/bench/plain.comp.
const Program& program(const GlContext& gl, bool gwn, PlainForm form = {}) {
    const std::string name = std::string(gwn ? "bench.plain.gwn" : "bench.plain.parity") + (form.texel ? ".texel" : "") +
                             (form.onePoint ? ".one" : "");
    return gl.program(name, [gwn, form] {
        std::string defines = gwn ? "#define VDS_PLAIN_GWN\n" : "";
        if (form.texel) defines += "#define VDS_PLAIN_TEXEL\n";
        if (form.onePoint) defines += "#define VDS_PLAIN_ONE\n";
        return buildProgram({{GL_COMPUTE_SHADER, "bench/plain.comp", ""}}, defines);
    });
}

// A buffer texture of `buffer`'s 32-bit items, each read as `format`.
Texture bufferTexture(GLuint buffer, GLenum format) {
    Texture t = Texture::create(GL_TEXTURE_BUFFER);
    glTextureBuffer(t.id(), format, buffer);
    checkGl("making a buffer texture of the columns");
    return t;
}

} // namespace

PlainKernels::PlainKernels(const GlContext& gl) : gl_(&gl) {
    registerShaders(kBenchShaders, kBenchShadersCount);
    parity_ = &program(gl, false);
    gwn_ = &program(gl, true);
}

void PlainKernels::parity(const GpuSprite& sprite, GLuint points, std::size_t count, GLuint labels) const {
    run(*parity_, sprite, points, count, labels);
}

void PlainKernels::generalizedWinding(const GpuSprite& sprite, GLuint points, std::size_t count, GLuint labels) const {
    run(*gwn_, sprite, points, count, labels);
}

void PlainKernels::parity(const GpuSprite& sprite, GLuint points, std::size_t count, GLuint labels,
                          PlainForm form) const {
    const Program& p = program(*gl_, false, form);
    if (!form.texel) {
        run(p, sprite, points, count, labels, form.onePoint);
        return;
    }
    const Texture offsets = bufferTexture(sprite.offsets().id(), GL_R32UI);
    const Texture crossings = bufferTexture(sprite.crossings().id(), GL_R32F);
    glBindTextureUnit(0, offsets.id());
    glBindTextureUnit(1, crossings.id());
    run(p, sprite, points, count, labels, form.onePoint);
    glBindTextureUnit(0, 0);
    glBindTextureUnit(1, 0);
}

void PlainKernels::run(const Program& program, const GpuSprite& sprite, GLuint points, std::size_t count,
                       GLuint labels, bool onePoint) const {
    const GLuint id = program.id();
    glUseProgram(id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, points);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, labels);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, sprite.offsets().id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, sprite.crossings().id());
    glUniform2i(glGetUniformLocation(id, "u_size"), GLint(sprite.size().x), GLint(sprite.size().y));
    glUniformMatrix3fv(glGetUniformLocation(id, "u_placement.matrix"), 1, GL_FALSE, &sprite.matrix()[0][0]);
    glUniform3fv(glGetUniformLocation(id, "u_placement.position"), 1, &sprite.position()[0]);
    glUniform1ui(glGetUniformLocation(id, "u_count"), GLuint(count));
    if (&program == gwn_) sprite.boundary().setUniforms(id, "u_boundary", kBoundaryBinding);
    const std::size_t invocations = onePoint ? count : (count + 3) / 4;
    const std::size_t groups = std::max<std::size_t>(1, (invocations + kLocal - 1) / kLocal);
    const std::size_t x = std::min<std::size_t>(groups, 65535);
    glDispatchCompute(GLuint(x), GLuint((groups + x - 1) / x), 1);
    glMemoryBarrier(GL_ALL_BARRIER_BITS);
    for (GLuint b = 0; b <= kBoundaryBinding; ++b) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, b, 0);
    glUseProgram(0);
    checkGl("running a plain kernel");
}

void warmUp(const std::function<void()>& dispatch, double seconds) {
    const auto start = std::chrono::steady_clock::now();
    do {
        dispatch();
        glFinish();
    } while (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() < seconds);
}

} // namespace vds::bench
