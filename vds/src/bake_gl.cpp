// The GL bakers (Trapp & Döllner 2008, section 4.1).
//  - Depth peeling (Everitt 2001): one pass per layer, each keeping the
//    nearest crossing behind the previous layer; an occlusion query finds d_S.
//  - Per-pixel fragment lists (Yang et al. 2010, "Real-time concurrent linked
//    list construction on the GPU"): every crossing in one pass, then sorted
//    per pixel in a compute pass.
// Both rasterize the same triangles with the same transform and viewport, so
// they see the same fragments; both order equal depths by triangle index.
#include "bake_gl.h"

#include <algorithm>
#include <cstring>
#include <functional>
#include <limits>

#include <GL/glext.h>

#include <vds/error.h>
#include <vds/gpu_mesh.h>
#include <vds/shader.h>

namespace vds::detail {
namespace {

constexpr std::uint32_t kEnteringBit = 0x80000000u;
constexpr std::uint32_t kNoNode = 0xffffffffu;

float encodeKeyed(float depth, std::uint32_t key) { return encodeCrossing(depth, (key & kEnteringBit) != 0); }

bool hasClipControl(const GlContext& gl) {
    const GlInfo& i = gl.info();
    return i.major > 4 || (i.major == 4 && i.minor >= 5);
}

std::string bakeDefines(const GlContext& gl) { return hasClipControl(gl) ? "#define VDS_CLIP_CONTROL\n" : ""; }

void setRasterState(const GlContext& gl, const SpriteGrid& grid, GLuint program) {
    if (hasClipControl(gl)) glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
    glViewport(0, 0, GLsizei(grid.width), GLsizei(grid.height));
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    glDisable(GL_MULTISAMPLE);
    glEnable(GL_DEPTH_CLAMP); // crossings on the box's near and far faces must not be clipped
    glFrontFace(GL_CW);       // the view keeps handedness: clockwise = normal towards the viewer = entering
    glUseProgram(program);
    // At bake time, world = mesh coordinates: the grid's own placement.
    glUniformMatrix3fv(glGetUniformLocation(program, "u_placement.matrix"), 1, GL_FALSE, &grid.matrix[0][0]);
    glUniform3fv(glGetUniformLocation(program, "u_placement.position"), 1, &grid.position[0]);
}

void restoreState(const GlContext& gl) {
    if (hasClipControl(gl)) glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
    glDisable(GL_DEPTH_CLAMP);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_DEPTH_TEST);
    glFrontFace(GL_CCW);
    glUseProgram(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

Texture makeTexture2D(GLenum format, const SpriteGrid& grid) {
    Texture t = Texture::create(GL_TEXTURE_2D);
    glTextureStorage2D(t.id(), 1, format, GLsizei(grid.width), GLsizei(grid.height));
    glTextureParameteri(t.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(t.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    checkGl("allocating a bake target");
    return t;
}

void report(const BakeOptions& options, const std::string& what) {
    if (options.progress) options.progress(what);
}

} // namespace

void bakePeel(const GlContext& gl, MeshView mesh, const SpriteGrid& grid, const BakeOptions& options,
              std::vector<std::uint32_t>& offsets, std::vector<float>& crossings) {
    const Program& program = gl.program("vds.peel", [&] {
        return buildProgram({{GL_VERTEX_SHADER, "vds/bake.vert", ""}, {GL_FRAGMENT_SHADER, "vds/peel.frag", ""}},
                            bakeDefines(gl));
    });
    const GpuMesh draw(mesh);
    const std::size_t pixels = std::size_t(grid.width) * grid.height;
    Texture depth[2] = {makeTexture2D(GL_R32F, grid), makeTexture2D(GL_R32F, grid)};
    Texture key[2] = {makeTexture2D(GL_R32UI, grid), makeTexture2D(GL_R32UI, grid)};
    Texture depthBuffer = makeTexture2D(GL_DEPTH_COMPONENT32F, grid);
    Framebuffer fbo[2] = {Framebuffer::create(), Framebuffer::create()};
    const GLenum drawBuffers[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    for (int i = 0; i < 2; ++i) {
        glNamedFramebufferTexture(fbo[i].id(), GL_COLOR_ATTACHMENT0, depth[i].id(), 0);
        glNamedFramebufferTexture(fbo[i].id(), GL_COLOR_ATTACHMENT1, key[i].id(), 0);
        glNamedFramebufferTexture(fbo[i].id(), GL_DEPTH_ATTACHMENT, depthBuffer.id(), 0);
        glNamedFramebufferDrawBuffers(fbo[i].id(), 2, drawBuffers);
        if (glCheckNamedFramebufferStatus(fbo[i].id(), GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
            throw GlError("depth peeling framebuffer is incomplete");
    }
    Query query = Query::create(GL_ANY_SAMPLES_PASSED);

    setRasterState(gl, grid, program.id());
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    const GLint firstLayer = glGetUniformLocation(program.id(), "u_firstLayer");

    // Layer k's encoded crossings, one image per layer (padding where empty).
    std::vector<std::vector<float>> layers;
    std::vector<float> layerDepth(pixels);
    std::vector<std::uint32_t> layerKey(pixels);
    const float emptyDepth[4] = {2.0f, 0, 0, 0};
    const GLuint emptyKey[4] = {kNoNode, 0, 0, 0};
    const float farDepth = 1.0f;
    for (int pass = 0;; ++pass) {
        const int cur = pass & 1, prev = cur ^ 1;
        glBindFramebuffer(GL_FRAMEBUFFER, fbo[cur].id());
        glClearNamedFramebufferfv(fbo[cur].id(), GL_COLOR, 0, emptyDepth);
        glClearNamedFramebufferuiv(fbo[cur].id(), GL_COLOR, 1, emptyKey);
        glClearNamedFramebufferfv(fbo[cur].id(), GL_DEPTH, 0, &farDepth);
        glBindTextureUnit(0, depth[prev].id());
        glBindTextureUnit(1, key[prev].id());
        glUniform1i(firstLayer, pass == 0 ? 1 : 0);
        glBeginQuery(GL_ANY_SAMPLES_PASSED, query.id());
        draw.draw();
        glEndQuery(GL_ANY_SAMPLES_PASSED);
        GLuint any = 0;
        glGetQueryObjectuiv(query.id(), GL_QUERY_RESULT, &any);
        checkGl("depth peeling pass");
        if (!any) break;
        glGetTextureImage(depth[cur].id(), 0, GL_RED, GL_FLOAT, GLsizei(pixels * sizeof(float)), layerDepth.data());
        glGetTextureImage(key[cur].id(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, GLsizei(pixels * sizeof(std::uint32_t)),
                          layerKey.data());
        checkGl("reading a peeled layer");
        std::vector<float> layer(pixels, 2.0f);
        for (std::size_t p = 0; p < pixels; ++p)
            if (layerKey[p] != kNoNode) layer[p] = encodeKeyed(layerDepth[p], layerKey[p]);
        layers.push_back(std::move(layer));
        report(options, "peeled layer " + std::to_string(layers.size()));
    }
    glBindTextureUnit(0, 0);
    glBindTextureUnit(1, 0);
    restoreState(gl);

    offsets.assign(pixels + 1, 0);
    for (std::size_t p = 0; p < pixels; ++p) {
        std::uint32_t n = 0;
        while (n < layers.size() && layers[n][p] != 2.0f) ++n;
        offsets[p + 1] = offsets[p] + n;
    }
    crossings.resize(offsets.back());
    for (std::size_t p = 0; p < pixels; ++p)
        for (std::uint32_t k = 0; k < offsets[p + 1] - offsets[p]; ++k) crossings[offsets[p] + k] = layers[k][p];
}

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
        setRasterState(gl, grid, fill.id());
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
        GLuint used = 0;
        glGetNamedBufferSubData(counter.id(), 0, sizeof used, &used);
        restoreState(gl);
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
