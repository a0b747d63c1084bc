// vds: the chain tree labels refine (chain_labels.h): its build, a node
// taken by its chord and expansion, and the decide-or-refine loop.
//
// The tree: over the loops (each node's surface the loops' fans, no
// chord), then within a loop over halves of its edges. A chain of edges
// running from P to Q, closed by its chord Q -> P, bounds the fan (g, b, a)
// over its edges a -> b and the chord, g the mean of its vertices; the fan
// lies in the node's ball. Where q's ray towards -axis misses the ball, the
// chain's per-edge angles sum to the chord's angle f(P -> Q)
// (edgeSolidAngle, exact) less the fan's solid angle, which the expansion
// takes (boundary_caps.h). Leaves sum their edges' angles as the per-edge
// sum does.
#include <vds/detail/chain_labels.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include <vds/detail/antipodal.h>
#include <vds/detail/tree_walk.h>

namespace vds::detail {

using namespace caps;

namespace {
/// Largest error bound of a node that labels take by its expansion; nodes
/// erring by more are opened at once (they cannot help decide a label, and
/// keeping every taken bound small keeps the running sums' drift small).
constexpr double kMaxTakenBound = 0.25;
/// Labels refine by the expansion to second order once the value lies
/// within this of the threshold (decide()); farther out, first order
/// (tuning: docs/benchmarks.md).
constexpr double kSecondOrderBelow = 0.1;
/// decide() opens, a round at a time, the taken nodes whose bound is at
/// least this fraction of the largest: the fewest rounds for the nodes
/// opened (tuning: docs/benchmarks.md).
constexpr double kOpenFraction = 0.5;
/// decide() gives up for the per-edge sum where this times its predicted
/// work (rising as the square root of the shrink of the bound still
/// needed) passes the budget: it bounds the work a point near 1/2 may
/// spend on the tree before the per-edge sum (tuning: docs/benchmarks.md).
constexpr double kGiveUp = 1.5;
/// Most edges a chain leaf holds.
constexpr std::uint32_t kLeafEdges = 4;
} // namespace

ChainLabels::ChainLabels(const CapLoops& loops) : loops_(loops) {
    if (!loops.capped()) return;
    std::vector<std::uint32_t> order(loops.loops().size());
    for (std::uint32_t l = 0; l < order.size(); ++l) order[l] = l;
    chains_.reserve(2 * loops.edgeCount() / 2 + 2 * loops.loops().size() + 2);
    buildChainGroup(order, 0, std::uint32_t(order.size()));
    loopStarts_.push_back(std::uint32_t(chainEdges_.size() / 2));
    lengthBefore_.assign(chainEdges_.size() / 2 + 1, 0.0);
    for (std::size_t k = 0; k + 1 < lengthBefore_.size(); ++k)
        lengthBefore_[k + 1] =
            lengthBefore_[k] + glm::length(glm::dvec3(chainEdges_[2 * k + 1]) - glm::dvec3(chainEdges_[2 * k]));
}

double ChainLabels::lengthOf(const ChainNode& n) const {
    return lengthBefore_[n.edgeFirst + n.edgeCount] - lengthBefore_[n.edgeFirst];
}

std::pair<std::uint32_t, std::uint32_t> ChainLabels::loopOf(std::uint32_t edge) const {
    const auto at = std::upper_bound(loopStarts_.begin(), loopStarts_.end(), edge);
    return {*(at - 1), *at};
}

std::uint32_t ChainLabels::buildChainGroup(std::vector<std::uint32_t>& loops, std::uint32_t first,
                                            std::uint32_t last) {
    if (last - first == 1) {
        const CapLoop& loop = loops_.loops()[loops[first]];
        const std::uint32_t treeFirst = std::uint32_t(chainEdges_.size() / 2);
        loopStarts_.push_back(treeFirst);
        chainEdges_.insert(chainEdges_.end(), loops_.loopEdges().begin() + 2 * std::ptrdiff_t(loop.first),
                          loops_.loopEdges().begin() + 2 * std::ptrdiff_t(loop.first + loop.count));
        return buildChain(loops[first], loop.first, loop.count, treeFirst);
    }
    const std::uint32_t index = std::uint32_t(chains_.size());
    const std::uint32_t treeFirst = std::uint32_t(chainEdges_.size() / 2);
    chains_.emplace_back();
    glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
    glm::dvec3 clo = lo, chi = hi;
    std::vector<std::array<glm::dvec3, 3>> tris;
    for (std::uint32_t l = first; l < last; ++l) {
        const CapLoop& loop = loops_.loops()[loops[l]];
        clo = glm::min(clo, loop.centroid);
        chi = glm::max(chi, loop.centroid);
        for (std::uint32_t k = loop.first; k < loop.first + loop.count; ++k) {
            const glm::dvec3 a(loops_.loopEdges()[2 * k]), b(loops_.loopEdges()[2 * k + 1]);
            lo = glm::min(lo, a);
            hi = glm::max(hi, a);
            tris.push_back({loop.centroid, b, a});
        }
    }
    ChainNode node{};
    node.centre = 0.5 * (lo + hi);
    // The ball holds every fan's corners (the centroids, rounded to float,
    // may lie off a flat loop's hull), so the fans too.
    for (const auto& t : tris)
        node.radius = std::max({node.radius, glm::length(t[0] - node.centre), glm::length(t[2] - node.centre)});
    setMoments(node, momentsOf(tris, 0, tris.size(), node.centre));
    finishNode(node);
    node.chord = false;
    node.loop = ChainNode::kNoLoop;
    const glm::dvec3 extent = chi - clo;
    const int split = extent.x >= extent.y && extent.x >= extent.z ? 0 : extent.y >= extent.z ? 1 : 2;
    const std::uint32_t middle = first + (last - first) / 2;
    std::nth_element(loops.begin() + first, loops.begin() + middle, loops.begin() + last,
                     [&](std::uint32_t x, std::uint32_t y) { return loops_.loops()[x].centroid[split] < loops_.loops()[y].centroid[split]; });
    node.left = buildChainGroup(loops, first, middle);
    node.right = buildChainGroup(loops, middle, last);
    node.edgeFirst = treeFirst;
    node.edgeCount = std::uint32_t(chainEdges_.size() / 2) - treeFirst;
    chains_[index] = node;
    return index;
}

std::uint32_t ChainLabels::buildChain(std::uint32_t loop, std::uint32_t first, std::uint32_t count,
                                       std::uint32_t treeFirst) {
    const std::uint32_t index = std::uint32_t(chains_.size());
    chains_.emplace_back();
    ChainNode node{};
    const bool whole = count == loops_.loops()[loop].count;
    glm::dvec3 apex(0.0);
    if (whole) {
        apex = loops_.loops()[loop].centroid;
    } else {
        for (std::uint32_t k = first; k < first + count; ++k) apex += glm::dvec3(loops_.loopEdges()[2 * k]);
        apex += glm::dvec3(loops_.loopEdges()[2 * (first + count - 1) + 1]);
        apex /= double(count + 1);
    }
    std::vector<std::array<glm::dvec3, 3>> tris;
    for (std::uint32_t k = first; k < first + count; ++k) {
        const glm::dvec3 a(loops_.loopEdges()[2 * k]), b(loops_.loopEdges()[2 * k + 1]);
        tris.push_back({apex, b, a});
        node.radius = std::max({node.radius, glm::length(a - apex), glm::length(b - apex)});
    }
    node.from = glm::dvec3(loops_.loopEdges()[2 * first]);
    node.to = glm::dvec3(loops_.loopEdges()[2 * (first + count - 1) + 1]);
    node.chord = !whole;
    node.loop = whole ? loop : ChainNode::kNoLoop;
    if (node.chord) tris.push_back({apex, node.from, node.to}); // the chord Q -> P closes the chain
    node.centre = apex;
    setMoments(node, momentsOf(tris, 0, tris.size(), apex));
    finishNode(node);
    node.edgeFirst = treeFirst;
    node.edgeCount = count;
    if (count <= kLeafEdges) {
        node.first = first;
        node.count = count;
        chains_[index] = node;
        return index;
    }
    const std::uint32_t half = count / 2;
    node.left = buildChain(loop, first, half, treeFirst);
    node.right = buildChain(loop, first + half, count - half, treeFirst + half);
    chains_[index] = node;
    return index;
}

bool ChainLabels::takeNode(const ChainNode& n, const glm::dvec3& p, bool secondOrder, double& bound,
                           double& value) const {
    const int a = loops_.axisIndex(), s = (a + 1) % 3, t = (a + 2) % 3;
    const glm::dvec3 y = n.centre - p;
    const double d2 = glm::dot(y, y);
    const double reach = n.radius * (1.0 + 1e-12);
    // q's ray towards -axis misses the ball: the fan's crossing count is 0
    const bool misses = y[s] * y[s] + y[t] * y[t] > reach * reach || p[a] < n.centre[a] - reach;
    if (!misses || !(d2 > reach * reach)) return false;
    const double d = std::sqrt(d2), e = d - reach;
    bound = secondOrder ? n.errorScale * remainderFactor(d, e, reach) : n.errorScale * firstOrderFactor(d, e);
    if (!(bound <= kMaxTakenBound)) return false;
    value = secondOrder ? -secondOrderTerm(n, y, d2, d) : -firstOrderTerm(n, y, d2, d);
    return true;
}

namespace {
/// The chords' angles of the chain nodes nodeAt(0 .. count - 1) (those with a chord), as
/// the per-edge sum takes an edge's (EdgeAngles: one atan2 for them all,
/// not one a chord). A chord's ends are loop vertices, floats.
template <class NodeAt>
double chordAngles(const std::vector<ChainNode>& chains, std::size_t count, const NodeAt& nodeAt, int axis,
                   const glm::dvec3& p) {
    thread_local std::vector<glm::vec3> ends;
    ends.clear();
    for (std::size_t k = 0; k < count; ++k) {
        const ChainNode& n = chains[nodeAt(k)];
        if (!n.chord) continue;
        ends.emplace_back(n.from);
        ends.emplace_back(n.to);
    }
    if (ends.empty()) return 0.0;
    EdgeAngles sum;
    sum.add(ends.data(), ends.size() / 2, axis, p);
    return sum.angle();
}
} // namespace

int ChainLabels::axisIndex() const { return loops_.axisIndex(); }

double ChainLabels::sumOver(const std::uint32_t* roots, std::size_t rootCount, const glm::dvec3& lo,
                           const glm::dvec3& hi, const glm::dvec3* points, std::size_t count, double tolerance,
                           double* out, double& work) const {
    const int a = loops_.axisIndex();
    // One cut for every point of the box: a node is taken where no ray
    // from the box towards -axis meets its ball (its footprint clear of
    // the box's, or the box below it) and its bound at the box's nearest
    // point, the largest, is within the tolerance; the rest opened.
    std::vector<std::uint32_t> taken;
    std::vector<glm::vec3> edges; // the taken chords and the leaves' edges
    double bound = 0.0;
    for (std::size_t r = 0; r < rootCount; ++r)
        walkTree(roots[r], [&](std::uint32_t i, TreeStack& stack) {
            const ChainNode& n = chains_[i];
            const double reach = n.radius * (1.0 + 1e-12);
            double across2 = 0.0, gap2 = 0.0;
            for (int k = 0; k < 3; ++k) {
                const double g = std::max({lo[k] - n.centre[k], 0.0, n.centre[k] - hi[k]});
                gap2 += g * g;
                if (k != a) across2 += g * g;
            }
            const bool misses = across2 > reach * reach || hi[a] < n.centre[a] - reach;
            const double d = std::sqrt(gap2) * (1.0 - 1e-12);
            if (misses && d > reach) {
                const double b = n.errorScale * remainderFactor(d, d - reach, reach);
                if (b <= tolerance) {
                    taken.push_back(i);
                    bound += b;
                    if (n.chord) {
                        edges.emplace_back(n.from);
                        edges.emplace_back(n.to);
                    }
                    return true;
                }
            }
            if (n.count == 0 && n.edgeCount > kDirectEdges) {
                stack.push(n.left);
                stack.push(n.right);
            } else {
                const auto first = chainEdges_.begin() + 2 * std::ptrdiff_t(n.edgeFirst);
                edges.insert(edges.end(), first, first + 2 * std::ptrdiff_t(n.edgeCount));
            }
            return true;
        });
    work = double(count) * double(taken.size() + edges.size() / 2);
    // Node by node over the points (the inner loop has no branch).
    std::fill(out, out + count, 0.0);
    for (const std::uint32_t i : taken) {
        const ChainNode& n = chains_[i];
        for (std::size_t k = 0; k < count; ++k) {
            const glm::dvec3 y = n.centre - points[k];
            const double d2 = glm::dot(y, y);
            out[k] -= secondOrderTerm(n, y, d2, std::sqrt(d2));
        }
    }
    for (std::size_t k = 0; k < count; ++k) {
        EdgeAngles angles;
        angles.add(edges.data(), edges.size() / 2, a, points[k]);
        out[k] = (out[k] + angles.angle()) / kFourPi;
    }
    return bound + kRoundingSlack;
}

bool ChainLabels::firstCut(int winding, const glm::vec3& q, const std::uint32_t* roots, std::size_t rootCount,
                            double farLo, double farHi, CapsEstimate& out) const {
    const glm::dvec3 p(q);
    const int a = loops_.axisIndex();
    double angles = 0.0, bound = 0.5 * (farHi - farLo), work = 0.0;
    EdgeAngles leafSum;
    bool leaves = false;
    thread_local std::vector<std::uint32_t> chords;
    chords.clear();
    for (std::size_t r = 0; r < rootCount; ++r) {
        // refine()'s open() on a root, its first step: the same tests and
        // terms (first order, as the first cut is).
        const ChainNode& n = chains_[roots[r]];
        double b, value;
        if (takeNode(n, p, false, b, value)) {
            work += n.chord ? 2.0 : 1.0;
            angles += value;
            bound += b;
            if (n.chord) chords.push_back(roots[r]);
            continue;
        }
        if (n.count == 0 && n.edgeCount > kDirectEdges) return false; // refine splits it
        work += double(n.edgeCount);
        leafSum.add(&chainEdges_[2 * std::size_t(n.edgeFirst)], n.edgeCount, a, p);
        leaves = true;
    }
    // As refine() finds its first value (margin 1).
    const double offset = double(winding) - 0.5 - kGeneralizedWindingTie + 0.5 * (farLo + farHi);
    angles += chordAngles(chains_, chords.size(), [&](std::size_t k) { return chords[k]; }, a, p);
    const double value = offset + (angles + (leaves ? leafSum.angle() : 0.0)) / kFourPi;
    if (!(std::fabs(value) > bound + kRoundingSlack)) return false;
    out = {value + 0.5 + kGeneralizedWindingTie, bound + kRoundingSlack, work};
    return true;
}

CapsEstimate ChainLabels::decide(int winding, const glm::vec3& q, double margin) const {
    if (!loops_.closed()) return {loops_.exact(winding, q), 0.0};
    if (chains_.empty()) return {double(winding), 0.0};
    const std::uint32_t root = 0;
    CapsEstimate out;
    if (refine(winding, q, margin, &root, 1, 0.0, 0.0, out)) return out;
    return {loops_.exact(winding, q), 0.0, out.work + double(loops_.edgeCount())};
}

/// refine()'s running state: the cut of the chain tree taken so far, its
/// per-edge angles' sum (in radians: of the taken nodes, and of the
/// leaves' edges as the per-edge sum takes them, EdgeAngles: one atan2
/// when a label is tried, not one an edge) and its summed bounds.
struct ChainLabels::Refinement {
    struct Taken {
        double bound;
        double value; ///< the node's fan's angle by its expansion (its chord's: chordAngles)
        std::uint32_t node;
    };
    Refinement(const ChainLabels& of, const glm::vec3& q, double farHalfWidth, std::vector<Taken>& takenNodes,
               std::vector<Taken>& openingNodes)
        : tree(of), p(q), axis(of.loops_.axisIndex()), farBound(farHalfWidth), budget(double(of.loops_.edgeCount())),
          bound(farHalfWidth), taken(takenNodes), opening(openingNodes) {}

    /// Opens the subtree at `index`: nodes q's ray misses and far enough by
    /// expansion, the rest down to nodes of at most kDirectEdges edges,
    /// whose edges are summed exactly. False once the work exceeds the
    /// budget. `expand`: not by its own expansion (a node taken before).
    bool open(std::uint32_t index, bool expand) {
        return walkTree(index, [&](std::uint32_t i, TreeStack& stack) {
            if (work > budget) return false;
            const ChainNode& n = tree.chains_[i];
            double b, value;
            if (!(expand && i == index) && tree.takeNode(n, p, secondOrder, b, value)) {
                work += n.chord ? 2.0 : 1.0;
                angles += value;
                bound += b;
                taken.push_back({b, value, i});
                chordsChanged |= n.chord;
                return true;
            }
            if (n.count == 0 && n.edgeCount > kDirectEdges) {
                stack.push(n.left);
                stack.push(n.right);
                return true;
            }
            work += double(n.edgeCount);
            leafSum.add(&tree.chainEdges_[2 * std::size_t(n.edgeFirst)], n.edgeCount, axis, p);
            leavesChanged = true;
            return true;
        });
    }

    /// Rounds of opening until the value, less (1/2 + tie) by `offset`,
    /// lies farther than `margin` times the bound from the threshold (then
    /// `out` and true), or no round can get it there.
    bool decide(double offset, double margin, CapsEstimate& out);
    /// Opens every taken node whose bound is at least kOpenFraction of the
    /// largest, adding to `moved` how far that may move the value; false
    /// once the work exceeds the budget.
    bool openRound(double& moved);

    const ChainLabels& tree;
    const glm::dvec3 p;
    const int axis;
    /// What stands for the loops not in `roots`: half the width of the
    /// range of their part.
    const double farBound;
    /// Work spent, in nodes taken (a chord's angle and an expansion) and
    /// edges summed: past the edge count the per-edge sum decides.
    const double budget;
    double work = 0.0;
    double angles = 0.0, bound;
    EdgeAngles leafSum;
    bool secondOrder = false;
    /// The leaves' angle, taken again (an atan2) only after edges were
    /// summed.
    bool leavesChanged = false;
    double leaves = 0.0;
    /// The taken nodes' chords' angle, taken again only after the taken
    /// chords changed.
    bool chordsChanged = false;
    double chords = 0.0;
    std::vector<Taken>& taken;
    std::vector<Taken>& opening;
};

bool ChainLabels::Refinement::decide(double offset, double margin, CapsEstimate& out) {
    // The value is found (the leaves' atan2) only where it may decide:
    // opening a node of bound b moves the value by at most b plus the
    // bounds its children add (the node's edges lie within b of its
    // value, the children's values within theirs of them), so |value|
    // is at most |the last one found| + `moved`, and while that is
    // within margin * bound no value decides.
    double value = 0.0, moved = 0.0;
    bool found = false;
    while (true) {
        const bool find = !found || std::fabs(value) + moved > margin * bound + kRoundingSlack;
        if (find) {
            if (leavesChanged) {
                leaves = leafSum.angle();
                leavesChanged = false;
            }
            if (chordsChanged) {
                chords = chordAngles(tree.chains_, taken.size(), [&](std::size_t k) { return taken[k].node; }, axis, p);
                chordsChanged = false;
            }
            value = offset + (angles + leaves + chords) / kFourPi;
            moved = 0.0;
            found = true;
            // The running sums drift by some 1e-13 at most (each taken
            // bound is at most kMaxTakenBound), within the slack.
            if (std::fabs(value) > margin * bound + kRoundingSlack) {
                out = {value + 0.5 + kGeneralizedWindingTie, bound + kRoundingSlack, work};
                return true;
            }
            // Within the far range's half width of 1/2 no refining
            // decides.
            if (std::fabs(value) <= margin * farBound + kRoundingSlack) return false;
            // The bound must shrink by margin * bound / |value|, which
            // takes about the work so far times its square root (a
            // node's first-order bound falls as its radius cubed, but
            // the cut's nodes rise faster than the radius falls, and a
            // taken node costs about three edges of the per-edge sum):
            // where that passes the budget, the per-edge sum is the
            // cheaper.
            if (kGiveUp * work * std::sqrt(margin * bound / std::fabs(value)) > budget) return false;
        }
        if (taken.empty() || work > budget) return false;
        // Close to the threshold, the nodes opened from here are taken
        // to second order (their bound about R / D of the first
        // order's, for about twice the work; bulk points stop at the
        // first cut; kSecondOrderBelow).
        secondOrder = std::fabs(value) < kSecondOrderBelow;
        if (!openRound(moved)) return false;
    }
}

bool ChainLabels::Refinement::openRound(double& moved) {
    double largest = 0.0;
    for (const Taken& tk : taken) largest = std::max(largest, tk.bound);
    const double least = kOpenFraction * largest;
    opening.clear();
    std::size_t kept = 0;
    for (const Taken& tk : taken) {
        if (tk.bound >= least) {
            opening.push_back(tk);
            chordsChanged |= tree.chains_[tk.node].chord;
            angles -= tk.value;
            bound -= tk.bound;
            moved += tk.bound;
        } else {
            taken[kept++] = tk;
        }
    }
    taken.resize(kept);
    if (taken.empty()) bound = farBound; // no drift left where nothing is taken
    const double before = bound;
    bool more = true;
    for (std::size_t k = 0; k < opening.size() && more; ++k) {
        const ChainNode& n = tree.chains_[opening[k].node];
        if (n.count == 0) more = open(n.left, false) && open(n.right, false);
        else more = open(opening[k].node, true); // a leaf: summed exactly
    }
    if (!more) return false;
    moved += bound - before;
    return true;
}

bool ChainLabels::refine(int winding, const glm::vec3& q, double margin, const std::uint32_t* roots,
                          std::size_t rootCount, double farLo, double farHi, CapsEstimate& out) const {
    thread_local std::vector<Refinement::Taken> taken, opening;
    taken.clear();
    // Decide-or-refine: start from the coarsest cut whose nodes each err by
    // at most kMaxTakenBound, then open, a round at a time, every taken
    // node whose bound is at least kOpenFraction of the largest, until the
    // value lies farther from 1/2 than the summed bounds.
    Refinement refinement(*this, q, 0.5 * (farHi - farLo), taken, opening);
    // value - (1/2 + tie) = offset + angles / 4 pi; the estimate lies
    // within bound + kRoundingSlack of the per-edge sum, so a value farther
    // than that from the threshold has the per-edge sum's label.
    const double offset = double(winding) - 0.5 - kGeneralizedWindingTie + 0.5 * (farLo + farHi);
    bool opened = true;
    for (std::size_t r = 0; r < rootCount && opened; ++r) opened = refinement.open(roots[r], false);
    if (opened && refinement.decide(offset, margin, out)) return true;
    out.work = refinement.work;
    return false;
}

void ChainLabels::frontier(const std::uint32_t* roots, std::size_t rootCount, const glm::dvec3& c, double half,
                           std::vector<std::uint32_t>& out) const {
    // A query lies within `half` of c (widened here against its rounding),
    // so its distance to a node's centre is at most d + half, where the
    // first-order bound, falling with the distance, is least.
    const auto noneTakes = [&](const ChainNode& n) {
        const double reach = n.radius * (1.0 + 1e-12), d = glm::length(n.centre - c);
        const double farthest = (d + half) * (1.0 + 1e-9);
        if (!(farthest > reach)) return true; // every query within the ball
        return n.errorScale * firstOrderFactor(farthest, farthest - reach) > kMaxTakenBound * (1.0 + 1e-9);
    };
    out.clear();
    for (std::size_t r = 0; r < rootCount; ++r)
        walkTree(roots[r], [&](std::uint32_t i, TreeStack& stack) {
            const ChainNode& n = chains_[i];
            if (n.count == 0 && n.edgeCount > kDirectEdges && noneTakes(n)) {
                stack.push(n.left);
                stack.push(n.right);
            } else {
                out.push_back(i);
            }
            return true;
        });
}

std::size_t ChainLabels::memoryBytes() const {
    return chains_.capacity() * sizeof(chains_[0]) + chainEdges_.capacity() * sizeof(chainEdges_[0]) +
           loopStarts_.capacity() * sizeof(loopStarts_[0]) + lengthBefore_.capacity() * sizeof(lengthBefore_[0]);
}

ChainTree chainTreeOf(const glm::vec3* edges, std::size_t edgeCount, Axis axis) {
    const CapLoops loops(edges, edgeCount, axis);
    const ChainLabels labels(loops);
    ChainTree tree;
    tree.closed = loops.closed();
    tree.loopEdges = loops.loopEdges();
    tree.nodes = labels.chains();
    return tree;
}

} // namespace vds::detail
