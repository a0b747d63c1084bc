// vds internal: the winding engine's trees as other layers see them
// (CapsValueTree and ChainLabels build them): their nodes, the error
// factor of a node's expansion, and a boundary's chain tree by value, for
// the GPU's packing of it (vds/gl).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include <vds/axis.h>

namespace vds::detail {

/// Index of the symmetric pair (j, k) in a row of CapsNode::quadrupole.
constexpr int kPairs[6][2] = {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {0, 2}, {1, 2}};

/// A node's error bound after its expansion to second order, over its
/// errorScale (3 S / 4 pi), at distance d = |q - c| > R, e = d - R: R
/// times the integral over t in [0, 1] of 4 (1 - t)^2 / (d - t R)^5
/// (Taylor's integral remainder after the second order term, with
/// |h|^3 <= R |h|^2 and the kernel's third derivative taken at distance
/// d - t|h| >= d - t R), in closed form.
inline double remainderFactor(double d, double e, double radius) {
    return radius * (d + 3.0 * e) / (3.0 * d * d * d * d * e * e);
}

/// A node of either tree: a ball (centre, radius) holding a surface,
/// with that surface's moments about the centre.
struct CapsNode {
    glm::dvec3 centre;
    double radius;
    double errorScale; ///< 3 S / 4 pi: the bound is errorScale R (D + 3e) / (3 D^4 e^2), e = D - R
    double area;       ///< unsigned
    glm::dvec3 vectorArea;
    std::array<double, 9> moment; ///< M_ij = integral of n_i (x - c)_j dA, row-major
    /// N_ijk = integral of n_i (x - c)_j (x - c)_k dA, row i holding the
    /// pairs (j, k) = 00, 11, 22, 01, 02, 12
    std::array<double, 18> quadrupole;
    double trace;                 ///< sum of M_ii
    glm::dvec3 quadrupoleRows;    ///< sum over j of N_ijj, for each i
    glm::dvec3 quadrupoleColumns; ///< sum over i of N_iik, for each k
    std::uint32_t first, count; ///< leaf: cap triangles [first, first + count)
    std::uint32_t left, right;  ///< inner: children (count == 0)
};

/// The tree labels refine (decide): over the loops, then within each
/// loop over halves of its edges (chains). A chain a node holds runs
/// from P to Q; closed by its chord Q -> P it bounds the fan from its
/// centre, a surface inside its ball. Where q's ray misses the ball the
/// fan's crossing count is 0, so the chain's edges sum to the chord's
/// angle f(P -> Q) less the fan's solid angle, which the expansion
/// takes: the fan hugs the chain (a lune, not a cap across the loop).
/// Node's moments are its fan's, about `centre` (the ball's centre);
/// a leaf's `first`, `count` are edges of CapLoops::loopEdges().
struct ChainNode : CapsNode {
    static constexpr std::uint32_t kNoLoop = 0xffffffffu; ///< `loop` of a node that is not one whole loop
    glm::dvec3 from, to; ///< the chord P -> Q (none for whole loops)
    bool chord;
    /// One whole loop: its index in CapLoops::loops(); else (a group
    /// of loops, or part of one) kNoLoop.
    std::uint32_t loop;
    /// Every edge under the node: [edgeFirst, edgeFirst + edgeCount)
    /// of the chain tree's edges (the loops in the tree's order),
    /// summed at once where the node is to be opened and holds few.
    std::uint32_t edgeFirst, edgeCount;
};

/// A boundary's chain tree: where its edges close into loops, the loops'
/// edges (loop by loop, each along the loop) and the tree over them ([0]
/// the root; a leaf's `first`, `count` index `loopEdges` by edge).
struct ChainTree {
    bool closed = false; ///< false: the edges do not close into loops (no tree)
    std::vector<glm::vec3> loopEdges;
    std::vector<ChainNode> nodes;
};

/// The chain tree ChainLabels builds over `edgeCount` edges (edge k from
/// edges[2k] to edges[2k+1]) for the integer term's ray along -`axis`.
ChainTree chainTreeOf(const glm::vec3* edges, std::size_t edgeCount, Axis axis);

} // namespace vds::detail
