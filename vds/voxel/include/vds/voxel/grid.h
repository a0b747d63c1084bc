// vds::voxel: the voxel grid every representation of this module is laid on,
// and the packed bit grid the binary voxelizations fill.
//
// A voxel grid is the library's one grid, `vds::Grid` (<vds/grid.h>): its
// box, its dims, its cells in the same order and their centres by the one
// formula (`Grid::cellCentre`, in double, rounded to float), plus the float
// lattice the voxelizers and their GLSL compute with. It derives from Grid
// rather than holding one, so that its fields read as every grid's
// (`grid.box.lo`, `grid.dims`) and it passes as it is wherever a Grid is
// taken. It is never a slab (`first` and `whole` stay 0).
//
// `makeVoxelGrid` makes the cubic grid: `vds::cubicGrid`'s, `resolution`
// cells along the box's longest side and the others rounded up
// (`vds::cubicCells`, the one sizing of every cubic grid), the box grown to
// whole cells. A slicemap keeps its columns and puts its own slices along z
// (`makeSlicemapGrid`). Every grid the library fills has at most
// `vds::kMaxGridCells` cells (`vds::checkGrid`, called by `makeBitGrid`).
//
// The lattice: a mesh point p has cell coordinates v = (p - box.lo) * scale
// (componentwise, in float); cell (i, j, k) holds the v in [i, i+1) x
// [j, j+1) x [k, k+1). `scale` is kept beside the box, not derived from it,
// because it is what the shaders are given (uniforms origin = box.lo and
// scale): the GLSL includes under shaders/voxel/ compute v with the same
// operations (no fused multiply-adds), so C++ and GLSL lookups agree bit for
// bit. The voxelizers snap v to 1/256 sub-cells (`snapToSubcells`) as the
// rasterizer does.
//
// The centre and the lattice agree: a centre is half a cell from every face
// of its cell, and the box's double arithmetic and the lattice's float one
// differ by a few roundings, under 2^-8 of a cell for at most
// `vds::kMaxResolution` cells along an axis (plus the coordinates' own float
// spacing, which any grid float can resolve keeps far below a cell). So
// `cellOf(cellCentre(i, j, k))` is cell (i, j, k): a lookup at a centre
// lands in its cell (tests/voxel/grid_test.cpp checks every cell of a few
// grids).
//
// Bit grids use the layout of Schwarz (GPU Pro 3, 2012, section 2.2.2,
// figure 2.4): 32 cells along z packed into one 32-bit word (cell k in bit
// k % 32 of word k / 32), then the columns along x, then along y:
//   word (y * dims.x + x) * zWords + z / 32.
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

/// The one grid (`vds::Grid`: box, dims, cell centres) with the float
/// lattice the voxelizers and their GLSL use. Cubic from `makeVoxelGrid`; a
/// slicemap's keeps the cubic columns and has its own dims.z and scale.z
/// (`makeSlicemapGrid`).
struct VoxelGrid : Grid {
    /// Cells per mesh unit along x, y, z: resolution / longest side of the
    /// box, in double rounded to float, on every axis of a cubic grid.
    glm::vec3 scale{0.0f};

    /// Words per column of a bit grid: ceil(dims.z / 32).
    std::uint32_t zWords() const { return (dims.z + 31u) / 32u; }
    /// Words of a bit grid: dims.x * dims.y * zWords().
    std::size_t wordCount() const { return std::size_t(dims.x) * dims.y * zWords(); }
    /// Edge of a cell across x and y, mesh units: the lattice's, 1 / scale.x
    /// in double, rounded to float.
    float cellSize() const;

    /// Cell coordinates of a mesh point: (p - box.lo) * scale, as the GLSL does.
    glm::vec3 toCells(const glm::vec3& p) const;
    /// The cell holding `p`; false (and `cell` untouched) outside the grid or for NaN.
    bool cellOf(const glm::vec3& p, glm::uvec3& cell) const;
};

/// Cubic cells over `box`, `resolution` along its longest side:
/// `cubicGrid(box, resolution)` with its lattice. Throws `InvalidArgument`
/// for a resolution of 0 or above `vds::kMaxResolution`, or a box that is not
/// finite or has no extent along some axis. The grid may have more cells than
/// `kMaxGridCells` (sizes are worked out on it, and a slicemap keeps only its
/// columns); `makeBitGrid` and the voxelizers refuse such a grid.
VoxelGrid makeVoxelGrid(const Box& box, std::uint32_t resolution);

/// A slicemap's grid: the columns of `makeVoxelGrid(box, resolution)` and
/// `slices` cells along z over exactly [box.lo.z, box.hi.z] (scale.z =
/// slices / (box.hi.z - box.lo.z), in double rounded to float). Throws as
/// `makeVoxelGrid`.
VoxelGrid makeSlicemapGrid(const Box& box, std::uint32_t resolution, std::uint32_t slices);
/// The same from the columns already made: `makeVoxelGrid(box, resolution)`.
VoxelGrid slicemapGridOver(const VoxelGrid& columns, const Box& box, std::uint32_t slices);

/// A binary voxelization: one bit per cell, in the layout described above.
struct BitGrid {
    VoxelGrid grid;
    std::vector<std::uint32_t> words; ///< grid.wordCount() words; bits past dims.z in a column are 0

    /// Word holding cell (x, y, z), and its bit.
    static std::size_t wordIndex(const VoxelGrid& g, std::uint32_t x, std::uint32_t y, std::uint32_t z) {
        return (std::size_t(y) * g.dims.x + x) * g.zWords() + (z >> 5);
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

/// An all-zero bit grid over `grid`. Throws `InvalidArgument` for a grid
/// `vds::checkGrid` refuses (more than `kMaxGridCells` cells), `OutOfMemory`
/// if it cannot be allocated.
BitGrid makeBitGrid(const VoxelGrid& grid);

/// The mesh must bound a solid by the parity rule, which every voxelizer here
/// uses: usable and closed (every edge shared by an even number of
/// triangles; non-manifold edges and orientation conflicts are allowed, see
/// `insideWarning`). Throws `InvalidMesh` naming `what` (`requireInsideDefined`).
void requireClosed(MeshView mesh, const char* what);

} // namespace vds::voxel
