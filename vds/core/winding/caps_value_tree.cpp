// vds: the value tree of the caps (caps_value_tree.h); the tree expansion
// is Barill, Dickson, Schmidt, Levin & Jacobson 2018, section 3.
#include <vds/detail/caps_value_tree.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

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
    std::vector<std::uint32_t> order(cut.size());
    for (std::size_t k = 0; k < order.size(); ++k) order[k] = std::uint32_t(k);
    nodes_.reserve(2 * cut.size() / kLeafTriangles + 2);
    std::vector<glm::dvec3> unsignedMoments;
    unsignedMoments.reserve(nodes_.capacity());
    build(0, std::uint32_t(cut.size()), order, cut, unsignedMoments);
}

std::uint32_t CapsValueTree::build(std::uint32_t first, std::uint32_t last, std::vector<std::uint32_t>& order,
                                   const Triangles& tris, std::vector<glm::dvec3>& unsignedMoments) {
    const std::uint32_t index = std::uint32_t(nodes_.size());
    nodes_.emplace_back();
    unsignedMoments.emplace_back(0.0);
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
    CapsNode node{};
    node.centre = 0.5 * (lo + hi);
    for (std::uint32_t k = first; k < last; ++k)
        for (const glm::dvec3& v : tris[order[k]]) node.radius = std::max(node.radius, glm::length(v - node.centre));
    if (last - first <= kLeafTriangles) {
        buildLeaf(node, index, first, last, order, tris, unsignedMoments);
        return index;
    }
    const glm::dvec3 extent = chi - clo;
    const int split = extent.x >= extent.y && extent.x >= extent.z ? 0 : extent.y >= extent.z ? 1 : 2;
    const std::uint32_t middle = first + (last - first) / 2;
    std::nth_element(order.begin() + first, order.begin() + middle, order.begin() + last,
                     [&](std::uint32_t x, std::uint32_t y) {
                         const auto& a = tris[x];
                         const auto& b = tris[y];
                         return a[0][split] + a[1][split] + a[2][split] < b[0][split] + b[1][split] + b[2][split];
                     });
    node.left = build(first, middle, order, tris, unsignedMoments);
    node.right = build(middle, last, order, tris, unsignedMoments);
    gatherChildren(node, index, unsignedMoments);
    return index;
}

void CapsValueTree::buildLeaf(CapsNode& node, std::uint32_t index, std::uint32_t first, std::uint32_t last,
                              const std::vector<std::uint32_t>& order, const Triangles& tris,
                              std::vector<glm::dvec3>& unsignedMoments) {
    struct Ordered {
        const std::vector<std::array<glm::dvec3, 3>>& tris;
        const std::vector<std::uint32_t>& order;
        const std::array<glm::dvec3, 3>& operator[](std::size_t k) const { return tris[order[k]]; }
    };
    const Moments m = momentsOf(Ordered{tris, order}, first, last, node.centre);
    setMoments(node, m);
    for (std::uint32_t k = first; k < last; ++k) {
        const auto& t = tris[order[k]];
        unsignedMoments[index] += glm::length(glm::cross(t[1] - t[0], t[2] - t[0])) * 0.5 *
                                  ((t[0] + t[1] + t[2]) / 3.0 - node.centre);
    }
    node.first = std::uint32_t(leafTris_.size());
    node.count = last - first;
    for (std::uint32_t k = first; k < last; ++k) leafTris_.push_back(tris[order[k]]);
    finishNode(node);
    nodes_[index] = node;
}

void CapsValueTree::gatherChildren(CapsNode& node, std::uint32_t index, std::vector<glm::dvec3>& unsignedMoments) {
    // The children's moments moved to this centre: with d = c' - c, M_ij
    // gains A_i d_j, the unsigned first moment P gains area d, and S gains
    // 2 d . P' + area |d|^2.
    double second = 0.0;
    for (const std::uint32_t child : {node.left, node.right}) {
        const CapsNode& n = nodes_[child];
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
        second += n.errorScale * kFourPi / 3.0 + 2.0 * glm::dot(d, unsignedMoments[child]) + n.area * glm::dot(d, d);
        unsignedMoments[index] += unsignedMoments[child] + n.area * d;
    }
    node.errorScale = 3.0 * second / kFourPi;
    finishNode(node);
    nodes_[index] = node;
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
