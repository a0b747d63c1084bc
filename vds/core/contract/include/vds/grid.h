// vds: the one grid type — a regular grid of cells over a box, the shape
// every occupancy call of every method fills (<vds/occupancy.h>,
// `Classifier::occupancy`); a voxel grid is one with the voxelizers' float
// lattice added (`vds::voxel::VoxelGrid`).
#pragma once

#include <cstddef>
#include <cstdint>

#include <glm/vec3.hpp>

#include <vds/mesh.h>

namespace vds {

/// A regular grid over `box`: `dims` cells along x, y and z. Cell (i, j, k)
/// has the centre lo + (i + 1/2, j + 1/2, k + 1/2) * (hi - lo) / dims,
/// evaluated in double and rounded to float (`cellCentre`), so every caller
/// that needs the points gets the same floats.
///
/// A slab (`slabX`) is part of a larger grid: its cells (i, j, k) are cells
/// `first` + (i, j, k) of the grid of `whole` cells over `box`, with those
/// cells' centres exactly, so a large grid can be labelled a slab at a time
/// (`vds voxelize --packed`) with the same labels as in one call.
struct Grid {
    Box box;
    glm::uvec3 dims{0u};
    glm::uvec3 first{0u}; ///< a slab's first cell in the whole grid
    glm::uvec3 whole{0u}; ///< the whole grid's cells; 0 (the default): `dims`, no slab

    glm::vec3 cellCentre(std::uint32_t i, std::uint32_t j, std::uint32_t k) const;
    /// Coordinate `axis` (0..2) of the centres of this grid's cells with
    /// index `index` along it: `cellCentre`'s, one axis at a time.
    float cellCoordinate(int axis, std::uint32_t index) const;
    /// Cells along axis a of the whole grid.
    std::uint32_t wholeCells(int a) const { return whole[a] ? whole[a] : dims[a]; }
    /// Cells [i0, i1) along x of this grid as a slab (of the same whole grid).
    Grid slabX(std::uint32_t i0, std::uint32_t i1) const {
        Grid s = *this;
        s.whole = glm::uvec3(wholeCells(0), wholeCells(1), wholeCells(2));
        s.first.x = first.x + i0;
        s.dims.x = i1 - i0;
        return s;
    }
    /// dims.x * dims.y * dims.z.
    std::size_t cellCount() const { return std::size_t(dims.x) * dims.y * dims.z; }
    /// Index of cell (i, j, k) in the label arrays: C order, k fastest,
    /// as numpy's shape (dims.x, dims.y, dims.z) indexed [i][j][k].
    std::size_t index(std::uint32_t i, std::uint32_t j, std::uint32_t k) const {
        return (std::size_t(i) * dims.y + j) * dims.z + k;
    }
};

/// Largest cell count of any grid the library makes or fills (occupancy,
/// distance and voxel grids): 2^34, 16 GiB of labels or 2 GiB of bits.
constexpr std::uint64_t kMaxGridCells = std::uint64_t(1) << 34;

/// Throws `InvalidArgument` for a zero dimension, more than
/// `kMaxGridCells` cells, or a box that is empty or not finite.
void checkGrid(const Grid& grid);

/// Cells along x, y and z when `n` cubic cells span the longest side of a
/// box of `extent` (mesh units): n along that side, and ceil(e / cell)
/// along the others, at least 1 and at most n, with cell = longest / n,
/// in double. 1 along every axis where the longest is not positive. The
/// one sizing of the library's cubic grids: `cubicGrid`, the voxel grids
/// (`vds::voxel::makeVoxelGrid`) and a sprite's texels (`makeGrid`, with a
/// 0 extent along the view axis).
glm::uvec3 cubicCells(const glm::vec3& extent, std::uint32_t n);

/// A grid of `n` cells along the longest side of `box` and as many cubic
/// cells as fit along the others (`cubicCells`), over the box grown to
/// whole cells along those others.
Grid cubicGrid(const Box& box, std::uint32_t n);

/// Packs one-byte labels into bits, eight cells a byte, the first cell in the
/// most significant bit (numpy's `packbits` order); `bits` holds
/// (count + 7) / 8 bytes. The last byte's unused bits are zero.
void packLabels(const std::uint8_t* cells, std::size_t count, std::uint8_t* bits);

} // namespace vds
