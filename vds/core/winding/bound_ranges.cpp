// vds: the grids of bounds labels answer from first (bound_ranges.h; how
// a label is decided: boundary_caps.h), their cells' fills and plans.
#include <vds/detail/bound_ranges.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

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
constexpr unsigned kVisitsCounted = 60000;
/// The node tolerance of the estimate at a cell's centre (estimate()):
/// coarse, as a range serves only where it keeps clear of 1/2; it bounds
/// the part of a cell's range that is the estimate's error (tuning:
/// docs/benchmarks.md).
constexpr double kRangeTolerance = 5e-2;
/// A plan's score of queries it left undecided (each adds 1, each it
/// decided takes 1 off): at kPlanMisses its cell drops it. A miss costs
/// the plan and then the tree from its root, so a plan pays while it
/// decides most of its queries (tuning: docs/benchmarks.md).
constexpr unsigned kPlanMisses = 4;
/// When a cell builds its field (CellField): once the work its queries
/// without a range spent (nodes taken and edges summed, CapsEstimate::work)
/// reaches twice what a field costs: the work of every build tried so far
/// (CellField::work), the failed ones too, over the fields they gave,
/// counting one more of kFirstFieldWork. A field is kept only where it
/// leaves a query at most half the work (fieldOf), so it saves at least
/// half the rent: renting until the rent saved would have paid the price
/// costs at most about twice what knowing the cell's queries beforehand
/// would, and a cell few queries land in, or whose queries are cheap
/// already, never pays. 125 samples of some 64 nodes and edges each.
constexpr double kFirstFieldWork = 125.0 * 64.0;
/// A field's near nodes: those within this many of its cell's longest
/// sides across the axis. Wider leaves more nodes to each query, and
/// bounds the rest's third derivative by the fourth power of a longer
/// distance.
constexpr double kFieldMargin = 1.0;
/// A field with a larger error is not kept: most of its queries would
/// not keep clear of 1/2 by that.
constexpr double kFieldLimit = 0.1;
/// -1: the range puts the value below the threshold, 1: above, 0: neither.
int sideOf(double lo, double hi) {
    const double threshold = 0.5 + kGeneralizedWindingTie;
    if (hi < threshold - kRoundingSlack) return -1;
    if (lo > threshold + kRoundingSlack) return 1;
    return 0;
}

/// A planned cell's far loops lie at least this many of its half
/// diagonals beyond it.
constexpr double kPlanReach = 2.0;
/// Widest range of the far loops' part a plan keeps.
constexpr double kPlanWidth = 0.45;
/// Most near loops a plan keeps, and their most relative to the work of
/// the tree from its root at the cell's centre.
constexpr std::size_t kPlanNear = 64;
constexpr double kPlanShare = 0.75;

/// Whether the ray towards -axis from some point within `half` of `c` may
/// cross loop `loop`'s cap: the cap (the fan from the centroid) lies in
/// the loop's ball, so the ray must pass within its radius across the axis
/// and start above the ball's lowest point (widened against rounding).
bool capMayCross(const CapLoop& loop, const glm::dvec3& c, double half, int axis) {
    const double reach = (loop.radius + half) * (1.0 + 1e-9) + kRoundingSlack;
    double across = 0.0;
    for (int a = 0; a < 3; ++a)
        if (a != axis) across += (loop.centroid[a] - c[a]) * (loop.centroid[a] - c[a]);
    return across <= reach * reach && loop.centroid[axis] - c[axis] <= reach;
}
} // namespace

BoundRanges::BoundRanges(const CapLoops& loops, const CapsValueTree& values, const ChainLabels& labels,
                         const EdgeTree& drift, const Box* domain, const CapsSurface* surface,
                         const CellWindings* windings)
    : loops_(loops), values_(values), labels_(labels), drift_(drift), surface_(surface) {
    if (!loops.capped() || !domain) return;
    if (surface) windings = nullptr; // the surface answers for every cell it does not meet
    // The domain and a margin of a quarter of its longest side all round
    // (queries beside a box are common: points in a padded box, a sprite's
    // columns in front of and behind it).
    const double side = std::max({double(domain->hi.x) - domain->lo.x, double(domain->hi.y) - domain->lo.y,
                                  double(domain->hi.z) - domain->lo.z});
    if (!(side > 0.0) || !std::isfinite(side)) return;
    const Box box{glm::vec3(glm::dvec3(domain->lo) - 0.25 * side), glm::vec3(glm::dvec3(domain->hi) + 0.25 * side)};
    buildGrid(coarse_, box, kRangeCells, windings, true);
    if (coarse_.state) {
        // The fine grid's cells only when a cell first turns busy
        // (fineCells): what the windings and the surface say of each is
        // asked now (the windings are not kept).
        buildGrid(fine_, box, kFineCells, windings, false);
        coarse_.blockDims = (coarse_.dims + 1u) / 2u;
        const std::size_t blocks = std::size_t(coarse_.blockDims.x) * coarse_.blockDims.y * coarse_.blockDims.z;
        coarse_.blockTried.reset(new std::atomic<std::uint8_t>[blocks]);
        for (std::size_t b = 0; b < blocks; ++b) coarse_.blockTried[b].store(0, std::memory_order_relaxed);
    }
}

bool BoundRanges::clearOfSweep(const RangeGrid& g, const glm::uvec3& at) const {
    // Every edge whose projection may meet the cell's column lies above
    // the cell (its top widened against rounding).
    const int a = loops_.axisIndex(), s = (a + 1) % 3, t = (a + 2) % 3;
    const glm::dvec3 lo(g.box.lo), hi(g.box.hi);
    const double slack = cellSlack(hi - lo);
    const double top = lo[a] + double(at[a] + 1) * g.size[a] + 2.0 * slack;
    return top < g.lowestEdge[std::size_t(at[t]) * g.dims[s] + at[s]];
}

bool BoundRanges::rangeOver(const CellsBall& ball, CapsEstimate& e, double& drift) const {
    // Coarse will do: a range serves only where it keeps clear of 1/2.
    // The drift first (not finished past half a unit): where it alone
    // spans a unit, no estimate helps.
    drift = drift_.driftWithin(ball.centre, ball.half * (1.0 + 1e-9), 0.5);
    if (!std::isfinite(drift)) return false;
    e = values_.estimate(ball.centre, kRangeTolerance);
    return e.bound + drift < 0.5;
}

bool BoundRanges::blockRange(const RangeGrid& g, std::size_t cell, const glm::uvec3& at) const {
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
    CapsEstimate e;
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

void BoundRanges::buildGrid(RangeGrid& g, const Box& box, double cellsAlong, const CellWindings* windings,
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
    const int a = loops_.axisIndex(), s = (a + 1) % 3, t = (a + 2) % 3;
    g.lowestEdge.assign(std::size_t(g.dims[s]) * g.dims[t], std::numeric_limits<double>::infinity());
    // Cell extents are widened by `slack` against the rounding of a point's
    // cell index (and an edge's box by twice that).
    const double slack = cellSlack(extent);
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
    const std::vector<glm::vec3>& edges = loops_.edges();
    for (std::size_t k = 0; k + 1 < edges.size(); k += 2) {
        const glm::dvec3 p(edges[k]), q(edges[k + 1]);
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
        windings->constantWindings(CellLattice{lo, g.size, g.dims}, &loops_.projected(), g.constantWinding, g.closedWinding);
    }
    g.capMet.assign(cells, 0);
    loops_.markCapCells(CellLattice{lo, g.size, g.dims}, 2.0 * slack, g.capMet);
    if (cellsNow) g.allocate();
}

CellState BoundRanges::rangeOf(const RangeGrid& g, std::size_t cell, const glm::uvec3& at, bool within) const {
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
        CapsEstimate e;
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
                base -= double(loops_.projected().winding(c));
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

std::size_t BoundRanges::memoryBytes() const {
    const auto held = [](const auto& v) { return v.capacity() * sizeof(v[0]); };
    std::size_t total = 0;
    for (const RangeGrid* g : {&coarse_, static_cast<const RangeGrid*>(&fine_)}) {
        total += held(g->met) + held(g->capMet) + held(g->constantWinding) + held(g->closedWinding) + held(g->lowestEdge);
        if (g == &fine_ ? !fineReady_.load(std::memory_order_acquire) : !g->state) continue;
        const std::size_t cells = std::size_t(g->dims.x) * g->dims.y * g->dims.z;
        // state, alone, planMisses, farCrossed; near, nearCount, nearLoops; lo, hi
        total += cells * (sizeof(CellState) + sizeof(CellVerdict) + 2 + sizeof(std::unique_ptr<std::uint32_t[]>) + 2 * sizeof(std::uint32_t) + 2 * sizeof(double));
        // visits, spent, fields, fieldState
        total += cells * (sizeof(std::uint16_t) + sizeof(std::uint32_t) + sizeof(std::unique_ptr<CellField>) + 1);
        if (g->blockTried) total += std::size_t(g->blockDims.x) * g->blockDims.y * g->blockDims.z;
        for (std::size_t c = 0; c < cells; ++c) // plans published so far
            if (g->state[c].load(std::memory_order_acquire) == CellState::Planned)
                total += (std::size_t(g->nearCount[c]) + g->nearLoops[c]) * sizeof(std::uint32_t);
        for (std::size_t c = 0; c < cells; ++c) // fields published so far
            if (g->fieldState[c].load(std::memory_order_acquire) == 2) total += g->fields[c]->memoryBytes();
    }
    return total;
}

bool BoundRanges::fineCells() const {
    if (fineReady_.load(std::memory_order_acquire)) return true;
    if (fine_.capMet.empty()) return false; // no fine grid (no grid at all)
    std::call_once(fineOnce_, [this] {
        fine_.allocate();
        fineReady_.store(true, std::memory_order_release);
    });
    return true;
}

bool BoundRanges::busy(const RangeGrid& g, std::size_t cell) const {
    // Counted on past kBusyVisits (a field weighs the work per visit), up
    // to kVisitsCounted, short of the counter's range by more than racing
    // threads can add.
    std::atomic<std::uint16_t>& visits = g.visits[cell];
    const unsigned now = visits.load(std::memory_order_relaxed);
    if (now < kVisitsCounted) visits.fetch_add(1, std::memory_order_relaxed);
    return now + 1 >= kBusyVisits;
}

const CellField* BoundRanges::fieldOf(const RangeGrid& g, std::size_t cell, CellState state) const {
    std::atomic<std::uint8_t>& built = g.fieldState[cell];
    std::uint8_t now = built.load(std::memory_order_acquire);
    if (now == 2) return g.fields[cell].get();
    const double price = (buildWork_.load(std::memory_order_relaxed) + kFirstFieldWork) /
                         double(fieldsBuilt_.load(std::memory_order_relaxed) + 1);
    if (now != 0 || double(g.spent[cell].load(std::memory_order_relaxed)) < 2.0 * price) return nullptr;
    if (!built.compare_exchange_strong(now, 1, std::memory_order_acquire)) return nullptr;
    // This thread builds it; the others go on without meanwhile.
    const glm::uvec3 at(cell % g.dims.x, cell / g.dims.x % g.dims.y, cell / (std::size_t(g.dims.x) * g.dims.y));
    const glm::dvec3 from(g.box.lo), to(g.box.hi);
    const double slack = 2.0 * cellSlack(to - from);
    const glm::dvec3 lo = from + glm::dvec3(at) * g.size - slack, hi = lo + g.size + 2.0 * slack;
    const double longest = std::max({g.size.x, g.size.y, g.size.z});
    auto field = std::make_unique<CellField>();
    // Only where it leaves each query at most half the work its queries
    // spent so far (a near node costs about two: its expansion and chord),
    // and fewer nodes than the cell's plan.
    const double rent = double(g.spent[cell].load(std::memory_order_relaxed)) /
                        std::max(1.0, double(g.visits[cell].load(std::memory_order_relaxed)));
    std::size_t nearLimit = std::size_t(std::max(0.0, 0.25 * rent));
    if (state == CellState::Planned) nearLimit = std::min<std::size_t>(nearLimit, g.nearCount[cell]);
    const bool made = field->build(labels_, lo, hi, kFieldMargin * longest, kFieldLimit, nearLimit);
    // The price the next cells weigh (a race loses a sample, no label).
    buildWork_.store(buildWork_.load(std::memory_order_relaxed) + field->work(), std::memory_order_relaxed);
    if (!made) {
        built.store(3, std::memory_order_release);
        return nullptr;
    }
    fieldsBuilt_.fetch_add(1, std::memory_order_relaxed);
    g.fields[cell] = std::move(field);
    built.store(2, std::memory_order_release);
    return g.fields[cell].get();
}

template <class Winding>
bool BoundRanges::insideBy(const glm::vec3& q, const Winding& windingAt, bool apart) const {
    std::size_t cell;
    glm::uvec3 at;
    if (!coarse_.cellOf(q, cell, at)) return generalizedWindingInside(labels_.decide(windingAt(), q, 1.0).term);
    CellState state = coarse_.state[cell].load(std::memory_order_acquire);
    if (state == CellState::Unvisited) state = rangeOf(coarse_, cell, at);
    const bool undecided = state == CellState::NoRange || state == CellState::Planned;
    const bool isBusy = undecided && busy(coarse_, cell);
    Route route;
    std::size_t fineCell;
    glm::uvec3 fineAt;
    const bool fine = isBusy && fineCells() && fine_.cellOf(q, fineCell, fineAt);
    if (undecided) {
        // The finest field there is: a busy coarse cell's fine cells build
        // their own (a margin and octants half as wide: fewer near nodes).
        route.charge[0] = &coarse_.spent[cell];
        if (fine) {
            busy(fine_, fineCell); // its visits, for the work per visit fieldOf weighs
            route.charge[1] = &fine_.spent[fineCell];
            route.field = fieldOf(fine_, fineCell, CellState::NoRange);
        }
        if (!route.field) route.field = fieldOf(coarse_, cell, state);
        if (route.field) return insideIn(coarse_, cell, state, q, windingAt, apart, route);
    }
    if (fine) {
        // The fine cell, where it has a range or a plan (or the coarse one
        // has none either).
        CellState fineState = fine_.state[fineCell].load(std::memory_order_acquire);
        if (fineState == CellState::Unvisited)
            fineState = rangeOf(fine_, fineCell, fineAt, state == CellState::Planned);
        if ((fineState != CellState::NoRange && fineState != CellState::Filling) || state == CellState::NoRange)
            return insideIn(fine_, fineCell, fineState, q, windingAt, apart, route);
    }
    return insideIn(coarse_, cell, state, q, windingAt, apart, route);
}

template <class Winding>
bool BoundRanges::insideIn(const RangeGrid& g, std::size_t cell, CellState state, const glm::vec3& q,
                            const Winding& windingAt, bool apart, const Route& route) const {
    // A closed count's range, for a query apart from it: -w_caps's range
    // (the count taken off), as CappedRange.
    const bool closedApart = state == CellState::WindingRange && apart && g.alone[cell].byClosed();
    if (state == CellState::WindingRange && !closedApart && g.alone[cell].label() != CellLabel::Undecided)
        return g.alone[cell].label() == CellLabel::Inside; // the whole winding number's range: no integer term asked
    const int winding = windingAt();
    if (state == CellState::BoundaryRange || state == CellState::CappedRange || closedApart) {
        double shift = double(state == CellState::BoundaryRange ? winding : winding + loops_.projected().winding(q));
        if (closedApart) shift -= double(g.closedWinding[cell]);
        const int side = sideOf(shift + g.lo[cell], shift + g.hi[cell]);
        if (side != 0) return side > 0;
    }
    if (const CellField* field = route.field) {
        // The near nodes refined, the rest by the field: first the one
        // pass of their first cut (each near node holds few edges).
        const double rest = field->rest(q), lo = rest - field->error(), hi = rest + field->error();
        const std::vector<std::uint32_t>& near = field->nearNodes();
        CapsEstimate out;
        const bool decided = labels_.firstCut(winding, q, near.data(), near.size(), lo, hi, out) ||
                             labels_.refine(winding, q, 1.0, near.data(), near.size(), lo, hi, out);
        // The rent a finer field would cut (a coarse field's fine cell).
        route.add(out.work);
        if (decided) return generalizedWindingInside(out.term);
    }
    double work = 0.0;
    if (state == CellState::Planned) {
        CapsEstimate planned;
        const bool decided = decidePlanned(g, winding, q, cell, planned);
        work = planned.work;
        if (decided) {
            std::uint8_t misses = g.planMisses[cell].load(std::memory_order_relaxed);
            if (misses != 0) // once: a race lost leaves the score a step high
                g.planMisses[cell].compare_exchange_weak(misses, std::uint8_t(misses - 1), std::memory_order_relaxed);
            route.add(work);
            return generalizedWindingInside(planned.term);
        }
        // Undecided: the query lies within the far range's width of 1/2.
        // A cell whose queries keep doing so does better from the root.
        if (unsigned(g.planMisses[cell].fetch_add(1, std::memory_order_relaxed)) + 1 >= kPlanMisses)
            g.state[cell].store(CellState::NoRange, std::memory_order_relaxed);
    }
    const CapsEstimate decided = labels_.decide(winding, q, 1.0);
    route.add(work + decided.work);
    return generalizedWindingInside(decided.term);
}

bool BoundRanges::inside(int winding, const glm::vec3& q, bool apart) const {
    return insideBy(q, [winding] { return winding; }, apart);
}

bool BoundRanges::inside(const glm::vec3& q) const {
    return insideBy(q, [&] { return surface_->winding(q); }, false);
}

bool BoundRanges::plan(const RangeGrid& g, std::size_t cell, const glm::vec3& c, double half, bool within) const {
    // A cut of the tree of loops for the cell: a node of whole loops far
    // enough from it (its ball at least kPlanReach cell half diagonals and
    // two radii beyond) is far, its caps' -w taken at the cell's centre by
    // the second-order expansion and widened over the cell by the caps'
    // steepness (2 area / distance^3 over 4 pi, edge_tree.h); a single
    // loop nearer is near, left to each query, a group nearer is split.
    // Chains (parts of loops) are never reached. No plan where the far
    // range would be wide or the near loops many: the tree from its root
    // does better there.
    const glm::dvec3 p(c);
    std::vector<std::uint32_t> near, loops;
    double value = 0.0, width = 0.0;
    const bool fits = walkTree(0, [&](std::uint32_t i, TreeStack& stack) {
        const ChainNode& n = labels_.chains()[i];
        const glm::dvec3 y = n.centre - p;
        const double d2 = glm::dot(y, y), d = std::sqrt(d2);
        const double radius = n.radius * (1.0 + 1e-12), gap = d - radius - half;
        if (!n.chord && gap >= std::max(2.0 * radius, kPlanReach * half)) {
            value -= secondOrderTerm(n, y, d2, d) / kFourPi;
            width += n.errorScale * remainderFactor(d, d - radius, radius) +
                     2.0 * n.area * half / (kFourPi * gap * gap * gap);
            return !(width > kPlanWidth);
        }
        if (n.loop != ChainNode::kNoLoop || n.chord) {
            near.push_back(i);
            return !(near.size() > kPlanNear);
        }
        stack.push(n.left);
        stack.push(n.right);
        return true;
    });
    if (!fits) return false;
    // The loops the near nodes hold.
    for (const std::uint32_t i : near)
        walkTree(i, [&](std::uint32_t index, TreeStack& stack) {
            const ChainNode& n = labels_.chains()[index];
            if (n.loop != ChainNode::kNoLoop) {
                loops.push_back(n.loop);
            } else {
                stack.push(n.left);
                stack.push(n.right);
            }
            return true;
        });
    // Worth it where the near loops are fewer than the tree from its root
    // takes at the centre (nodes and edges). Within a planned cell that
    // test was passed: a fine cell's near loops lie within the coarse
    // cell's reach (its centre within half the coarse half diagonal), so
    // they are no more than the coarse cell's, and the decide() at the
    // centre (some 2 us of the soup's) is not asked again.
    if (!within && double(near.size()) > kPlanShare * labels_.decide(0, c, 1.0).work) return false;
    std::sort(loops.begin(), loops.end());
    // Whether a query must count the far loops' caps crossed in front of it
    // (decidePlanned): not where no far cap lies in the cell's column below it.
    bool farCrossed = false;
    for (std::uint32_t l = 0; l < loops_.loops().size() && !farCrossed; ++l)
        farCrossed = !std::binary_search(loops.begin(), loops.end(), l) &&
                     capMayCross(loops_.loops()[l], p, half, loops_.axisIndex());
    g.farCrossed[cell] = farCrossed ? 1 : 0;
    // The filling thread owns the cell (Filling).
    width = width * (1.0 + 1e-9) + kRoundingSlack;
    g.lo[cell] = value - width;
    g.hi[cell] = value + width;
    // Its queries refine the near loops from the nodes each of them reaches.
    std::vector<std::uint32_t> starts;
    labels_.frontier(near.data(), near.size(), p, half, starts);
    g.nearCount[cell] = std::uint32_t(starts.size());
    g.nearLoops[cell] = std::uint32_t(loops.size());
    g.near[cell].reset(new std::uint32_t[starts.size() + loops.size()]);
    std::copy(starts.begin(), starts.end(), g.near[cell].get());
    std::copy(loops.begin(), loops.end(), g.near[cell].get() + starts.size());
    return true;
}

bool BoundRanges::decidePlanned(const RangeGrid& g, int winding, const glm::vec3& q, std::size_t cell,
                                 CapsEstimate& out) const {
    const std::uint32_t* near = g.near[cell].get();
    const std::uint32_t count = g.nearCount[cell];
    const std::uint32_t* loops = near + count;
    const std::uint32_t* loopsEnd = loops + g.nearLoops[cell];
    // The far loops' caps crossed in front of q: C_caps less the near loops'.
    int far = 0;
    if (g.farCrossed[cell]) {
        thread_local std::vector<std::pair<std::uint32_t, int>> crossed;
        loops_.capCrossings(q, crossed);
        for (const auto& [loop, crossing] : crossed)
            if (!std::binary_search(loops, loopsEnd, loop)) far += crossing;
    }
    // Where every near node is summed whole when not taken (a loop of few
    // edges: a soup's), most planned queries decide on the first cut: that
    // round alone first, in one pass.
    bool small = true;
    for (std::uint32_t k = 0; k < count; ++k) small &= labels_.chains()[near[k]].edgeCount <= kDirectEdges;
    if (small && labels_.firstCut(winding + far, q, near, count, g.lo[cell], g.hi[cell], out)) return true;
    return labels_.refine(winding + far, q, 1.0, near, count, g.lo[cell], g.hi[cell], out);
}

} // namespace vds::detail
