// vds internal: the boundary term of the generalized winding number by
// capping the boundary loops, fast where the boundary is long.
//
// The signed boundary edges of an oriented triangle mesh form a 1-cycle (at
// every vertex as many run out as in), so they split into closed directed
// loops L. Close each with a cap: the fan of triangles (c, b, a) from the
// loop's centroid c over its edges a -> b, whose boundary is L reversed.
// Mesh plus caps is then a closed 2-cycle, whose generalized winding number
// is its signed crossing count along any ray. With C the signed count along
// the ray from q towards -axis (the integer term's ray) and w the solid-angle
// sum over 4 pi:
//
//     GWN_mesh(q) = C_mesh(q) + C_caps(q) - w_caps(q),
//
// so the boundary term is B(q) = C_caps(q) - w_caps(q). C_caps is counted
// with the exact predicates and top-left tie rule of projected_mesh.h, like
// the mesh's own count, so that the two jump together where q's ray passes
// over a boundary edge. w_caps is smooth away from the caps: a tree over the
// cap triangles (Barill et al. 2018, "Fast winding numbers for soups and
// clouds", section 3) takes each node whose sphere (centre c, radius R) lies
// far enough from q by its Taylor expansion to second order about c (the
// vector area, the first moments M_ij and the second moments N_ijk of the
// normal), and sums the remaining leaves' triangles exactly.
//
// Error of a node taken by expansion, with D = |q - c| > R: Taylor's
// remainder of the kernel K(y) = y / |y|^3 after its second order term, for
// the point x = c + h, is the integral over t in [0, 1] of
// (1 - t)^2 / 2 n . D^3K(c - q + t h)[h, h, h] dt. D^3K contracted with a
// unit n and h three times is the fourth derivative of 1 / |y| along n, h,
// h, h, at most 4! = 24 / |y|^5 (with y unit, b = h.y and the maximum over
// n taken, its square is (105 b^3 - 45 b)^2 + (9 - 45 b^2)^2 +
// 2 b (105 b^3 - 45 b)(9 - 45 b^2), which peaks at 576 for b^2 = 1), and
// |c - q + t h| >= D - t R. With |h|^3 <= R |h|^2 and |h|^2 integrating to
// S, and the integral of 12 (1 - t)^2 / (D - t R)^5 over t in [0, 1] being
// (D + 3e) / (D^4 e^2) with e = D - R, the node errs by at most
//
//     (1 / 4 pi) * R * S * (D + 3e) / (D^4 e^2),   S = sum over its triangles
//                                                  of the integral of
//                                                  |x - c|^2 dA,
//
// (S = area * (|g - c|^2 + (sum of squared sides) / 36) for a triangle of
// centroid g): about R / D times the first-order expansion's bound. Values
// take a node by expansion when that bound is at most a tolerance times the
// solid angle the node subtends (area / D^2, so that the bounds sum to
// about the tolerance times the caps' apparent solid angle); the sum of the
// taken nodes' bounds comes back with the value, and values fall back to
// the per-edge sum (antipodal.h) where it exceeds their tolerance.
//
// Labels use a second tree whose nodes are chains of edges, not pieces of
// the caps: a chain from P to Q closed by its chord Q -> P bounds a thin fan
// along the boundary, and where q's ray misses the node's ball the chain's
// per-edge angles sum to its chord's angle less that fan's solid angle
// (the identity above, with no crossing). The fan is taken by its
// expansion to first order, whose remainder bound is, the same way (second
// derivative 3! / |y|^4 at most), S (D + 2e) / (4 pi D^3 e^2). From the
// coarsest cut whose nodes each err by at most 1/4, the nodes with the
// largest bounds (at least half the largest) are opened a round at a time
// (their children, or the edges of a node holding at most 16 summed
// exactly; within 0.1 of the threshold, the children to second order)
// until the value lies farther from the label's threshold (1/2 plus the
// tie, antipodal.h) than the summed bounds; past a budget of the per-edge
// sum's work, or where the work the bounds still ask for is predicted to
// pass it, the per-edge sum decides. So labels equal the per-edge sum's,
// and a point near a large loop costs a few chains near it and the chords
// of the rest, where the caps' fans, meeting across the opening, would
// cost the loop's every edge.
#pragma once

#include <array>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <vds/mesh.h>

#include <vds/detail/projected_mesh.h>
#include <vds/detail/chain_tree.h>
#include <vds/detail/edge_tree.h>
#include <vds/detail/range_grid.h>

namespace vds::detail {

/// Error bound a tree node may add when taken by its expansion, per unit of
/// the solid angle it subtends, for values (then exactly where the bound
/// exceeds the value's tolerance).
constexpr double kCapValueTolerance = 1e-3;

/// A surface's integral of n . (x - q) / |x - q|^3 dA by its expansion to
/// first order about c, at y = c - q (|y| = d): vector area A, first
/// moments M_ij (row-major) and their trace.
inline double firstOrderTerm(const glm::dvec3& vectorArea, const std::array<double, 9>& M, double trace,
                             const glm::dvec3& y, double d2, double d) {
    const double inv2 = 1.0 / d2, inv3 = inv2 / d;
    const double yMy = y.x * (M[0] * y.x + M[1] * y.y + M[2] * y.z) + y.y * (M[3] * y.x + M[4] * y.y + M[5] * y.z) +
                       y.z * (M[6] * y.x + M[7] * y.y + M[8] * y.z);
    return (vectorArea.x * y.x + vectorArea.y * y.y + vectorArea.z * y.z + trace - 3.0 * yMy * inv2) * inv3;
}

/// The cells of a grid: cell (i, j, k) spans lo + (i, j, k) * size to
/// lo + (i + 1, j + 1, k + 1) * size.
struct CellLattice {
    glm::dvec3 lo{0.0}, size{0.0};
    glm::uvec3 dims{0};
    std::size_t index(const glm::uvec3& at) const { return (std::size_t(at.z) * dims.y + at.y) * dims.x + at.x; }
};

/// The surface a boundary belongs to, for ranges of its whole generalized
/// winding number: over a cell that no part of the surface meets, the
/// winding number is smooth (its gradient is the boundary's Biot-Savart
/// integral, which BoundaryCaps::driftWithin bounds in any direction;
/// across a cap or a boundary edge's sweep its integer term and boundary
/// term jump together), so its value at the cell's centre and the drift
/// over the cell give its range, and a query there needs neither term.
class CapsSurface {
public:
    virtual ~CapsSurface() = default;
    /// The integer term at q, as the caller counts it (crossings strictly
    /// in front of q towards -axis, the top-left rule on ties).
    virtual int winding(const glm::vec3& q) const = 0;
    /// Sets met[cells.index(at)] = 1 for every cell the surface may meet:
    /// a cell left 0 must be clear of every triangle, a cell set may be.
    virtual void markCells(const CellLattice& cells, std::vector<std::uint8_t>& met) const = 0;
};

/// What a caller knows of its integer term over whole cells, where the
/// surface itself is not at hand (a sprite has columns, not triangles):
/// over a cell clear of the boundary's sweep B is smooth, so an integer
/// term that is one integer n over the cell, as the queries landing in it
/// ask it, makes n plus B's range the whole winding number's range there,
/// and a query in the cell needs neither term.
class CellWindings {
public:
    static constexpr std::int32_t kUnknown = std::numeric_limits<std::int32_t>::min();
    virtual ~CellWindings() = default;
    /// Sets windings[cells.index(at)] = n for every cell over which the
    /// integer term is known to be n; leaves the rest (kUnknown). And
    /// closed[cells.index(at)] = n for every cell over which the integer
    /// term plus `caps`' crossing count (ProjectedMesh::winding) at the
    /// point B is taken at is known to be n: the crossing count of the
    /// closed surface the caps make of the mesh, one integer where that
    /// surface keeps out of the cell, across the boundary's sweep too: for
    /// the queries that ask inside() (those that ask insideApart are not
    /// held to it).
    virtual void constantWindings(const CellLattice& cells, const ProjectedMesh* caps,
                                  std::vector<std::int32_t>& windings, std::vector<std::int32_t>& closed) const = 0;
};

/// Marks the cells triangle (a, b, c) may meet: those its box overlaps
/// that its plane does not pass clear of, both with a margin of `slack`.
void markTriangleCells(const CellLattice& cells, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                       double slack, std::vector<std::uint8_t>& met);

/// A projected mesh as the surface of its boundary edges: its crossing
/// count, and the cells its triangles (parallel ones too: the winding
/// number jumps across them as well) may meet. Keeps a reference.
class ProjectedSurface final : public CapsSurface {
public:
    explicit ProjectedSurface(const ProjectedMesh& mesh) : mesh_(mesh) {}
    int winding(const glm::vec3& q) const override { return mesh_.winding(q); }
    void markCells(const CellLattice& cells, std::vector<std::uint8_t>& met) const override;

private:
    const ProjectedMesh& mesh_;
};

/// The boundary term of a set of boundary edges by their capped loops. Built
/// once (O(E log E)), then thread safe to query.
class BoundaryCaps {
public:
    /// `edges`: 2 * `edgeCount` points, edge k from [2k] to [2k+1] (copied).
    /// `axis`: the integer term's ray runs towards -axis.
    /// `domain`: where most queries lie (the mesh's or sprite's box), for
    /// the grid of bounds `inside` answers from first (see there); none:
    /// every query refines the tree.
    /// `surface` (kept, to outlive this): the surface of which the edges
    /// are the boundary, for cells of the grid that it does not meet (see
    /// CapsSurface); none: only cells clear of the boundary's sweep.
    /// `windings` (asked once, here, not kept): where no surface is given,
    /// the cells over which the integer term is one integer (CellWindings).
    BoundaryCaps(const glm::vec3* edges, std::size_t edgeCount, Axis axis, const Box* domain = nullptr,
                 const CapsSurface* surface = nullptr, const CellWindings* windings = nullptr);

    struct Estimate {
        double term = 0.0;  ///< B(q)
        double bound = 0.0; ///< |B(q) - exact| <= bound; +inf where q lies on a cap (use the exact sum)
        /// decide(): nodes taken and edges summed (the per-edge sum adds
        /// its edges), the cost in edges' angles of the per-edge sum.
        double work = 0.0;
    };
    /// B(q) and its error bound, taking nodes whose bound is at most
    /// `nodeTolerance` by expansion. Points are float so that the crossing
    /// count and the solid angles are taken at the same point.
    Estimate estimate(const glm::vec3& q, double nodeTolerance) const;


    /// How far B may drift from B(q) along a move from q (Reach, EdgeTree).
    using Reach = detail::Reach;
    Reach reach(const glm::vec3& q, double steepest = std::numeric_limits<double>::infinity()) const {
        return edgeTree_.reach(q, steepest);
    }
    double driftWithin(const glm::vec3& q, double length, double limit) const {
        return edgeTree_.driftWithin(q, length, limit);
    }

    /// `winding + B(q)` within `tolerance` of `winding + boundaryTermExact`,
    /// falling back to the per-edge sum where the estimate's bound is larger.
    double generalizedWinding(int winding, const glm::vec3& q, double tolerance) const;

    /// Whether `winding + B(q) > 1/2`, with the per-edge sum's answer: the
    /// chain tree is refined greedily until the value is farther from 1/2
    /// than its bound. Within the domain, first from a coarse grid of
    /// bounds on B: each cell, when a query first lands in it, gets B's
    /// range over the cell, from an estimate at its centre and the drift
    /// over its half diagonal, where no part of the boundary curve nor of
    /// its sweep along +axis (where B jumps) passes through the cell; a
    /// winding that this range puts clear of 1/2 answers at once. Where
    /// the caps know their surface, a cell it does not meet gets the range
    /// of the whole winding number, which answers without `winding` (so
    /// does a cell clear of the sweep over which the caller's integer term
    /// is one integer, CellWindings); a
    /// cell the caps do not meet, the range of -w_caps, to which the caps'
    /// crossing count at q is added. A cell with no range gets a plan
    /// where it pays: the loops far from it collapsed into the range of
    /// their caps' -w over the cell (plus their crossing count at q), the
    /// few near ones refined from each query as decide() does.
    bool inside(int winding, const glm::vec3& q) const;
    /// As `inside(winding, q)`, for a query whose integer term is not the
    /// one CellWindings' closed counts speak of (a sprite's point beside its
    /// texture, where the count is 0 and B is taken at the point itself):
    /// a cell whose range came from a closed count is taken as the range
    /// of -w_caps it holds, plus the caps' crossing count at q.
    bool insideApart(int winding, const glm::vec3& q) const;
    /// As `inside`, asking the surface (given at construction) for the
    /// integer term only where the grid does not answer alone.
    bool inside(const glm::vec3& q) const;
    /// The label where q's cell answers without the integer term (a range
    /// of the whole winding number clear of 1/2): 1 inside, 0 outside; -1
    /// where it does not (then `inside(winding, q)`). Fills q's cell on its
    /// first visit, as `inside` does. `apart`: a query as insideApart's
    /// (then a cell whose range came from a closed count answers -1).
    inline int insideAlone(const glm::vec3& q, bool apart = false) const;

    /// `winding + B(q)` within `bound` of the per-edge sum's value, refined
    /// as `inside` does until it lies farther than `margin` (>= 1) times
    /// its bound from 1/2 (plus the tie), or the per-edge sum's value with
    /// bound 0 where the tree does not get there: its side of the
    /// threshold is the per-edge sum's label, and with margin > 1 the rest
    /// of that distance is left for neighbours (Reach).
    Estimate decide(int winding, const glm::vec3& q, double margin) const;

    /// Cells of the grid of bounds with a range so far, by kind: of B
    /// (clear of the boundary's sweep), of the whole winding number (clear
    /// of the surface), of -w_caps (clear of the caps; the caps' crossing
    /// count is asked at the query).
    struct RangedCells {
        std::size_t boundary = 0, winding = 0, capped = 0;
        std::size_t all() const { return boundary + winding + capped; }
        /// Cells with no range but a plan: the loops near the cell, the
        /// rest's -w_caps by its range over the cell (see decide).
        std::size_t planned = 0;
        /// Of `winding`: cells in the boundary's sweep, by the closed
        /// surface's crossing count (CellWindings).
        std::size_t closed = 0;
    };
    /// The coarse grid's cells; `fine`: the fine grid's (busy cells').
    RangedCells rangedCells(bool fine = false) const;
    /// Bytes held: the loops, caps, trees and both grids of bounds (the
    /// plans filled so far included).
    std::size_t memoryBytes() const;

    /// False when the edges do not close into loops (not a mesh's boundary):
    /// every query then takes the per-edge sum.
    bool closed() const { return closed_; }
    const std::vector<CapLoop>& loops() const { return loops_; }
    /// The edges in loop order: loop l's edges are [first, first + count),
    /// edge k from [2k] to [2k+1].
    const std::vector<glm::vec3>& loopEdges() const { return loopEdges_; }
    std::size_t edgeCount() const { return edges_.size() / 2; }

    /// A node of either tree (chain_tree.h).
    using Node = CapsNode;
    using ChainNode = vds::detail::ChainNode;
    static constexpr std::uint32_t kNoLoop = ChainNode::kNoLoop;
    /// [0] is the root; empty where the edges do not close into loops.
    const std::vector<ChainNode>& chains() const { return chains_; }
    /// A node's fan's solid angle seen from q by its expansion to first
    /// order, and the bound on that expansion's error (over 4 pi: in B's
    /// units) at distance `distance` > radius from its centre, which falls
    /// as the distance grows.
    static double firstOrderSolidAngle(const Node& n, const glm::dvec3& q) {
        const glm::dvec3 y = n.centre - q;
        const double d2 = y.x * y.x + y.y * y.y + y.z * y.z;
        return firstOrderTerm(n.vectorArea, n.moment, n.trace, y, d2, std::sqrt(d2));
    }
    static double firstOrderBound(const Node& n, double distance);

private:
    // ---- the caps and their tree of cap triangles, for values (caps_tree.cpp)
    double exact(int winding, const glm::vec3& q) const;
    /// Loop `loop`'s cap: its centroid, radius and area, its fan among the
    /// caps' triangles, and (appended to `tris`) in double.
    void addCap(CapLoop& loop, std::vector<std::array<glm::dvec3, 3>>& tris);
    static void finish(Node& node);
    static double firstOrder(const Node& n, const glm::dvec3& y, double d2, double d);
    static double expansion(const Node& n, const glm::dvec3& y, double d2, double d);
    /// `unsignedMoments[node]`: the integral of |n| (x - centre) dA, for the
    /// parent's moments from its children's.
    std::uint32_t build(std::uint32_t first, std::uint32_t last, std::vector<std::uint32_t>& order,
                        const std::vector<std::array<glm::dvec3, 3>>& tris,
                        std::vector<glm::dvec3>& unsignedMoments);
    /// build()'s leaf `node` (its ball set) at `index`: its triangles'
    /// moments, and the triangles themselves into leafTris_.
    void buildLeaf(Node& node, std::uint32_t index, std::uint32_t first, std::uint32_t last,
                   const std::vector<std::uint32_t>& order, const std::vector<std::array<glm::dvec3, 3>>& tris,
                   std::vector<glm::dvec3>& unsignedMoments);
    /// build()'s inner `node` at `index`: its children's moments moved to
    /// its centre and summed.
    void gatherChildren(Node& node, std::uint32_t index, std::vector<glm::dvec3>& unsignedMoments);

    // ---- the chain tree labels refine (chain_tree.cpp)
    void buildChains();
    std::uint32_t buildChainGroup(std::vector<std::uint32_t>& loops, std::uint32_t first, std::uint32_t last);
    std::uint32_t buildChain(std::uint32_t loop, std::uint32_t first, std::uint32_t count, std::uint32_t treeFirst);
    /// refine()'s first round over chain nodes `roots`, each taken by its
    /// first-order term or its edges summed (as refine's first cut takes
    /// them, in the same order: the same value and bound), in one pass with
    /// no stack; true where that decides (then `out` is refine's answer),
    /// false where it does not or a root would be split.
    bool firstCut(int winding, const glm::vec3& q, const std::uint32_t* roots, std::size_t rootCount, double farLo,
                  double farHi, Estimate& out) const;
    /// refine()'s step on one chain node at p: where q's ray misses its
    /// ball and its bound (first order, or the remainder where `fine`) is
    /// at most kMaxTakenBound, that bound and its edges' angle (its chord's
    /// less its fan's, by the expansion); false where it must be opened.
    inline bool takeNode(const ChainNode& n, const glm::dvec3& p, bool fine, double& bound, double& value) const;
    /// The decide-or-refine of decide(), from the chain nodes `roots`
    /// (whole loops, or the root) with `farCrossings` + [farLo, farHi]
    /// standing for the rest; false where it runs out of nodes with the
    /// far range left (planned) or of budget.
    bool refine(int winding, const glm::vec3& q, double margin, const std::uint32_t* roots, std::size_t rootCount,
                double farLo, double farHi, Estimate& out) const;
    struct Refinement; ///< refine()'s running state (chain_tree.cpp)

    // ---- a grid cell's plan (cell_plans.cpp)
    /// The cap triangles q's ray towards -axis crosses in front of q, as
    /// (loop, +1 or -1): C_caps loop by loop, counted as projected_ counts.
    void capCrossings(const glm::vec3& q, std::vector<std::pair<std::uint32_t, int>>& out) const;
    /// A cell's plan, on the fill: false where the far loops' range would
    /// be too wide to help.
    bool plan(const RangeGrid& g, std::size_t cell, const glm::vec3& c, double half, bool within) const;
    /// decide() from a planned cell's near loops; false where that does
    /// not decide (the far range is as wide as the rest of the distance).
    bool decidePlanned(const RangeGrid& g, int winding, const glm::vec3& q, std::size_t cell, Estimate& out) const;

    // ---- the grids of bounds (range_grid.cpp)
    void buildRangeGrid(const Box& domain, const CellWindings* windings);
    /// `cellsNow`: allocate its cells' states and ranges too (RangeGrid::allocate).
    void buildGrid(RangeGrid& g, const Box& box, double cellsAlong, const CellWindings* windings, bool cellsNow);
    /// The fine grid's cells, allocated on the first call (once, whichever
    /// thread comes first); false where there is no fine grid.
    bool fineCells() const;
    /// The cell's state, filling it on the first visit; `within`: a fine
    /// cell within a planned coarse one (plan()).
    CellState rangeOf(const RangeGrid& g, std::size_t cell, const glm::uvec3& at, bool within = false) const;
    /// Clear of the boundary curve and its sweep along +axis: every edge
    /// whose projection may meet the cell's column lies above the cell.
    bool clearOfSweep(const RangeGrid& g, const glm::uvec3& at) const;
    /// B over the ball: `e` at its centre, to be widened by `drift`; false
    /// where the two span half a unit or more (no range clear of 1/2).
    bool rangeOver(const CellsBall& ball, Estimate& e, double& drift) const;
    /// On a coarse cell's fill (the caller owns `cell`, Filling), once a
    /// block: where no cell of its block of 2 x 2 x 2 meets the surface
    /// (or, without one, every cell is clear of the boundary's sweep and
    /// the caller knew one integer term for them all), the range of the
    /// whole winding number over the block, clear of 1/2, for every cell
    /// of it not yet filled: one fill for eight far from the surface.
    /// True where `cell` got it (then WindingRange is the caller's to publish).
    bool blockRange(const RangeGrid& g, std::size_t cell, const glm::uvec3& at) const;
    /// Whether a coarse cell without a range has had queries enough to
    /// ask the fine grid (counting this one).
    bool busy(std::size_t cell) const;
    /// insideBy() in cell `cell` of `g`, of state `state`.
    template <class Winding>
    bool insideIn(const RangeGrid& g, std::size_t cell, CellState state, const glm::vec3& q,
                  const Winding& windingAt, bool apart) const;
    /// inside(), asking `windingAt()` for the integer term only where the
    /// cell's range does not answer without it.
    template <class Winding>
    bool insideBy(const glm::vec3& q, const Winding& windingAt, bool apart) const;

    int axisIndex_;
    const CapsSurface* surface_ = nullptr;
    bool closed_ = true;
    std::vector<glm::vec3> edges_;
    std::vector<glm::vec3> loopEdges_;
    std::vector<CapLoop> loops_;
    std::vector<glm::vec3> capPositions_;
    std::vector<glm::uvec3> capTriangles_;
    std::vector<std::uint32_t> capLoopOf_; ///< the loop of each cap triangle
    std::vector<std::array<glm::dvec3, 3>> leafTris_; ///< cap triangles in tree order
    std::vector<Node> nodes_;                         ///< [0] is the root
    std::optional<ProjectedMesh> projected_;          ///< the caps, for C_caps
    std::vector<ChainNode> chains_;
    /// loopEdges_ with the loops in the chain tree's order, so that every
    /// chain node's edges lie together (ChainNode::edgeFirst).
    std::vector<glm::vec3> chainEdges_;
    /// The grid of bounds, and one of cells half as wide along each side
    /// over the same box: a coarse cell without a range (NoRange, Planned)
    /// that many queries land in hands them to its fine cells, whose
    /// ranges and far ranges, taken over half the width, keep clear of 1/2
    /// more often (the near loops a plan keeps are about as many: a soup's
    /// small loops are near by their own size). Only those fine cells are
    /// filled: a fill costs a few queries' work.
    RangeGrid ranges_;
    mutable RangeGrid fine_; ///< its cells allocated by fineCells()
    mutable std::once_flag fineOnce_;
    mutable std::atomic<bool> fineReady_{false};
    EdgeTree edgeTree_; ///< for reach() and driftWithin()
};

// Inline: asked once a query (a sprite's batch asks insideAlone of every point).

int BoundaryCaps::insideAlone(const glm::vec3& q, bool apart) const {
    std::size_t cell;
    glm::uvec3 at;
    if (!ranges_.cellOf(q, cell, at)) return -1;
    CellState state = ranges_.state[cell].load(std::memory_order_acquire);
    if (state == CellState::Unvisited) state = rangeOf(ranges_, cell, at);
    if (state != CellState::WindingRange) return -1;
    const CellVerdict verdict = ranges_.alone[cell];
    if ((apart && verdict.byClosed()) || verdict.label() == CellLabel::Undecided) return -1;
    return verdict.label() == CellLabel::Inside ? 1 : 0;
}

// Inline: taken once a node by the walks of the labels and values.
//
// The node's integral of n . (x - q) / |x - q|^3 dA by its Taylor expansion
// about its centre to second order, at y = c - q (|y| = d): with
// K_i(y) = y_i / d^3, the terms are A . K, M_ij dK_i/dy_j and
// N_ijk d2K_i/dy_j dy_k / 2, where dK_i/dy_j = delta_ij / d^3 - 3 y_i y_j / d^5
// and d2K_i/dy_j dy_k = -3 (delta_ij y_k + delta_ik y_j + delta_jk y_i) / d^5
// + 15 y_i y_j y_k / d^7.
inline double BoundaryCaps::firstOrder(const Node& n, const glm::dvec3& y, double d2, double d) {
    return firstOrderTerm(n.vectorArea, n.moment, n.trace, y, d2, d);
}

inline double BoundaryCaps::expansion(const Node& n, const glm::dvec3& y, double d2, double d) {
    const double inv2 = 1.0 / d2, inv3 = inv2 / d;
    const std::array<double, 18>& N = n.quadrupole;
    const double yy[6] = {y.x * y.x, y.y * y.y, y.z * y.z, 2.0 * y.x * y.y, 2.0 * y.x * y.z, 2.0 * y.y * y.z};
    double yNyy = 0.0;
    for (int i = 0; i < 3; ++i) {
        const double* row = N.data() + 6 * i;
        yNyy += y[i] * (row[0] * yy[0] + row[1] * yy[1] + row[2] * yy[2] + row[3] * yy[3] + row[4] * yy[4] +
                        row[5] * yy[5]);
    }
    const double second =
        0.5 * inv2 * (-3.0 * (2.0 * glm::dot(n.quadrupoleColumns, y) + glm::dot(n.quadrupoleRows, y)) + 15.0 * yNyy * inv2);
    return firstOrder(n, y, d2, d) + second * inv3;
}

} // namespace vds::detail
