// vds::voxel internal: the voxelizers on a mesh already found closed.
// `buildSlicemap` and `voxelizeSolid` check the mesh (`requireClosed`) and
// call these; `buildModel` checks it once and calls them directly, so a
// model's mesh is validated once, not once per layer.
#pragma once

#include <cstdint>

#include <vds/gl/context.h>
#include <vds/mesh.h>
#include <vds/voxel/grid.h>
#include <vds/voxel/slicemap.h>
#include <vds/voxel/solid.h>

namespace vds::voxel::detail {

/// `buildSlicemap` of a mesh `requireClosed` accepted.
Slicemap sliceClosed(const GlContext& gl, MeshView mesh, const Box& box, std::uint32_t resolution,
                     const SlicemapOptions& options);

/// `voxelizeSolid` of a mesh `requireClosed` accepted.
BitGrid voxelizeClosed(const GlContext& gl, MeshView mesh, const VoxelGrid& grid, SolidMethod method);

} // namespace vds::voxel::detail
