// vds::voxel internal: the solid voxelizer on a mesh already found closed
// (solid.cpp). `voxelizeSolid` checks the mesh (`requireClosed`) and calls
// it; `buildModel` checks the mesh once and calls it directly, so a model's
// mesh is validated once.
#pragma once

#include <vds/gl/context.h>
#include <vds/mesh.h>
#include <vds/voxel/grid.h>
#include <vds/voxel/solid.h>

namespace vds::voxel::detail {

/// `voxelizeSolid` of a mesh `requireClosed` accepted.
BitGrid voxelizeClosed(const GlContext& gl, MeshView mesh, const VoxelGrid& grid, SolidMethod method);

} // namespace vds::voxel::detail
