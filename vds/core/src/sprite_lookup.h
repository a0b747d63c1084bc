// vds internal: the VPT on one column, shared by the point queries
// (sprite.cpp) and the column sweeps (occupancy.cpp), so both answer alike.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

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
    return rule == Rule::Parity ? parity != 0 : insideByRule(winding, rule);
}

/// A column's record for queries that should miss the cache once: its
/// first two crossings (`kPadding` where the column has fewer, a depth no
/// point reaches), where the column starts in the sprite's crossings, and
/// how many it has. 16 bytes: four records a cache line.
struct PackedColumn {
    float first[2];
    std::uint32_t begin;
    std::uint32_t count;
};
constexpr float kPadding = 2.0f;

std::vector<PackedColumn> packColumns(const Sprite& sprite, unsigned threads);

/// testColumn on a packed record; `crossings` are the sprite's.
inline bool testPacked(const PackedColumn& c, const float* crossings, float r, Rule rule) {
    if (!(std::fabs(c.first[0]) < r)) return false; // no crossing in front
    if (!(std::fabs(c.first[1]) < r)) return true;  // one: odd, and a winding of +-1
    int parity = 0, winding = (crossingEnters(c.first[0]) ? 1 : -1) + (crossingEnters(c.first[1]) ? 1 : -1);
    for (const float *e = crossings + c.begin + 2, *end = crossings + c.begin + c.count; e < end; ++e) {
        if (!(std::fabs(*e) < r)) break;
        parity ^= 1;
        winding += crossingEnters(*e) ? 1 : -1;
    }
    return rule == Rule::Parity ? parity != 0 : insideByRule(winding, rule);
}

} // namespace vds::detail
