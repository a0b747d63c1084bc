// vds::voxel internal: the slicemap builder on a mesh already found closed
// (slicemap.cpp). `buildSlicemap` checks the mesh (`requireClosed`) and
// calls it; `buildModel` checks the mesh once and calls it directly, so a
// model's mesh is validated once.
#pragma once

#include <cstdint>

#include <vds/gl/context.h>
#include <vds/mesh.h>
#include <vds/voxel/slicemap.h>

namespace vds::voxel::detail {

/// `buildSlicemap` of a mesh `requireClosed` accepted.
Slicemap sliceClosed(const GlContext& gl, MeshView mesh, const Box& box, std::uint32_t resolution,
                     const SlicemapOptions& options);

} // namespace vds::voxel::detail
