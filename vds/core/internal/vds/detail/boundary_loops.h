// vds internal: a boundary's closed loops packed for the GLSL include
// (vpt.glsl's VdsBoundaryEdges), so that a shader takes each far loop by
// its cap's expansion instead of summing its edges.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <vds/sprite.h>

namespace vds::detail {

/// Vec4s per loop record after the edges.
constexpr std::uint32_t kLoopRecordSize = 12;
/// Loops with fewer edges get no record: their edges come last, summed.
constexpr std::uint32_t kLoopMinEdges = 4;

struct PackedBoundary {
    /// 2 * edgeCount endpoints (xyz, w unused) in the sprite's (s, t, r)
    /// order, where the edges close into loops first the loops of
    /// kLoopMinEdges edges or more, loop by loop, then the rest; then
    /// kLoopRecordSize vec4s a loop, all in the (s, t, r) frame and about
    /// the loop's centroid c: [0] (c, R: the radius of the ball around c
    /// holding the loop and its cap, the fan from c), [1] (the cap's vector
    /// area A, 3 S / 4 pi with S its integral of |x - c|^2), [2] to [4] the
    /// first moments M_ij = integral of n_i (x - c)_j row by row in 9
    /// floats, then the loop's first edge and edge count as int bits
    /// (intBitsToFloat) and 0, [5] (sum over j of N_ijj, 0), [6] (sum over
    /// i of N_iik, 0), [7] to [11] the second moments N_ijk = integral of
    /// n_i (x - c)_j (x - c)_k, row i holding the pairs (j, k) = 00, 11, 22,
    /// 01, 02, 12, 18 floats and 2 zeros.
    std::vector<glm::vec4> data;
    std::uint32_t edgeCount = 0;
    std::uint32_t loopCount = 0; ///< records: the loops of kLoopMinEdges edges or more
};

/// `edges` (2 * count points, mesh coordinates) packed for a sprite baked
/// along `axis`.
PackedBoundary packBoundary(const std::vector<glm::vec3>& edges, Axis axis);

} // namespace vds::detail
