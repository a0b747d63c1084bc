// vds::voxel: the voxel grid every representation of this module is laid on,
// and the packed bit grid the binary voxelizations fill.
//
// Cells are cubes of `cellSize` mesh units, `resolution` of them along the
// longest side of a box (the others rounded up: `vds::cubicCells`, the one
// sizing of every cubic grid), the grid starting at the box's low corner. A mesh point p has cell coordinates
// v = (p - origin) * scale (componentwise); cell (i, j, k) holds the v in
// [i, i+1) x [j, j+1) x [k, k+1) and its centre is at v = (i, j, k) + 0.5.
// The GLSL includes under shaders/voxel/ compute v with the same operations
// (no fused multiply-adds), so C++ and GLSL lookups agree bit for bit.
//
// Bit grids use the layout of Schwarz (GPU Pro 3, 2012, section 2.2.2,
// figure 2.4): 32 cells along z packed into one 32-bit word (cell k in bit
// k % 32 of word k / 32), then the columns along x, then along y:
//   word (y * size.x + x) * zWords + z / 32.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include <vds/grid.h>
#include <vds/mesh.h>

namespace vds::voxel {

/// Sub-cell precision of the voxelizers: the GL rasterizer snaps window
/// positions to 1/256 of a pixel (GL_SUBPIXEL_BITS = 8 on llvmpipe and current
/// GPUs). The voxelizers snap cell coordinates to this grid themselves, so
/// that rasterization and their compute shaders see the same triangles.
constexpr int kSubcellBits = 8;
constexpr float kSubcells = float(1 << kSubcellBits);

/// Rounds a cell coordinate to the nearest multiple of 1/256 (ties upwards),
/// as `floor(v * 256 + 0.5) / 256`: exact for |v| < 32768, like the GLSL
/// `vdsSnapToSubcells`.
float snapToSubcells(float v);

/// A regular grid of cells over a box: cubic from `makeVoxelGrid`; a
/// slicemap keeps the cubic columns but puts its slices along z (its own
/// size.z and scale.z).
struct VoxelGrid {
    glm::vec3 origin{0.0f}; ///< low corner of cell (0,0,0), mesh coordinates
    float cellSize = 0.0f;  ///< edge of a cell across x and y, mesh units
    glm::vec3 scale{0.0f};  ///< cells per mesh unit along x, y, z (each 1 / cellSize for cubic cells)
    glm::uvec3 size{0u};    ///< cells along x, y, z, each >= 1

    /// Words per column of a bit grid: ceil(size.z / 32).
    std::uint32_t zWords() const { return (size.z + 31u) / 32u; }
    /// Words of a bit grid: size.x * size.y * zWords().
    std::size_t wordCount() const { return std::size_t(size.x) * size.y * zWords(); }
    std::size_t cellCount() const { return std::size_t(size.x) * size.y * size.z; }

    /// Cell coordinates of a mesh point: (p - origin) * scale, as the GLSL does.
    glm::vec3 toCells(const glm::vec3& p) const;
    /// The cell holding `p`; false (and `cell` untouched) outside the grid or for NaN.
    bool cellOf(const glm::vec3& p, glm::uvec3& cell) const;
    /// Centre of cell (i, j, k) in mesh coordinates, origin + (i + 0.5) *
    /// cellSize on each axis (a cubic grid's; for a slicemap's, x and y only).
    glm::vec3 cellCentre(std::uint32_t i, std::uint32_t j, std::uint32_t k) const;
    /// The box the cells cover, mesh coordinates (at least the box it was made for).
    Box box() const;
};

/// Cubic cells over `box`, `resolution` along its longest side. Throws
/// `InvalidArgument` for a resolution of 0 or above `vds::kMaxResolution`, a
/// box that is not finite or has no extent along some axis, or more than
/// `maxCells` cells (a slicemap, which keeps only the columns, passes no limit).
VoxelGrid makeVoxelGrid(const Box& box, std::uint32_t resolution, std::uint64_t maxCells = kMaxGridCells);

/// A binary voxelization: one bit per cell, in the layout described above.
struct BitGrid {
    VoxelGrid grid;
    std::vector<std::uint32_t> words; ///< grid.wordCount() words; bits past size.z in a column are 0

    /// Word holding cell (x, y, z), and its bit.
    static std::size_t wordIndex(const VoxelGrid& g, std::uint32_t x, std::uint32_t y, std::uint32_t z) {
        return (std::size_t(y) * g.size.x + x) * g.zWords() + (z >> 5);
    }
    bool test(std::uint32_t x, std::uint32_t y, std::uint32_t z) const {
        return (words[wordIndex(grid, x, y, z)] >> (z & 31u)) & 1u;
    }
    void set(std::uint32_t x, std::uint32_t y, std::uint32_t z, bool on);

    /// Point lookup: the bit of the cell holding `p`, false outside the grid.
    /// Same answer as `vdsBitGridContains` in shaders/voxel/solid.glsl.
    bool contains(const glm::vec3& p) const;
    /// Number of set cells.
    std::size_t count() const;
    /// Bytes of the words (host and GPU alike).
    std::size_t memoryBytes() const { return words.size() * sizeof(std::uint32_t); }
};

/// An all-zero bit grid over `grid`. Throws `OutOfMemory` if it cannot be allocated.
BitGrid makeBitGrid(const VoxelGrid& grid);

/// The mesh must bound a solid by the parity rule, which every voxelizer here
/// uses: usable and closed (every edge shared by an even number of
/// triangles; non-manifold edges and orientation conflicts are allowed, see
/// `insideWarning`). Throws `InvalidMesh` naming `what` (`requireInsideDefined`).
void requireClosed(MeshView mesh, const char* what);

} // namespace vds::voxel
