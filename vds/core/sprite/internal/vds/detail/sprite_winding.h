// vds internal: the generalized winding number of a sprite, for sprites
// (Sprite::contains, classify) and the occupancy sweeps: the integer term
// counted in a column, the boundary term as winding/ gives it.
#pragma once

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

/// Batch GWN labels for a sprite with boundary edges (sprite.cpp's
/// `classify` hands over to it): by `caps`, the sprite's (built by
/// BoundaryCapsCache::get), or by the per-edge sum where `caps` is null.
void classifyGeneralizedWinding(const Sprite& sprite, const BoundaryCaps* caps, const float* xyz, std::size_t count,
                                std::size_t strideBytes, std::uint8_t* labels, const ClassifyOptions& options);

} // namespace vds::detail
