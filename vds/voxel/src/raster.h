// vds::voxel internal: what the voxelizers' raster passes share (raster.cpp):
// the mesh upload, grid uniforms, the rasterization set-up of
// voxel/raster.vert. Buffers and dispatch sizes are vds::gl's toolkit
// (<vds/gl/detail/buffers.h>, <vds/gl/detail/dispatch.h>).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include <GL/gl.h>

#include <vds/gl/context.h>
#include <vds/gl/objects.h>
#include <vds/gl/mesh.h>
#include <vds/mesh.h>
#include <vds/voxel/grid.h>

namespace vds::voxel::detail {

/// The mesh on the GPU (vds::GpuMesh), checked first to fit the shader
/// storage of voxel/triangles.glsl (`bindStorage`).
struct MeshBuffers : GpuMesh {
    MeshBuffers(const GlContext& gl, MeshView mesh);
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

} // namespace vds::voxel::detail
