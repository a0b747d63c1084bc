// Conservative surface voxelization in compute: Schwarz, "Practical Binary
// Surface and Solid Voxelization with Direct3D 11", GPU Pro 3, 2012, section
// 2.4 (the triangle/box overlap test of Schwarz & Seidel 2010). Shader:
// shaders/voxel/surface.comp.
#include <vds/voxel/surface.h>

#include <GL/glext.h>

#include <vds/error.h>
#include <vds/gl/shader.h>
#include <vds/mesh_check.h>

#include <vds/gl/detail/buffers.h>
#include <vds/gl/detail/dispatch.h>

#include "raster.h"

namespace vds::voxel {

BitGrid voxelizeSurface(const GlContext& gl, MeshView mesh, const VoxelGrid& grid) {
    requireUsable(validateMesh(mesh), "mesh");
    const CurrentContext current(gl); // the caller's context is current again on return
    const Program& program = gl.program("voxel.surface", [] {
        return buildProgram({{GL_COMPUTE_SHADER, "voxel/surface.comp", ""}});
    });
    BitGrid result = makeBitGrid(grid);
    const Buffer voxels = vds::detail::zeroedBuffer(result.memoryBytes(), gl.limits().maxStorageBlockBytes, "the surface voxel grid");
    const detail::MeshBuffers buffers(gl, mesh);
    detail::setGridUniform(program.id(), "u_grid", grid);
    glProgramUniform1ui(program.id(), glGetUniformLocation(program.id(), "u_triangleCount"),
                        GLuint(mesh.triangleCount));
    buffers.bindStorage();
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, voxels.id());
    glUseProgram(program.id());
    vds::detail::dispatchItems(mesh.triangleCount, 64);
    glMemoryBarrier(GL_ALL_BARRIER_BITS);
    glUseProgram(0);
    glGetNamedBufferSubData(voxels.id(), 0, GLsizeiptr(result.memoryBytes()), result.words.data());
    checkGl("conservative surface voxelization");
    return result;
}

} // namespace vds::voxel
