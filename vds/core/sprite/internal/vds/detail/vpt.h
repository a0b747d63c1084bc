// vds internal: the VPT on one column, shared by the point queries
// (sprite.cpp) and the column sweeps (occupancy.cpp), so both answer alike.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include <vds/sprite.h>

namespace vds::detail {

class BoundaryCapsCache; // <vds/detail/sprite_winding.h>

/// The sprite's batch on packed or strided float points (`classify` and
/// `SpriteClassifier` share it): see `classify` in <vds/sprite.h>. `caps`
/// holds the sprite's caps for Rule::GeneralizedWinding, built by the first
/// query that needs them.
void classifySpriteFloats(const Sprite& sprite, const BoundaryCapsCache& caps, const SpriteQueryOptions& query,
                          const float* xyz, std::size_t count, std::size_t strideBytes, std::uint8_t* labels,
                          const ClassifyOptions& options);


/// SpriteGrid::toTexture, inline for the batches that ask it of every
/// point (vds_core is built with -ffp-contract=off: every caller rounds
/// alike, as the GLSL include does).
inline glm::vec3 textureOf(const SpriteGrid& grid, const glm::vec3& world) {
    const glm::vec3 d(world.x - grid.position.x, world.y - grid.position.y, world.z - grid.position.z);
    const glm::mat3& m = grid.matrix;
    return {(m[0][0] * d.x + m[1][0] * d.y) + m[2][0] * d.z,
            (m[0][1] * d.x + m[1][1] * d.y) + m[2][1] * d.z,
            (m[0][2] * d.x + m[1][2] * d.y) + m[2][2] * d.z};
}

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

/// The packed column table: for queries that should miss the cache once.
/// Column c's record is `width` floats at `records + c * width`: its first
/// `width` crossings, `kPadding` where the column has fewer; a column with
/// more keeps its first `width - 1` and `kMore` in the last slot, and a
/// point behind those reads the column from the sprite. Records are 16 bytes
/// (four crossings, four records a cache line), or 32 (eight) when more than
/// `kWideShare` of the columns have over four crossings. Depths lie in
/// [0, 1], so neither marker is ever in front of a point. The table lives
/// in memory aligned to 2 MiB and advised as transparent huge pages where
/// the system has them: random lookups over tens of MB otherwise miss the
/// TLB on most points.
constexpr float kPadding = 2.0f;
constexpr float kMore = 3.0f;
constexpr double kWideShare = 0.05;

class PackedTable {
public:
    PackedTable(const Sprite& sprite, unsigned threads);
    const float* records() const { return table_.get(); }
    unsigned width() const { return width_; }

private:
    struct Free {
        void operator()(float* p) const;
    };
    std::unique_ptr<float[], Free> table_;
    unsigned width_ = 4;
};

/// testColumn on the packed record of `column` (`Width` floats at
/// `record`), without branches on the data unless the point lies behind the
/// record's crossings in a column that has more.
template <unsigned Width>
inline bool testPacked(const float* record, const Sprite& sprite, std::size_t column, float r, Rule rule) {
    bool front[Width];
    for (unsigned k = 0; k < Width; ++k) front[k] = std::fabs(record[k]) < r;
    if (__builtin_expect(front[Width - 2] && record[Width - 1] == kMore, 0))
        return testColumn(sprite.crossings.data() + sprite.offsets[column],
                          sprite.crossings.data() + sprite.offsets[column + 1], r, rule);
    if (rule == Rule::Parity) {
        unsigned parity = 0;
        for (unsigned k = 0; k < Width; ++k) parity ^= unsigned(front[k]);
        return parity != 0;
    }
    int winding = 0;
    for (unsigned k = 0; k < Width; ++k) winding += int(front[k]) * (std::signbit(record[k]) ? -1 : 1);
    return insideByRule(winding, rule);
}

} // namespace vds::detail
