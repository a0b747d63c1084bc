// vds internal: the tree of a boundary's edges that bounds how far the
// boundary term may drift over a move (BoundaryCaps::reach, driftWithin):
// over the loops (each ball holding its loop's edges and cap), then within
// each loop over its edges.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include <glm/vec3.hpp>

namespace vds::detail {

/// One boundary loop and its cap, the fan from its centroid.
struct CapLoop {
    glm::dvec3 centroid{0.0};      ///< c: the fan's apex (mean of the loop's vertices, rounded to float)
    double radius = 0.0;           ///< R: max |vertex - c|
    double area = 0.0;             ///< sum of the fan triangles' unsigned areas
    std::uint32_t first = 0;       ///< the loop's first edge in `loopEdges()`
    std::uint32_t count = 0;       ///< its edges
};

/// How far the boundary term B (boundary_caps.h) may drift from B(q) along a
/// move from q parallel to the axis. Along such a line B is continuous off
/// the boundary curve G (where it passes a cap, w_caps and C_caps jump together; across the
/// curtain below G, which such a line does not cross, C_caps alone
/// steps), and its gradient is the sum over the loops of the
/// Biot-Savart integral over the loop, the integral of
/// (x - q) x dx / |x - q|^3 over 4 pi (the solid angle's gradient
/// depends only on the curve it is bounded by), of norm at most the sum
/// over its edges of length / (4 pi distance^2); and, the loop's B
/// being its cap's crossing count less its cap's winding number, also
/// at most the cap's area times 2 / (4 pi distance^3) (the gradient of
/// n . (x - q) / |x - q|^3 has norm at most 2 / |x - q|^3), which is
/// smaller for small loops afar. `steepness` is at least the sum over
/// the loops of the smaller of the two at q (clusters taken at the
/// distance of their bounding balls, which hold their edges and caps),
/// `gap` at most q's distance to any edge or far cluster; a move by
/// L < gap shrinks every such distance by at most the factor
/// 1 - L / gap, so it changes B by at most
/// steepness * L / (1 - L / gap)^3.
struct Reach {
    double gap = 0.0;
    double steepness = 0.0;
    /// The largest change of B over a move by `length` (+inf from `gap` on).
    double drift(double length) const {
        if (!(length < gap)) return std::numeric_limits<double>::infinity();
        const double shrink = 1.0 - length / gap;
        return steepness * length / (shrink * shrink * shrink);
    }
};

/// A tree over a boundary's edges: the loops' balls (each holding its
/// loop's edges and cap), then each loop's edges; or, where the edges do
/// not close into loops, the edges alone. Built once, then thread safe.
class EdgeTree {
public:
    /// `edges` (edge k from [2k] to [2k+1]) and, where they close, their
    /// `loops` over `loopEdges` (then the tree's edges are in loop order).
    void build(const std::vector<glm::vec3>& edges, const std::vector<glm::vec3>& loopEdges,
               const std::vector<CapLoop>& loops, bool closed);
    /// Reach{} (no move certain) once the steepness is known to exceed
    /// `steepest`: where that cannot carry a label one cell further, the
    /// rest of the sum is not worth taking.
    Reach reach(const glm::vec3& q, double steepest = std::numeric_limits<double>::infinity()) const;
    /// The largest change of B (and of w_caps) over a move from q by at
    /// most `length` in any direction along which B is smooth, the same
    /// bounds taken term by term: each edge or cluster at distance r
    /// (beyond `length`) adds its bound at r - length, so that far parts
    /// are not charged for the nearest one's closeness as Reach::drift
    /// charges them. +inf past `limit`, or where an edge lies within
    /// `length` of q.
    double driftWithin(const glm::vec3& q, double length, double limit) const;
    std::size_t memoryBytes() const {
        return treeEdges_.capacity() * sizeof(glm::vec3) + edgeNodes_.capacity() * sizeof(EdgeNode);
    }

private:
    /// A ball holding its edges (and for whole loops their caps).
    struct EdgeNode {
        glm::dvec3 centre;
        double radius;
        double length;              ///< of its edges, summed
        double capArea;             ///< of its loops' caps (whole loops only)
        std::uint32_t first, count; ///< leaf: edges [first, first + count) of treeEdges_
        std::uint32_t left, right;  ///< inner: children (count == 0); a loop's node: its edges' subtree in left
        bool wholeLoops;            ///< its edges are whole loops, capped
        bool loopNode;              ///< one loop
    };
    /// driftWithin()'s sums over a leaf's edges, each at its nearest to p:
    /// of length / (distance - `length`)^2 into `sumMoved`, of length /
    /// distance^2 into `sumAt`, the least distance into `nearest`; false
    /// where a move by `length` may reach one.
    bool addEdgeDrifts(const EdgeNode& leaf, const glm::dvec3& p, double length, double& sumMoved, double& sumAt,
                       double& nearest) const;
    /// Distance from p to tree edge k (at its nearest), and the edge's
    /// squared length into `length2`.
    double edgeDistance(std::uint32_t k, const glm::dvec3& p, double& length2) const;
    std::uint32_t buildLoops(std::vector<std::uint32_t>& nodes, std::uint32_t first, std::uint32_t last);
    std::uint32_t buildEdges(std::uint32_t first, std::uint32_t last);
    std::vector<glm::vec3> treeEdges_; ///< the edges in the tree's order
    std::vector<EdgeNode> edgeNodes_;  ///< [0] is the root
};

} // namespace vds::detail
