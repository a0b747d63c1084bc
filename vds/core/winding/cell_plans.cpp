// vds: a grid cell's plan: the loops far from the cell collapsed into the
// range of their caps' -w over it, the near ones refined per query.
#include <vds/detail/caps_tree.h>

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
/// A planned cell's far loops lie at least this many of its half
/// diagonals beyond it.
constexpr double kPlanReach = 2.0;
/// Widest range of the far loops' part a plan keeps.
constexpr double kPlanWidth = 0.45;
/// Most near loops a plan keeps, and their most relative to the work of
/// the tree from its root at the cell's centre.
constexpr std::size_t kPlanNear = 64;
constexpr double kPlanShare = 0.75;
} // namespace

void BoundaryCaps::capCrossings(const glm::vec3& q, std::vector<std::pair<std::uint32_t, int>>& out) const {
    out.clear();
    float v[3];
    projected_->toViewSpace(q, v);
    projected_->crossings(projected_->grid.find(v), v,
                          [&](const Triangle& t, int crossing) { out.emplace_back(capLoopOf_[t.index], crossing); });
}

bool BoundaryCaps::plan(const RangeGrid& g, std::size_t cell, const glm::vec3& c, double half, bool within) const {
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
        const ChainNode& n = chains_[i];
        const glm::dvec3 y = n.centre - p;
        const double d2 = glm::dot(y, y), d = std::sqrt(d2);
        const double radius = n.radius * (1.0 + 1e-12), gap = d - radius - half;
        if (!n.chord && gap >= std::max(2.0 * radius, kPlanReach * half)) {
            value -= expansion(n, y, d2, d) / kFourPi;
            width += n.errorScale * remainderFactor(d, d - radius, radius) +
                     2.0 * n.area * half / (kFourPi * gap * gap * gap);
            return !(width > kPlanWidth);
        }
        if (n.loop != kNoLoop || n.chord) {
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
            const ChainNode& n = chains_[index];
            if (n.loop != kNoLoop) {
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
    if (!within && double(near.size()) > kPlanShare * decide(0, c, 1.0).work) return false;
    std::sort(loops.begin(), loops.end());
    // The filling thread owns the cell (Filling).
    width = width * (1.0 + 1e-9) + kRoundingSlack;
    g.lo[cell] = value - width;
    g.hi[cell] = value + width;
    g.nearCount[cell] = std::uint32_t(near.size());
    g.nearLoops[cell] = std::uint32_t(loops.size());
    g.near[cell].reset(new std::uint32_t[near.size() + loops.size()]);
    std::copy(near.begin(), near.end(), g.near[cell].get());
    std::copy(loops.begin(), loops.end(), g.near[cell].get() + near.size());
    return true;
}

bool BoundaryCaps::decidePlanned(const RangeGrid& g, int winding, const glm::vec3& q, std::size_t cell,
                                 Estimate& out) const {
    const std::uint32_t* near = g.near[cell].get();
    const std::uint32_t count = g.nearCount[cell];
    const std::uint32_t* loops = near + count;
    const std::uint32_t* loopsEnd = loops + g.nearLoops[cell];
    // The far loops' caps crossed in front of q: C_caps less the near loops'.
    thread_local std::vector<std::pair<std::uint32_t, int>> crossed;
    capCrossings(q, crossed);
    int far = 0;
    for (const auto& [loop, crossing] : crossed)
        if (!std::binary_search(loops, loopsEnd, loop)) far += crossing;
    // Where every near node is summed whole when not taken (a loop of few
    // edges: a soup's), most planned queries decide on the first cut: that
    // round alone first, in one pass.
    bool small = true;
    for (std::uint32_t k = 0; k < count; ++k) small &= chains_[near[k]].edgeCount <= kDirectEdges;
    if (small && firstCut(winding + far, q, near, count, g.lo[cell], g.hi[cell], out)) return true;
    return refine(winding + far, q, 1.0, near, count, g.lo[cell], g.hi[cell], out);
}

} // namespace vds::detail
