// vds internal: the boundary term of the generalized winding number by
// capping the boundary loops, fast where the boundary is long: a label and
// a value for a point. Read on its own, this says why the answers are the
// per-edge sum's (antipodal.h); the parts it names say how.
//
// Why caps. The signed boundary edges of an oriented mesh form a 1-cycle,
// so they split into closed loops L (CapLoops). Close each with its cap,
// the fan (c, b, a) from the loop's centroid c over its edges a -> b, whose
// boundary is L reversed. Mesh plus caps is a closed 2-cycle, whose
// generalized winding number is its signed crossing count along any ray.
// With C the signed count along the ray from q towards -axis and w the
// solid-angle sum over 4 pi:
//
//     GWN_mesh(q) = C_mesh(q) + C_caps(q) - w_caps(q),
//
// so the boundary term is B(q) = C_caps(q) - w_caps(q). C_caps is counted
// with the exact predicates and tie rule of projected_mesh.h, as the
// mesh's own count is, so both jump together where the ray passes over a
// boundary edge. Values: w_caps by a tree over the cap triangles
// (CapsValueTree; Barill et al. 2018, section 3), each node far enough
// from q taken by its Taylor expansion to second order about its centre.
// Labels: a tree of chains (ChainLabels): a chain from P to Q closed by its
// chord Q -> P bounds a thin fan along the boundary, and where q's ray
// misses the node's ball the chain's per-edge angles sum to its chord's
// angle less that fan's solid angle (the identity above, with no
// crossing), the fan taken by its expansion to first order (to second
// within 0.1 of the threshold). A point near a large loop then costs a few
// chains near it and the chords of the rest.
//
// The bound that makes them exact. A node (ball of centre c, radius R) at
// D = |q - c| > R, e = D - R: Taylor's remainder of K(y) = y / |y|^3 after
// the order-k term, for x = c + h, is an integral over t in [0, 1] of the
// kernel's (k + 1)-th derivative at c - q + t h, at distance >= D - t R.
// That derivative contracted with a unit normal is at most (k + 2)! / |y|^(k+3)
// (for k = 2: the fourth derivative of 1 / |y|, whose square along n, h, h, h
// peaks at 576 = 24^2). With |h|^3 <= R |h|^2 and S the integral of
// |x - c|^2 dA over the node's triangles (a triangle of centroid g: area *
// (|g - c|^2 + (sum of squared sides) / 36)), the node errs by at most
//
//     second order:  R S (D + 3e) / (4 pi D^4 e^2)   (remainderFactor)
//     first order:     S (D + 2e) / (4 pi D^3 e^2)   (firstOrderFactor)
//
// over 4 pi, in B's units. Values take a node when its bound is at most a
// tolerance times the solid angle it subtends (area / D^2) and fall back
// to the per-edge sum where the taken bounds exceed their tolerance.
//
// How a label is decided (inside, insideApart, insideAlone). Every path has
// the per-edge sum's answer: a range, plan or bound answers only where it
// keeps clear of 1/2 (plus the tie) by more than its error.
//  1. q outside the coarse grid (BoundRanges): the chain tree from its root (7).
//  2. q's cell Unvisited: the first query fills it (Filling meanwhile):
//     a. its block of 2 x 2 x 2 cells clear of the surface, or of the sweep
//        with one known integer term: WindingRange for all (blockRange);
//     b. else, with the drift over the cell (EdgeTree) under half a unit:
//        clear of the surface, WindingRange; clear of the sweep,
//        BoundaryRange (or WindingRange with a known integer term); clear
//        of the caps, CappedRange (or WindingRange by a closed count);
//     c. else Planned where the far loops' range is narrow and the near
//        loops few, else NoRange.
//  3. NoRange or Planned, once many queries landed: the fine cell (half as
//     wide), where it holds a range or a plan. Before that, once a cell's
//     queries past its range spent twice what a field costs, and where it
//     halves their work: its field (CellField; the fine cell's in a busy
//     coarse cell), the chain nodes near its column refined (as 7) with
//     the rest's interpolated value and bound as the far range; where
//     that does not decide, on.
//  4. WindingRange clear of 1/2: its label, no integer term asked; a cell
//     by a closed count, for a query apart from its count: as CappedRange.
//  5. BoundaryRange: winding + [lo, hi]; CappedRange: winding + C_caps(q)
//     + [lo, hi]; the label where that keeps clear of 1/2.
//  6. Planned: the near loops refined, the far ones by their range (plus
//     their caps' crossing count, counted only in a cell whose column
//     below it a far cap may reach); a few net misses turn the cell NoRange.
//  7. Else the chain tree (ChainLabels::decide): the coarsest cut whose
//     nodes each err by at most 1/4, then the nodes with the largest bounds
//     opened a round at a time until the value is farther from 1/2 than the
//     summed bounds; past a budget of the per-edge sum's work, or where the
//     work still needed is predicted to pass it, the per-edge sum decides.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include <glm/vec3.hpp>

#include <vds/mesh.h>

#include <vds/detail/bound_ranges.h>
#include <vds/detail/cap_loops.h>
#include <vds/detail/caps_math.h>
#include <vds/detail/caps_surface.h>
#include <vds/detail/caps_value_tree.h>
#include <vds/detail/chain_labels.h>
#include <vds/detail/chain_tree.h>
#include <vds/detail/edge_tree.h>

namespace vds::detail {

/// The boundary term of a set of boundary edges by their capped loops: a
/// label and a value for a point. Built once (O(E log E)), then thread safe
/// to query; not copied (its parts refer to each other, BoundRanges).
class BoundaryCaps {
public:
    /// `edges`: 2 * `edgeCount` points, edge k from [2k] to [2k+1] (copied).
    /// `axis`: the integer term's ray runs towards -axis.
    /// `domain`: where most queries lie (the mesh's or sprite's box), for
    /// the grids of bounds `inside` answers from first; none: every query
    /// refines the tree.
    /// `surface` (kept, to outlive this): the surface of which the edges
    /// are the boundary, for cells of the grid that it does not meet (see
    /// CapsSurface); none: only cells clear of the boundary's sweep.
    /// `windings` (asked once, here, not kept): where no surface is given,
    /// the cells over which the integer term is one integer (CellWindings).
    BoundaryCaps(const glm::vec3* edges, std::size_t edgeCount, Axis axis, const Box* domain = nullptr,
                 const CapsSurface* surface = nullptr, const CellWindings* windings = nullptr);

    using Estimate = CapsEstimate;
    using Reach = detail::Reach;
    using Node = CapsNode;
    using ChainNode = detail::ChainNode;

    // ---- values
    /// B(q) and its error bound, taking nodes whose bound is at most
    /// `nodeTolerance` by expansion (CapsValueTree::estimate).
    Estimate estimate(const glm::vec3& q, double nodeTolerance) const { return values_.estimate(q, nodeTolerance); }
    /// `winding + B(q)` within `tolerance` of the per-edge sum's, falling
    /// back to the per-edge sum where the estimate's bound is larger.
    double generalizedWinding(int winding, const glm::vec3& q, double tolerance) const;
    /// How far B may drift from B(q) along a move from q (EdgeTree).
    Reach reach(const glm::vec3& q, double steepest = std::numeric_limits<double>::infinity()) const {
        return edgeTree_.reach(q, steepest);
    }
    double driftWithin(const glm::vec3& q, double length, double limit) const {
        return edgeTree_.driftWithin(q, length, limit);
    }

    // ---- labels (the list above)
    /// Whether `winding + B(q) > 1/2`, with the per-edge sum's answer.
    bool inside(int winding, const glm::vec3& q) const { return ranges_.inside(winding, q, false); }
    /// As `inside(winding, q)`, for a query whose integer term is not the
    /// one CellWindings' closed counts speak of (a sprite's point beside its
    /// texture, where the count is 0 and B is taken at the point itself):
    /// a cell whose range came from a closed count is taken as the range
    /// of -w_caps it holds, plus the caps' crossing count at q.
    bool insideApart(int winding, const glm::vec3& q) const { return ranges_.inside(winding, q, true); }
    /// As `inside`, asking the surface (given at construction) for the
    /// integer term only where the grid does not answer alone.
    bool inside(const glm::vec3& q) const { return ranges_.inside(q); }
    /// The label where q's cell answers without the integer term (a range
    /// of the whole winding number clear of 1/2): 1 inside, 0 outside; -1
    /// where it does not (then `inside(winding, q)`). Fills q's cell on its
    /// first visit, as `inside` does. `apart`: a query as insideApart's.
    int insideAlone(const glm::vec3& q, bool apart = false) const { return ranges_.insideAlone(q, apart); }
    /// The chain tree's decide (ChainLabels::decide), for callers that
    /// carry a label to neighbours (Reach).
    Estimate decide(int winding, const glm::vec3& q, double margin) const { return labels_.decide(winding, q, margin); }

    // ---- the boundary
    /// False when the edges do not close into loops (not a mesh's boundary):
    /// every query then takes the per-edge sum.
    bool closed() const { return loops_.closed(); }
    const std::vector<CapLoop>& loops() const { return loops_.loops(); }
    /// The edges in loop order: loop l's edges are [first, first + count),
    /// edge k from [2k] to [2k+1].
    const std::vector<glm::vec3>& loopEdges() const { return loops_.loopEdges(); }
    /// [0] is the root; empty where the edges do not close into loops.
    const std::vector<ChainNode>& chains() const { return labels_.chains(); }
    /// Bytes held: the loops, caps, trees and both grids of bounds (the
    /// plans and fields filled so far included).
    std::size_t memoryBytes() const;
    /// The grid cells' fields built so far (CellField: bound_ranges.h).
    std::size_t fieldsBuilt() const { return ranges_.fieldsBuilt(); }

private:
    CapLoops loops_;
    EdgeTree edgeTree_; ///< for reach() and driftWithin()
    ChainLabels labels_;
    CapsValueTree values_;
    BoundRanges ranges_;
};

} // namespace vds::detail
