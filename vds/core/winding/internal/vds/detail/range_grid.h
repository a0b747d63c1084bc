// vds internal: a grid of bounds of the winding engine (BoundRanges): a
// box of cells, each with a state and, once a query lands in it, a range
// of the boundary term or of the whole winding number over it, or a plan.
// What each state means for a label: boundary_caps.h.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include <glm/vec3.hpp>

#include <vds/mesh.h>

#include <vds/detail/cell_field.h>

namespace vds::detail {

/// What a cell of the grids of bounds holds (how a label uses it: the list
/// in boundary_caps.h).
enum class CellState : std::uint8_t {
    Unvisited,     ///< no query has landed in it yet
    BoundaryRange, ///< a range of B (clear of the boundary's sweep): the query adds its integer term
    NoRange,       ///< no range clear of 1/2 and no plan: the tree from its root
    Filling,       ///< one thread fills it; the others go by the tree meanwhile
    WindingRange,  ///< a range of the whole winding number (clear of the surface): CellVerdict says
    CappedRange,   ///< a range of -w_caps (clear of the caps): the query adds its integer term and C_caps
    Planned,       ///< the far loops' range over the cell, and the loops near it refined per query
};

/// A WindingRange cell's answer, set before its state is published.
enum class CellLabel : std::uint8_t { Outside, Inside, Undecided };
class CellVerdict {
public:
    CellVerdict() = default;
    CellVerdict(CellLabel label, bool byClosed)
        : bits_(std::uint8_t(std::uint8_t(label) | (byClosed ? kByClosed : 0u))) {}
    /// Where the range puts every value (Undecided: it straddles 1/2).
    CellLabel label() const { return CellLabel(bits_ & ~kByClosed); }
    /// The range came from a closed count (CellWindings): a query apart
    /// from it (insideApart) takes it as -w_caps's range instead.
    bool byClosed() const { return (bits_ & kByClosed) != 0; }

private:
    /// One byte a cell, as the states: the grid's bytes a query reads stay
    /// within the first level of cache.
    static constexpr std::uint8_t kByClosed = 0x80;
    std::uint8_t bits_ = std::uint8_t(CellLabel::Undecided);
};

/// A ball holding a box of cells (RangeGrid::ballOf).
struct CellsBall {
    glm::vec3 centre;
    double half;
};

/// A grid of bounds: cells of a box and what is known of each before any
/// query (built once, by BoundRanges), then a cache of what queries found:
/// each cell's state (CellState) and range or plan, filled on a query's
/// first visit (one thread fills a cell; the others go on by the tree
/// meanwhile). The cache is `mutable`: a filled cell changes no label
/// (every range, plan and bound answers only where it keeps clear of 1/2
/// by more than its error), only how fast the label comes; states are
/// atomic, and a cell's other fields are written before its state is
/// published (release) and read after it is seen (acquire).
struct RangeGrid {
    /// The cell q lies in; false outside the grid (or before its cells are
    /// allocated).
    inline bool cellOf(const glm::vec3& q, std::size_t& cell, glm::uvec3& at) const;
    /// A ball about the box of cells [first, last]: its centre (a float
    /// point, as queries are) and a radius holding every point of those
    /// cells, widened against the rounding of a point's cell index.
    CellsBall ballOf(const glm::uvec3& first, const glm::uvec3& last) const;
    /// The cache's cells: states (all Unvisited), answers, ranges and plans.
    void allocate() const;
    std::size_t cellCount() const { return std::size_t(dims.x) * dims.y * dims.z; }

    // ---- known before any query
    Box box;
    glm::uvec3 dims{0};
    glm::dvec3 size{0.0};
    glm::dvec3 inverse{0.0}; ///< 1 / size (0 where size is 0)
    /// 1 where the surface may meet the cell (CapsSurface::markCells);
    /// empty without a surface.
    std::vector<std::uint8_t> met;
    /// 1 where a cap may meet the cell.
    std::vector<std::uint8_t> capMet;
    /// The integer term over each cell where the caller knew it to be
    /// one integer (CellWindings), else kUnknown; empty without.
    std::vector<std::int32_t> constantWinding;
    /// CellWindings' closed counts: in the sweep, where the caps keep
    /// out of a cell, n - w_caps is the whole winding number.
    std::vector<std::int32_t> closedWinding;
    /// Per column of cells along the axis: the lowest height along the
    /// axis of a boundary edge whose projection's box meets the
    /// column's (+inf: none), so the cells wholly below it are clear
    /// of the curve and its sweep.
    std::vector<double> lowestEdge;
    glm::uvec3 blockDims{0}; ///< the coarse grid's blocks of 2 x 2 x 2 cells

    // ---- the cache, filled by queries
    mutable std::unique_ptr<std::atomic<CellState>[]> state;
    /// A WindingRange cell's answer (set before the state is published).
    mutable std::unique_ptr<CellVerdict[]> alone;
    mutable std::unique_ptr<double[]> lo, hi;
    mutable std::atomic<std::size_t> closedCells{0}; ///< WindingRange by closedWinding
    /// A planned cell's chain nodes its queries refine the near loops
    /// from (ChainLabels::frontier), then the near loops, ascending:
    /// nearCount[cell] of the first, nearLoops[cell] of the second.
    mutable std::unique_ptr<std::unique_ptr<std::uint32_t[]>[]> near;
    mutable std::unique_ptr<std::uint32_t[]> nearCount, nearLoops;
    /// A planned cell's: 1 where a far loop's cap may lie in the column
    /// below it (its queries count the caps they cross), else 0.
    mutable std::unique_ptr<std::uint8_t[]> farCrossed;
    /// A planned cell's score of queries the plan did not decide, less
    /// those it did: past a few, the cell goes back to NoRange (most of
    /// its queries lie close to 1/2).
    mutable std::unique_ptr<std::atomic<std::uint8_t>[]> planMisses;
    /// Queries that found no range in the cell (NoRange and Planned; in
    /// the fine grid, those of a busy coarse cell), up to a bound
    /// (bound_ranges.cpp): from kBusyVisits on, a coarse cell's ask the
    /// fine grid's cell, and from kFieldVisits on a cell builds its field.
    mutable std::unique_ptr<std::atomic<std::uint16_t>[]> visits;
    /// A cell's field (CellField), built once enough of its queries found
    /// no range (visits), published by fieldState: 0 none yet, 1 being
    /// built, 2 built, 3 none to be had.
    mutable std::unique_ptr<std::unique_ptr<CellField>[]> fields;
    /// The work its queries without a range spent (nodes taken and edges
    /// summed), up to a bound: its field is built once that reaches what
    /// a field costs (bound_ranges.cpp).
    mutable std::unique_ptr<std::atomic<std::uint32_t>[]> spent;
    mutable std::unique_ptr<std::atomic<std::uint8_t>[]> fieldState;
    /// The coarse grid's: per block of 2 x 2 x 2 cells, 1 once a cell
    /// of it tried the block's range (BoundRanges::blockRange).
    mutable std::unique_ptr<std::atomic<std::uint8_t>[]> blockTried;
};

// Inline: asked once a query (a sprite's batch asks insideAlone of every point).
bool RangeGrid::cellOf(const glm::vec3& q, std::size_t& cell, glm::uvec3& at) const {
    const RangeGrid& g = *this;
    if (!g.state) return false;
    for (int a = 0; a < 3; ++a) {
        // By the reciprocal: its extra rounding (a few ulps of the index)
        // is far inside the slack the cells are widened by.
        const double x = g.size[a] > 0.0 ? (double(q[a]) - double(g.box.lo[a])) * g.inverse[a]
                                         : (q[a] == g.box.lo[a] ? 0.0 : -1.0);
        if (!(x >= 0.0 && x < double(g.dims[a]))) return false;
        at[a] = std::uint32_t(x);
    }
    cell = (std::size_t(at.z) * g.dims.y + at.y) * g.dims.x + at.x;
    return true;
}

} // namespace vds::detail
