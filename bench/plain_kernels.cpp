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
// word; VDS_PLAIN_GWN adds the boundary term summed over every edge.
const char* const kSource = R"(
layout(local_size_x = 256) in;
#ifdef VDS_PLAIN_GWN
#define VDS_BOUNDARY_BINDING 5
#endif
#include "vds/vpt.glsl"
layout(std430, binding = 0) readonly buffer Points { float points[]; };
layout(std430, binding = 2) writeonly buffer Labels { uint labels[]; };
layout(std430, binding = 3) readonly buffer Offsets { uint offsets[]; };
layout(std430, binding = 4) readonly buffer Crossings { float crossings[]; };
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
    for (uint k = offsets[c]; k < offsets[c + 1u]; ++k) {
        float e = crossings[k];
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
    if (q >= (u_count + 3u) / 4u) return;
    uint word = 0u;
    for (uint k = 0u; k < 4u; ++k)
        if (4u * q + k < u_count && inside(4u * q + k)) word |= 1u << (8u * k);
    labels[q] = word;
}
)";

const Program& program(const GlContext& gl, bool gwn) {
    return gl.program(gwn ? "bench.plain.gwn" : "bench.plain.parity", [gwn] {
        return buildProgram({{GL_COMPUTE_SHADER, gwn ? "bench/plain_gwn.comp" : "bench/plain_parity.comp", kSource}},
                            gwn ? "#define VDS_PLAIN_GWN\n" : "");
    });
}

} // namespace

PlainKernels::PlainKernels(const GlContext& gl) : parity_(&program(gl, false)), gwn_(&program(gl, true)) {}

void PlainKernels::parity(const GpuSprite& sprite, GLuint points, std::size_t count, GLuint labels) const {
    run(*parity_, sprite, points, count, labels);
}

void PlainKernels::generalizedWinding(const GpuSprite& sprite, GLuint points, std::size_t count, GLuint labels) const {
    run(*gwn_, sprite, points, count, labels);
}

void PlainKernels::run(const Program& program, const GpuSprite& sprite, GLuint points, std::size_t count,
                       GLuint labels) const {
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
    const std::size_t groups = std::max<std::size_t>(1, ((count + 3) / 4 + kLocal - 1) / kLocal);
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
