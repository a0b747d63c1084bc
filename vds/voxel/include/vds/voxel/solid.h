// vds::voxel: solid voxelization, two ways (Schwarz, "Practical Binary
// Surface and Solid Voxelization with Direct3D 11", GPU Pro 3, 2012).
//
// A voxel is set iff its centre is inside the closed mesh by the parity rule:
// the ray from the centre towards -z crosses the surface an odd number of
// times (crossings at the centre's own depth do not count), the convention of
// vds::ExactClassifier with Axis::Z.
//  - Raster (section 2.3): the mesh is rasterized with one pixel per voxel
//    column; every fragment flips, with atomic XOR, every voxel of its column
//    behind it. No depth test and no depth clipping.
//  - Compute (section 2.5): one invocation per triangle flips only the first
//    voxel behind it in each column whose centre it covers, a centre on an
//    edge going to one triangle by the fill rule (Direct3D's top-left rule
//    with window y down: left edges and, y up, horizontal bottom edges);
//    a propagation pass turns each column into its prefix XOR.
//
// Both see the triangles with x and y snapped to 1/256 of a cell (the
// rasterizer's sub-pixel grid; voxel/raster.vert makes the viewport mapping
// exact) and compute the depth of a triangle at a column centre with the same
// exact-weight formula, so they give the same bits. The fill rule is the one
// llvmpipe applies to framebuffer objects, so there even the flips coincide;
// the GL leaves the rule to the driver, and another driver's may give a
// centre on a shared edge to the other triangle, but never changes a parity:
// on a closed mesh a centre on an edge where the surface continues is claimed
// by exactly one of the two triangles, and on a fold by none or both,
// whichever consistent rule is used; both triangles have the same depth there.
// Against the exact classifier at voxel centres they differ only where the
// snapping moves an edge across a centre (within 1/256 cell of a projected
// edge) or the centre lies within rounding of the surface in depth.
#pragma once

#include <cstdint>
#include <string>

#include <vds/enum_names.h>
#include <vds/gl/context.h>
#include <vds/mesh.h>
#include <vds/voxel/grid.h>

namespace vds::voxel {

enum class SolidMethod : std::uint8_t {
    Raster,  ///< per-fragment XOR of the column behind (section 2.3)
    Compute, ///< per-triangle first-voxel flip + prefix XOR (section 2.5)
};

} // namespace vds::voxel

template <> struct vds::EnumNames<vds::voxel::SolidMethod> {
    static constexpr const char* kind = "solid voxelization method";
    static constexpr EnumName<voxel::SolidMethod> table[] = {{"raster", voxel::SolidMethod::Raster},
                                                             {"compute", voxel::SolidMethod::Compute}};
};

namespace vds::voxel {

/// Parses "raster" / "compute" (`parseEnum`); throws `InvalidArgument`.
SolidMethod parseSolidMethod(const std::string& s);
const char* toString(SolidMethod m);

/// Voxelizes the solid bounded by `mesh` on `grid` with `gl` (made current).
/// Throws `InvalidMesh` if the mesh is not closed (see `requireClosed`),
/// `OutOfMemory` if the grid exceeds a GL storage buffer, `GlError` on GL
/// failure. Triangles outside the grid's columns are ignored; parts of the
/// mesh in front of or behind the grid still count (no depth clipping).
BitGrid voxelizeSolid(const GlContext& gl, MeshView mesh, const VoxelGrid& grid, SolidMethod method);

} // namespace vds::voxel
