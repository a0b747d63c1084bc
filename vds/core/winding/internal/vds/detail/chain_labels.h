// vds internal: the chain tree labels refine (boundary_caps.h says why a
// chain's edges sum to its chord's angle less its fan's): its build, a node
// taken by its chord and expansion, and the decide-or-refine loop.
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include <vds/detail/cap_loops.h>
#include <vds/detail/caps_math.h>
#include <vds/detail/chain_tree.h>

namespace vds::detail {

/// The chain tree over `loops` (kept by reference: it must outlive this)
/// and the labels it decides. Built once, then thread safe.
class ChainLabels {
public:
    explicit ChainLabels(const CapLoops& loops);
    /// [0] is the root; empty where the caps are no mesh.
    const std::vector<ChainNode>& chains() const { return chains_; }
    /// The loops' edges in the tree's order (ChainNode::edgeFirst), 2
    /// points an edge.
    const std::vector<glm::vec3>& edges() const { return chainEdges_; }
    int axisIndex() const;
    /// The summed length of a node's edges.
    double lengthOf(const ChainNode& n) const;
    /// The loop tree edge `edge` lies in: its edges [first, end).
    std::pair<std::uint32_t, std::uint32_t> loopOf(std::uint32_t edge) const;

    /// The per-edge sum over the edges of chain nodes `roots` (over 4 pi)
    /// at `count` points of the box [lo, hi] into `out`, and the bound
    /// that holds at each: one cut for them all, a node q's ray misses
    /// from anywhere in the box taken by its expansion to second order
    /// where that errs by at most `tolerance` at the box's nearest point,
    /// the rest opened down to nodes of at most kDirectEdges edges, whose
    /// edges are summed (a cell's field samples its far part so). `work`:
    /// the nodes taken and edges summed, over all the points.
    double sumOver(const std::uint32_t* roots, std::size_t rootCount, const glm::dvec3& lo, const glm::dvec3& hi,
                   const glm::dvec3* points, std::size_t count, double tolerance, double* out, double& work) const;

    /// `winding + B(q)` within `bound` of the per-edge sum's value, refined
    /// until it lies farther than `margin` (>= 1) times its bound from 1/2
    /// (plus the tie), or the per-edge sum's value with bound 0 where the
    /// tree does not get there: its side of the threshold is the per-edge
    /// sum's label, and with margin > 1 the rest of that distance is left
    /// for neighbours (Reach).
    CapsEstimate decide(int winding, const glm::vec3& q, double margin) const;
    /// The decide-or-refine of decide(), from the chain nodes `roots`
    /// (whole loops, or the root) with `farCrossings` + [farLo, farHi]
    /// standing for the rest; false where it runs out of nodes with the
    /// far range left (planned) or of budget.
    bool refine(int winding, const glm::vec3& q, double margin, const std::uint32_t* roots, std::size_t rootCount,
                double farLo, double farHi, CapsEstimate& out) const;
    /// refine()'s first round over chain nodes `roots`, each taken by its
    /// first-order term or its edges summed (as refine's first cut takes
    /// them, in the same order: the same value and bound), in one pass with
    /// no stack; true where that decides (then `out` is refine's answer),
    /// false where it does not or a root would be split.
    bool firstCut(int winding, const glm::vec3& q, const std::uint32_t* roots, std::size_t rootCount, double farLo,
                  double farHi, CapsEstimate& out) const;
    /// The nodes refine() from `roots` reaches for every query within
    /// `half` of `c`: a root that no such query can take (its ball holds
    /// them all, or its first-order bound exceeds kMaxTakenBound at the
    /// farthest of them) and that refine() would split is replaced by its
    /// children, and so on. refine() from these takes the same nodes and
    /// sums the same edges for each such query, without the tests on the
    /// nodes above them (a planned cell's queries start here).
    void frontier(const std::uint32_t* roots, std::size_t rootCount, const glm::dvec3& c, double half,
                  std::vector<std::uint32_t>& out) const;
    std::size_t memoryBytes() const;

private:
    struct Refinement; ///< refine()'s running state (chain_labels.cpp)

    std::uint32_t buildChainGroup(std::vector<std::uint32_t>& loops, std::uint32_t first, std::uint32_t last);
    std::uint32_t buildChain(std::uint32_t loop, std::uint32_t first, std::uint32_t count, std::uint32_t treeFirst);
    /// refine()'s step on one chain node at p: where q's ray misses its
    /// ball and its bound (first order, or the remainder where
    /// `secondOrder`) is at most kMaxTakenBound, that bound and minus its
    /// fan's angle by the expansion (its edges' angle is that plus its
    /// chord's, which the caller sums with the other taken chords' at one
    /// atan2: chain_labels.cpp); false where it must be opened.
    inline bool takeNode(const ChainNode& n, const glm::dvec3& p, bool secondOrder, double& bound,
                         double& value) const;

    const CapLoops& loops_;
    std::vector<ChainNode> chains_;
    /// The loops' edges with the loops in the chain tree's order, so that
    /// every chain node's edges lie together (ChainNode::edgeFirst).
    std::vector<glm::vec3> chainEdges_;
    /// Each loop's first edge in chainEdges_, ascending, then their count.
    std::vector<std::uint32_t> loopStarts_;
    /// The edges' lengths summed up to each edge.
    std::vector<double> lengthBefore_;
};

} // namespace vds::detail
