// vds: a narrow band of signed distances computed sparsely — only the cells
// within the half-width W of the surface hold a value, in blocks of 8^3
// cells, and the rest of the grid is whole blocks ("tiles") that are inside
// or outside. Memory is proportional to the band, not to the grid, so grids
// far past the dense limit (`kMaxGridCells`) fit: a 4096^3 band of a
// million triangles in about a gigabyte (docs/distance.md).
//
// The cells near the surface are found from the triangles: each triangle's
// box grown by W marks the blocks it meets (a triangle's plane far from a
// block rules the block out), and only the marked blocks' cells are asked
// their distance, by `SignedDistance::unsignedDistance` bounded by W, and
// their sign, by the classifier's occupancy of that block (a sweep of its
// columns). So every cell equals the dense band's
// (`SignedDistance::grid` with `DistanceGridOptions::band` = W): the same
// float, the same sign. The blocks no grown box meets hold no surface point;
// their sign is that of the block's centre, from one occupancy sweep of a
// grid with a cell per block. On a closed mesh (and by any rule on a mesh
// without boundary) that is every cell's sign in the block; on an open mesh
// by the generalized winding number, whose 1/2 level may cross an open hole
// far from the surface, a tile takes its centre's label (tests compare
// closed meshes cell by cell).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include <vds/distance.h>
#include <vds/grid.h>
#include <vds/rule.h>

namespace vds {

/// Cells a band block has along each axis (OpenVDB's leaf, so that a block
/// is one leaf of a .vdb file).
constexpr std::uint32_t kBandBlockSide = 8;
/// Largest cell count of a sparse band's grid: 2^40 (the per-block marks and
/// tile labels are two bits a block, 512 MiB at this size).
constexpr std::uint64_t kMaxSparseCells = std::uint64_t(1) << 40;

/// One block of the band: cells `origin` + (x, y, z), x, y, z in [0, 8),
/// those inside the grid. Cell (x, y, z) is bit (y * 8 + z) of word x of the
/// masks (bit 0 the lowest), OpenVDB's leaf order x * 64 + y * 8 + z.
struct BandBlock {
    glm::uvec3 origin{0u};    ///< its first cell, a multiple of 8 on each axis
    std::uint64_t first = 0;  ///< its first value in `SparseBand::values`
    std::uint64_t band[8]{};  ///< cells in the band: one value each, in bit order
    std::uint64_t inside[8]{}; ///< each cell's label (1 inside), band or not
};

/// A narrow band over `grid`, as `sparseBand` makes it. Plain data: the
/// caller may read `blocks`, `values` and the tiles directly.
struct SparseBand {
    Grid grid;
    double halfWidth = 0.0; ///< W, mesh units; cells off the band hold -W or +W
    Rule rule = Rule::Parity;
    glm::uvec3 blockDims{0u}; ///< blocks along x, y, z: ceil(grid.dims / 8)
    /// Blocks that hold a band cell, or whose cells' labels differ; in
    /// ascending order of `blockIndex` of their origin / 8.
    std::vector<BandBlock> blocks;
    /// The band cells' signed distances (negative inside), block by block.
    std::vector<float> values;
    /// Bit b % 64 of word b / 64: block b (`blockIndex`) is inside. Its label
    /// for every cell of a block not in `blocks`.
    std::vector<std::uint64_t> tiles;

    /// (bx * blockDims.y + by) * blockDims.z + bz.
    std::uint64_t blockIndex(const glm::uvec3& block) const {
        return (std::uint64_t(block.x) * blockDims.y + block.y) * blockDims.z + block.z;
    }
    bool tileInside(const glm::uvec3& block) const {
        const std::uint64_t b = blockIndex(block);
        return (tiles[b / 64] >> (b % 64)) & 1u;
    }
    /// The block holding cell (i, j, k), or null where it is a tile.
    const BandBlock* blockOf(std::uint32_t i, std::uint32_t j, std::uint32_t k) const;
    /// The value of cell (i, j, k): its distance in the band, else -W or +W
    /// (as float) by its label; exactly the dense band's cell.
    float value(std::uint32_t i, std::uint32_t j, std::uint32_t k) const;
    /// Bytes held: blocks, values and tiles.
    std::size_t memoryBytes() const;
};

/// Options of `sparseBand`.
struct SparseBandOptions {
    unsigned threads = 0;   ///< CPU threads, 0: one per hardware thread
    double halfWidth = 0.0; ///< W, mesh units: finite and > 0
};

/// The band of `mesh` over `grid`, `distance` built from the same mesh (the
/// triangles mark the blocks; the distances and signs are `distance`'s, by
/// its rule): every cell whose distance is below W (as float) holds it,
/// signed as the dense band's. Throws `InvalidArgument` (one line) for a W that is not finite
/// and above 0, a grid with a zero dimension, an empty or non-finite box, or
/// more than `kMaxSparseCells` cells, or a slab (`Grid::first` not 0); `InvalidMesh` for a flat mesh, as
/// `SignedDistance::grid`; `OutOfMemory` when the band does not fit.
SparseBand sparseBand(const SignedDistance& distance, MeshView mesh, const Grid& grid,
                      const SparseBandOptions& options);

/// The grid a sparse band of cubic cells of side `voxelSize` covers over
/// `box`: ceil(extent / voxelSize) cells along each axis (at least 1), from
/// box.lo. Throws `InvalidArgument` for a size that is not finite and above
/// 0, and as `sparseBand` for a grid past its limits.
Grid voxelSizeGrid(const Box& box, double voxelSize);

} // namespace vds
