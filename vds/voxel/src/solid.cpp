// Solid voxelization by rasterization and in compute: Schwarz, "Practical
// Binary Surface and Solid Voxelization with Direct3D 11", GPU Pro 3, 2012,
// sections 2.3 and 2.5. The shaders are shaders/voxel/solid*.
#include <vds/voxel/solid.h>

#include <GL/glext.h>

#include <vds/error.h>
#include <vds/gl/shader.h>

#include <vds/gl/detail/buffers.h>
#include <vds/gl/detail/dispatch.h>

#include "detail/solid.h"
#include "raster.h"

namespace vds::voxel {

SolidMethod parseSolidMethod(const std::string& s) { return parseEnum<SolidMethod>(s); }
const char* toString(SolidMethod m) { return enumName(m); }

namespace {

void rasterize(const GlContext& gl, const detail::MeshBuffers& mesh, const VoxelGrid& grid, const Buffer& voxels) {
    const Program& program = gl.program("voxel.solid.raster", [] {
        return buildProgram(
            {{GL_VERTEX_SHADER, "voxel/raster.vert", ""}, {GL_FRAGMENT_SHADER, "voxel/solid.frag", ""}});
    });
    const std::uint32_t viewport = detail::rasterViewport(grid);
    Framebuffer fbo = Framebuffer::create();
    glNamedFramebufferParameteri(fbo.id(), GL_FRAMEBUFFER_DEFAULT_WIDTH, GLint(grid.dims.x));
    glNamedFramebufferParameteri(fbo.id(), GL_FRAMEBUFFER_DEFAULT_HEIGHT, GLint(grid.dims.y));
    if (glCheckNamedFramebufferStatus(fbo.id(), GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        throw GlError("solid voxelization framebuffer is incomplete");
    detail::setGridUniform(program.id(), "u_grid", grid);
    glProgramUniform1f(program.id(), glGetUniformLocation(program.id(), "u_viewport"), float(viewport));
    {
        const detail::RasterState state(grid, viewport);
        glBindFramebuffer(GL_FRAMEBUFFER, fbo.id());
        glUseProgram(program.id());
        mesh.bindStorage();
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, voxels.id());
        mesh.draw();
        glMemoryBarrier(GL_ALL_BARRIER_BITS);
    }
    checkGl("solid voxelization by rasterization");
}

void computeFlips(const GlContext& gl, const detail::MeshBuffers& mesh, const VoxelGrid& grid, const Buffer& voxels) {
    const Program& flip = gl.program("voxel.solid.flip", [] {
        return buildProgram({{GL_COMPUTE_SHADER, "voxel/solid_flip.comp", ""}});
    });
    const Program& propagate = gl.program("voxel.solid.propagate", [] {
        return buildProgram({{GL_COMPUTE_SHADER, "voxel/solid_propagate.comp", ""}});
    });
    detail::setGridUniform(flip.id(), "u_grid", grid);
    glProgramUniform1ui(flip.id(), glGetUniformLocation(flip.id(), "u_triangleCount"), GLuint(mesh.triangleCount()));
    mesh.bindStorage();
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, voxels.id());
    glUseProgram(flip.id());
    vds::detail::dispatchItems(mesh.triangleCount(), 64);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    glProgramUniform3i(propagate.id(), glGetUniformLocation(propagate.id(), "u_size"), GLint(grid.dims.x),
                       GLint(grid.dims.y), GLint(grid.dims.z));
    glUseProgram(propagate.id());
    glDispatchCompute((grid.dims.x + 7) / 8, (grid.dims.y + 7) / 8, 1);
    glMemoryBarrier(GL_ALL_BARRIER_BITS);
    glUseProgram(0);
    checkGl("solid voxelization in compute");
}

} // namespace

BitGrid voxelizeSolid(const GlContext& gl, MeshView mesh, const VoxelGrid& grid, SolidMethod method) {
    requireClosed(mesh, "mesh");
    return detail::voxelizeClosed(gl, mesh, grid, method);
}

namespace detail {

BitGrid voxelizeClosed(const GlContext& gl, MeshView mesh, const VoxelGrid& grid, SolidMethod method) {
    const CurrentContext current(gl); // the caller's context is current again on return
    BitGrid result = makeBitGrid(grid);
    const Buffer voxels = vds::detail::zeroedBuffer(result.memoryBytes(), gl.limits().maxStorageBlockBytes, "the solid voxel grid");
    const detail::MeshBuffers buffers(gl, mesh);
    if (method == SolidMethod::Raster)
        rasterize(gl, buffers, grid, voxels);
    else
        computeFlips(gl, buffers, grid, voxels);
    glGetNamedBufferSubData(voxels.id(), 0, GLsizeiptr(result.memoryBytes()), result.words.data());
    checkGl("reading the solid voxel grid");
    return result;
}

} // namespace detail

} // namespace vds::voxel
