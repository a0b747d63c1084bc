// vds internal: a boundary's edges and its chain tree (<vds/detail/chain_tree.h>,
// BoundaryCaps::chains) packed for the GLSL include (vpt.glsl's
// VdsBoundaryEdges), so that a shader takes each node whose ball the
// point's ray misses by its chord and its fan's expansion instead of
// summing its edges.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <vds/sprite.h>

namespace vds::detail {

/// Vec4s per node record after the edges.
constexpr std::uint32_t kBoundaryNodeSize = 14;
/// The shader's VDS_NODE_TOLERANCE: the largest remainder bound (winding
/// number units) of a node it takes by its expansion.
constexpr double kBoundaryNodeTolerance = 1e-5;
/// Node flags (record [1].w, int bits, below the edge count shifted by 2).
constexpr std::uint32_t kBoundaryNodeLeaf = 1;  ///< no children: its edges are summed where it is not taken
constexpr std::uint32_t kBoundaryNodeChord = 2; ///< a chain of part of a loop, closed by its chord

struct PackedBoundary {
    /// 2 * edgeCount endpoints (xyz, w unused) in the sprite's (s, t, r)
    /// order: where the edges close into loops, in the order of the
    /// chain tree's leaves (loop by loop, each in order along the loop as
    /// in BoundaryCaps::loopEdges(), the loops in the tree's order), so
    /// that every node's edges are one range; else as given. Then
    /// nodeCount records of kBoundaryNodeSize vec4s, in preorder (a node's
    /// first child is the next record; groups of loops whose expansion
    /// could not be taken within a diagonal of the boundary's box are left
    /// out, their children in their place), each in the (s, t, r) frame and
    /// about its ball's centre c (see BoundaryCaps::ChainNode; the node's
    /// surface is the fan over its edges, closed by its chord where it has
    /// one):
    ///   [0]       (c, R): the ball, holding the node's edges and fan
    ///   [1]       (errorScale = 3 S / 4 pi, S the fan's integral of
    ///             |x - c|^2; then int bits (intBitsToFloat): the record
    ///             after the node's subtree, the node's first edge, its edge
    ///             count << 2 | kBoundaryNodeLeaf | kBoundaryNodeChord); the
    ///             node's edges are [first, first + count)
    ///   [2]       (vector area A of the fan, M_00)
    ///   [3] [4]   M_01, M_02, M_10, M_11, M_12, M_20, M_21, M_22: the first
    ///             moments M_ij = integral of n_i (x - c)_j dA, row-major
    ///   [5]       (sum over j of N_ijj for each i, 0)
    ///   [6]       (sum over i of N_iik for each k, 0)
    ///   [7]..[11] the second moments N_ijk = integral of
    ///             n_i (x - c)_j (x - c)_k dA, row i holding the pairs
    ///             (j, k) = 00, 11, 22, 01, 02, 12: 18 floats, 2 zeros
    ///   [12] [13] (P, 0), (Q, 0): the chain runs from P to Q and its chord
    ///             closes it Q -> P (zeros without a chord)
    std::vector<glm::vec4> data;
    std::uint32_t edgeCount = 0;
    /// Node records; 0 where the edges do not close into loops (then every
    /// edge is summed).
    std::uint32_t nodeCount = 0;
};

/// `edges` (2 * count points, mesh coordinates) packed for a sprite baked
/// along `axis`.
PackedBoundary packBoundary(const std::vector<glm::vec3>& edges, Axis axis);

} // namespace vds::detail
