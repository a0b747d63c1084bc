// vds: a boundary's chain tree (<vds/detail/chain_tree.h>) packed in the
// std430 layout the GLSL include reads (pack_boundary.h).
#include <vds/gl/detail/pack_boundary.h>

#include <algorithm>
#include <cstring>
#include <limits>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <vds/detail/chain_tree.h>
#include <vds/detail/tree_walk.h>

namespace vds::detail {

namespace {

/// A node as packed: its index in the tree, the record after its subtree,
/// and its edges' range in the packed order.
struct Placed {
    std::uint32_t node, skip, first, count;
};

/// The nodes in preorder (a node's first child follows it, `skip` is the
/// node after its subtree) and, into `ordered`, the edges in the order of
/// the leaves, so that every node's edges are one range: the shader walks
/// the tree without a stack and sums a small node's range at once. A group
/// of loops whose expansion would not meet the shader's tolerance even one
/// diagonal of the boundary's box away is left out (its children take its
/// place): a point would only visit it to open it.
std::vector<Placed> placeNodes(const ChainTree& tree, std::vector<glm::vec3>& ordered) {
    const std::vector<ChainNode>& chains = tree.nodes;
    const std::vector<glm::vec3>& loopEdges = tree.loopEdges;
    std::vector<Placed> placed;
    placed.reserve(chains.size());
    ordered.reserve(loopEdges.size());
    glm::dvec3 boxLo(std::numeric_limits<double>::max()), boxHi(-std::numeric_limits<double>::max());
    for (const glm::vec3& v : loopEdges) {
        boxLo = glm::min(boxLo, glm::dvec3(v));
        boxHi = glm::max(boxHi, glm::dvec3(v));
    }
    const double diagonal = glm::length(boxHi - boxLo);
    // A walk in preorder, the left child first; an entry marked kClose
    // closes placed[entry & ~kClose] once its subtree is placed.
    constexpr std::uint32_t kClose = 0x80000000u;
    const auto close = [&](std::uint32_t at) {
        placed[at].skip = std::uint32_t(placed.size());
        placed[at].count = std::uint32_t(ordered.size() / 2) - placed[at].first;
    };
    walkTree(0, [&](std::uint32_t entry, TreeStack& stack) {
        if (entry & kClose) {
            close(entry & ~kClose);
            return true;
        }
        const ChainNode& node = chains[entry];
        const bool group = !node.chord && node.count == 0 && !chains[node.left].chord;
        const double e = diagonal - node.radius;
        if (group && (e <= 0.0 || node.errorScale * remainderFactor(diagonal, e, node.radius) > kBoundaryNodeTolerance)) {
            stack.push(node.right);
            stack.push(node.left);
            return true;
        }
        const std::uint32_t at = std::uint32_t(placed.size());
        placed.push_back({entry, 0, std::uint32_t(ordered.size() / 2), 0});
        if (node.count != 0) {
            ordered.insert(ordered.end(), loopEdges.begin() + 2 * std::ptrdiff_t(node.first),
                           loopEdges.begin() + 2 * std::ptrdiff_t(node.first + node.count));
            close(at);
            return true;
        }
        stack.push(at | kClose);
        stack.push(node.right);
        stack.push(node.left);
        return true;
    });
    return placed;
}

float intBits(std::uint32_t v) {
    float f;
    const std::int32_t i = std::int32_t(v);
    std::memcpy(&f, &i, 4);
    return f;
}

/// Appends node `at`'s record (kBoundaryNodeSize vec4s, pack_boundary.h)
/// in the (s, t, r) frame of permutation `p`.
void packNode(const ChainNode& node, const Placed& at, const glm::ivec3& p, std::vector<glm::vec4>& data) {
    const auto permuted = [&](const glm::dvec3& v) { return glm::vec3(float(v[p.x]), float(v[p.y]), float(v[p.z])); };
    const auto pairIndex = [](int j, int k) {
        if (j == k) return j;
        const int lo = std::min(j, k), hi = std::max(j, k);
        return lo == 0 ? (hi == 1 ? 3 : 4) : 5;
    };
    // In the (s, t, r) frame: every index through the permutation.
    const auto M = [&](int i, int j) { return node.moment[std::size_t(3 * p[i] + p[j])]; };
    const auto N = [&](int i, int j, int k) { return node.quadrupole[std::size_t(6 * p[i] + pairIndex(p[j], p[k]))]; };
    const bool leaf = node.count != 0;
    const std::uint32_t flags = (leaf ? kBoundaryNodeLeaf : 0u) | (node.chord ? kBoundaryNodeChord : 0u);
    // Float may round the radius down; the shader's tests of whether q's
    // ray misses the ball round too.
    data.emplace_back(permuted(node.centre), float(node.radius * (1.0 + 1e-5)));
    data.emplace_back(float(node.errorScale), intBits(at.skip), intBits(at.first), intBits(at.count << 2 | flags));
    data.emplace_back(permuted(node.vectorArea), M(0, 0));
    data.emplace_back(M(0, 1), M(0, 2), M(1, 0), M(1, 1));
    data.emplace_back(M(1, 2), M(2, 0), M(2, 1), M(2, 2));
    glm::dvec3 rows(0.0), columns(0.0);
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            rows[i] += N(i, j, j);
            columns[j] += N(i, i, j);
        }
    data.emplace_back(glm::vec3(rows), 0.0f);
    data.emplace_back(glm::vec3(columns), 0.0f);
    float n[20] = {};
    for (int i = 0; i < 3; ++i)
        for (int pair = 0; pair < 6; ++pair) n[6 * i + pair] = float(N(i, kPairs[pair][0], kPairs[pair][1]));
    for (int v = 0; v < 5; ++v) data.emplace_back(n[4 * v], n[4 * v + 1], n[4 * v + 2], n[4 * v + 3]);
    data.emplace_back(permuted(node.chord ? node.from : glm::dvec3(0.0)), 0.0f);
    data.emplace_back(permuted(node.chord ? node.to : glm::dvec3(0.0)), 0.0f);
}

} // namespace

PackedBoundary packBoundary(const std::vector<glm::vec3>& edges, Axis axis) {
    PackedBoundary packed;
    const glm::ivec3 p = axisPermutation(axis);
    const auto permuted = [&](const glm::dvec3& v) { return glm::vec3(float(v[p.x]), float(v[p.y]), float(v[p.z])); };
    packed.edgeCount = std::uint32_t(edges.size() / 2);
    if (packed.edgeCount == 0) return packed;
    const ChainTree tree = chainTreeOf(edges.data(), packed.edgeCount, axis);
    if (!tree.closed || tree.loopEdges.size() != edges.size() || tree.nodes.empty()) {
        for (const glm::vec3& v : edges) packed.data.emplace_back(permuted(glm::dvec3(v)), 0.0f);
        return packed;
    }
    std::vector<glm::vec3> ordered;
    const std::vector<Placed> placed = placeNodes(tree, ordered);
    for (const glm::vec3& v : ordered) packed.data.emplace_back(permuted(glm::dvec3(v)), 0.0f);
    packed.nodeCount = std::uint32_t(placed.size());
    for (const Placed& at : placed) packNode(tree.nodes[at.node], at, p, packed.data);
    return packed;
}

} // namespace vds::detail
