// vds: occupancy grids — the inside/outside label of every cell centre of a
// regular grid, by one sweep per column instead of one lookup per cell.
//
// A grid column along a sprite's view axis meets the column's crossings in
// depth order, so one walk over them labels every cell of the column; the
// cost is writing the labels. `occupancy(mesh, ...)` does the same on the triangles
// themselves with the exact classifier's predicates: for each triangle a
// column's centre ray claims (the top-left rule of <vds/exact.h>), a binary
// search over the column's cell centres with the exact orientation
// predicate finds the first cell the crossing lies strictly in front of;
// the winding number of every cell then follows by a prefix sum over those
// events. Its labels therefore equal `ExactClassifier(mesh, Axis::Z)` on
// every cell centre, as computed by `Grid::cellCentre`.
#pragma once

#include <cstddef>
#include <cstdint>

#include <glm/vec3.hpp>

#include <vds/grid.h>
#include <vds/mesh.h>
#include <vds/sprite.h>

namespace vds {

/// Labels every cell centre of `grid` with `sprite` (its placement applied):
/// `cells[grid.index(i, j, k)]` = 1 inside, 0 outside; `cells` holds
/// `grid.cellCount()` bytes, owned by the caller. The answers equal
/// `sprite.contains(grid.cellCentre(i, j, k), rule)` on every cell. When the
/// sprite's axes are the grid's (no rotation since the bake) each column
/// along the view axis is one walk over its crossings; otherwise the cells
/// are classified one by one. Throws like `checkGrid`.
void occupancy(const Sprite& sprite, const Grid& grid, std::uint8_t* cells,
               const ClassifyOptions& options = {});

/// Exact labels of every cell centre of `grid` for `mesh`, by a column sweep
/// along z on the triangles themselves (see above): equal to
/// `ExactClassifier(mesh, Axis::Z).contains(grid.cellCentre(i, j, k), rule)`
/// on every cell. `cells` as for `occupancy`. Throws `InvalidMesh` for an
/// unusable mesh and like `checkGrid`.
void occupancy(MeshView mesh, const Grid& grid, std::uint8_t* cells, const ClassifyOptions& options = {});

} // namespace vds
