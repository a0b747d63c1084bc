// vds internal: the one plan of a sprite's occupancy sweep, consumed by the
// CPU sweep (occupancy.cpp) and the GPU sweep (gl/src/grids/occupancy.cpp,
// shaders/vds/occupancy.comp), so the two give the same labels by
// construction.
//
// With a sprite whose texture s, t and r each follow one world axis (depth
// growing along the world axis `a` r follows: sweepsByColumns), a grid column along `a` falls in one
// texel column, and a cell's texture depth depends on its slice alone:
// one depth per slice, shared by every column, increasing; cells with
// depth outside [0, 1] are outside.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include <vds/detail/aligned_axes.h>
#include <vds/grid.h>
#include <vds/sprite.h>

namespace vds::detail {

struct SweepPlan {
    /// False unless `sweepsByColumns(sprite)` (a sprite rotated against the
    /// grid, or mirrored along its axis): no column sweep, each cell is
    /// classified on its own (the other fields are unset).
    bool aligned = false;
    int a = 2, u = 0, v = 1;  ///< the sweep axis and the column axes (u, v): the sprite's permutation
    std::uint32_t n = 0;      ///< cells along `a`
    std::size_t step = 1;     ///< distance in the label array between consecutive cells of a column
    std::size_t columns = 0;  ///< dims[u] * dims[v]; column = i_u * dims[v] + i_v
    std::vector<float> depth; ///< texture depth of each slice
    std::uint32_t firstSlice = 0, endSlice = 0; ///< slices with depth in [0, 1]
    /// The sprite's texel column of each grid column (exactly `Sprite::contains`'s
    /// rule, at the first slice inside), -1 where it misses the sprite.
    std::vector<std::int32_t> texels;

    /// The grid cell at slice 0 of `column`.
    glm::uvec3 firstCell(std::size_t column, const Grid& grid) const {
        glm::uvec3 c(0u);
        c[u] = std::uint32_t(column / grid.dims[v]);
        c[v] = std::uint32_t(column % grid.dims[v]);
        return c;
    }
};

/// The plan for sweeping `grid` through a sprite placed by `sprite` (its
/// width, height, matrix and position; its `axis` is not read: the matrix
/// says which world axis depth follows). Texels computed on `threads`.
SweepPlan planSweep(const SpriteGrid& sprite, const Grid& grid, unsigned threads);

class BoundaryCapsCache; // <vds/detail/sprite_winding.h>

/// `occupancy(sprite, ...)` (<vds/occupancy.h>) with a sprite's caps cache:
/// its `SpriteClassifier`'s, or the call's.
void occupancyOfSprite(const Sprite& sprite, const BoundaryCapsCache& caps, const Grid& grid, std::uint8_t* cells,
                       const ClassifyOptions& options);

} // namespace vds::detail
