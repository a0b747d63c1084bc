// vds internal: "is the sprite axis-aligned?", asked in one place by the
// CPU sprite's fast path (sprite.cpp), the occupancy sweep's plan
// (occupancy.cpp, detail::planSweep) and `sweepsByColumns` (<vds/sprite.h>).
#pragma once

#include <optional>

#include <glm/vec3.hpp>

#include <vds/sprite.h>

namespace vds::detail {

/// The world axis each texture axis of the sprite follows (`axes[0]` for s,
/// `[1]` for t, `[2]` for r), when its matrix has exactly one non-zero entry
/// in each row and each column: the sprite was moved, scaled, mirrored or
/// turned by quarter turns since the bake, not rotated by other angles. A
/// texture coordinate is then one product. Empty for any other matrix.
inline std::optional<glm::ivec3> alignedAxes(const SpriteGrid& grid) {
    glm::ivec3 axes(-1);
    unsigned columns = 0;
    for (int row = 0; row < 3; ++row)
        for (int col = 0; col < 3; ++col) {
            if (grid.matrix[col][row] == 0.0f) continue;
            if (axes[row] >= 0 || (columns >> col & 1u)) return std::nullopt;
            axes[row] = col;
            columns |= 1u << col;
        }
    if (columns != 7u) return std::nullopt;
    return axes;
}

} // namespace vds::detail
