// vds: occupancy grids on the GPU — the column sweep of <vds/occupancy.h>
// in a compute shader (shaders/vds/occupancy.comp), one invocation per grid
// column, the labels left in a GL buffer.
//
// Belongs to the GL context given at construction (which must outlive it),
// made current for every call, the caller's restored (<vds/gl/context.h>).
#pragma once

#include <cstddef>
#include <cstdint>

#include <vds/gl/context.h>
#include <vds/gl/objects.h>
#include <vds/gl/sprite.h>
#include <vds/classify.h>
#include <vds/grid.h>

namespace vds {

/// Labels the cell centres of an `Grid` with a `GpuSprite` on the
/// GPU: the same labels as `vds::occupancy` on the CPU for the same sprite
/// (the host computes each column's texel and each slice's depth with the
/// CPU's arithmetic; the shader only compares depths). Not thread safe.
///
/// Rule::GeneralizedWinding on a sprite with boundary edges adds, per cell,
/// the boundary term at the cell's texel-centre point (the point the CPU
/// takes) to the column's signed count, in float (vpt.glsl), for every cell
/// of the grid: in front of and behind the sprite's box (none or all of the
/// column's crossings), and beside it (no crossing, the term at the cell
/// itself), where an open mesh's winding number can exceed 1/2. A label may
/// then differ from the CPU's (double) only where |w - 1/2| is within float
/// error (vpt.glsl gives its size, and the near-tie of a boundary edge along
/// the view axis), and the sweep costs O(boundary edges) a cell. With no
/// boundary edges the rule is Winding.
class GpuOccupancy {
public:
    /// Takes the compute program from `gl`'s cache (built on first use).
    /// Throws `GlError`.
    explicit GpuOccupancy(const GlContext& gl);
    GpuOccupancy(GpuOccupancy&&) noexcept = default;
    GpuOccupancy& operator=(GpuOccupancy&&) noexcept = default;
    GpuOccupancy(const GpuOccupancy&) = delete;
    GpuOccupancy& operator=(const GpuOccupancy&) = delete;

    /// Bytes the label buffer needs for `grid`: 4 * ceil(cellCount / 4).
    static std::size_t labelBytes(const Grid& grid) { return (grid.cellCount() + 3) / 4 * 4; }

    /// GL buffer to GL buffer (a name of the occupancy's context): byte `grid.index(i, j, k)` of `cells` (at
    /// least `labelBytes(grid)` bytes from offset 0) becomes 1 inside, 0
    /// outside, written as 32-bit words (low byte first); the buffer is
    /// cleared first. Only queues GL commands: a glMemoryBarrier after it
    /// makes the labels visible to later GL commands.
    /// `sprite` needs its columns (`offsets()` not empty) and must be placed with
    /// its axes along the grid's (as baked, moved or scaled but not rotated);
    /// throws `InvalidArgument` otherwise, for a grid `checkGrid`
    /// refuses, for more than 2^32 cells, for a buffer larger than GL's
    /// largest shader storage block, and for Rule::GeneralizedWinding on a
    /// sprite whose boundary is unknown (`GpuBoundary::known()`: a version 1 file).
    void occupancy(const GpuSprite& sprite, const Grid& grid, GLuint cells, const ClassifyOptions& options = {});

    /// Host array out: `cells` holds `grid.cellCount()` bytes (caller-owned).
    /// Waits for the GPU and reads the labels back.
    void occupancy(const GpuSprite& sprite, const Grid& grid, std::uint8_t* cells, const ClassifyOptions& options = {});

private:
    void sweep(const GpuSprite& sprite, const Grid& grid, GLuint cells, const ClassifyOptions& options);
    const GlContext* gl_ = nullptr;
    ContextStamp stamp_;
    /// occupancy.comp's program of a rule and a sweep: single columns, or
    /// quads of columns along v or u (VDS_SWEEP_QUADS_ALONG_V / _U).
    enum class Sweep : std::uint8_t { Columns, QuadsAlongV, QuadsAlongU };
    const Program& program(Rule rule, Sweep sweep) const;
    std::uint64_t maxBlock_ = 0;
};

} // namespace vds
