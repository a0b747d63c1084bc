// vds::voxel: conservative surface voxelization in compute (Schwarz, GPU Pro
// 3, 2012, section 2.4, after Schwarz & Seidel, "Fast Parallel Surface and
// Solid Voxelization on GPUs", SIGGRAPH Asia 2010).
//
// Every voxel that a triangle touches (closed sets: touching counts) is set.
// One invocation per triangle: the triangle's plane must cross the voxel and
// its projections onto the xy, yz and zx planes must overlap the voxel's
// (edge functions at the critical box corner); candidates are the voxels of
// each column along the axis the triangle faces most, within the plane's
// range over the column (section 2.4.2, "candidate voxel selection").
//
// Vertices are snapped to 1/256 of a cell in all three axes and every test is
// evaluated on those multiples of 2^-8 in double precision: the 2D tests are
// exact for any grid, the plane test is exact for triangles whose bounding box
// spans fewer than 447 cells (beyond, rounding may only affect voxels the
// triangle touches within about 2^-40 cells). The set is thus exactly that of
// an exact triangle/box overlap test on the snapped triangle; the unsnapped
// triangle may touch voxels up to 1/512 cell away that it does not.
// Open meshes are fine here (a surface, not a solid).
#pragma once

#include <vds/gl/context.h>
#include <vds/mesh.h>
#include <vds/voxel/grid.h>

namespace vds::voxel {

/// Sets every voxel of `grid` touched by a triangle of `mesh`. Throws
/// `InvalidMesh` for an unusable mesh (empty, non-finite, bad indices),
/// `OutOfMemory` if the grid exceeds a GL storage buffer, `GlError` on GL
/// failure.
BitGrid voxelizeSurface(const GlContext& gl, MeshView mesh, const VoxelGrid& grid);

} // namespace vds::voxel
