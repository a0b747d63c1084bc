// vds internal: the grids of bounds labels answer from first (the list in
// boundary_caps.h says how): a coarse grid over the domain, a fine one
// (cells half as wide) for the coarse cells many queries land in without a
// range, each cell's range or plan found on a query's first visit, and
// where they do not answer, the chain tree.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <algorithm>
#include <mutex>

#include <glm/vec3.hpp>

#include <vds/mesh.h>

#include <vds/detail/cap_loops.h>
#include <vds/detail/caps_surface.h>
#include <vds/detail/caps_value_tree.h>
#include <vds/detail/chain_labels.h>
#include <vds/detail/edge_tree.h>
#include <vds/detail/range_grid.h>

namespace vds::detail {

/// The grids of bounds over a domain, and the labels they give. Keeps
/// references to the parts it asks (they must outlive it). Built once,
/// then thread safe: the cells' cache (RangeGrid) fills as queries land.
class BoundRanges {
public:
    /// `domain` (none: no grid, every label from the chain tree), `surface`
    /// and `windings` as BoundaryCaps takes them.
    BoundRanges(const CapLoops& loops, const CapsValueTree& values, const ChainLabels& labels, const EdgeTree& drift,
                const Box* domain, const CapsSurface* surface, const CellWindings* windings);
    BoundRanges(const BoundRanges&) = delete;
    BoundRanges& operator=(const BoundRanges&) = delete;

    /// Whether `winding + B(q) > 1/2`, with the per-edge sum's answer.
    /// `apart`: a query whose integer term is not the one CellWindings'
    /// closed counts speak of (BoundaryCaps::insideApart).
    bool inside(int winding, const glm::vec3& q, bool apart) const;
    /// As `inside`, asking the surface for the integer term only where the
    /// grid does not answer alone.
    bool inside(const glm::vec3& q) const;
    /// 1 inside, 0 outside where q's cell answers without the integer term;
    /// else -1 (BoundaryCaps::insideAlone).
    inline int insideAlone(const glm::vec3& q, bool apart) const;
    /// Bytes held by both grids (the plans and fields filled so far included).
    std::size_t memoryBytes() const;
    /// The cells' fields built so far (CellField).
    std::size_t fieldsBuilt() const { return fieldsBuilt_.load(std::memory_order_relaxed); }

private:
    /// `cellsNow`: allocate its cells' cache too (RangeGrid::allocate).
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
    bool rangeOver(const CellsBall& ball, CapsEstimate& e, double& drift) const;
    /// On a coarse cell's fill (the caller owns `cell`, Filling), once a
    /// block: where no cell of its block of 2 x 2 x 2 meets the surface
    /// (or, without one, every cell is clear of the boundary's sweep and
    /// the caller knew one integer term for them all), the range of the
    /// whole winding number over the block, clear of 1/2, for every cell
    /// of it not yet filled: one fill for eight far from the surface.
    /// True where `cell` got it (then WindingRange is the caller's to publish).
    bool blockRange(const RangeGrid& g, std::size_t cell, const glm::uvec3& at) const;
    /// Whether a cell without a range has had queries enough for a coarse
    /// one to ask the fine grid (counting this one).
    bool busy(const RangeGrid& g, std::size_t cell) const;
    /// A cell's field (`state` its state, Planned or not), built here once
    /// its queries without a range reach kFieldVisits; none where it is
    /// not (yet) to be had.
    const CellField* fieldOf(const RangeGrid& g, std::size_t cell, CellState state) const;
    /// A cell's plan, on the fill: false where the far loops' range would
    /// be too wide to help.
    bool plan(const RangeGrid& g, std::size_t cell, const glm::vec3& c, double half, bool within) const;
    /// decide() from a planned cell's near loops; false where that does
    /// not decide (the far range is as wide as the rest of the distance).
    bool decidePlanned(const RangeGrid& g, int winding, const glm::vec3& q, std::size_t cell, CapsEstimate& out) const;
    /// A query's way past its cell's range: the field it asks first, and
    /// the cells charged with the work it then spends (RangeGrid::spent).
    struct Route {
        const CellField* field = nullptr;
        std::atomic<std::uint32_t>* charge[2] = {nullptr, nullptr};
        /// Adds `work` to each cell charged (saturating well short of the
        /// counter's range).
        void add(double work) const {
            for (std::atomic<std::uint32_t>* c : charge)
                if (c && c->load(std::memory_order_relaxed) < (1u << 30))
                    c->fetch_add(std::uint32_t(std::min(work, 65536.0)), std::memory_order_relaxed);
        }
    };
    /// insideBy() in cell `cell` of `g`, of state `state`, asking the
    /// route's field (where given) before a plan or the tree.
    template <class Winding>
    bool insideIn(const RangeGrid& g, std::size_t cell, CellState state, const glm::vec3& q,
                  const Winding& windingAt, bool apart, const Route& route) const;
    /// inside(), asking `windingAt()` for the integer term only where the
    /// cell's range does not answer without it.
    template <class Winding>
    bool insideBy(const glm::vec3& q, const Winding& windingAt, bool apart) const;

    const CapLoops& loops_;
    const CapsValueTree& values_;
    const ChainLabels& labels_;
    const EdgeTree& drift_;
    const CapsSurface* surface_;
    /// The grid of bounds, and one of cells half as wide along each side
    /// over the same box: a coarse cell without a range (NoRange, Planned)
    /// that many queries land in hands them to its fine cells, whose
    /// ranges and far ranges, taken over half the width, keep clear of 1/2
    /// more often (the near loops a plan keeps are about as many: a soup's
    /// small loops are near by their own size). Only those fine cells are
    /// filled: a fill costs a few queries' work.
    RangeGrid coarse_;
    RangeGrid fine_; ///< its cells' cache allocated by fineCells()
    /// The fine grid's cache allocated once (`mutable`: part of the cache).
    mutable std::once_flag fineOnce_;
    mutable std::atomic<bool> fineReady_{false};
    /// What fields cost, in the work units of RangeGrid::spent: every
    /// build's work, and the fields built (bound_ranges.cpp, kFirstFieldWork).
    mutable std::atomic<double> buildWork_{0.0};
    mutable std::atomic<std::size_t> fieldsBuilt_{0};
};

// Inline: asked once a query (a sprite's batch asks insideAlone of every point).
int BoundRanges::insideAlone(const glm::vec3& q, bool apart) const {
    std::size_t cell;
    glm::uvec3 at;
    if (!coarse_.cellOf(q, cell, at)) return -1;
    CellState state = coarse_.state[cell].load(std::memory_order_acquire);
    if (state == CellState::Unvisited) state = rangeOf(coarse_, cell, at);
    if (state != CellState::WindingRange) return -1;
    const CellVerdict verdict = coarse_.alone[cell];
    if ((apart && verdict.byClosed()) || verdict.label() == CellLabel::Undecided) return -1;
    return verdict.label() == CellLabel::Inside ? 1 : 0;
}

} // namespace vds::detail
