// vds: the auto axis counted in the GL bakers' own raster (layer_count.h's
// countLayersOnGl): the mesh drawn along each axis with the bake's vertex
// stage and raster state, each fragment counted in its column, the counts
// reduced on the GPU to d_S and the crossings; two words read back per axis.
// On a GPU that is a few milliseconds where the CPU's count takes a share
// of a core for every triangle and row.
#include <vds/gl/detail/layer_count.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <string>

#include <GL/glext.h>

#include <vds/error.h>
#include <vds/gl/bake.h>
#include <vds/gl/mesh.h>
#include <vds/gl/shader.h>
#include <vds/gl/detail/context.h>
#include <vds/gl/detail/dispatch.h>
#include <vds/gl/detail/raster_state.h>
#include <vds/mesh_check.h>

namespace vds::detail {

namespace {

constexpr std::uint32_t kReduceLocal = 256; // count_layers.comp's local_size_x
// The most GPU memory the three axes' counts take at once (a 4 bytes a
// column: three 2048² images are 48 MiB); larger counts share one buffer,
// axis after axis.
constexpr std::uint64_t kPendingCountBytes = std::uint64_t(256) << 20;

struct CountPrograms {
    const Program* raster;
    const Program* reduce;
};

CountPrograms countPrograms(const GlContext& gl) {
    const std::string defines = bakeDefines(gl);
    return {&gl.program("vds.count.raster",
                        [&] {
                            return buildProgram({{GL_VERTEX_SHADER, "vds/bake.vert", ""},
                                                 {GL_FRAGMENT_SHADER, "vds/count_layers.frag", ""}},
                                                defines);
                        }),
            &gl.program("vds.count.reduce",
                        [] { return buildProgram({{GL_COMPUTE_SHADER, "vds/count_layers.comp", ""}}); })};
}

// d_S and the crossings of the GL bake along `grid.axis`, into `result`
// (two words), issued and not waited for. Each axis has its own `counts`
// and `result`: a clear of counts a reduce still reads would race it (a
// memory barrier orders shader writes, not reads, before a clear).
void countAxis(const GlContext& gl, const CountPrograms& programs, const GpuMesh& mesh, const SpriteGrid& grid,
               GLuint counts, GLuint result) {
    const std::uint64_t columns = std::uint64_t(grid.width) * grid.height;
    const GLuint zero = 0;
    glClearNamedBufferSubData(counts, GL_R32UI, 0, GLsizeiptr(columns * 4), GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    glClearNamedBufferSubData(result, GL_R32UI, 0, 8, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    Framebuffer fbo = Framebuffer::create();
    glNamedFramebufferParameteri(fbo.id(), GL_FRAMEBUFFER_DEFAULT_WIDTH, GLint(grid.width));
    glNamedFramebufferParameteri(fbo.id(), GL_FRAMEBUFFER_DEFAULT_HEIGHT, GLint(grid.height));
    {
        const BakeRasterState state(gl, grid, programs.raster->id());
        glBindFramebuffer(GL_FRAMEBUFFER, fbo.id());
        glDisable(GL_DEPTH_TEST);
        glUniform1ui(glGetUniformLocation(programs.raster->id(), "u_width"), grid.width);
        glBindBufferRange(GL_SHADER_STORAGE_BUFFER, 0, counts, 0, GLsizeiptr(columns * 4));
        mesh.draw();
    }
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    glUseProgram(programs.reduce->id());
    glUniform1ui(glGetUniformLocation(programs.reduce->id(), "u_columns"), GLuint(columns));
    glBindBufferRange(GL_SHADER_STORAGE_BUFFER, 1, result, 0, 8);
    glDispatchCompute(strideGroups(columns, kReduceLocal), 1, 1);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, 0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, 0);
    glUseProgram(0);
    checkGl("counting the layers on the GPU");
}

} // namespace

std::optional<PendingLayerCount> PendingLayerCount::start(const GlContext& gl, const GpuMesh& drawn,
                                                          const Box& bounds, std::uint32_t resolution) {
    const CurrentContext current(gl);
    std::array<SpriteGrid, 3> grids;
    std::uint64_t most = 0;
    for (Axis axis : {Axis::X, Axis::Y, Axis::Z}) {
        grids[std::size_t(axis)] = makeGrid(bounds, axis, resolution);
        most = std::max(most, std::uint64_t(grids[std::size_t(axis)].width) * grids[std::size_t(axis)].height);
    }
    // The counts of one axis in one storage block; each fewer than 2^32 (as a sprite's crossings are).
    if (most * 4 > gl.limits().maxStorageBlockBytes || drawn.triangleCount() >= (std::uint64_t(1) << 32)) return std::nullopt;
    const CountPrograms programs = countPrograms(gl);
    static const char* const kCounts[3] = {"vds.count.columns.x", "vds.count.columns.y", "vds.count.columns.z"};
    static const char* const kResults[3] = {"vds.count.result.x", "vds.count.result.y", "vds.count.result.z"};
    PendingLayerCount pending(gl, resolution);
    // Three axes' counts at once up to kPendingCountBytes; past it one
    // buffer serves them in turn, each axis read back before the next clear.
    const bool atOnce = 3 * most * 4 <= kPendingCountBytes;
    for (std::size_t a = 0; a < 3; ++a) {
        const SpriteGrid& grid = grids[a];
        const GLuint counts = gl.scratchBuffer(kCounts[atOnce ? a : 0], std::size_t(most) * 4).id();
        pending.results_[a] = gl.scratchBuffer(kResults[a], 8).id();
        countAxis(gl, programs, drawn, grid, counts, pending.results_[a]);
        if (!atOnce) pending.read(a);
    }
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT); // the reduces' atomics before the read-back
    glFlush();                                     // the GPU starts while the host goes on
    return pending;
}

void PendingLayerCount::read(std::size_t a) {
    std::uint32_t out[2] = {0, 0};
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glGetNamedBufferSubData(results_[a], 0, 8, out);
    checkGl("reading the layer counts back");
    choice_.layers[a] = out[0];
    choice_.crossings[a] = out[1];
    read_[a] = true;
}

AxisChoice PendingLayerCount::finish() {
    const CurrentContext current(*gl_);
    for (std::size_t a = 0; a < 3; ++a)
        if (!read_[a]) read(a);
    choice_.resolution = resolution_;
    pickFewestLayers(choice_);
    return choice_;
}

std::optional<AxisChoice> countLayersOnGl(const GlContext& gl, MeshView mesh, const Box& bounds,
                                          std::uint32_t resolution) {
    const CurrentContext current(gl);
    return countLayersOnGl(gl, GpuMesh(mesh), bounds, resolution);
}

std::optional<AxisChoice> countLayersOnGl(const GlContext& gl, const GpuMesh& drawn, const Box& bounds,
                                          std::uint32_t resolution) {
    std::optional<PendingLayerCount> pending = PendingLayerCount::start(gl, drawn, bounds, resolution);
    if (!pending) return std::nullopt;
    return pending->finish();
}

bool countsOnGpu(const GlContext& gl) {
    const char* place = std::getenv("VDS_AXIS_COUNT");
    if (place && std::string(place) == "gpu") return true;
    if (place && std::string(place) == "cpu") return false;
    return !gl.info().software;
}

} // namespace vds::detail

namespace vds {

AxisChoice chooseViewAxisOnGl(const GlContext& gl, MeshView mesh, std::uint32_t resolution) {
    const MeshReport report = validateMesh(mesh);
    requireUsable(report, "mesh");
    requireVolume(report, "mesh");
    const std::optional<AxisChoice> counted = detail::countLayersOnGl(gl, mesh, report.bounds, resolution);
    return counted ? *counted : chooseViewAxis(mesh, report, resolution);
}

} // namespace vds
