// vds internal: the generalized winding number of a sprite, for sprites
// (Sprite::contains, classify) and the occupancy sweeps: the integer term
// counted in a column, the boundary term as winding/ gives it.
#pragma once

#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include <glm/vec3.hpp>

#include <vds/classify.h>
#include <vds/sprite.h>

namespace vds::detail {

/// Signed count of a column's crossings strictly in front of depth r.
inline int columnWinding(const float* begin, const float* end, float r) {
    int winding = 0;
    for (const float* e = begin; e != end; ++e) {
        if (!(std::fabs(*e) < r)) break;
        winding += crossingEnters(*e) ? 1 : -1;
    }
    return winding;
}

/// Throws `InvalidArgument` when `sprite` cannot answer `rule`: the
/// generalized winding number of an open sprite read from a version-1 file,
/// which has no boundary edges.
void requireBoundaryKnown(const Sprite& sprite, Rule rule);

/// True when the sprite answers Rule::GeneralizedWinding with a boundary
/// term (it has boundary edges); otherwise the rule reads as Winding.
inline bool needsBoundaryTerm(const Sprite& sprite, Rule rule) {
    return rule == Rule::GeneralizedWinding && !sprite.boundaryEdges.empty();
}

/// `Sprite::contains` for Rule::GeneralizedWinding on a sprite with
/// boundary edges: the label of the per-edge sum.
bool containsGeneralizedWinding(const Sprite& sprite, const glm::vec3& world);


class BoundaryCaps;

/// A sprite's derived data for Rule::GeneralizedWinding (its boundary loops
/// and their caps), built from `Sprite::boundaryEdges` on first use, thread
/// safe; held by `SpriteClassifier` (or by one call), not by the plain-data
/// `Sprite`. A copy or an assignment starts empty, a move takes it along.
class BoundaryCapsCache {
public:
    BoundaryCapsCache() noexcept = default;
    BoundaryCapsCache(const BoundaryCapsCache&) noexcept {}
    BoundaryCapsCache(BoundaryCapsCache&& other) noexcept : caps_(other.caps_.exchange(nullptr)) {}
    BoundaryCapsCache& operator=(const BoundaryCapsCache& other) noexcept {
        if (this != &other) reset();
        return *this;
    }
    BoundaryCapsCache& operator=(BoundaryCapsCache&& other) noexcept {
        if (this != &other) {
            reset();
            caps_.store(other.caps_.exchange(nullptr));
        }
        return *this;
    }
    ~BoundaryCapsCache() { reset(); }
    void reset() noexcept;
    /// The caps of the sprite's boundary edges for the integer term along
    /// its axis, built by the first caller, with the sprite's box as the
    /// domain of their grid of bounds and its columns telling the cells
    /// over which their count is one integer, found on `threads` threads
    /// (0: all cores).
    const BoundaryCaps& get(const Sprite& sprite, unsigned threads = 1) const;

private:
    /// The cache: set once by the first `get`, read by every later one.
    mutable std::atomic<const BoundaryCaps*> caps_{nullptr};
};

/// Batch GWN labels for a sprite with boundary edges (sprite.cpp's
/// `classify` hands over to it): by `caps`, the sprite's (built by
/// BoundaryCapsCache::get), or by the per-edge sum where `caps` is null.
void classifyGeneralizedWinding(const Sprite& sprite, const BoundaryCaps* caps, const float* xyz, std::size_t count,
                                std::size_t strideBytes, std::uint8_t* labels, const ClassifyOptions& options);

} // namespace vds::detail

namespace vds {

/// A `SpriteClassifier`'s caps (<vds/sprite.h> holds them by pointer, so
/// that the installed header names no internal type).
struct SpriteClassifier::Caps {
    detail::BoundaryCapsCache cache;
};

} // namespace vds
