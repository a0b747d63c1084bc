// The fragment-list baker (Trapp & Döllner 2008, section 4.1, in one pass:
// Yang et al. 2010, "Real-time concurrent linked list construction on the
// GPU"): every crossing appended to a per-pixel list, then counted and sorted
// per pixel in compute passes. When the node pool overflows it is grown, then
// the image is baked in row bands; no crossing is ever dropped.
#include "bake_gl.h"

#include <algorithm>
#include <cstring>
#include <functional>

#include <GL/glext.h>

#include <vds/error.h>
#include <vds/gpu_mesh.h>
#include <vds/shader.h>

namespace vds::detail {

void bakeLists(const GlContext& gl, MeshView mesh, const SpriteGrid& grid, const BakeOptions& options,
               std::vector<std::uint32_t>& offsets, std::vector<float>& crossings) {
    const std::string defines = bakeDefines(gl);
    const Program& fill = gl.program("vds.lists.fill", [&] {
        return buildProgram({{GL_VERTEX_SHADER, "vds/bake.vert", ""}, {GL_FRAGMENT_SHADER, "vds/lists.frag", ""}},
                            defines);
    });
    const Program& count = gl.program("vds.lists.count", [&] {
        return buildProgram({{GL_COMPUTE_SHADER, "vds/lists_sort.comp", ""}}, "#define VDS_COUNT\n");
    });
    const Program& sort = gl.program("vds.lists.sort", [&] {
        return buildProgram({{GL_COMPUTE_SHADER, "vds/lists_sort.comp", ""}}, "");
    });

    GLint64 maxBlock = 0;
    glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &maxBlock);
    std::uint64_t maxNodes = std::uint64_t(maxBlock) / 12;
    if (options.maxListNodes) maxNodes = std::min<std::uint64_t>(maxNodes, options.maxListNodes);
    maxNodes = std::min<std::uint64_t>(maxNodes, 0xfffffff0u);

    const GpuMesh draw(mesh);
    Texture heads = makeTexture2D(GL_R32UI, grid);
    Buffer counter = Buffer::create();
    glNamedBufferStorage(counter.id(), sizeof(GLuint), nullptr, GL_DYNAMIC_STORAGE_BIT);
    Framebuffer fbo = Framebuffer::create();
    glNamedFramebufferParameteri(fbo.id(), GL_FRAMEBUFFER_DEFAULT_WIDTH, GLint(grid.width));
    glNamedFramebufferParameteri(fbo.id(), GL_FRAMEBUFFER_DEFAULT_HEIGHT, GLint(grid.height));
    if (glCheckNamedFramebufferStatus(fbo.id(), GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        throw GlError("fragment list framebuffer is incomplete");

    std::uint64_t capacity = std::min<std::uint64_t>(maxNodes, std::uint64_t(grid.width) * grid.height * 2 + 1024);
    Buffer nodes;
    auto allocateNodes = [&] {
        nodes = Buffer::create();
        glNamedBufferStorage(nodes.id(), GLsizeiptr(capacity * 12), nullptr, 0);
        checkGl("allocating the fragment node pool");
    };
    allocateNodes();

    offsets.assign(1, 0);
    crossings.clear();
    const GLint capacityLoc = glGetUniformLocation(fill.id(), "u_capacity");

    // Bakes rows [y0, y1); appends their columns. Splits the band when the
    // node pool cannot hold its fragments.
    std::function<void(std::uint32_t, std::uint32_t)> band = [&](std::uint32_t y0, std::uint32_t y1) {
        const GLuint noNode = kNoNode;
        glClearTexImage(heads.id(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &noNode);
        const GLuint zero = 0;
        glNamedBufferSubData(counter.id(), 0, sizeof zero, &zero);
        GLuint used = 0;
        {
        const BakeRasterState state(gl, grid, fill.id());
        glBindFramebuffer(GL_FRAMEBUFFER, fbo.id());
        glDisable(GL_DEPTH_TEST);
        glEnable(GL_SCISSOR_TEST);
        glScissor(0, GLint(y0), GLsizei(grid.width), GLsizei(y1 - y0));
        glUniform1ui(capacityLoc, GLuint(capacity));
        glBindImageTexture(0, heads.id(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
        glBindBufferBase(GL_ATOMIC_COUNTER_BUFFER, 0, counter.id());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, nodes.id());
        draw.draw();
        glMemoryBarrier(GL_ALL_BARRIER_BITS);
        glGetNamedBufferSubData(counter.id(), 0, sizeof used, &used);
        }
        checkGl("fragment list pass");
        if (used > capacity) {
            if (used <= maxNodes) {
                capacity = used;
                allocateNodes();
                report(options, "fragment lists: node pool grown to " + std::to_string(capacity));
                band(y0, y1);
            } else if (y1 - y0 > 1) {
                const std::uint32_t mid = y0 + (y1 - y0) / 2;
                report(options, "fragment lists: baking rows in bands");
                band(y0, mid);
                band(mid, y1);
            } else {
                throw OutOfMemory("one row of the image has " + std::to_string(used) +
                                  " crossings, more than a GL buffer holds; lower the resolution");
            }
            return;
        }
        // Count per pixel, prefix-sum on the host, then copy and sort per pixel.
        const std::size_t columns = std::size_t(grid.width) * (y1 - y0);
        Buffer counts = Buffer::create();
        glNamedBufferStorage(counts.id(), GLsizeiptr(columns * sizeof(GLuint)), nullptr, GL_DYNAMIC_STORAGE_BIT);
        glBindImageTexture(0, heads.id(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_R32UI);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, nodes.id());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, counts.id());
        const GLuint groupsX = (grid.width + 15) / 16, groupsY = (y1 - y0 + 15) / 16;
        glUseProgram(count.id());
        glUniform2i(glGetUniformLocation(count.id(), "u_size"), GLint(grid.width), GLint(grid.height));
        glUniform1i(glGetUniformLocation(count.id(), "u_rowBegin"), GLint(y0));
        glDispatchCompute(groupsX, groupsY, 1);
        glMemoryBarrier(GL_ALL_BARRIER_BITS);
        std::vector<GLuint> n(columns);
        glGetNamedBufferSubData(counts.id(), 0, GLsizeiptr(columns * sizeof(GLuint)), n.data());
        std::vector<GLuint> start(columns);
        std::uint64_t total = 0;
        for (std::size_t c = 0; c < columns; ++c) {
            start[c] = GLuint(total);
            total += n[c];
        }
        if (crossings.size() + total > 0xffffffffull) throw OutOfMemory("sprite has more than 2^32 crossings");
        glNamedBufferSubData(counts.id(), 0, GLsizeiptr(columns * sizeof(GLuint)), start.data());
        Buffer sorted = Buffer::create();
        glNamedBufferStorage(sorted.id(), GLsizeiptr(std::max<std::uint64_t>(total, 1) * 8), nullptr, 0);
        checkGl("allocating the sorted crossings");
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, sorted.id());
        glUseProgram(sort.id());
        glUniform2i(glGetUniformLocation(sort.id(), "u_size"), GLint(grid.width), GLint(grid.height));
        glUniform1i(glGetUniformLocation(sort.id(), "u_rowBegin"), GLint(y0));
        glDispatchCompute(groupsX, groupsY, 1);
        glMemoryBarrier(GL_ALL_BARRIER_BITS);
        std::vector<std::uint32_t> pairs(total * 2);
        if (total) glGetNamedBufferSubData(sorted.id(), 0, GLsizeiptr(total * 8), pairs.data());
        glUseProgram(0);
        checkGl("sorting fragment lists");
        const std::size_t base = crossings.size();
        crossings.resize(base + total);
        for (std::uint64_t k = 0; k < total; ++k) {
            float depth;
            std::memcpy(&depth, &pairs[2 * k], sizeof depth);
            crossings[base + k] = encodeKeyed(depth, pairs[2 * k + 1]);
        }
        for (std::size_t c = 0; c < columns; ++c) offsets.push_back(offsets.back() + n[c]);
        report(options, "fragment lists: rows " + std::to_string(y1) + " of " + std::to_string(grid.height));
    };
    band(0, grid.height);
}

} // namespace vds::detail
