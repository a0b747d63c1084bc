// vds::voxel: slicemaps (Eisemann & Décoret, "Fast Scene Voxelization and
// Applications", I3D 2006).
//
// A slicemap is a w x h x S boundary grid, S = 32 k slices (k <= 32): the
// slices of a column are the bits of the unsigned-integer render targets of
// one pixel (RGBA32UI: 128 slices per target, 8 targets = 1024 slices),
// filled in one geometry pass that ORs a one-bit slice mask per fragment into
// the targets (glLogicOp(GL_OR), section 2.2). Bit s % 32 of word s / 32 is
// slice s; slice 0 is the nearest (low z), as the paper's cellmask 2^0.
//  - Uniform slicing: the slices divide the box's depth range evenly.
//  - Local slicing (section 2.3): a first pass renders, per column, the
//    nearest and farthest fragment depth (min/max blending); the slicemap pass
//    then divides each column's own range [near, far] into the S slices.
//
// A slicemap marks only boundaries. For inside/outside, front-facing and
// back-facing fragments go into two slicemaps (section 3.3, one pass with
// multiple render targets when both fit in 8 targets, else one pass each),
// and the paper's inner-voxel rule decides, along the column from near to far:
//  - a boundary voxel (front, back or both, "ambiguous") counts as inside;
//  - an empty voxel is inside iff the last boundary voxel before it is a
//    front voxel; if that one is ambiguous, iff the next boundary voxel after
//    it is a back voxel (a following ambiguous voxel leaves it unresolved:
//    outside, as the paper chooses); no boundary before it: outside.
// Where this fails (docs/voxel.md): the part of every boundary voxel outside
// the surface is called inside (errors up to one slice thick on the outside);
// thin parts between two ambiguous voxels are called outside; columns are
// sampled at their centres (errors near silhouettes, as with any LDI); and
// slices are thick: uniform ones are the box depth / S, local ones the
// column's depth range / S.
//
// Depth here is the slice coordinate d = (z - box.lo.z) * S / (box.hi.z -
// box.lo.z) in [0, S] (the cell z coordinate of the slicemap's grid): uniform
// slice floor(d), the last slice closed at d = S. The columns are the cubic
// cells of `makeVoxelGrid(box, resolution)` across x and y.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <vds/enum_names.h>
#include <vds/gl/context.h>
#include <vds/mesh.h>
#include <vds/voxel/grid.h>

namespace vds::voxel {

enum class Slicing : std::uint8_t {
    Uniform, ///< slices divide the box's depth range evenly
    Local,   ///< slices divide each column's [near, far] fragment range
};

} // namespace vds::voxel

template <> struct vds::EnumNames<vds::voxel::Slicing> {
    static constexpr const char* kind = "slicing";
    static constexpr EnumName<voxel::Slicing> table[] = {{"uniform", voxel::Slicing::Uniform},
                                                         {"local", voxel::Slicing::Local}};
};

namespace vds::voxel {

/// Parses "uniform" / "local" (`parseEnum`); throws `InvalidArgument`.
Slicing parseSlicing(const std::string& s);
const char* toString(Slicing s);

constexpr std::uint32_t kMaxSlices = 1024; ///< 8 RGBA32UI targets

struct SlicemapOptions {
    Slicing slicing = Slicing::Uniform;
    /// Slices, a multiple of 32 in [32, 1024]; 0: the box depth in cells
    /// (as many slices as a cubic voxel grid has cells along z), rounded up to
    /// a multiple of 32 and capped at 1024.
    std::uint32_t slices = 0;
};

/// A front/back slicemap pair in host memory.
struct Slicemap {
    /// Columns: cubic cells across x and y (grid.dims.x by grid.dims.y,
    /// grid.cellSize()); grid.dims.z is the slice count S and grid.scale.z =
    /// S / box depth, so grid.toCells(p).z is the slice coordinate.
    VoxelGrid grid;
    Slicing slicing = Slicing::Uniform;
    /// S / 32 words per column and map. Column c = y * size.x + x holds words
    /// [c * words, (c + 1) * words) of `front` and of `back`.
    std::uint32_t words = 0;
    std::vector<std::uint32_t> front; ///< slices crossed by front-facing (entering) fragments
    std::vector<std::uint32_t> back;  ///< slices crossed by back-facing (leaving) fragments
    /// Local slicing only, one value per column: the nearest and farthest
    /// fragment depth d (near > far: no fragment), and the slices per unit of
    /// d, S / (far - near) (0 when far == near). Slice of depth d:
    /// min(floor((d - near) * slicesPerDepth), S - 1), for d in [near, far]
    /// (uniform slicing: near 0, far S, 1 slice per unit everywhere).
    std::vector<float> nearDepth, farDepth, slicesPerDepth;
    std::uint32_t renderTargets = 0; ///< RGBA32UI targets per map: ceil(S / 128)
    std::uint32_t passes = 0;        ///< geometry passes for the pair (1 or 2), plus 1 for local ranges

    std::uint32_t slices() const { return grid.dims.z; }
    /// Whether slice s of column (x, y) is set in the front / back map.
    bool frontBit(std::uint32_t x, std::uint32_t y, std::uint32_t s) const;
    bool backBit(std::uint32_t x, std::uint32_t y, std::uint32_t s) const;
    /// The slice and column of a point; false outside the box (and, with local
    /// slicing, outside its column's [near, far]).
    bool locate(const glm::vec3& p, std::uint32_t& column, std::uint32_t& slice) const;
    /// Inside test by the inner-voxel rule. Same answer as
    /// `vdsSlicemapContains` / `vdsSlicemapLocalContains` in
    /// shaders/voxel/slicemap.glsl for the same point.
    bool contains(const glm::vec3& p) const;
    /// Bytes of the pair of bit maps plus, for local slicing, near, far and
    /// slices-per-depth per column (what the point query reads).
    std::size_t memoryBytes() const;
    /// Bytes of the GL textures the GLSL lookup reads: 2 * renderTargets
    /// RGBA32UI layers, plus an RGBA32F range texture (near, far,
    /// slices per depth) for local slicing.
    std::size_t gpuBytes() const;
};

/// The inner-voxel rule on one column: `front` and `back` hold `words` words
/// (bit s % 32 of word s / 32 = slice s); true if slice `slice` is inside.
bool slicemapInside(const std::uint32_t* front, const std::uint32_t* back, std::uint32_t words, std::uint32_t slice);

/// Number of slices `SlicemapOptions::slices == 0` picks for a box at a resolution.
std::uint32_t defaultSlices(const Box& box, std::uint32_t resolution);

/// Builds the front/back slicemap pair of a closed mesh over `box` (usually
/// its bounds; the mesh may extend past it), columns as `makeVoxelGrid(box,
/// resolution)` lays them out. Throws `InvalidMesh` for an open mesh,
/// `InvalidArgument` for a bad resolution or slice count, `GlError` on GL
/// failure.
Slicemap buildSlicemap(const GlContext& gl, MeshView mesh, const Box& box, std::uint32_t resolution,
                       const SlicemapOptions& options = {});

} // namespace vds::voxel
