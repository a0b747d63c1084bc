// vds::voxel internal: the slicemap builder on a mesh already found closed
// (slicemap.cpp). `buildSlicemap` checks the mesh (`requireClosed`) and
// calls it; `buildModel` checks the mesh once and calls it directly, so a
// model's mesh is validated once.
#pragma once

#include <vds/gl/context.h>
#include <vds/mesh.h>
#include <vds/voxel/grid.h>
#include <vds/voxel/slicemap.h>

namespace vds::voxel::detail {

/// `buildSlicemap` of a mesh `requireClosed` accepted, over its cubic
/// `columns` (`makeVoxelGrid(box, resolution)`).
Slicemap sliceClosed(const GlContext& gl, MeshView mesh, const Box& box, const VoxelGrid& columns,
                     const SlicemapOptions& options);

} // namespace vds::voxel::detail
