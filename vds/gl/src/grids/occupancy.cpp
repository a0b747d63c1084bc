// vds: occupancy grids on the GPU (see <vds/gl/occupancy.h>): the sprite
// sweep of occupancy.cpp (Trapp & Döllner 2008, section 3.2, for a whole
// column of cells at once) with the walk down each column in
// shaders/vds/occupancy.comp. The per-column texels and per-slice depths
// come from the one sweep plan the CPU sweep consumes too (detail::planSweep).
// Rule::GeneralizedWinding on an open sprite adds vpt.glsl's boundary term
// per cell in the shader, where the CPU classifies the cells one by one.
#include <vds/gl/occupancy.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include <vds/error.h>
#include <vds/detail/sweep_plan.h>
#include <vds/gl/shader.h>

#include <vds/gl/detail/buffers.h>
#include <vds/gl/detail/dispatch.h>

namespace vds {

namespace {

constexpr std::uint32_t kLocalSize = 64;    // occupancy.comp's local_size_x
constexpr GLuint kBoundaryBinding = 5;     // occupancy.comp's VDS_BOUNDARY_BINDING
constexpr GLuint kColumnPointsBinding = 6; // occupancy.comp's ColumnPoints


// The generalized winding number everywhere (as the CPU's Sprite::classify
// answers it): each grid column's texel by the sprite's "across" rule (in
// front of and behind the box too; -1 beside the texture) and its texture
// (s, t), where a column beside the texture takes the boundary term at the
// cell itself. The texture point of a column's first cell: the sprite
// follows the grid's axes, so s and t are the same in every slice.
struct AcrossColumns {
    std::vector<std::int32_t> texels;
    std::vector<glm::vec2> st;
};

AcrossColumns acrossColumns(const SpriteGrid& sg, const Grid& grid, const detail::SweepPlan& plan) {
    AcrossColumns out;
    out.texels.resize(plan.columns);
    out.st.resize(plan.columns);
    const float w = float(sg.width), h = float(sg.height);
    for (std::size_t column = 0; column < plan.columns; ++column) {
        const glm::uvec3 c = plan.firstCell(column, grid);
        const glm::vec3 t = sg.toTexture(grid.cellCentre(c.x, c.y, c.z));
        const float xs = t.x * w, ys = t.y * h;
        const bool in = xs >= 0.0f && xs < w && ys >= 0.0f && ys < h;
        out.texels[column] = in ? std::int32_t(std::uint32_t(ys) * sg.width + std::uint32_t(xs)) : -1;
        out.st[column] = glm::vec2(t.x, t.y);
    }
    return out;
}

// The labels' index steps along x, y and z: (i * dims.y + j) * dims.z + k.
glm::uvec3 labelStrides(const Grid& grid) { return {grid.dims.y * grid.dims.z, grid.dims.z, 1u}; }

// The sweep's uniforms: where each column's cells lie in the labels, and
// which slices it walks (every one where the boundary term counts).
void setSweepUniforms(GLuint id, const Grid& grid, const detail::SweepPlan& plan, const SpriteGrid& sg,
                      bool boundaryTerm) {
    const glm::uvec3 stride = labelStrides(grid);
    glUniform1ui(glGetUniformLocation(id, "u_columns"), GLuint(plan.columns));
    glUniform1ui(glGetUniformLocation(id, "u_dimV"), grid.dims[plan.v]);
    glUniform1ui(glGetUniformLocation(id, "u_strideU"), stride[plan.u]);
    glUniform1ui(glGetUniformLocation(id, "u_strideV"), stride[plan.v]);
    glUniform1ui(glGetUniformLocation(id, "u_step"), stride[plan.a]);
    glUniform1ui(glGetUniformLocation(id, "u_firstSlice"), boundaryTerm ? 0u : plan.firstSlice);
    glUniform1ui(glGetUniformLocation(id, "u_endSlice"), boundaryTerm ? plan.n : plan.endSlice);
    glUniform1ui(glGetUniformLocation(id, "u_width"), sg.width);
    glUniform1ui(glGetUniformLocation(id, "u_dimU"), grid.dims[plan.u]);
    if (!boundaryTerm) // quads along v: how many a row of v holds (occupancy.comp's vdsQuadColumn)
        glUniform1ui(glGetUniformLocation(id, "u_quads"), (grid.dims[plan.v] + 3) / 4);
    glUniform2i(glGetUniformLocation(id, "u_size"), GLint(sg.width), GLint(sg.height));
}

} // namespace

// The sweep of one rule and form (occupancy.comp), chosen at compile time:
// the generalized winding number's boundary term, and each sweep's walk
// (quads of columns along the labels' fastest axis where the sweep does not
// follow it, else single columns), are compiled into their own programs.
const Program& GpuOccupancy::program(Rule rule, Sweep sweep) const {
    static const char* const kSweeps[3] = {"columns", "quads.v", "quads.u"};
    const int id = rule == Rule::Parity ? 0 : rule == Rule::Winding ? 1 : 2;
    return gl_->program(std::string("vds.occupancy.") + toString(rule) + "." + kSweeps[int(sweep)], [id, sweep] {
        std::string defines = "#define VDS_RULE_ID " + std::to_string(id) + "\n";
        if (id == 2) defines += "#define VDS_BOUNDARY_TERM\n";
        if (sweep == Sweep::QuadsAlongV) defines += "#define VDS_SWEEP_QUADS_ALONG_V\n";
        if (sweep == Sweep::QuadsAlongU) defines += "#define VDS_SWEEP_QUADS_ALONG_U\n";
        return buildProgram({{GL_COMPUTE_SHADER, "vds/occupancy.comp", ""}}, defines);
    });
}

GpuOccupancy::GpuOccupancy(const GlContext& gl) : gl_(&gl) {
    const CurrentContext current(gl);
    stamp_ = ContextStamp::current("GpuOccupancy");
    program(Rule::Parity, Sweep::Columns); // a shader error shows at construction, not at the first call
    maxBlock_ = gl.limits().maxStorageBlockBytes;
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
    if (rule == Rule::GeneralizedWinding && !sprite.boundary().known())
        throw InvalidArgument("this sprite of an open mesh was written by .vds format version 1, which does not "
                              "store the boundary edges the generalized winding number needs: bake it again");
    if (!bool(sprite.offsets())) throw InvalidArgument("GpuOccupancy: the sprite has no columns in GL");
    if (grid.cellCount() > (std::uint64_t(1) << 32))
        throw InvalidArgument("GpuOccupancy: at most 2^32 cells (use vds::occupancy on the CPU)");
    if (labelBytes(grid) > maxBlock_)
        throw InvalidArgument("GpuOccupancy: " + std::to_string(labelBytes(grid)) +
                              " bytes of labels exceed GL's largest shader storage block (" +
                              std::to_string(maxBlock_) + ")");
    // The sprite's placement as a grid: the same sweep plan as the CPU's
    // (occupancy.cpp), so both give the same labels by construction.
    SpriteGrid sg;
    sg.width = sprite.size().x;
    sg.height = sprite.size().y;
    sg.matrix = sprite.matrix();
    sg.position = sprite.position();
    const detail::SweepPlan plan = detail::planSweep(sg, grid, options.threads);
    if (!plan.aligned)
        throw InvalidArgument("GpuOccupancy: the sprite is rotated against the grid (use vds::occupancy on the CPU)");
    // With no boundary edges (a mesh that bounds a solid) the generalized
    // winding number is the winding number: the plain sweep, over the
    // sprite's columns and depth range; with them every cell counts.
    const bool boundaryTerm = rule == Rule::GeneralizedWinding && sprite.boundary().edgeCount() > 0;
    const AcrossColumns across = boundaryTerm ? acrossColumns(sg, grid, plan) : AcrossColumns{};
    const std::vector<std::int32_t>& texels = boundaryTerm ? across.texels : plan.texels;
    const Buffer texelBuffer = detail::uploadBuffer(texels.data(), texels.size() * 4, "uploading the occupancy columns");
    const Buffer depthBuffer = detail::uploadBuffer(plan.depth.data(), plan.depth.size() * 4, "uploading the occupancy depths");
    const Buffer stBuffer = detail::uploadBuffer(across.st.data(), across.st.size() * 8, "uploading the occupancy columns");

    const GLuint zero = 0;
    glClearNamedBufferSubData(cells, GL_R32UI, 0, GLsizeiptr(labelBytes(grid)), GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    const glm::uvec3 stride = labelStrides(grid);
    const Sweep walk = boundaryTerm            ? Sweep::Columns
                       : stride[plan.v] == 1 ? Sweep::QuadsAlongV
                       : stride[plan.u] == 1 ? Sweep::QuadsAlongU
                                             : Sweep::Columns;
    const GLuint id = program(boundaryTerm || rule == Rule::Parity ? rule : Rule::Winding, walk).id();
    glUseProgram(id);
    const std::uint64_t offsetBytes = (std::uint64_t(sg.width) * sg.height + 1) * 4;
    glBindBufferRange(GL_SHADER_STORAGE_BUFFER, 0, sprite.offsets().id(), 0, GLsizeiptr(offsetBytes));
    glBindBufferRange(GL_SHADER_STORAGE_BUFFER, 1, sprite.crossings().id(), 0,
                      GLsizeiptr(std::max<std::uint64_t>(sprite.crossingCount(), 1) * 4));
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, texelBuffer.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, depthBuffer.id());
    glBindBufferRange(GL_SHADER_STORAGE_BUFFER, 4, cells, 0, GLsizeiptr(labelBytes(grid)));
    setSweepUniforms(id, grid, plan, sg, boundaryTerm);
    if (boundaryTerm) {
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kColumnPointsBinding, stBuffer.id());
        sprite.boundary().setUniforms(id, "u_boundary", kBoundaryBinding);
    }
    glDispatchCompute(detail::strideGroups(plan.columns, kLocalSize), 1, 1);
    for (GLuint binding = 0; binding <= kColumnPointsBinding; ++binding) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, 0);
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
