// vds: the boundary term of the generalized winding number by capping the
// boundary loops (see caps_tree.h); the Antipodal split is Martens,
// Trettner & Bessmeltsev 2026, the tree expansion Barill, Dickson, Schmidt,
// Levin & Jacobson 2018, section 3.
#include <vds/detail/caps_tree.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <tuple>

#include <glm/geometric.hpp>

#include <vds/detail/antipodal.h>
#include <vds/detail/caps_math.h>
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
    const glm::dvec3 u = t[0] - p, v = t[1] - p, w = t[2] - p;
    const double lu = glm::length(u), lv = glm::length(v), lw = glm::length(w);
    const double det = glm::dot(u, glm::cross(v, w));
    const double den = lu * lv * lw + glm::dot(u, v) * lw + glm::dot(u, w) * lv + glm::dot(v, w) * lu;
    const double scale = lu * lv * lw;
    if (std::fabs(det) <= 1e-9 * scale && den <= 1e-9 * scale) return false;
    integral += 2.0 * std::atan2(det, den);
    return true;
}

/// The boundary's edges as a graph on their welded endpoints, walked loop
/// by loop.
class LoopWalker {
public:
    /// Welds endpoints by bitwise-equal positions, as boundaryEdges() does.
    LoopWalker(const glm::vec3* edges, std::size_t edgeCount)
        : edges_(edges), tail_(edgeCount), head_(edgeCount), used_(edgeCount, 0) {
        std::map<std::tuple<float, float, float>, std::uint32_t> ids;
        const auto idOf = [&](const glm::vec3& p) {
            return ids.emplace(std::make_tuple(p.x, p.y, p.z), std::uint32_t(ids.size())).first->second;
        };
        for (std::size_t k = 0; k < edgeCount; ++k) {
            tail_[k] = idOf(edges[2 * k]);
            head_[k] = idOf(edges[2 * k + 1]);
        }
        out_.resize(ids.size());
        for (std::size_t k = 0; k < edgeCount; ++k) out_[tail_[k]].push_back(std::uint32_t(k));
        nextOut_.assign(ids.size(), 0);
    }

    bool used(std::size_t edge) const { return used_[edge] != 0; }

    /// Appends the loop from edge `start` along unused outgoing edges until
    /// it returns to its start, edge k as two points of `loopEdges`; false
    /// where it runs into a vertex with no unused edge out (an open chain).
    bool walk(std::size_t start, std::vector<glm::vec3>& loopEdges) {
        std::ptrdiff_t e = std::ptrdiff_t(start);
        while (true) {
            used_[std::size_t(e)] = 1;
            loopEdges.push_back(edges_[2 * std::size_t(e)]);
            loopEdges.push_back(edges_[2 * std::size_t(e) + 1]);
            if (head_[std::size_t(e)] == tail_[start]) return true;
            e = takeOut(std::size_t(e));
            if (e < 0) return false;
        }
    }

private:
    // The next edge out of the head of edge `in`: where several are unused
    // (a vertex the boundary passes more than once, as along a fin on a
    // non-manifold ring of edges), the one turning back most sharply, so
    // that loops stay small and tight (a fin's own triangle) instead of
    // running around the ring: small loops have small caps, which the tree
    // takes by expansion from close by.
    std::ptrdiff_t takeOut(std::size_t in) {
        const std::uint32_t v = head_[in];
        std::vector<std::uint32_t>& out = out_[v];
        std::size_t& n = nextOut_[v];
        while (n < out.size() && used_[out[n]]) ++n;
        if (n == out.size()) return -1;
        std::size_t best = n;
        const glm::dvec3 arrive = glm::dvec3(edges_[2 * in + 1]) - glm::dvec3(edges_[2 * in]);
        double bestTurn = std::numeric_limits<double>::infinity();
        for (std::size_t m = n; m < out.size(); ++m) {
            const std::uint32_t e = out[m];
            if (used_[e]) continue;
            const glm::dvec3 leave = glm::dvec3(edges_[2 * e + 1]) - glm::dvec3(edges_[2 * e]);
            const double scale = glm::length(arrive) * glm::length(leave);
            const double turn = scale > 0.0 ? glm::dot(arrive, leave) / scale : 1.0;
            if (turn < bestTurn) {
                bestTurn = turn;
                best = m;
            }
        }
        std::swap(out[n], out[best]);
        return std::ptrdiff_t(out[n++]);
    }

    const glm::vec3* edges_;
    std::vector<std::uint32_t> tail_, head_; ///< each edge's welded endpoints
    std::vector<std::vector<std::uint32_t>> out_; ///< each vertex's edges out
    std::vector<std::size_t> nextOut_;            ///< each vertex's first edge out that may be unused
    std::vector<std::uint8_t> used_;
};

/// Appends to `fine` the fan triangles [firstTri, end of `tris`) of `loop`,
/// each cut into m^2 triangles of about the loop's edge length: fan
/// triangles of a long loop are slivers as long as its radius, which a
/// tree cannot split; the tree sums the same surface.
void cutFans(const CapLoop& loop, const std::vector<glm::vec3>& loopEdges,
             const std::vector<std::array<glm::dvec3, 3>>& tris, std::size_t firstTri,
             std::vector<std::array<glm::dvec3, 3>>& fine) {
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
                fine.push_back({{at(i, j), at(i + 1, j), at(i, j + 1)}});
                if (i + j < m - 1) fine.push_back({{at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)}});
            }
    }
}

} // namespace

BoundaryCaps::BoundaryCaps(const glm::vec3* edges, std::size_t edgeCount, Axis axis, const Box* domain,
                           const CapsSurface* surface, const CellWindings* windings)
    : axisIndex_(axisPermutation(axis).z), surface_(surface), edges_(edges, edges + 2 * edgeCount) {
    LoopWalker walker(edges, edgeCount);
    std::vector<std::array<glm::dvec3, 3>> tris, fine; // the caps' fans, and cut finer for the tree
    for (std::size_t start = 0; start < edgeCount && closed_; ++start) {
        if (walker.used(start)) continue;
        CapLoop loop;
        loop.first = std::uint32_t(loopEdges_.size() / 2);
        // an open chain: these are not a mesh's boundary
        if (!walker.walk(start, loopEdges_)) closed_ = false;
        loop.count = std::uint32_t(loopEdges_.size() / 2) - loop.first;
        const std::size_t firstTri = tris.size();
        addCap(loop, tris);
        loops_.push_back(loop);
        cutFans(loop, loopEdges_, tris, firstTri, fine);
    }
    edgeTree_.build(edges_, loopEdges_, loops_, closed_);
    if (!closed_ || tris.empty()) return;
    buildChains();
    projected_.emplace(MeshView(capPositions_.data(), capPositions_.size(), capTriangles_.data(), capTriangles_.size()),
                       axis);
    if (domain) buildRangeGrid(*domain, surface ? nullptr : windings);
    std::vector<std::uint32_t> order(fine.size());
    for (std::size_t k = 0; k < order.size(); ++k) order[k] = std::uint32_t(k);
    nodes_.reserve(2 * fine.size() / kLeafTriangles + 2);
    std::vector<glm::dvec3> unsignedMoments;
    unsignedMoments.reserve(nodes_.capacity());
    build(0, std::uint32_t(fine.size()), order, fine, unsignedMoments);
}

void BoundaryCaps::addCap(CapLoop& loop, std::vector<std::array<glm::dvec3, 3>>& tris) {
    glm::dvec3 sum(0.0);
    for (std::uint32_t k = loop.first; k < loop.first + loop.count; ++k) sum += glm::dvec3(loopEdges_[2 * k]);
    const glm::vec3 c(sum / double(loop.count)); // rounded: the caps' float and double forms agree
    loop.centroid = glm::dvec3(c);
    const std::uint32_t apex = std::uint32_t(capPositions_.size());
    capPositions_.push_back(c);
    const std::size_t firstTri = tris.size();
    for (std::uint32_t k = loop.first; k < loop.first + loop.count; ++k) {
        const glm::vec3 a = loopEdges_[2 * k], b = loopEdges_[2 * k + 1];
        const std::uint32_t ia = std::uint32_t(capPositions_.size());
        capPositions_.push_back(a);
        capPositions_.push_back(b);
        capTriangles_.emplace_back(apex, ia + 1, ia); // (c, b, a): the cap's boundary is the loop reversed
        capLoopOf_.push_back(std::uint32_t(loops_.size()));
        tris.push_back({loop.centroid, glm::dvec3(b), glm::dvec3(a)});
        loop.radius = std::max(loop.radius, glm::length(glm::dvec3(a) - loop.centroid));
    }
    for (std::size_t f = firstTri; f < tris.size(); ++f)
        loop.area += 0.5 * glm::length(glm::cross(tris[f][1] - tris[f][0], tris[f][2] - tris[f][0]));
}

std::uint32_t BoundaryCaps::build(std::uint32_t first, std::uint32_t last, std::vector<std::uint32_t>& order,
                                  const std::vector<std::array<glm::dvec3, 3>>& tris,
                                  std::vector<glm::dvec3>& unsignedMoments) {
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
    Node node{};
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

void BoundaryCaps::buildLeaf(Node& node, std::uint32_t index, std::uint32_t first, std::uint32_t last,
                             const std::vector<std::uint32_t>& order,
                             const std::vector<std::array<glm::dvec3, 3>>& tris,
                             std::vector<glm::dvec3>& unsignedMoments) {
    struct Ordered {
        const std::vector<std::array<glm::dvec3, 3>>& tris;
        const std::vector<std::uint32_t>& order;
        const std::array<glm::dvec3, 3>& operator[](std::size_t k) const { return tris[order[k]]; }
    };
    const Moments m = momentsOf(Ordered{tris, order}, first, last, node.centre);
    node.vectorArea = m.vectorArea;
    node.moment = m.moment;
    node.quadrupole = m.quadrupole;
    node.errorScale = 3.0 * m.second / kFourPi;
    node.area = m.area;
    for (std::uint32_t k = first; k < last; ++k) {
        const auto& t = tris[order[k]];
        unsignedMoments[index] += glm::length(glm::cross(t[1] - t[0], t[2] - t[0])) * 0.5 *
                                  ((t[0] + t[1] + t[2]) / 3.0 - node.centre);
    }
    node.first = std::uint32_t(leafTris_.size());
    node.count = last - first;
    for (std::uint32_t k = first; k < last; ++k) leafTris_.push_back(tris[order[k]]);
    finish(node);
    nodes_[index] = node;
}

void BoundaryCaps::gatherChildren(Node& node, std::uint32_t index, std::vector<glm::dvec3>& unsignedMoments) {
    // The children's moments moved to this centre: with d = c' - c, M_ij
    // gains A_i d_j, the unsigned first moment P gains area d, and S gains
    // 2 d . P' + area |d|^2.
    double second = 0.0;
    for (const std::uint32_t child : {node.left, node.right}) {
        const Node& n = nodes_[child];
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
    finish(node);
    nodes_[index] = node;
}

void BoundaryCaps::finish(Node& node) {
    node.trace = node.moment[0] + node.moment[4] + node.moment[8];
    node.quadrupoleRows = glm::dvec3(0.0);
    node.quadrupoleColumns = glm::dvec3(0.0);
    for (int i = 0; i < 3; ++i) {
        node.quadrupoleRows[i] = node.quadrupole[std::size_t(6 * i)] + node.quadrupole[std::size_t(6 * i + 1)] +
                                 node.quadrupole[std::size_t(6 * i + 2)];
        // sum over i of N_iik: the pair (i, k) of row i
        for (int k = 0; k < 3; ++k) {
            int pair = 0;
            while (!((kPairs[pair][0] == i && kPairs[pair][1] == k) || (kPairs[pair][0] == k && kPairs[pair][1] == i)))
                ++pair;
            node.quadrupoleColumns[k] += node.quadrupole[std::size_t(6 * i + pair)];
        }
    }
}

double BoundaryCaps::firstOrderBound(const Node& n, double distance) {
    return n.errorScale * firstOrderFactor(distance, distance - n.radius);
}

BoundaryCaps::Estimate BoundaryCaps::estimate(const glm::vec3& q, double nodeTolerance) const {
    if (!closed_) return {0.0, std::numeric_limits<double>::infinity()};
    if (nodes_.empty()) return {0.0, 0.0};
    const glm::dvec3 p(q);
    double integral = 0.0, bound = 0.0;
    const bool offCaps = walkTree(0, [&](std::uint32_t index, TreeStack& stack) {
        const Node& n = nodes_[index];
        const glm::dvec3 y = n.centre - p;
        const double d2 = glm::dot(y, y);
        const double d = std::sqrt(d2), e = d - n.radius;
        // Taken when its bound is within the tolerance per unit of solid
        // angle it subtends (about area / D^2): the taken nodes' bounds then
        // sum to about the tolerance times the caps' apparent solid angle.
        const double b = e > 0.0 ? n.errorScale * remainderFactor(d, e, n.radius) : 0.0;
        if (e > 0.0 && b * d2 <= nodeTolerance * n.area) {
            integral += expansion(n, y, d2, d);
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
    const int crossings = projected_->winding(q);
    return {double(crossings) - integral / kFourPi, bound + kRoundingSlack};
}

double BoundaryCaps::exact(int winding, const glm::vec3& q) const {
    return double(winding) + boundaryTermExact(edges_.data(), edges_.size() / 2, axisIndex_, glm::dvec3(q));
}

double BoundaryCaps::generalizedWinding(int winding, const glm::vec3& q, double tolerance) const {
    const Estimate e = estimate(q, kCapValueTolerance);
    return e.bound <= tolerance ? double(winding) + e.term : exact(winding, q);
}

} // namespace vds::detail
