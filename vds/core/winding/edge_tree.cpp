// vds: the tree of the boundary's edges (loops, then each loop's edges)
// that bounds how far the boundary term may drift over a move: reach() and
// driftWithin(), which the grid of bounds widens its ranges by.
#include <vds/detail/edge_tree.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include <vds/detail/antipodal.h>
#include <vds/detail/caps_math.h>
#include <vds/detail/tree_walk.h>

namespace vds::detail {

namespace {
/// Distance from p to the segment a b, and its squared length.
double segmentDistance(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& p, double& length2) {
    const glm::dvec3 ab = b - a;
    length2 = glm::dot(ab, ab);
    const double t = length2 > 0.0 ? std::clamp(glm::dot(p - a, ab) / length2, 0.0, 1.0) : 0.0;
    return glm::length(a + t * ab - p);
}
} // namespace

double EdgeTree::edgeDistance(std::uint32_t k, const glm::dvec3& p, double& length2) const {
    return segmentDistance(glm::dvec3(treeEdges_[2 * k]), glm::dvec3(treeEdges_[2 * k + 1]), p, length2);
}

using namespace caps;

std::uint32_t EdgeTree::buildEdges(std::uint32_t first, std::uint32_t last) {
    const std::uint32_t index = std::uint32_t(edgeNodes_.size());
    edgeNodes_.emplace_back();
    EdgeNode node{};
    glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
    for (std::uint32_t k = first; k < last; ++k)
        for (int end = 0; end < 2; ++end) {
            lo = glm::min(lo, glm::dvec3(treeEdges_[2 * k + end]));
            hi = glm::max(hi, glm::dvec3(treeEdges_[2 * k + end]));
        }
    node.centre = 0.5 * (lo + hi);
    for (std::uint32_t k = first; k < last; ++k) {
        const glm::dvec3 a(treeEdges_[2 * k]), b(treeEdges_[2 * k + 1]);
        node.radius = std::max({node.radius, glm::length(a - node.centre), glm::length(b - node.centre)});
        node.length += glm::length(b - a);
    }
    if (last - first <= kLeafTriangles) {
        node.first = first;
        node.count = last - first;
        edgeNodes_[index] = node;
        return index;
    }
    // Split at the median of the midpoints along the box's longest side,
    // reordering the edges (pairs of points) in place.
    const glm::dvec3 extent = hi - lo;
    const int split = extent.x >= extent.y && extent.x >= extent.z ? 0 : extent.y >= extent.z ? 1 : 2;
    std::vector<std::array<glm::vec3, 2>> pairs(last - first);
    for (std::uint32_t k = first; k < last; ++k) pairs[k - first] = {treeEdges_[2 * k], treeEdges_[2 * k + 1]};
    const std::size_t middle = pairs.size() / 2;
    std::nth_element(pairs.begin(), pairs.begin() + std::ptrdiff_t(middle), pairs.end(),
                     [split](const auto& x, const auto& y) { return x[0][split] + x[1][split] < y[0][split] + y[1][split]; });
    for (std::uint32_t k = first; k < last; ++k) {
        treeEdges_[2 * k] = pairs[k - first][0];
        treeEdges_[2 * k + 1] = pairs[k - first][1];
    }
    node.left = buildEdges(first, first + std::uint32_t(middle));
    node.right = buildEdges(first + std::uint32_t(middle), last);
    edgeNodes_[index] = node;
    return index;
}

void EdgeTree::build(const std::vector<glm::vec3>& edges, const std::vector<glm::vec3>& loopEdges,
                     const std::vector<CapLoop>& loops, bool closed) {
    const std::size_t edgeCount = edges.size() / 2;
    if (edgeCount == 0) return;
    edgeNodes_.reserve(2 * edgeCount / kLeafTriangles + 2 * loops.size() + 2);
    if (!closed) { // no loops: the edges alone
        treeEdges_ = edges;
        buildEdges(0, std::uint32_t(edgeCount));
        return;
    }
    // Each loop's edges get a subtree of their own (in loop order, so that
    // a loop's edges are contiguous), under a tree over the loops.
    treeEdges_ = loopEdges;
    edgeNodes_.emplace_back(); // [0]: the root, filled below
    std::vector<std::uint32_t> loopNodes(loops.size());
    for (std::size_t l = 0; l < loops.size(); ++l) {
        const CapLoop& loop = loops[l];
        const std::uint32_t edgesRoot = buildEdges(loop.first, loop.first + loop.count);
        EdgeNode node{};
        node.centre = loop.centroid; // the ball (centroid, radius) holds the loop and its cap
        node.radius = loop.radius;
        node.length = edgeNodes_[edgesRoot].length;
        node.capArea = loop.area;
        node.wholeLoops = true;
        node.left = edgesRoot;
        node.loopNode = true;
        loopNodes[l] = std::uint32_t(edgeNodes_.size());
        edgeNodes_.push_back(node);
    }
    const std::uint32_t root = buildLoops(loopNodes, 0, std::uint32_t(loopNodes.size()));
    edgeNodes_[0] = edgeNodes_[root];
}

std::uint32_t EdgeTree::buildLoops(std::vector<std::uint32_t>& nodes, std::uint32_t first, std::uint32_t last) {
    if (last - first == 1) return nodes[first];
    glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
    for (std::uint32_t k = first; k < last; ++k) {
        const EdgeNode& n = edgeNodes_[nodes[k]];
        lo = glm::min(lo, n.centre - glm::dvec3(n.radius));
        hi = glm::max(hi, n.centre + glm::dvec3(n.radius));
    }
    const glm::dvec3 extent = hi - lo;
    const int split = extent.x >= extent.y && extent.x >= extent.z ? 0 : extent.y >= extent.z ? 1 : 2;
    const std::uint32_t middle = first + (last - first) / 2;
    std::nth_element(nodes.begin() + first, nodes.begin() + middle, nodes.begin() + last,
                     [&](std::uint32_t x, std::uint32_t y) { return edgeNodes_[x].centre[split] < edgeNodes_[y].centre[split]; });
    EdgeNode node{};
    node.left = buildLoops(nodes, first, middle);
    node.right = buildLoops(nodes, middle, last);
    node.wholeLoops = true;
    node.centre = 0.5 * (lo + hi);
    for (const std::uint32_t child : {node.left, node.right}) {
        const EdgeNode& c = edgeNodes_[child];
        node.radius = std::max(node.radius, glm::length(c.centre - node.centre) + c.radius);
        node.length += c.length;
        node.capArea += c.capArea;
    }
    edgeNodes_.push_back(node);
    return std::uint32_t(edgeNodes_.size() - 1);
}

Reach EdgeTree::reach(const glm::vec3& q, double steepest) const {
    const double limit = steepest * kFourPi; // on the sum below
    Reach r;
    r.gap = std::numeric_limits<double>::infinity();
    if (edgeNodes_.empty()) return r;
    const glm::dvec3 p(q);
    double sum = 0.0; // of length / distance^2
    const bool certain = walkTree(0, [&](std::uint32_t index, TreeStack& stack) {
        const EdgeNode& n = edgeNodes_[index];
        const double d = glm::length(n.centre - p), e = d - n.radius;
        // A cluster at least three radii away: every edge, and for whole
        // loops every cap, at distance e or more (the sum then exceeds its
        // edges' by at most (d / e)^2 <= 2.25). Whole loops take the
        // smaller of the two bounds: by the curve, length / e^2, or by the
        // caps, 2 area / e^3 (far small loops: their dipole).
        if (e >= 2.0 * n.radius && e > 0.0) {
            r.gap = std::min(r.gap, e);
            sum += n.wholeLoops ? std::min(n.length / (e * e), 2.0 * n.capArea / (e * e * e)) : n.length / (e * e);
            return !(sum > limit);
        }
        if (n.loopNode) { // the loop's own edges
            stack.push(n.left);
            return true;
        }
        if (n.count == 0) {
            stack.push(n.left);
            stack.push(n.right);
            return true;
        }
        for (std::uint32_t k = n.first; k < n.first + n.count; ++k) {
            double length2;
            const double distance = edgeDistance(k, p, length2);
            if (!(distance > 0.0)) return false; // on the curve: no move is certain
            r.gap = std::min(r.gap, distance);
            sum += std::sqrt(length2) / (distance * distance);
        }
        return !(sum > limit);
    });
    if (!certain) return Reach{};
    // A little slack on the distances: they are rounded.
    r.gap *= 1.0 - 1e-9;
    r.steepness = sum / kFourPi * (1.0 + 1e-9);
    return r;
}

bool EdgeTree::addEdgeDrifts(const EdgeNode& leaf, const glm::dvec3& p, double length, double& sumMoved,
                                 double& sumAt, double& nearest) const {
    for (std::uint32_t k = leaf.first; k < leaf.first + leaf.count; ++k) {
        double length2;
        const double distance = edgeDistance(k, p, length2);
        if (!(distance > length)) return false;
        const double edge = std::sqrt(length2);
        sumMoved += edge / ((distance - length) * (distance - length));
        sumAt += edge / (distance * distance);
        nearest = std::min(nearest, distance);
    }
    return true;
}

double EdgeTree::driftWithin(const glm::vec3& q, double length, double limit) const {
    constexpr double kInfinity = std::numeric_limits<double>::infinity();
    if (edgeNodes_.empty()) return 0.0;
    const double sumLimit = limit / length * kFourPi; // on the sums below
    const glm::dvec3 p(q);
    // Two bounds from one walk, the smaller taken: each part at its
    // nearest a move reaches (moved), and Reach's, all at their distance
    // from q (at) times the nearest part's shrink factor.
    double moved = 0.0, at = 0.0, gap = kInfinity;
    const auto over = [&] {
        const double shrink = 1.0 - length / gap;
        return moved > sumLimit && (!(shrink > 0.0) || at / (shrink * shrink * shrink) > sumLimit);
    };
    const auto addEdges = [&](const EdgeNode& leaf, double& sumMoved, double& sumAt, double& nearest) {
        return addEdgeDrifts(leaf, p, length, sumMoved, sumAt, nearest);
    };
    const bool finite = walkTree(0, [&](std::uint32_t index, TreeStack& stack) {
        const EdgeNode& n = edgeNodes_[index];
        // e: q's distance to the node's ball (which holds its edges, and
        // for whole loops its caps); a move reaches within e - length.
        const double d = glm::length(n.centre - p), e = d - n.radius, near = e - length;
        if (near >= 2.0 * n.radius && near > 0.0) {
            const auto term = [&](double r) {
                return n.wholeLoops ? std::min(n.length / (r * r), 2.0 * n.capArea / (r * r * r)) : n.length / (r * r);
            };
            moved += term(near);
            at += term(e);
            gap = std::min(gap, e);
            return !over();
        }
        if (n.loopNode) {
            // The loop's edges one by one, or where that sums to more, its
            // cap's bound (its ball clear of every move: near > 0).
            double loopMoved = 0.0, loopAt = 0.0, loopGap = kInfinity;
            const bool clear = walkTree(n.left, [&](std::uint32_t inner, TreeStack& innerStack) {
                const EdgeNode& m = edgeNodes_[inner];
                if (m.count == 0) {
                    innerStack.push(m.left);
                    innerStack.push(m.right);
                    return true;
                }
                return addEdges(m, loopMoved, loopAt, loopGap);
            });
            if (!clear) return false;
            if (near > 0.0) {
                loopMoved = std::min(loopMoved, 2.0 * n.capArea / (near * near * near));
                loopAt = std::min(loopAt, 2.0 * n.capArea / (e * e * e));
                loopGap = std::min(loopGap, e);
            }
            moved += loopMoved;
            at += loopAt;
            gap = std::min(gap, loopGap);
            return !over();
        }
        if (n.count == 0) {
            stack.push(n.left);
            stack.push(n.right);
            return true;
        }
        return addEdges(n, moved, at, gap) && !over();
    });
    if (!finite) return kInfinity;
    const double shrink = 1.0 - length / gap;
    const double byReach = shrink > 0.0 ? at / (shrink * shrink * shrink) : kInfinity;
    // A little slack: the distances are rounded.
    return std::min(moved, byReach) / kFourPi * length * (1.0 + 1e-8);
}

} // namespace vds::detail
