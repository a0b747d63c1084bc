// vds: the value tree of the caps (caps_value_tree.h); the tree expansion
// is Barill, Dickson, Schmidt, Levin & Jacobson 2018, section 3.
#include <vds/detail/caps_value_tree.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include <glm/geometric.hpp>

#include <vds/detail/parallel.h>
#include <vds/detail/solid_angle.h>
#include <vds/detail/tree_walk.h>

namespace vds::detail {

using namespace caps;

namespace {

/// Most pieces a fan triangle's sides are cut into for the tree.
constexpr int kMaxCut = 8;

/// Adds twice the signed solid angle of cap triangle `t` seen from `p` (Van
/// Oosterom & Strackee) to `integral`; false, adding nothing, when `p` lies
/// in (or within rounding of) the triangle, where the angle jumps by 4 pi and
/// the crossing count's side is not certain.
bool addCapTriangle(const std::array<glm::dvec3, 3>& t, const glm::dvec3& p, double& integral) {
    const SolidAngleParts s = solidAngleParts(t[0] - p, t[1] - p, t[2] - p);
    if (std::fabs(s.det) <= 1e-9 * s.scale && s.den <= 1e-9 * s.scale) return false;
    integral += 2.0 * std::atan2(s.det, s.den);
    return true;
}

/// Appends to `cut` the fan triangles [firstTri, end of `tris`) of `loop`,
/// each cut into m^2 triangles of about the loop's edge length: fan
/// triangles of a long loop are slivers as long as its radius, which a
/// tree cannot split; the tree sums the same surface.
void cutFans(const CapLoop& loop, const std::vector<glm::vec3>& loopEdges,
             const std::vector<std::array<glm::dvec3, 3>>& tris, std::size_t firstTri,
             std::vector<std::array<glm::dvec3, 3>>& cut) {
    double length = 0.0;
    for (std::uint32_t k = loop.first; k < loop.first + loop.count; ++k)
        length += glm::length(glm::dvec3(loopEdges[2 * k + 1]) - glm::dvec3(loopEdges[2 * k]));
    const double meanEdge = length / double(loop.count);
    const int m = meanEdge > 0.0 ? int(std::clamp(std::ceil(loop.radius / meanEdge), 1.0, double(kMaxCut))) : 1;
    for (std::size_t f = firstTri; f < tris.size(); ++f) {
        const glm::dvec3 corner = tris[f][0], db = (tris[f][1] - corner) / double(m), da = (tris[f][2] - corner) / double(m);
        const auto at = [&](int i, int j) { return corner + double(i) * db + double(j) * da; };
        for (int i = 0; i < m; ++i)
            for (int j = 0; i + j < m; ++j) {
                cut.push_back({{at(i, j), at(i + 1, j), at(i, j + 1)}});
                if (i + j < m - 1) cut.push_back({{at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)}});
            }
    }
}

using Triangles = std::vector<std::array<glm::dvec3, 3>>;

/// The tree in the making: nodes in pre-order (a node, its left subtree,
/// its right), leaf triangles in the same order, and each node's integral
/// of |n| (x - centre) dA, for its parent's moments from its children's.
/// Sized in advance (nodeCount), so that subtrees built on threads write
/// their own ranges in place.
struct Tree {
    std::vector<CapsNode> nodes;
    Triangles leafTris;
    std::vector<glm::dvec3> unsignedMoments;
};

/// Where a subtree writes next: its next node and leaf triangle.
struct Cursor {
    std::uint32_t node = 0, leaf = 0;
};

/// Nodes of the tree over n triangles: a leaf holds at most kLeafTriangles,
/// an inner node splits them at the middle (shape).
std::uint32_t nodeCount(std::uint32_t n) {
    return n <= kLeafTriangles ? 1 : 1 + nodeCount(n / 2) + nodeCount(n - n / 2);
}

/// The ball of the triangles order[first, last) into `node`; for more than
/// a leaf's, splits them at the middle along the centroids' widest axis
/// (order partitioned) and returns the middle, else 0.
std::uint32_t shape(CapsNode& node, std::uint32_t first, std::uint32_t last, std::vector<std::uint32_t>& order,
                    const Triangles& tris) {
    glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
    glm::dvec3 clo = lo, chi = hi; // of the triangles' centroids
    for (std::uint32_t k = first; k < last; ++k) {
        const auto& t = tris[order[k]];
        for (const glm::dvec3& v : t) {
            lo = glm::min(lo, v);
            hi = glm::max(hi, v);
        }
        const glm::dvec3 g = (t[0] + t[1] + t[2]) / 3.0;
        clo = glm::min(clo, g);
        chi = glm::max(chi, g);
    }
    node.centre = 0.5 * (lo + hi);
    // The largest squared distance, then one root: the same radius as the
    // largest of the roots (the square root is monotone and rounded once).
    double radius2 = 0.0;
    for (std::uint32_t k = first; k < last; ++k)
        for (const glm::dvec3& v : tris[order[k]]) {
            const glm::dvec3 d = v - node.centre;
            radius2 = std::max(radius2, d.x * d.x + d.y * d.y + d.z * d.z);
        }
    node.radius = std::sqrt(radius2);
    if (last - first <= kLeafTriangles) return 0;
    const glm::dvec3 extent = chi - clo;
    const int split = extent.x >= extent.y && extent.x >= extent.z ? 0 : extent.y >= extent.z ? 1 : 2;
    const std::uint32_t middle = first + (last - first) / 2;
    std::nth_element(order.begin() + first, order.begin() + middle, order.begin() + last,
                     [&](std::uint32_t x, std::uint32_t y) {
                         const auto& a = tris[x];
                         const auto& b = tris[y];
                         return a[0][split] + a[1][split] + a[2][split] < b[0][split] + b[1][split] + b[2][split];
                     });
    return middle;
}

/// A leaf `node` (its ball set) at `index`: its triangles' moments, and
/// the triangles themselves into the tree's leafTris at the cursor.
void buildLeaf(CapsNode& node, std::uint32_t index, std::uint32_t first, std::uint32_t last,
               const std::vector<std::uint32_t>& order, const Triangles& tris, Tree& part, Cursor& at) {
    struct Ordered {
        const Triangles& tris;
        const std::vector<std::uint32_t>& order;
        const std::array<glm::dvec3, 3>& operator[](std::size_t k) const { return tris[order[k]]; }
    };
    const Moments m = momentsOf(Ordered{tris, order}, first, last, node.centre);
    setMoments(node, m);
    for (std::uint32_t k = first; k < last; ++k) {
        const auto& t = tris[order[k]];
        part.unsignedMoments[index] += glm::length(glm::cross(t[1] - t[0], t[2] - t[0])) * 0.5 *
                                       ((t[0] + t[1] + t[2]) / 3.0 - node.centre);
    }
    node.first = at.leaf;
    node.count = last - first;
    for (std::uint32_t k = first; k < last; ++k) part.leafTris[at.leaf++] = tris[order[k]];
    finishNode(node);
    part.nodes[index] = node;
}

/// An inner `node` at `index`: its children's moments moved to its centre
/// and summed.
void gatherChildren(CapsNode& node, std::uint32_t index, Tree& part) {
    // The children's moments moved to this centre: with d = c' - c, M_ij
    // gains A_i d_j, the unsigned first moment P gains area d, and S gains
    // 2 d . P' + area |d|^2.
    double second = 0.0;
    for (const std::uint32_t child : {node.left, node.right}) {
        const CapsNode& n = part.nodes[child];
        const glm::dvec3 d = n.centre - node.centre;
        node.vectorArea += n.vectorArea;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                node.moment[std::size_t(3 * i + j)] += n.moment[std::size_t(3 * i + j)] + n.vectorArea[i] * d[j];
        // N_ijk gains M_ij d_k + M_ik d_j + A_i d_j d_k (the child's M, A).
        for (int i = 0; i < 3; ++i)
            for (int pair = 0; pair < 6; ++pair) {
                const int j = kPairs[pair][0], k = kPairs[pair][1];
                node.quadrupole[std::size_t(6 * i + pair)] +=
                    n.quadrupole[std::size_t(6 * i + pair)] + n.moment[std::size_t(3 * i + j)] * d[k] +
                    n.moment[std::size_t(3 * i + k)] * d[j] + n.vectorArea[i] * d[j] * d[k];
            }
        node.area += n.area;
        second += n.errorScale * kFourPi / 3.0 + 2.0 * glm::dot(d, part.unsignedMoments[child]) + n.area * glm::dot(d, d);
        part.unsignedMoments[index] += part.unsignedMoments[child] + n.area * d;
    }
    node.errorScale = 3.0 * second / kFourPi;
    finishNode(node);
    part.nodes[index] = node;
}

/// The subtree of order[first, last) written from the cursor on; its
/// root's index.
std::uint32_t build(std::uint32_t first, std::uint32_t last, std::vector<std::uint32_t>& order, const Triangles& tris,
                    Tree& part, Cursor& at) {
    const std::uint32_t index = at.node++;
    CapsNode node{};
    const std::uint32_t middle = shape(node, first, last, order, tris);
    if (middle == 0) {
        buildLeaf(node, index, first, last, order, tris, part, at);
        return index;
    }
    node.left = build(first, middle, order, tris, part, at);
    node.right = build(middle, last, order, tris, part, at);
    gatherChildren(node, index, part);
    return index;
}

/// Levels of the tree split before the subtrees below are built on threads
/// (2^3 = 8 subtrees), where there are at least kThreadedTriangles: the
/// build is O(n log n) over the cut fans (500k triangles and 0.5 s on one
/// thread for a room scan of 8,327 boundary edges); below, one thread.
constexpr int kThreadedLevels = 3;
constexpr std::size_t kThreadedTriangles = std::size_t(1) << 15;

/// The tree's top levels, split in place on this thread; at their bottom,
/// the subtrees the threads build, each into its own range of the tree.
struct TopSplit {
    struct Node {
        CapsNode node{};
        std::uint32_t first = 0, last = 0;
        int left = -1, right = -1, subtree = -1; ///< subtree: its index in `subtrees`
    };
    std::vector<Node> nodes;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> subtrees; ///< ranges of order

    /// Splits the top levels a level at a time, the nodes of a level on the
    /// library's threads (their ranges of `order` are disjoint).
    void split(std::uint32_t count, std::vector<std::uint32_t>& order, const Triangles& tris) {
        nodes.assign(1, Node{});
        nodes[0].last = count;
        std::vector<int> level = {0};
        for (int depth = 0; depth < kThreadedLevels && !level.empty(); ++depth) {
            std::vector<std::uint32_t> middles(level.size());
            parallelFor(0, level.size(), 1, [&](std::size_t begin, std::size_t end) {
                for (std::size_t k = begin; k < end; ++k) {
                    Node& n = nodes[std::size_t(level[k])];
                    middles[k] = shape(n.node, n.first, n.last, order, tris);
                }
            });
            std::vector<int> next;
            for (std::size_t k = 0; k < level.size(); ++k) {
                if (middles[k] == 0) continue; // a leaf: built below as a subtree of one node
                const int at = level[k];
                for (const auto& [first, last] : {std::pair{nodes[std::size_t(at)].first, middles[k]},
                                                  std::pair{middles[k], nodes[std::size_t(at)].last}}) {
                    Node child;
                    child.first = first;
                    child.last = last;
                    nodes.push_back(child);
                    next.push_back(int(nodes.size()) - 1);
                }
                nodes[std::size_t(at)].left = next[next.size() - 2];
                nodes[std::size_t(at)].right = next.back();
            }
            level = std::move(next);
        }
        for (Node& n : nodes)
            if (n.left < 0) {
                n.subtree = int(subtrees.size());
                subtrees.emplace_back(n.first, n.last);
            }
    }

    /// Pre-order indices from `at` on: each top node's, and where each
    /// subtree starts (its cursor); the index of node `top`.
    std::uint32_t place(int top, Cursor& at, std::vector<Cursor>& starts, std::vector<std::uint32_t>& indices) const {
        const Node& n = nodes[std::size_t(top)];
        if (n.subtree >= 0) {
            starts[std::size_t(n.subtree)] = at;
            indices[std::size_t(top)] = at.node;
            at.node += nodeCount(n.last - n.first);
            at.leaf += n.last - n.first;
            return indices[std::size_t(top)];
        }
        indices[std::size_t(top)] = at.node++;
        place(n.left, at, starts, indices);
        place(n.right, at, starts, indices);
        return indices[std::size_t(top)];
    }

    /// The top nodes' moments from their children's, bottom up.
    void gather(int top, const std::vector<std::uint32_t>& indices, Tree& tree) const {
        const Node& n = nodes[std::size_t(top)];
        if (n.subtree >= 0) return;
        gather(n.left, indices, tree);
        gather(n.right, indices, tree);
        CapsNode node = n.node;
        node.left = indices[std::size_t(n.left)];
        node.right = indices[std::size_t(n.right)];
        gatherChildren(node, indices[std::size_t(top)], tree);
    }
};

/// The whole tree of `tris`: its top levels split on this thread and the
/// library's, the subtrees below built on the library's threads, each in
/// its own range of the arrays (the one-thread build's order: the same
/// tree, node for node).
Tree buildTree(const Triangles& tris) {
    std::vector<std::uint32_t> order(tris.size());
    for (std::size_t k = 0; k < order.size(); ++k) order[k] = std::uint32_t(k);
    const auto count = std::uint32_t(tris.size());
    Tree tree;
    tree.nodes.resize(nodeCount(count));
    tree.unsignedMoments.assign(tree.nodes.size(), glm::dvec3(0.0));
    tree.leafTris.resize(tris.size());
    if (tris.size() < kThreadedTriangles) {
        Cursor at;
        build(0, count, order, tris, tree, at);
        return tree;
    }
    TopSplit top;
    top.split(count, order, tris);
    std::vector<Cursor> starts(top.subtrees.size());
    std::vector<std::uint32_t> indices(top.nodes.size());
    Cursor at;
    top.place(0, at, starts, indices);
    parallelFor(0, starts.size(), 1, [&](std::size_t begin, std::size_t end) {
        for (std::size_t k = begin; k < end; ++k)
            build(top.subtrees[k].first, top.subtrees[k].second, order, tris, tree, starts[k]);
    });
    top.gather(0, indices, tree);
    return tree;
}

} // namespace

CapsValueTree::CapsValueTree(const CapLoops& loops) : loops_(loops) {
    if (!loops.capped()) return;
    // The caps' fans, cut finer for the tree.
    const std::vector<glm::vec3>& loopEdges = loops.loopEdges();
    Triangles fans, cut;
    for (const CapLoop& loop : loops.loops()) {
        const std::size_t firstTri = fans.size();
        for (std::uint32_t k = loop.first; k < loop.first + loop.count; ++k)
            fans.push_back({loop.centroid, glm::dvec3(loopEdges[2 * k + 1]), glm::dvec3(loopEdges[2 * k])});
        cutFans(loop, loopEdges, fans, firstTri, cut);
    }
    Tree tree = buildTree(cut);
    nodes_ = std::move(tree.nodes);
    leafTris_ = std::move(tree.leafTris);
}

CapsEstimate CapsValueTree::estimate(const glm::vec3& q, double nodeTolerance) const {
    if (!loops_.closed()) return {0.0, std::numeric_limits<double>::infinity()};
    if (nodes_.empty()) return {0.0, 0.0};
    const glm::dvec3 p(q);
    double integral = 0.0, bound = 0.0;
    const bool offCaps = walkTree(0, [&](std::uint32_t index, TreeStack& stack) {
        const CapsNode& n = nodes_[index];
        const glm::dvec3 y = n.centre - p;
        const double d2 = glm::dot(y, y);
        const double d = std::sqrt(d2), e = d - n.radius;
        // Taken when its bound is within the tolerance per unit of solid
        // angle it subtends (about area / D^2): the taken nodes' bounds then
        // sum to about the tolerance times the caps' apparent solid angle.
        const double b = e > 0.0 ? n.errorScale * remainderFactor(d, e, n.radius) : 0.0;
        if (e > 0.0 && b * d2 <= nodeTolerance * n.area) {
            integral += secondOrderTerm(n, y, d2, d);
            bound += b;
            return true;
        }
        if (n.count == 0) {
            stack.push(n.left);
            stack.push(n.right);
            return true;
        }
        for (std::uint32_t k = n.first; k < n.first + n.count; ++k)
            if (!addCapTriangle(leafTris_[k], p, integral)) return false;
        return true;
    });
    if (!offCaps) return {0.0, std::numeric_limits<double>::infinity()};
    const int crossings = loops_.projected().winding(q);
    return {double(crossings) - integral / kFourPi, bound + kRoundingSlack};
}

std::size_t CapsValueTree::memoryBytes() const {
    return leafTris_.capacity() * sizeof(leafTris_[0]) + nodes_.capacity() * sizeof(nodes_[0]);
}

} // namespace vds::detail
