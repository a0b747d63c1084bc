#include "plain_kernels.h"

#include <algorithm>
#include <chrono>
#include <string>

#include <GL/gl.h>
#include <GL/glext.h>

#include <vds/error.h>
#include <vds/gl/shader.h>

namespace vds::bench {
namespace {

constexpr GLuint kBoundaryBinding = 5;
constexpr std::uint32_t kLocal = 256;

// One invocation, four points (point 4q + k, k < u_count - 4q), one label
// word; VDS_PLAIN_GWN adds the boundary term summed over every edge. The
// parity kernel's forms: VDS_PLAIN_TEXEL reads the columns through buffer
// textures (the texture cache) instead of storage buffers; VDS_PLAIN_ONE
// takes one point an invocation and writes a 32-bit label, as a CUDA kernel
// of one thread a point would.
const char* const kSource = R"(
layout(local_size_x = 256) in;
#ifdef VDS_PLAIN_GWN
#define VDS_BOUNDARY_BINDING 5
#endif
#include "vds/vpt.glsl"
layout(std430, binding = 0) readonly buffer Points { float points[]; };
layout(std430, binding = 2) writeonly buffer Labels { uint labels[]; };
#ifdef VDS_PLAIN_TEXEL
layout(binding = 0) uniform usamplerBuffer u_offsets;
layout(binding = 1) uniform samplerBuffer u_crossings;
#define VDS_OFFSET(i) texelFetch(u_offsets, int(i)).x
#define VDS_CROSSING(i) texelFetch(u_crossings, int(i)).x
#else
layout(std430, binding = 3) readonly buffer Offsets { uint offsets[]; };
layout(std430, binding = 4) readonly buffer Crossings { float crossings[]; };
#define VDS_OFFSET(i) offsets[i]
#define VDS_CROSSING(i) crossings[i]
#endif
uniform ivec2 u_size;
uniform VdsPlacement u_placement;
uniform uint u_count;
#ifdef VDS_PLAIN_GWN
uniform VdsBoundary u_boundary;
#endif

bool inside(uint i) {
    vec3 T = vdsToTexture(u_placement, vec3(points[3u * i], points[3u * i + 1u], points[3u * i + 2u]));
    ivec2 column;
#ifdef VDS_PLAIN_GWN
    if (!vdsFinite(T)) return false;
    if (!vdsColumnAcross(T, u_size, column))
        return vdsEdgePairs(0, u_boundary.edgeCount, vdsBesidePoint(u_boundary, u_size, T)) / 12.566370614359172 > 0.5;
#else
    if (!vdsColumnOf(T, u_size, column)) return false;
#endif
    uint c = uint(column.y) * uint(u_size.x) + uint(column.x);
    int winding = 0, parity = 0;
    for (uint k = VDS_OFFSET(c), end = VDS_OFFSET(c + 1u); k < end; ++k) {
        float e = VDS_CROSSING(k);
        if (!(abs(e) < T.z)) break;
        parity ^= 1;
        winding += floatBitsToInt(e) < 0 ? -1 : 1;
    }
#ifdef VDS_PLAIN_GWN
    vec3 q = vdsColumnPoint(u_boundary, column, T.z);
    return float(winding) + vdsEdgePairs(0, u_boundary.edgeCount, q) / 12.566370614359172 > 0.5;
#else
    return parity != 0;
#endif
}

void main() {
    uint q = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * 256u + gl_LocalInvocationID.x;
#ifdef VDS_PLAIN_ONE
    if (q < u_count) labels[q] = inside(q) ? 1u : 0u;
#else
    if (q >= (u_count + 3u) / 4u) return;
    uint word = 0u;
    for (uint k = 0u; k < 4u; ++k)
        if (4u * q + k < u_count && inside(4u * q + k)) word |= 1u << (8u * k);
    labels[q] = word;
#endif
}
)";

const Program& program(const GlContext& gl, bool gwn, PlainForm form = {}) {
    const std::string name = std::string(gwn ? "bench.plain.gwn" : "bench.plain.parity") + (form.texel ? ".texel" : "") +
                             (form.onePoint ? ".one" : "");
    return gl.program(name, [gwn, form] {
        std::string defines = gwn ? "#define VDS_PLAIN_GWN\n" : "";
        if (form.texel) defines += "#define VDS_PLAIN_TEXEL\n";
        if (form.onePoint) defines += "#define VDS_PLAIN_ONE\n";
        return buildProgram({{GL_COMPUTE_SHADER, gwn ? "bench/plain_gwn.comp" : "bench/plain_parity.comp", kSource}},
                            defines);
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

PlainKernels::PlainKernels(const GlContext& gl)
    : gl_(&gl), parity_(&program(gl, false)), gwn_(&program(gl, true)) {}

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
    if (&program == gwn_) sprite.setBoundaryUniforms(id, "u_boundary", kBoundaryBinding);
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
