// vds::voxel internal: GL plumbing the voxelizers share (mesh upload, grid
// uniforms, the rasterization set-up of voxel/raster.vert, dispatch sizes).
#pragma once

#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <string>
#include <vector>

#include <GL/gl.h>

#include <vds/gl/context.h>
#include <vds/gl/objects.h>
#include <vds/gl/mesh.h>
#include <vds/mesh.h>
#include <vds/gl/shader.h>
#include <vds/voxel/grid.h>

namespace vds::voxel::detail {

/// The mesh on the GPU (vds::GpuMesh), checked first to fit the shader
/// storage of voxel/triangles.glsl (`bindStorage`).
struct MeshBuffers : GpuMesh {
    explicit MeshBuffers(MeshView mesh);
};

/// Sets the VdsVoxelGrid uniform `name` of `program` (in use).
void setGridUniform(GLuint program, const std::string& name, const VoxelGrid& grid);

/// Side of the square power-of-two viewport that holds the grid's columns
/// (see voxel/raster.vert). Throws `InvalidArgument` past GL_MAX_VIEWPORT_DIMS.
std::uint32_t rasterViewport(const VoxelGrid& grid);

/// GL state for rasterizing into voxel columns: viewport, scissor to the
/// grid, no culling, depth test or clipping in depth, front faces clockwise
/// (gl_FrontFacing = the ray towards +z enters the solid). On destruction
/// these, and the blending and logic-op state a pass may have set, go back
/// to GL's defaults.
class RasterState {
public:
    RasterState(const VoxelGrid& grid, std::uint32_t viewport);
    ~RasterState();
    RasterState(const RasterState&) = delete;
    RasterState& operator=(const RasterState&) = delete;
};

/// Throws `OutOfMemory` if `bytes` exceed what one shader storage buffer may
/// hold on this context; `what` names the buffer.
void requireStorageSize(std::size_t bytes, const std::string& what);

/// Storage buffer of `bytes`, zeroed, for GPU read and write.
Buffer zeroedBuffer(std::size_t bytes, const char* what);

/// Dispatches `count` invocations of a 1D compute shader whose local size is
/// `local`; the shader indexes them as gl_GlobalInvocationID.y *
/// gl_NumWorkGroups.x * gl_WorkGroupSize.x + gl_GlobalInvocationID.x.
void dispatchLinear(std::size_t count, std::uint32_t local);

/// What one draw cost: GL_TIME_ELAPSED, and the wall clock to glFinish.
struct DrawTimes {
    double gpuMilliseconds = 0.0;
    double wallMilliseconds = 0.0;
};

/// Draws the bound vertex array's first triangle (a full-screen triangle)
/// twice, timing the second: drivers compile shader variants at their first
/// draw (llvmpipe does), which is no part of a frame's cost. `what` names the
/// pass in GL errors.
DrawTimes timedFullScreenDraw(const char* what);

/// The colour targets of the casters' full-screen draws (a receiver plane,
/// a view): one 2D texture of each format, `width` x `height`, attached in
/// order to one framebuffer that draws into all of them.
class PlaneTargets {
public:
    /// Throws `GlError` naming `what` if the framebuffer is incomplete.
    PlaneTargets(std::initializer_list<GLenum> formats, GLsizei width, GLsizei height, const char* what);
    const Texture& operator[](std::size_t k) const { return targets_[k]; }
    /// Binds the framebuffer and the viewport and puts `program` in use,
    /// for the caller's uniforms.
    void use(GLuint program) const;
    /// `timedFullScreenDraw`, then no vertex array, program or framebuffer
    /// bound and no texture on units 0 and 1 (those the casters bind).
    DrawTimes draw(const char* what) const;

private:
    std::vector<Texture> targets_;
    Framebuffer fbo_;
    VertexArray vao_;
    GLsizei width_, height_;
};

/// Seconds since `start` (steady clock), for build timings.
double secondsSince(std::uint64_t startNanoseconds);
std::uint64_t nowNanoseconds();

} // namespace vds::voxel::detail
