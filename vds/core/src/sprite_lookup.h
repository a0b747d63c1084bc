// vds internal: the VPT on one column, shared by the point queries
// (sprite.cpp) and the column sweeps (occupancy.cpp), so both answer alike.
#pragma once

#include <cmath>
#include <cstddef>

#include <vds/sprite.h>

namespace vds::detail {

// The column a texture-space point falls in, or -1 outside the box.
inline std::ptrdiff_t columnOf(const SpriteGrid& grid, const glm::vec3& t) {
    if (!(t.z >= 0.0f && t.z <= 1.0f)) return -1;
    const float fs = std::floor(t.x * float(grid.width));
    const float ft = std::floor(t.y * float(grid.height));
    if (!(fs >= 0.0f && fs < float(grid.width) && ft >= 0.0f && ft < float(grid.height))) return -1;
    return std::ptrdiff_t(ft) * std::ptrdiff_t(grid.width) + std::ptrdiff_t(fs);
}

// The VPT on one column: crossings strictly in front of depth r.
inline bool testColumn(const float* begin, const float* end, float r, Rule rule) {
    int parity = 0, winding = 0;
    for (const float* e = begin; e != end; ++e) {
        if (!(std::fabs(*e) < r)) break;
        parity ^= 1;
        winding += crossingEnters(*e) ? 1 : -1;
    }
    return rule == Rule::Parity ? parity != 0 : winding != 0;
}

} // namespace vds::detail
