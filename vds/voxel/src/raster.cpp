#include "raster.h"

#include <algorithm>
#include <limits>

#include <GL/glext.h>

#include <vds/error.h>
#include <vds/gl/detail/buffers.h>

namespace vds::voxel::detail {

namespace {
MeshView checkedForStorage(const GlContext& gl, MeshView mesh) {
    const std::uint64_t limit = gl.limits().maxStorageBlockBytes;
    vds::detail::requireStorageSize(mesh.positionCount * sizeof(glm::vec3), limit, "the mesh positions");
    vds::detail::requireStorageSize(mesh.triangleCount * sizeof(glm::uvec3), limit, "the mesh indices");
    return mesh;
}
} // namespace

MeshBuffers::MeshBuffers(const GlContext& gl, MeshView mesh) : GpuMesh(checkedForStorage(gl, mesh)) {}

void setGridUniform(GLuint program, const std::string& name, const VoxelGrid& grid) {
    glProgramUniform3fv(program, glGetUniformLocation(program, (name + ".origin").c_str()), 1, &grid.box.lo[0]);
    glProgramUniform3fv(program, glGetUniformLocation(program, (name + ".scale").c_str()), 1, &grid.scale[0]);
    glProgramUniform3i(program, glGetUniformLocation(program, (name + ".size").c_str()), GLint(grid.dims.x),
                       GLint(grid.dims.y), GLint(grid.dims.z));
}

std::uint32_t rasterViewport(const VoxelGrid& grid) {
    std::uint32_t side = 1;
    while (side < std::max(grid.dims.x, grid.dims.y)) side *= 2;
    GLint dims[2] = {0, 0};
    glGetIntegerv(GL_MAX_VIEWPORT_DIMS, dims);
    if (side > std::uint32_t(std::min(dims[0], dims[1])))
        throw InvalidArgument("a " + std::to_string(grid.dims.x) + "x" + std::to_string(grid.dims.y) +
                              " column grid needs a " + std::to_string(side) +
                              " pixel viewport, more than GL allows here; lower the resolution");
    return side;
}

RasterState::RasterState(const VoxelGrid& grid, std::uint32_t viewport) {
    glViewport(0, 0, GLsizei(viewport), GLsizei(viewport));
    glEnable(GL_SCISSOR_TEST);
    glScissor(0, 0, GLsizei(grid.dims.x), GLsizei(grid.dims.y));
    glDisable(GL_CULL_FACE);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glDisable(GL_MULTISAMPLE);
    glEnable(GL_DEPTH_CLAMP);
    glFrontFace(GL_CW);
}

RasterState::~RasterState() {
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_DEPTH_CLAMP);
    glDisable(GL_COLOR_LOGIC_OP);
    glLogicOp(GL_COPY);
    glDisable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFunc(GL_ONE, GL_ZERO);
    glFrontFace(GL_CCW);
    glUseProgram(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

} // namespace vds::voxel::detail
