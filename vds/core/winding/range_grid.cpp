// vds: the grids of bounds BoundaryCaps::inside answers from first, and
// where they do not answer, the chain tree (chain_tree.cpp).
//
// How a label is decided (inside, insideApart, insideAlone), every path
// with the per-edge sum's answer: a range, plan or bound answers only
// where it keeps clear of 1/2 (plus the tie) by more than its error.
//  1. q outside the coarse grid: decide() from the chain tree's root (7).
//  2. q's cell Unvisited: the first query fills it (Filling meanwhile):
//     a. its block of 2 x 2 x 2 cells clear of the surface, or of the sweep
//        with one known integer term: WindingRange for all (blockRange);
//     b. else, with the drift over the cell under half a unit: clear of
//        the surface, WindingRange; clear of the sweep, BoundaryRange (or
//        WindingRange with a known integer term); clear of the caps,
//        CappedRange (or WindingRange by a closed count, byClosed);
//     c. else Planned where the far loops' range is narrow and the near
//        loops few (cell_plans.cpp), else NoRange.
//  3. NoRange or Planned, once kBusyVisits queries landed: the fine cell
//     (half as wide), where it holds a range or a plan.
//  4. WindingRange clear of 1/2: its label, no integer term asked; a
//     byClosed cell, for a query apart from its count: as CappedRange.
//  5. BoundaryRange: winding + [lo, hi]; CappedRange: winding + C_caps(q)
//     + [lo, hi]; the label where that keeps clear of 1/2.
//  6. Planned: the near loops refined, the far ones by their range
//     (decidePlanned); kPlanMisses net misses turn the cell NoRange.
//  7. Else decide(): the chain tree refined until the value is farther
//     from 1/2 than its bound, or the per-edge sum where that costs less.
#include <vds/detail/caps_tree.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include <vds/detail/antipodal.h>
#include <vds/detail/caps_math.h>
#include <vds/detail/tree_walk.h>

namespace vds::detail {

using namespace caps;

namespace {
/// Cells of the range grid along its longest side, and of the fine grid.
constexpr double kRangeCells = 24.0;
constexpr double kFineCells = 2.0 * kRangeCells;
/// Queries without a range a coarse cell takes before it hands them to
/// its fine cells.
constexpr unsigned kBusyVisits = 1024;
/// The node tolerance of the estimate at a cell's centre (estimate()):
/// coarse, as a range serves only where it keeps clear of 1/2; it bounds
/// the part of a cell's range that is the estimate's error (tuning:
/// docs/benchmarks.md).
constexpr double kRangeTolerance = 5e-2;
} // namespace

namespace {
/// A plan's score of queries it left undecided (each adds 1, each it
/// decided takes 1 off): at kPlanMisses its cell drops it. A miss costs
/// the plan and then the tree from its root, so a plan pays while it
/// decides most of its queries (tuning: docs/benchmarks.md).
constexpr unsigned kPlanMisses = 4;
} // namespace

namespace {
/// -1: the range puts the value below the threshold, 1: above, 0: neither.
int sideOf(double lo, double hi) {
    const double threshold = 0.5 + kGeneralizedWindingTie;
    if (hi < threshold - kRoundingSlack) return -1;
    if (lo > threshold + kRoundingSlack) return 1;
    return 0;
}
} // namespace

void BoundaryCaps::buildRangeGrid(const Box& domain, const CellWindings* windings) {
    // The domain and a margin of a quarter of its longest side all round
    // (queries beside a box are common: points in a padded box, a sprite's
    // columns in front of and behind it).
    const double side = std::max({double(domain.hi.x) - domain.lo.x, double(domain.hi.y) - domain.lo.y,
                                  double(domain.hi.z) - domain.lo.z});
    if (!(side > 0.0) || !std::isfinite(side)) return;
    const Box box{glm::vec3(glm::dvec3(domain.lo) - 0.25 * side), glm::vec3(glm::dvec3(domain.hi) + 0.25 * side)};
    buildGrid(ranges_, box, kRangeCells, windings, true);
    if (ranges_.state) {
        // The fine grid's cells only when a cell first turns busy
        // (fineCells): what the windings and the surface say of each is
        // asked now (the windings are not kept).
        buildGrid(fine_, box, kFineCells, windings, false);
        const std::size_t cells = std::size_t(ranges_.dims.x) * ranges_.dims.y * ranges_.dims.z;
        ranges_.visits.reset(new std::atomic<std::uint16_t>[cells]);
        for (std::size_t c = 0; c < cells; ++c) ranges_.visits[c].store(0, std::memory_order_relaxed);
        ranges_.blockDims = (ranges_.dims + 1u) / 2u;
        const std::size_t blocks = std::size_t(ranges_.blockDims.x) * ranges_.blockDims.y * ranges_.blockDims.z;
        ranges_.blockTried.reset(new std::atomic<std::uint8_t>[blocks]);
        for (std::size_t b = 0; b < blocks; ++b) ranges_.blockTried[b].store(0, std::memory_order_relaxed);
    }
}

CellsBall RangeGrid::ballOf(const glm::uvec3& first, const glm::uvec3& last) const {
    const glm::dvec3 from(box.lo), to(box.hi);
    const double slack = 1e-7 * std::max({to.x - from.x, to.y - from.y, to.z - from.z});
    const glm::dvec3 centre = from + 0.5 * (glm::dvec3(first) + glm::dvec3(last + 1u)) * size;
    const glm::vec3 c(centre);
    // Every point of the widened cells lies within this of c.
    return {c, 0.5 * glm::length(glm::dvec3(last + 1u - first) * size) + glm::length(glm::dvec3(c) - centre) +
                   2.0 * slack};
}

bool BoundaryCaps::clearOfSweep(const RangeGrid& g, const glm::uvec3& at) const {
    // Every edge whose projection may meet the cell's column lies above
    // the cell (its top widened against rounding).
    const int a = axisIndex_, s = (a + 1) % 3, t = (a + 2) % 3;
    const glm::dvec3 lo(g.box.lo), hi(g.box.hi);
    const double slack = 1e-7 * std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
    const double top = lo[a] + double(at[a] + 1) * g.size[a] + 2.0 * slack;
    return top < g.lowestEdge[std::size_t(at[t]) * g.dims[s] + at[s]];
}

bool BoundaryCaps::rangeOver(const CellsBall& ball, Estimate& e, double& drift) const {
    // Coarse will do: a range serves only where it keeps clear of 1/2.
    // The drift first (not finished past half a unit): where it alone
    // spans a unit, no estimate helps.
    drift = driftWithin(ball.centre, ball.half * (1.0 + 1e-9), 0.5);
    if (!std::isfinite(drift)) return false;
    e = estimate(ball.centre, kRangeTolerance);
    return e.bound + drift < 0.5;
}

bool BoundaryCaps::blockRange(const RangeGrid& g, std::size_t cell, const glm::uvec3& at) const {
    const glm::uvec3 first = at / 2u * 2u, last = glm::min(first + 1u, g.dims - 1u);
    const std::size_t block = (std::size_t(first.z / 2) * g.blockDims.y + first.y / 2) * g.blockDims.x + first.x / 2;
    if (g.blockTried[block].exchange(1, std::memory_order_relaxed) != 0) return false;
    const auto index = [&](const glm::uvec3& c) { return (std::size_t(c.z) * g.dims.y + c.y) * g.dims.x + c.x; };
    // One integer term over the block: no cell meets the surface, or every
    // one is clear of the sweep with the same known integer term.
    const bool bySurface = !g.met.empty();
    std::int32_t known = CellWindings::kUnknown;
    glm::uvec3 c;
    for (c.z = first.z; c.z <= last.z; ++c.z)
        for (c.y = first.y; c.y <= last.y; ++c.y)
            for (c.x = first.x; c.x <= last.x; ++c.x) {
                const std::size_t k = index(c);
                if (bySurface) {
                    if (g.met[k] != 0) return false;
                    continue;
                }
                if (!clearOfSweep(g, c)) return false;
                if (g.constantWinding.empty() || g.constantWinding[k] == CellWindings::kUnknown) return false;
                if (known != CellWindings::kUnknown && g.constantWinding[k] != known) return false;
                known = g.constantWinding[k];
            }
    const CellsBall ball = g.ballOf(first, last);
    Estimate e;
    double drift;
    if (!rangeOver(ball, e, drift)) return false;
    const double base = e.term + double(bySurface ? surface_->winding(ball.centre) : known);
    const double rangeLo = base - e.bound - drift, rangeHi = base + e.bound + drift;
    const int side = sideOf(rangeLo, rangeHi);
    if (side == 0) return false;
    // Every cell of the block not yet filled (this one is the caller's).
    for (c.z = first.z; c.z <= last.z; ++c.z)
        for (c.y = first.y; c.y <= last.y; ++c.y)
            for (c.x = first.x; c.x <= last.x; ++c.x) {
                const std::size_t k = index(c);
                CellState unvisited = CellState::Unvisited;
                if (k != cell &&
                    !g.state[k].compare_exchange_strong(unvisited, CellState::Filling, std::memory_order_acquire))
                    continue;
                g.lo[k] = rangeLo;
                g.hi[k] = rangeHi;
                g.alone[k] = {side > 0 ? CellLabel::Inside : CellLabel::Outside, false};
                if (k != cell) g.state[k].store(CellState::WindingRange, std::memory_order_release);
            }
    return true;
}

void BoundaryCaps::buildGrid(RangeGrid& g, const Box& box, double cellsAlong, const CellWindings* windings,
                             bool cellsNow) {
    g.box = box;
    const glm::dvec3 lo(g.box.lo), hi(g.box.hi), extent = hi - lo;
    const double longest = std::max({extent.x, extent.y, extent.z});
    if (!(longest > 0.0) || !std::isfinite(longest) || !(extent.x >= 0.0 && extent.y >= 0.0 && extent.z >= 0.0)) return;
    for (int a = 0; a < 3; ++a) {
        g.dims[a] = std::uint32_t(std::clamp(std::ceil(extent[a] / longest * cellsAlong), 1.0, cellsAlong));
        g.size[a] = extent[a] / double(g.dims[a]);
        g.inverse[a] = g.size[a] > 0.0 ? 1.0 / g.size[a] : 0.0;
    }
    const int a = axisIndex_, s = (a + 1) % 3, t = (a + 2) % 3;
    g.lowestEdge.assign(std::size_t(g.dims[s]) * g.dims[t], std::numeric_limits<double>::infinity());
    // Cell extents are widened by `slack` against the rounding of a point's
    // cell index (and an edge's box by twice that).
    const double slack = 1e-7 * longest;
    const auto span = [&](int axis, double from, double to, std::uint32_t& first, std::uint32_t& last) {
        if (to < lo[axis] - 2.0 * slack || from > hi[axis] + 2.0 * slack) return false;
        const auto index = [&](double x) {
            if (!(g.size[axis] > 0.0)) return 0.0;
            return std::clamp(std::floor((x - lo[axis]) / g.size[axis]), 0.0, double(g.dims[axis] - 1));
        };
        first = std::uint32_t(index(from - 2.0 * slack));
        last = std::uint32_t(index(to + 2.0 * slack));
        return true;
    };
    for (std::size_t k = 0; k + 1 < edges_.size(); k += 2) {
        const glm::dvec3 p(edges_[k]), q(edges_[k + 1]);
        std::uint32_t s0, s1, t0, t1;
        if (!span(s, std::min(p[s], q[s]), std::max(p[s], q[s]), s0, s1) ||
            !span(t, std::min(p[t], q[t]), std::max(p[t], q[t]), t0, t1))
            continue;
        const double low = std::min(p[a], q[a]);
        for (std::uint32_t i = s0; i <= s1; ++i)
            for (std::uint32_t j = t0; j <= t1; ++j) {
                double& lowest = g.lowestEdge[std::size_t(j) * g.dims[s] + i];
                lowest = std::min(lowest, low);
            }
    }
    const std::size_t cells = std::size_t(g.dims.x) * g.dims.y * g.dims.z;
    if (surface_) {
        g.met.assign(cells, 0);
        surface_->markCells(CellLattice{lo, g.size, g.dims}, g.met);
    }
    if (windings) {
        g.constantWinding.assign(cells, CellWindings::kUnknown);
        g.closedWinding.assign(cells, CellWindings::kUnknown);
        windings->constantWindings(CellLattice{lo, g.size, g.dims}, &*projected_, g.constantWinding, g.closedWinding);
    }
    g.capMet.assign(cells, 0);
    for (const glm::uvec3& c : capTriangles_)
        markTriangleCells(CellLattice{lo, g.size, g.dims}, glm::dvec3(capPositions_[c.x]), glm::dvec3(capPositions_[c.y]),
                          glm::dvec3(capPositions_[c.z]), 2.0 * slack, g.capMet);
    if (cellsNow) g.allocate();
}

void RangeGrid::allocate() {
    RangeGrid& g = *this;
    const std::size_t cells = std::size_t(g.dims.x) * g.dims.y * g.dims.z;
    g.state.reset(new std::atomic<CellState>[cells]);
    g.near.reset(new std::unique_ptr<std::uint32_t[]>[cells]);
    g.nearCount.reset(new std::uint32_t[cells]());
    g.nearLoops.reset(new std::uint32_t[cells]());
    g.planMisses.reset(new std::atomic<std::uint8_t>[cells]);
    for (std::size_t c = 0; c < cells; ++c) g.planMisses[c].store(0, std::memory_order_relaxed);
    for (std::size_t c = 0; c < cells; ++c) g.state[c].store(CellState::Unvisited, std::memory_order_relaxed);
    g.alone.reset(new CellVerdict[cells]);
    g.lo.reset(new double[cells]);
    g.hi.reset(new double[cells]);
}

CellState BoundaryCaps::rangeOf(const RangeGrid& g, std::size_t cell, const glm::uvec3& at, bool within) const {
    CellState state = g.state[cell].load(std::memory_order_acquire);
    if (state != CellState::Unvisited) return state;
    // One thread fills the cell (Filling while it does); the others go on
    // by the tree meanwhile.
    if (!g.state[cell].compare_exchange_strong(state, CellState::Filling, std::memory_order_acquire)) return state;
    CellState result = CellState::NoRange;
    // Clear of the boundary curve and its sweep along +axis.
    const bool clearOfSweep = this->clearOfSweep(g, at);
    // Clear of the surface: the whole winding number is smooth over the
    // cell (the boundary curve too lies on the surface).
    const bool clearOfSurface = !g.met.empty() && g.met[cell] == 0;
    // Clear of the caps: w_caps is smooth over the cell, and B is the caps'
    // crossing count (an integer, asked at the query) less w_caps.
    const bool clearOfCaps = g.capMet[cell] == 0;
    const CellsBall ball = g.ballOf(at, at);
    if (g.blockTried && blockRange(g, cell, at)) {
        result = CellState::WindingRange;
    } else if (clearOfSweep || clearOfSurface || clearOfCaps) {
        const glm::vec3 c = ball.centre;
        Estimate e;
        double drift;
        if (rangeOver(ball, e, drift)) {
            // The cheapest range to ask at a query: the whole winding
            // number's, then B's, then -w_caps.
            double base = e.term;
            result = CellState::BoundaryRange;
            bool byClosed = false;
            if (clearOfSurface) {
                base += double(surface_->winding(c));
                result = CellState::WindingRange;
            } else if (!clearOfSweep) {
                base -= double(projected_->winding(c));
                result = CellState::CappedRange;
                if (!g.closedWinding.empty() && g.closedWinding[cell] != CellWindings::kUnknown) {
                    // -w_caps's range (the caps keep out of the cell), and
                    // an integer term plus caps' crossing count the caller
                    // knows is one integer over the cell.
                    base += double(g.closedWinding[cell]);
                    result = CellState::WindingRange;
                    byClosed = true;
                    ++g.closedCells;
                }
            } else if (!g.constantWinding.empty() && g.constantWinding[cell] != CellWindings::kUnknown) {
                // B's range, and an integer term the caller knows is one
                // integer over the cell.
                base += double(g.constantWinding[cell]);
                result = CellState::WindingRange;
            }
            g.lo[cell] = base - e.bound - drift;
            g.hi[cell] = base + e.bound + drift;
            if (result == CellState::WindingRange) {
                const int side = sideOf(g.lo[cell], g.hi[cell]);
                g.alone[cell] = {side == 0 ? CellLabel::Undecided : side > 0 ? CellLabel::Inside : CellLabel::Outside,
                                 byClosed};
            }
        }
    }
    if (result == CellState::NoRange && plan(g, cell, ball.centre, ball.half, within)) result = CellState::Planned;
    g.state[cell].store(result, std::memory_order_release);
    return result;
}

BoundaryCaps::RangedCells BoundaryCaps::rangedCells(bool fine) const {
    const RangeGrid& g = fine ? fine_ : ranges_;
    RangedCells ranged;
    if (fine ? !fineReady_.load(std::memory_order_acquire) : !g.state) return ranged;
    for (std::size_t c = 0, n = std::size_t(g.dims.x) * g.dims.y * g.dims.z; c < n; ++c) {
        const CellState state = g.state[c].load(std::memory_order_acquire);
        ranged.boundary += state == CellState::BoundaryRange;
        ranged.winding += state == CellState::WindingRange;
        ranged.capped += state == CellState::CappedRange;
        ranged.planned += state == CellState::Planned;
    }
    ranged.closed = g.closedCells.load(std::memory_order_relaxed);
    return ranged;
}

std::size_t BoundaryCaps::memoryBytes() const {
    const auto held = [](const auto& v) { return v.capacity() * sizeof(v[0]); };
    std::size_t total = held(edges_) + held(loopEdges_) + held(loops_) + held(capPositions_) + held(capTriangles_) +
                        held(capLoopOf_) + held(chains_) + held(chainEdges_) + edgeTree_.memoryBytes() +
                        held(leafTris_) + held(nodes_) + (projected_ ? projected_->memoryBytes() : 0);
    for (const RangeGrid* g : {&ranges_, static_cast<const RangeGrid*>(&fine_)}) {
        total += held(g->met) + held(g->capMet) + held(g->constantWinding) + held(g->closedWinding) + held(g->lowestEdge);
        if (g == &fine_ ? !fineReady_.load(std::memory_order_acquire) : !g->state) continue;
        const std::size_t cells = std::size_t(g->dims.x) * g->dims.y * g->dims.z;
        // state, alone, planMisses; near, nearCount, nearLoops; lo, hi
        total += cells * (sizeof(CellState) + sizeof(CellVerdict) + 1 + sizeof(std::unique_ptr<std::uint32_t[]>) + 2 * sizeof(std::uint32_t) + 2 * sizeof(double));
        if (g->visits) total += cells * sizeof(std::uint16_t);
        if (g->blockTried) total += std::size_t(g->blockDims.x) * g->blockDims.y * g->blockDims.z;
        for (std::size_t c = 0; c < cells; ++c) // plans published so far
            if (g->state[c].load(std::memory_order_acquire) == CellState::Planned)
                total += (std::size_t(g->nearCount[c]) + g->nearLoops[c]) * sizeof(std::uint32_t);
    }
    return total;
}

bool BoundaryCaps::fineCells() const {
    if (fineReady_.load(std::memory_order_acquire)) return true;
    if (fine_.capMet.empty()) return false; // no fine grid (no grid at all)
    std::call_once(fineOnce_, [this] {
        fine_.allocate();
        fineReady_.store(true, std::memory_order_release);
    });
    return true;
}

bool BoundaryCaps::busy(std::size_t cell) const {
    std::atomic<std::uint16_t>& visits = ranges_.visits[cell];
    if (visits.load(std::memory_order_relaxed) >= kBusyVisits) return true;
    return unsigned(visits.fetch_add(1, std::memory_order_relaxed)) + 1 >= kBusyVisits;
}

template <class Winding>
bool BoundaryCaps::insideBy(const glm::vec3& q, const Winding& windingAt, bool apart) const {
    std::size_t cell;
    glm::uvec3 at;
    if (!ranges_.cellOf(q, cell, at)) return generalizedWindingInside(decide(windingAt(), q, 1.0).term);
    CellState state = ranges_.state[cell].load(std::memory_order_acquire);
    if (state == CellState::Unvisited) state = rangeOf(ranges_, cell, at);
    if ((state == CellState::NoRange || state == CellState::Planned) && busy(cell) && fineCells()) {
        // The fine cell, where it has a range or a plan (or the coarse one
        // has none either).
        std::size_t fineCell;
        glm::uvec3 fineAt;
        if (fine_.cellOf(q, fineCell, fineAt)) {
            CellState fineState = fine_.state[fineCell].load(std::memory_order_acquire);
            if (fineState == CellState::Unvisited)
                fineState = rangeOf(fine_, fineCell, fineAt, state == CellState::Planned);
            if ((fineState != CellState::NoRange && fineState != CellState::Filling) || state == CellState::NoRange)
                return insideIn(fine_, fineCell, fineState, q, windingAt, apart);
        }
    }
    return insideIn(ranges_, cell, state, q, windingAt, apart);
}

template <class Winding>
bool BoundaryCaps::insideIn(const RangeGrid& g, std::size_t cell, CellState state, const glm::vec3& q,
                            const Winding& windingAt, bool apart) const {
    // A closed count's range, for a query apart from it: -w_caps's range
    // (the count taken off), as CappedRange.
    const bool closedApart = state == CellState::WindingRange && apart && g.alone[cell].byClosed();
    if (state == CellState::WindingRange && !closedApart && g.alone[cell].label() != CellLabel::Undecided)
        return g.alone[cell].label() == CellLabel::Inside; // the whole winding number's range: no integer term asked
    const int winding = windingAt();
    if (state == CellState::BoundaryRange || state == CellState::CappedRange || closedApart) {
        double shift = double(state == CellState::BoundaryRange ? winding : winding + projected_->winding(q));
        if (closedApart) shift -= double(g.closedWinding[cell]);
        const int side = sideOf(shift + g.lo[cell], shift + g.hi[cell]);
        if (side != 0) return side > 0;
    }
    if (state == CellState::Planned) {
        Estimate planned;
        if (decidePlanned(g, winding, q, cell, planned)) {
            std::uint8_t misses = g.planMisses[cell].load(std::memory_order_relaxed);
            if (misses != 0) // once: a race lost leaves the score a step high
                g.planMisses[cell].compare_exchange_weak(misses, std::uint8_t(misses - 1), std::memory_order_relaxed);
            return generalizedWindingInside(planned.term);
        }
        // Undecided: the query lies within the far range's width of 1/2.
        // A cell whose queries keep doing so does better from the root.
        if (unsigned(g.planMisses[cell].fetch_add(1, std::memory_order_relaxed)) + 1 >= kPlanMisses)
            g.state[cell].store(CellState::NoRange, std::memory_order_relaxed);
    }
    return generalizedWindingInside(decide(winding, q, 1.0).term);
}

bool BoundaryCaps::inside(int winding, const glm::vec3& q) const {
    return insideBy(q, [winding] { return winding; }, false);
}

bool BoundaryCaps::insideApart(int winding, const glm::vec3& q) const {
    return insideBy(q, [winding] { return winding; }, true);
}

bool BoundaryCaps::inside(const glm::vec3& q) const {
    return insideBy(q, [&] { return surface_->winding(q); }, false);
}

void ProjectedSurface::markCells(const CellLattice& cells, std::vector<std::uint8_t>& met) const {
    // Against the rounding of a point's cell index, as the grid's edges.
    const double slack = 1e-7 * std::max({cells.size.x * cells.dims.x, cells.size.y * cells.dims.y,
                                          cells.size.z * cells.dims.z});
    for (const Triangle& t : mesh_.tris) {
        glm::dvec3 v[3];
        for (int k = 0; k < 3; ++k)
            for (int i = 0; i < 3; ++i) v[k][mesh_.perm[i]] = double(t.v[k][i]);
        markTriangleCells(cells, v[0], v[1], v[2], slack, met);
    }
}

void markTriangleCells(const CellLattice& cells, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                       double slack, std::vector<std::uint8_t>& met) {
    glm::uvec3 first(0), last(0);
    for (int k = 0; k < 3; ++k) {
        const double from = std::min({a[k], b[k], c[k]}) - slack, to = std::max({a[k], b[k], c[k]}) + slack;
        const double end = cells.lo[k] + double(cells.dims[k]) * cells.size[k];
        if (!(to >= cells.lo[k] && from <= end)) return; // NaN too
        const auto index = [&](double x) {
            if (!(cells.size[k] > 0.0)) return 0.0;
            return std::clamp(std::floor((x - cells.lo[k]) / cells.size[k]), 0.0, double(cells.dims[k] - 1));
        };
        first[k] = std::uint32_t(index(from));
        last[k] = std::uint32_t(index(to));
    }
    const glm::dvec3 n = glm::cross(b - a, c - a);
    const glm::dvec3 half = 0.5 * cells.size + slack;
    const double reach = std::fabs(n.x) * half.x + std::fabs(n.y) * half.y + std::fabs(n.z) * half.z;
    // The plane's offset at a cell's centre, against its reach over the
    // cell, with room for the rounding of both (relative 1e-9).
    const double rounding = 1e-9 * (glm::length(n) * (glm::length(a - cells.lo) + glm::length(cells.size * glm::dvec3(cells.dims))) + reach);
    glm::uvec3 at;
    for (at.z = first.z; at.z <= last.z; ++at.z)
        for (at.y = first.y; at.y <= last.y; ++at.y)
            for (at.x = first.x; at.x <= last.x; ++at.x) {
                const glm::dvec3 centre = cells.lo + (glm::dvec3(at) + 0.5) * cells.size;
                if (std::fabs(glm::dot(n, centre - a)) > reach + rounding) continue;
                met[cells.index(at)] = 1;
            }
}

} // namespace vds::detail
