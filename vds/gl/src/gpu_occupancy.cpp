// vds: occupancy grids on the GPU (see <vds/gl/occupancy.h>): the sprite
// sweep of occupancy.cpp (Trapp & Döllner 2008, section 3.2, for a whole
// column of cells at once) with the walk down each column in
// shaders/vds/occupancy.comp. The per-column texels and per-slice depths
// are computed here, on the CPU, exactly as occupancy.cpp computes them.
// Rule::GeneralizedWinding on an open sprite adds vpt.glsl's boundary term
// per cell in the shader, where the CPU classifies the cells one by one.
#include <vds/gl/occupancy.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <vds/error.h>
#include <vds/gl/shader.h>

#include "bake_gl.h"

namespace vds {

namespace {

constexpr std::uint32_t kLocalSize = 64;    // occupancy.comp's local_size_x
constexpr GLuint kBoundaryBinding = 5;     // occupancy.comp's VDS_BOUNDARY_BINDING

// The texel column of a texture-space point, or -1 outside (Sprite::contains's rule).
std::int32_t texelOf(const SpriteGrid& grid, const glm::vec3& t) {
    if (!(t.z >= 0.0f && t.z <= 1.0f)) return -1;
    const float fs = std::floor(t.x * float(grid.width));
    const float ft = std::floor(t.y * float(grid.height));
    if (!(fs >= 0.0f && fs < float(grid.width) && ft >= 0.0f && ft < float(grid.height))) return -1;
    return std::int32_t(ft) * std::int32_t(grid.width) + std::int32_t(fs);
}

Buffer upload(const void* data, std::size_t bytes, const char* what) {
    Buffer b = Buffer::create();
    glNamedBufferStorage(b.id(), GLsizeiptr(std::max<std::size_t>(bytes, 4)), bytes ? data : nullptr, 0);
    checkGl(what);
    return b;
}

} // namespace

GpuOccupancy::GpuOccupancy(const GlContext& gl) : gl_(&gl) {
    const CurrentContext current(gl);
    stamp_ = detail::ContextStamp::current("GpuOccupancy");
    program_ = &gl.program("vds.occupancy", [] { return buildProgram({{GL_COMPUTE_SHADER, "vds/occupancy.comp", ""}}); });
    GLint64 maxBlock = 0;
    glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &maxBlock);
    maxBlock_ = std::uint64_t(maxBlock);
}

void GpuOccupancy::occupancy(const GpuSprite& sprite, const Grid& grid, GLuint cells, const ClassifyOptions& options) {
    stamp_.checkThread("GpuOccupancy::occupancy");
    const CurrentContext current(*gl_);
    sprite.requireContext("GpuOccupancy::occupancy: the sprite");
    sweep(sprite, grid, cells, options);
}

void GpuOccupancy::sweep(const GpuSprite& sprite, const Grid& grid, GLuint cells, const ClassifyOptions& options) {
    const Rule rule = options.rule;
    checkGrid(grid);
    if (rule == Rule::GeneralizedWinding && !sprite.boundaryKnown())
        throw InvalidArgument("this sprite of an open mesh was written by .vds format version 1, which does not "
                              "store the boundary edges the generalized winding number needs: bake it again");
    if (!sprite.hasColumns()) throw InvalidArgument("GpuOccupancy: the sprite has no columns in GL");
    if (grid.cellCount() > (std::uint64_t(1) << 32))
        throw InvalidArgument("GpuOccupancy: at most 2^32 cells (use vds::occupancy on the CPU)");
    if (labelBytes(grid) > maxBlock_)
        throw InvalidArgument("GpuOccupancy: " + std::to_string(labelBytes(grid)) +
                              " bytes of labels exceed GL's largest shader storage block (" +
                              std::to_string(maxBlock_) + ")");
    // The sprite's placement as a grid, and its view axis: the world axis
    // its depth follows. The sweep needs s, t and r to follow one axis each.
    SpriteGrid sg;
    sg.width = sprite.size().x;
    sg.height = sprite.size().y;
    sg.matrix = sprite.matrix();
    sg.position = sprite.position();
    int a = -1;
    for (int col = 0; col < 3; ++col)
        if (sg.matrix[col][2] > 0.0f) a = col;
    bool aligned = a >= 0;
    if (aligned) {
        sg.axis = Axis(a); // axisPermutation(X).z = 0, Y: 1, Z: 2
        const glm::ivec3 p = axisPermutation(sg.axis);
        for (int row = 0; row < 3; ++row)
            for (int col = 0; col < 3; ++col)
                if (col != p[row] && sg.matrix[col][row] != 0.0f) aligned = false;
    }
    if (!aligned)
        throw InvalidArgument("GpuOccupancy: the sprite is rotated against the grid (use vds::occupancy on the CPU)");
    const glm::ivec3 p = axisPermutation(sg.axis);
    const int u = p.x, v = p.y;
    const std::uint32_t n = grid.dims[a];

    // As occupancy.cpp: one depth per slice, shared by every column.
    const auto centre = [&](int axis, std::uint32_t index) {
        glm::uvec3 c(0u);
        c[axis] = index;
        return grid.cellCentre(c.x, c.y, c.z)[axis];
    };
    std::vector<float> depth(n);
    glm::vec3 probe = sg.position;
    for (std::uint32_t k = 0; k < n; ++k) {
        probe[a] = centre(a, k);
        depth[k] = sg.toTexture(probe).z;
    }
    const auto firstSlice = std::uint32_t(std::lower_bound(depth.begin(), depth.end(), 0.0f) - depth.begin());
    const auto endSlice = std::uint32_t(std::upper_bound(depth.begin(), depth.end(), 1.0f) - depth.begin());
    const std::size_t columns = std::size_t(grid.dims[u]) * grid.dims[v];
    std::vector<std::int32_t> texels(columns, -1);
    if (firstSlice < endSlice) {
        std::vector<float> acrossV(grid.dims[v]);
        for (std::uint32_t j = 0; j < grid.dims[v]; ++j) acrossV[j] = centre(v, j);
        for (std::uint32_t i = 0; i < grid.dims[u]; ++i) {
            glm::vec3 world;
            world[u] = centre(u, i);
            world[a] = centre(a, firstSlice);
            for (std::uint32_t j = 0; j < grid.dims[v]; ++j) {
                world[v] = acrossV[j];
                texels[std::size_t(i) * grid.dims[v] + j] = texelOf(sg, sg.toTexture(world));
            }
        }
    }
    const Buffer texelBuffer = upload(texels.data(), texels.size() * 4, "uploading the occupancy columns");
    const Buffer depthBuffer = upload(depth.data(), depth.size() * 4, "uploading the occupancy depths");
    const glm::uvec3 stride(grid.dims.y * grid.dims.z, grid.dims.z, 1u);

    const GLuint zero = 0;
    glClearNamedBufferSubData(cells, GL_R32UI, 0, GLsizeiptr(labelBytes(grid)), GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    const GLuint id = program_->id();
    glUseProgram(id);
    const std::uint64_t offsetBytes = (std::uint64_t(sg.width) * sg.height + 1) * 4;
    glBindBufferRange(GL_SHADER_STORAGE_BUFFER, 0, sprite.offsets().id(), 0, GLsizeiptr(offsetBytes));
    glBindBufferRange(GL_SHADER_STORAGE_BUFFER, 1, sprite.crossings().id(), 0,
                      GLsizeiptr(std::max<std::uint64_t>(sprite.crossingCount(), 1) * 4));
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, texelBuffer.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, depthBuffer.id());
    glBindBufferRange(GL_SHADER_STORAGE_BUFFER, 4, cells, 0, GLsizeiptr(labelBytes(grid)));
    glUniform1ui(glGetUniformLocation(id, "u_columns"), GLuint(columns));
    glUniform1ui(glGetUniformLocation(id, "u_dimV"), grid.dims[v]);
    glUniform1ui(glGetUniformLocation(id, "u_strideU"), stride[u]);
    glUniform1ui(glGetUniformLocation(id, "u_strideV"), stride[v]);
    glUniform1ui(glGetUniformLocation(id, "u_step"), stride[a]);
    glUniform1ui(glGetUniformLocation(id, "u_firstSlice"), firstSlice);
    glUniform1ui(glGetUniformLocation(id, "u_endSlice"), endSlice);
    glUniform1ui(glGetUniformLocation(id, "u_width"), sg.width);
    // With no boundary edges (a mesh that bounds a solid) the generalized
    // winding number is the winding number: the plain sweep.
    const bool boundaryTerm = rule == Rule::GeneralizedWinding && sprite.boundaryEdgeCount() > 0;
    if (boundaryTerm) sprite.setBoundaryUniforms(id, "u_boundary", kBoundaryBinding);
    glUniform1i(glGetUniformLocation(id, "u_rule"), boundaryTerm ? 2 : rule == Rule::Parity ? 0 : 1);
    glDispatchCompute(detail::strideGroups(columns, kLocalSize), 1, 1);
    for (GLuint binding = 0; binding <= kBoundaryBinding; ++binding) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, 0);
    glUseProgram(0);
    checkGl("running the occupancy sweep");
    // The small buffers may go: GL keeps them alive until the dispatch is done.
}

void GpuOccupancy::occupancy(const GpuSprite& sprite, const Grid& grid, std::uint8_t* cells,
                             const ClassifyOptions& options) {
    stamp_.checkThread("GpuOccupancy::occupancy");
    const CurrentContext current(*gl_);
    sprite.requireContext("GpuOccupancy::occupancy: the sprite");
    checkGrid(grid);
    const std::size_t bytes = labelBytes(grid);
    Buffer out = Buffer::create();
    glNamedBufferStorage(out.id(), GLsizeiptr(std::max<std::size_t>(bytes, 4)), nullptr, 0);
    checkGl("allocating the occupancy labels");
    sweep(sprite, grid, out.id(), options);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glGetNamedBufferSubData(out.id(), 0, GLsizeiptr(grid.cellCount()), cells);
    checkGl("reading the occupancy labels");
}

} // namespace vds
