// vds: occupancy grids — the inside/outside label of every cell centre of a
// regular grid, by one sweep per column instead of one lookup per cell.
//
// A grid column along a sprite's view axis meets the column's crossings in
// depth order, so one walk over them labels every cell of the column; the
// cost is writing the labels. `voxelize` does the same on the triangles
// themselves with the exact classifier's predicates: for each triangle a
// column's centre ray claims (the top-left rule of <vds/exact.h>), a binary
// search over the column's cell centres with the exact orientation
// predicate finds the first cell the crossing lies strictly in front of;
// the winding number of every cell then follows by a prefix sum over those
// events. Its labels therefore equal `ExactClassifier(mesh, Axis::Z)` on
// every cell centre, as computed by `OccupancyGrid::cellCentre`.
#pragma once

#include <cstddef>
#include <cstdint>

#include <glm/vec3.hpp>

#include <vds/mesh.h>
#include <vds/sprite.h>

namespace vds {

/// A regular grid over `box`: `dims` cells along x, y and z. Cell (i, j, k)
/// has the centre lo + (i + 1/2, j + 1/2, k + 1/2) * (hi - lo) / dims,
/// evaluated in double and rounded to float (`cellCentre`), so every caller
/// that needs the points gets the same floats.
struct OccupancyGrid {
    Box box;
    glm::uvec3 dims{0u};

    glm::vec3 cellCentre(std::uint32_t i, std::uint32_t j, std::uint32_t k) const;
    /// dims.x * dims.y * dims.z.
    std::size_t cellCount() const { return std::size_t(dims.x) * dims.y * dims.z; }
    /// Index of cell (i, j, k) in the label arrays: C order, k fastest,
    /// as numpy's shape (dims.x, dims.y, dims.z) indexed [i][j][k].
    std::size_t index(std::uint32_t i, std::uint32_t j, std::uint32_t k) const {
        return (std::size_t(i) * dims.y + j) * dims.z + k;
    }
};

/// Largest cell count accepted: 2^34 (16 GiB of labels).
constexpr std::uint64_t kMaxOccupancyCells = std::uint64_t(1) << 34;

/// Throws `InvalidArgument` for a zero dimension, more than
/// `kMaxOccupancyCells` cells, or a box that is empty or not finite.
void checkOccupancyGrid(const OccupancyGrid& grid);

/// A grid of `n` cells along the longest side of `box` and as many cubic
/// cells as fit along the others (at least 1), over the same box.
OccupancyGrid cubicOccupancyGrid(const Box& box, std::uint32_t n);

struct OccupancyOptions {
    Rule rule = Rule::Parity;
    unsigned threads = 0; ///< 0: one per hardware thread
};

/// Labels every cell centre of `grid` with `sprite` (its placement applied):
/// `cells[grid.index(i, j, k)]` = 1 inside, 0 outside; `cells` holds
/// `grid.cellCount()` bytes, owned by the caller. The answers equal
/// `sprite.contains(grid.cellCentre(i, j, k), rule)` on every cell. When the
/// sprite's axes are the grid's (no rotation since the bake) each column
/// along the view axis is one walk over its crossings; otherwise the cells
/// are classified one by one. Throws like `checkOccupancyGrid`.
void occupancy(const Sprite& sprite, const OccupancyGrid& grid, std::uint8_t* cells,
               const OccupancyOptions& options = {});

/// Exact labels of every cell centre of `grid` for `mesh`, by a column sweep
/// along z on the triangles themselves (see above): equal to
/// `ExactClassifier(mesh, Axis::Z).contains(grid.cellCentre(i, j, k), rule)`
/// on every cell. `cells` as for `occupancy`. Throws `InvalidMesh` for an
/// unusable mesh and like `checkOccupancyGrid`.
void voxelize(MeshView mesh, const OccupancyGrid& grid, std::uint8_t* cells, const OccupancyOptions& options = {});

/// Packs one-byte labels into bits, eight cells a byte, the first cell in the
/// most significant bit (numpy's `packbits` order); `bits` holds
/// (count + 7) / 8 bytes. The last byte's unused bits are zero.
void packLabels(const std::uint8_t* cells, std::size_t count, std::uint8_t* bits);

} // namespace vds
