// vds: the boundary term of the generalized winding number by capping the
// boundary loops (see caps_tree.h); the Antipodal split is Martens,
// Trettner & Bessmeltsev 2026, the tree expansion Barill, Dickson, Schmidt,
// Levin & Jacobson 2018, section 3.
#include "winding/caps_tree.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <memory>
#include <tuple>

#include <glm/geometric.hpp>

#include "winding/antipodal.h"
#include <vds/detail/boundary_loops.h>

namespace vds::detail {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kFourPi = 4.0 * kPi;
constexpr std::uint32_t kLeafTriangles = 4;
/// Most pieces a fan triangle's sides are cut into for the tree.
constexpr int kMaxCut = 8;
/// Rounding slack on the estimate: the solid angles and the expansion are
/// summed in double, some 1e-15 each.
constexpr double kRoundingSlack = 1e-9;
/// Largest error bound of a node that labels take by its expansion; nodes
/// erring by more are opened at once (they cannot help decide a label, and
/// keeping every taken bound small keeps the running sums' drift small).
constexpr double kMaxTakenBound = 0.25;
/// Labels refine by the expansion to second order once the value lies
/// within this of the threshold (decide()).
constexpr double kFineBelow = 0.1;
/// decide() opens, a round at a time, the taken nodes whose bound is at
/// least this fraction of the largest. Measured on the bench's generated
/// cases against opening the largest alone (from a heap): 1.2-2x the rate
/// within 0.1 of 1/2 on the soup and the non-manifold shell, the rest
/// unchanged.
constexpr double kOpenFraction = 0.5;
/// A node to be opened that holds at most this many edges has them summed
/// at once: with the per-edge sum a block of edges per instruction
/// (EdgeAngles), 16 edges cost about as much as two nodes taken. Measured
/// (4, 8, 16, 32, 64): 16 is the fastest on the soup within 0.1 of 1/2
/// (1.2-1.6x that of 4) with the bulk unchanged or faster; 32 and more
/// slow the non-manifold shell's bulk.
constexpr std::uint32_t kDirectEdges = 16;
/// decide() gives up for the per-edge sum where this times its predicted
/// work passes the budget (see there). Measured (0, 1, 1.5, 2, 3, with the
/// predicted work rising as the cube root, the square root and the 2/3
/// power of the shrink needed): 1.5 with the square root keeps every band
/// of |w - 1/2| on the bench's meshes within about 19x the bulk's cost,
/// and the soup's points within 0.001 of 1/2 at 1.7x their rate by the
/// cube root (which left them at half the per-edge sum's rate); 0 (never)
/// leaves the soup's and the non-manifold shell's points within 0.001 at
/// 30x, 2 and 3 slow the bunny's and the teapot's near 1/2.
constexpr double kGiveUp = 1.5;

struct Moments {
    glm::dvec3 vectorArea{0.0};
    std::array<double, 9> moment{};
    std::array<double, 18> quadrupole{}; ///< N_ijk, see Node::quadrupole
    double area = 0.0;
    double second = 0.0; ///< S: the integral of |x - centre|^2 dA
};

/// Index of the symmetric pair (j, k) in a row of Node::quadrupole.
constexpr int kPairs[6][2] = {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {0, 2}, {1, 2}};

// Sum over triangles of their vector areas, first and second moments about
// `centre` and unsigned areas. A flat triangle's integral of (x - c)(x - c)^T
// is its area / 12 times (sum of v v^T over its corners v, taken from c,
// plus s s^T, s the sum of the corners).
template <class Tris>
Moments momentsOf(const Tris& tris, std::size_t first, std::size_t last, const glm::dvec3& centre) {
    Moments m;
    for (std::size_t k = first; k < last; ++k) {
        const auto& t = tris[k];
        const glm::dvec3 a = 0.5 * glm::cross(t[1] - t[0], t[2] - t[0]);
        const glm::dvec3 arm = (t[0] + t[1] + t[2]) / 3.0 - centre;
        m.vectorArea += a;
        const double area = glm::length(a);
        m.area += area;
        const double sides = glm::dot(t[1] - t[0], t[1] - t[0]) + glm::dot(t[2] - t[1], t[2] - t[1]) +
                             glm::dot(t[0] - t[2], t[0] - t[2]);
        m.second += area * (glm::dot(arm, arm) + sides / 36.0);
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) m.moment[std::size_t(3 * i + j)] += a[i] * arm[j];
        const glm::dvec3 v[3] = {t[0] - centre, t[1] - centre, t[2] - centre};
        const glm::dvec3 sum = v[0] + v[1] + v[2];
        for (int pair = 0; pair < 6; ++pair) {
            const int j = kPairs[pair][0], l = kPairs[pair][1];
            const double xx = (v[0][j] * v[0][l] + v[1][j] * v[1][l] + v[2][j] * v[2][l] + sum[j] * sum[l]) / 12.0;
            for (int i = 0; i < 3; ++i) m.quadrupole[std::size_t(6 * i + pair)] += a[i] * xx;
        }
    }
    return m;
}

// The bound of the expansion to first order (Taylor's remainder after the
// linear term, |n . D^2K[h, h]| <= 3! |h|^2 / |y|^4), over errorScale:
// twice the integral of (1 - t) / (d - t R)^4, in closed form. Labels take
// nodes to first order (they need coarse bounds, and the second order term
// costs about as much again as the rest: 0.87-0.98x the rate measured),
// values to second order (at their 1e-3 tolerance 1.4-2.8x faster).
// The node's error bound over its errorScale (3 S / 4 pi), at distance
// d = |q - c| > R, e = d - R: R times the integral over t in [0, 1] of
// 4 (1 - t)^2 / (d - t R)^5 (Taylor's integral remainder after the second
// order term, with |h|^3 <= R |h|^2 and the kernel's third derivative taken
// at distance d - t|h| >= d - t R), in closed form.
double firstOrderFactor(double d, double e) { return (d + 2.0 * e) / (3.0 * d * d * d * e * e); }

double remainderFactor(double d, double e, double radius) { return radius * (d + 3.0 * e) / (3.0 * d * d * d * d * e * e); }

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

} // namespace

BoundaryCaps::BoundaryCaps(const glm::vec3* edges, std::size_t edgeCount, Axis axis, const Box* domain,
                           const CapsSurface* surface, const CellWindings* windings)
    : axisIndex_(axisPermutation(axis).z), surface_(surface), edges_(edges, edges + 2 * edgeCount) {
    // Weld endpoints by bitwise-equal positions, as boundaryEdges() does.
    std::map<std::tuple<float, float, float>, std::uint32_t> ids;
    const auto idOf = [&](const glm::vec3& p) {
        return ids.emplace(std::make_tuple(p.x, p.y, p.z), std::uint32_t(ids.size())).first->second;
    };
    std::vector<std::uint32_t> tail(edgeCount), head(edgeCount);
    for (std::size_t k = 0; k < edgeCount; ++k) {
        tail[k] = idOf(edges[2 * k]);
        head[k] = idOf(edges[2 * k + 1]);
    }
    std::vector<std::vector<std::uint32_t>> out(ids.size());
    for (std::size_t k = 0; k < edgeCount; ++k) out[tail[k]].push_back(std::uint32_t(k));
    std::vector<std::size_t> nextOut(ids.size(), 0);
    std::vector<std::uint8_t> used(edgeCount, 0);
    // The next edge out of the head of edge `in`: where several are unused
    // (a vertex the boundary passes more than once, as along a fin on a
    // non-manifold ring of edges), the one turning back most sharply, so
    // that loops stay small and tight (a fin's own triangle) instead of
    // running around the ring: small loops have small caps, which the tree
    // takes by expansion from close by.
    const auto takeOut = [&](std::size_t in) -> std::ptrdiff_t {
        const std::uint32_t v = head[in];
        std::size_t& n = nextOut[v];
        while (n < out[v].size() && used[out[v][n]]) ++n;
        if (n == out[v].size()) return -1;
        std::size_t best = n;
        const glm::dvec3 arrive = glm::dvec3(edges[2 * in + 1]) - glm::dvec3(edges[2 * in]);
        double bestTurn = std::numeric_limits<double>::infinity();
        for (std::size_t m = n; m < out[v].size(); ++m) {
            const std::uint32_t e = out[v][m];
            if (used[e]) continue;
            const glm::dvec3 leave = glm::dvec3(edges[2 * e + 1]) - glm::dvec3(edges[2 * e]);
            const double scale = glm::length(arrive) * glm::length(leave);
            const double turn = scale > 0.0 ? glm::dot(arrive, leave) / scale : 1.0;
            if (turn < bestTurn) {
                bestTurn = turn;
                best = m;
            }
        }
        std::swap(out[v][n], out[v][best]);
        return std::ptrdiff_t(out[v][n++]);
    };

    // Walk each loop along unused outgoing edges until it returns to its start.
    std::vector<std::array<glm::dvec3, 3>> tris, fine; // the caps' fans, and cut finer for the tree
    for (std::size_t start = 0; start < edgeCount && closed_; ++start) {
        if (used[start]) continue;
        CapLoop loop;
        loop.first = std::uint32_t(loopEdges_.size() / 2);
        std::ptrdiff_t e = std::ptrdiff_t(start);
        while (true) {
            used[std::size_t(e)] = 1;
            loopEdges_.push_back(edges[2 * std::size_t(e)]);
            loopEdges_.push_back(edges[2 * std::size_t(e) + 1]);
            if (head[std::size_t(e)] == tail[start]) break;
            e = takeOut(std::size_t(e));
            if (e < 0) {
                closed_ = false; // an open chain: these are not a mesh's boundary
                break;
            }
        }
        loop.count = std::uint32_t(loopEdges_.size() / 2) - loop.first;
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
        loops_.push_back(loop);
        // The tree sums the same surface, each fan triangle cut into m^2
        // triangles of about the loop's edge length: fan triangles of a long
        // loop are slivers as long as its radius, which a tree cannot split.
        double length = 0.0;
        for (std::uint32_t k = loop.first; k < loop.first + loop.count; ++k)
            length += glm::length(glm::dvec3(loopEdges_[2 * k + 1]) - glm::dvec3(loopEdges_[2 * k]));
        const double meanEdge = length / double(loop.count);
        const int m = meanEdge > 0.0 ? int(std::clamp(std::ceil(loop.radius / meanEdge), 1.0, double(kMaxCut))) : 1;
        const std::size_t fanEnd = tris.size();
        for (std::size_t f = firstTri; f < fanEnd; ++f) {
            const glm::dvec3 corner = tris[f][0], db = (tris[f][1] - corner) / double(m), da = (tris[f][2] - corner) / double(m);
            const auto at = [&](int i, int j) { return corner + double(i) * db + double(j) * da; };
            for (int i = 0; i < m; ++i)
                for (int j = 0; i + j < m; ++j) {
                    fine.push_back({{at(i, j), at(i + 1, j), at(i, j + 1)}});
                    if (i + j < m - 1) fine.push_back({{at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)}});
                }
        }
    }
    buildReach();
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
    return index;
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

// The node's integral of n . (x - q) / |x - q|^3 dA by its Taylor expansion
// about its centre to second order, at y = c - q (|y| = d): with
// K_i(y) = y_i / d^3, the terms are A . K, M_ij dK_i/dy_j and
// N_ijk d2K_i/dy_j dy_k / 2, where dK_i/dy_j = delta_ij / d^3 - 3 y_i y_j / d^5
// and d2K_i/dy_j dy_k = -3 (delta_ij y_k + delta_ik y_j + delta_jk y_i) / d^5
// + 15 y_i y_j y_k / d^7.

double BoundaryCaps::firstOrderBound(const Node& n, double distance) {
    return n.errorScale * firstOrderFactor(distance, distance - n.radius);
}

double BoundaryCaps::firstOrder(const Node& n, const glm::dvec3& y, double d2, double d) {
    return firstOrderTerm(n.vectorArea, n.moment, n.trace, y, d2, d);
}

double BoundaryCaps::expansion(const Node& n, const glm::dvec3& y, double d2, double d) {
    const double inv2 = 1.0 / d2, inv3 = inv2 / d;
    const std::array<double, 18>& N = n.quadrupole;
    const double yy[6] = {y.x * y.x, y.y * y.y, y.z * y.z, 2.0 * y.x * y.y, 2.0 * y.x * y.z, 2.0 * y.y * y.z};
    double yNyy = 0.0;
    for (int i = 0; i < 3; ++i) {
        const double* row = N.data() + 6 * i;
        yNyy += y[i] * (row[0] * yy[0] + row[1] * yy[1] + row[2] * yy[2] + row[3] * yy[3] + row[4] * yy[4] +
                        row[5] * yy[5]);
    }
    const double second =
        0.5 * inv2 * (-3.0 * (2.0 * glm::dot(n.quadrupoleColumns, y) + glm::dot(n.quadrupoleRows, y)) + 15.0 * yNyy * inv2);
    return firstOrder(n, y, d2, d) + second * inv3;
}

BoundaryCaps::Estimate BoundaryCaps::estimate(const glm::vec3& q, double nodeTolerance) const {
    if (!closed_) return {0.0, std::numeric_limits<double>::infinity()};
    if (nodes_.empty()) return {0.0, 0.0};
    const glm::dvec3 p(q);
    double integral = 0.0, bound = 0.0;
    std::uint32_t stack[64];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const Node& n = nodes_[stack[--top]];
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
            continue;
        }
        if (n.count == 0) {
            stack[top++] = n.left;
            stack[top++] = n.right;
            continue;
        }
        for (std::uint32_t k = n.first; k < n.first + n.count; ++k)
            if (!addCapTriangle(leafTris_[k], p, integral)) return {0.0, std::numeric_limits<double>::infinity()};
    }
    const int crossings = projected_->winding(q);
    return {double(crossings) - integral / kFourPi, bound + kRoundingSlack};
}

std::uint32_t BoundaryCaps::buildEdges(std::uint32_t first, std::uint32_t last) {
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

void BoundaryCaps::buildReach() {
    const std::size_t edgeCount = edges_.size() / 2;
    if (edgeCount == 0) return;
    edgeNodes_.reserve(2 * edgeCount / kLeafTriangles + 2 * loops_.size() + 2);
    if (!closed_) { // no loops: the edges alone
        treeEdges_ = edges_;
        buildEdges(0, std::uint32_t(edgeCount));
        return;
    }
    // Each loop's edges get a subtree of their own (in loop order, so that
    // a loop's edges are contiguous), under a tree over the loops.
    treeEdges_ = loopEdges_;
    edgeNodes_.emplace_back(); // [0]: the root, filled below
    std::vector<std::uint32_t> loopNodes(loops_.size());
    for (std::size_t l = 0; l < loops_.size(); ++l) {
        const CapLoop& loop = loops_[l];
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

std::uint32_t BoundaryCaps::buildLoops(std::vector<std::uint32_t>& nodes, std::uint32_t first, std::uint32_t last) {
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

BoundaryCaps::Reach BoundaryCaps::reach(const glm::vec3& q, double steepest) const {
    const double limit = steepest * kFourPi; // on the sum below
    Reach r;
    r.gap = std::numeric_limits<double>::infinity();
    if (edgeNodes_.empty()) return r;
    const glm::dvec3 p(q);
    double sum = 0.0; // of length / distance^2
    std::uint32_t stack[64];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const EdgeNode& n = edgeNodes_[stack[--top]];
        const double d = glm::length(n.centre - p), e = d - n.radius;
        // A cluster at least three radii away: every edge, and for whole
        // loops every cap, at distance e or more (the sum then exceeds its
        // edges' by at most (d / e)^2 <= 2.25). Whole loops take the
        // smaller of the two bounds: by the curve, length / e^2, or by the
        // caps, 2 area / e^3 (far small loops: their dipole).
        if (e >= 2.0 * n.radius && e > 0.0) {
            r.gap = std::min(r.gap, e);
            sum += n.wholeLoops ? std::min(n.length / (e * e), 2.0 * n.capArea / (e * e * e)) : n.length / (e * e);
            if (sum > limit) return Reach{};
            continue;
        }
        if (n.loopNode) { // the loop's own edges
            stack[top++] = n.left;
            continue;
        }
        if (n.count == 0) {
            stack[top++] = n.left;
            stack[top++] = n.right;
            continue;
        }
        for (std::uint32_t k = n.first; k < n.first + n.count; ++k) {
            const glm::dvec3 a(treeEdges_[2 * k]), b(treeEdges_[2 * k + 1]);
            const glm::dvec3 ab = b - a;
            const double length2 = glm::dot(ab, ab);
            const double t = length2 > 0.0 ? std::clamp(glm::dot(p - a, ab) / length2, 0.0, 1.0) : 0.0;
            const double distance = glm::length(a + t * ab - p);
            if (!(distance > 0.0)) return Reach{}; // on the curve: no move is certain
            r.gap = std::min(r.gap, distance);
            sum += std::sqrt(length2) / (distance * distance);
        }
        if (sum > limit) return Reach{};
    }
    // A little slack on the distances: they are rounded.
    r.gap *= 1.0 - 1e-9;
    r.steepness = sum / kFourPi * (1.0 + 1e-9);
    return r;
}

double BoundaryCaps::driftWithin(const glm::vec3& q, double length, double limit) const {
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
    // A leaf's edges, each at its nearest to q; false where a move may
    // reach one.
    const auto addEdges = [&](const EdgeNode& leaf, double& sumMoved, double& sumAt, double& nearest) {
        for (std::uint32_t k = leaf.first; k < leaf.first + leaf.count; ++k) {
            const glm::dvec3 a(treeEdges_[2 * k]), b(treeEdges_[2 * k + 1]);
            const glm::dvec3 ab = b - a;
            const double length2 = glm::dot(ab, ab);
            const double t = length2 > 0.0 ? std::clamp(glm::dot(p - a, ab) / length2, 0.0, 1.0) : 0.0;
            const double distance = glm::length(a + t * ab - p);
            if (!(distance > length)) return false;
            const double edge = std::sqrt(length2);
            sumMoved += edge / ((distance - length) * (distance - length));
            sumAt += edge / (distance * distance);
            nearest = std::min(nearest, distance);
        }
        return true;
    };
    std::uint32_t stack[64];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const EdgeNode& n = edgeNodes_[stack[--top]];
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
            if (over()) return kInfinity;
            continue;
        }
        if (n.loopNode) {
            // The loop's edges one by one, or where that sums to more, its
            // cap's bound (its ball clear of every move: near > 0).
            double loopMoved = 0.0, loopAt = 0.0, loopGap = kInfinity;
            std::uint32_t inner[64];
            int depth = 0;
            inner[depth++] = n.left;
            while (depth > 0) {
                const EdgeNode& m = edgeNodes_[inner[--depth]];
                if (m.count == 0) {
                    inner[depth++] = m.left;
                    inner[depth++] = m.right;
                    continue;
                }
                if (!addEdges(m, loopMoved, loopAt, loopGap)) return kInfinity;
            }
            if (near > 0.0) {
                loopMoved = std::min(loopMoved, 2.0 * n.capArea / (near * near * near));
                loopAt = std::min(loopAt, 2.0 * n.capArea / (e * e * e));
                loopGap = std::min(loopGap, e);
            }
            moved += loopMoved;
            at += loopAt;
            gap = std::min(gap, loopGap);
            if (over()) return kInfinity;
            continue;
        }
        if (n.count == 0) {
            stack[top++] = n.left;
            stack[top++] = n.right;
            continue;
        }
        if (!addEdges(n, moved, at, gap) || over()) return kInfinity;
    }
    const double shrink = 1.0 - length / gap;
    const double byReach = shrink > 0.0 ? at / (shrink * shrink * shrink) : kInfinity;
    // A little slack: the distances are rounded.
    return std::min(moved, byReach) / kFourPi * length * (1.0 + 1e-8);
}

double BoundaryCaps::exact(int winding, const glm::vec3& q) const {
    return double(winding) + boundaryTermExact(edges_.data(), edges_.size() / 2, axisIndex_, glm::dvec3(q));
}

double BoundaryCaps::generalizedWinding(int winding, const glm::vec3& q, double tolerance) const {
    const Estimate e = estimate(q, kCapValueTolerance);
    return e.bound <= tolerance ? double(winding) + e.term : exact(winding, q);
}

// ------------------------------------------------------------ range grid

namespace {
/// Cells of the range grid along its longest side, and of the fine grid.
constexpr double kRangeCells = 24.0;
constexpr double kFineCells = 2.0 * kRangeCells;
/// Queries without a range a coarse cell takes before it hands them to
/// its fine cells.
constexpr unsigned kBusyVisits = 1024;
/// The node tolerance of the estimate at a cell's centre (estimate()):
/// coarse, as a range serves only where it keeps clear of 1/2. Measured
/// (exact classifier, first call, 200,000 points, this project's VM):
/// 5e-2 against 1e-2, 1.1-1.25x on the fins and the punched sphere, the
/// rest within noise; 1e-1 costs the teapot 9%.
constexpr double kRangeTolerance = 5e-2;
} // namespace

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
/// A plan's score of queries it left undecided (each adds 1, each it
/// decided takes 1 off): at kPlanMisses its cell drops it. A miss costs
/// the plan and then the tree from its root (2.6 us of the soup's), a
/// planned answer 0.5 and the root alone 2.1, so a plan pays while it
/// decides most of its queries: counting misses alone, a busy cell lost
/// its plan to its first few queries near 1/2 (the soup's exact path
/// 1.84 -> 1.58 M points/s over six calls of 2,000,000 points).
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

BoundaryCaps::CellsBall BoundaryCaps::ballOf(const RangeGrid& g, const glm::uvec3& first, const glm::uvec3& last) {
    const glm::dvec3 lo(g.box.lo), hi(g.box.hi);
    const double slack = 1e-7 * std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
    const glm::dvec3 centre = lo + 0.5 * (glm::dvec3(first) + glm::dvec3(last + 1u)) * g.size;
    const glm::vec3 c(centre);
    // Every point of the widened cells lies within this of c.
    return {c, 0.5 * glm::length(glm::dvec3(last + 1u - first) * g.size) + glm::length(glm::dvec3(c) - centre) +
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
    const CellsBall ball = ballOf(g, first, last);
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
                std::uint8_t zero = 0;
                if (k != cell && !g.state[k].compare_exchange_strong(zero, 3, std::memory_order_acquire)) continue;
                g.lo[k] = rangeLo;
                g.hi[k] = rangeHi;
                g.alone[k] = std::uint8_t(side > 0);
                if (k != cell) g.state[k].store(4, std::memory_order_release);
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
    if (cellsNow) allocateCells(g);
}

void BoundaryCaps::allocateCells(RangeGrid& g) {
    const std::size_t cells = std::size_t(g.dims.x) * g.dims.y * g.dims.z;
    g.state.reset(new std::atomic<std::uint8_t>[cells]);
    g.near.reset(new std::unique_ptr<std::uint32_t[]>[cells]);
    g.nearCount.reset(new std::uint32_t[cells]());
    g.nearLoops.reset(new std::uint32_t[cells]());
    g.planMisses.reset(new std::atomic<std::uint8_t>[cells]);
    for (std::size_t c = 0; c < cells; ++c) g.planMisses[c].store(0, std::memory_order_relaxed);
    for (std::size_t c = 0; c < cells; ++c) g.state[c].store(0, std::memory_order_relaxed);
    g.alone.reset(new std::uint8_t[cells]);
    g.lo.reset(new double[cells]);
    g.hi.reset(new double[cells]);
}

std::uint8_t BoundaryCaps::rangeOf(const RangeGrid& g, std::size_t cell, const glm::uvec3& at, bool within) const {
    std::uint8_t state = g.state[cell].load(std::memory_order_acquire);
    if (state != 0) return state;
    // One thread fills the cell (state 3 while it does); the others go on
    // by the tree meanwhile.
    if (!g.state[cell].compare_exchange_strong(state, 3, std::memory_order_acquire)) return state;
    std::uint8_t result = 2;
    // Clear of the boundary curve and its sweep along +axis.
    const bool clearOfSweep = this->clearOfSweep(g, at);
    // Clear of the surface: the whole winding number is smooth over the
    // cell (the boundary curve too lies on the surface).
    const bool clearOfSurface = !g.met.empty() && g.met[cell] == 0;
    // Clear of the caps: w_caps is smooth over the cell, and B is the caps'
    // crossing count (an integer, asked at the query) less w_caps.
    const bool clearOfCaps = g.capMet[cell] == 0;
    const CellsBall ball = ballOf(g, at, at);
    if (g.blockTried && blockRange(g, cell, at)) {
        result = 4;
    } else if (clearOfSweep || clearOfSurface || clearOfCaps) {
        const glm::vec3 c = ball.centre;
        Estimate e;
        double drift;
        if (rangeOver(ball, e, drift)) {
            // The cheapest range to ask at a query: the whole winding
            // number's, then B's, then -w_caps.
            double base = e.term;
            result = 1;
            std::uint8_t byClosed = 0;
            if (clearOfSurface) {
                base += double(surface_->winding(c));
                result = 4;
            } else if (!clearOfSweep) {
                base -= double(projected_->winding(c));
                result = 5;
                if (!g.closedWinding.empty() && g.closedWinding[cell] != CellWindings::kUnknown) {
                    // -w_caps's range (the caps keep out of the cell), and
                    // an integer term plus caps' crossing count the caller
                    // knows is one integer over the cell.
                    base += double(g.closedWinding[cell]);
                    result = 4;
                    byClosed = kByClosed;
                    ++g.closedCells;
                }
            } else if (!g.constantWinding.empty() && g.constantWinding[cell] != CellWindings::kUnknown) {
                // B's range, and an integer term the caller knows is one
                // integer over the cell.
                base += double(g.constantWinding[cell]);
                result = 4;
            }
            g.lo[cell] = base - e.bound - drift;
            g.hi[cell] = base + e.bound + drift;
            if (result == 4) {
                const int side = sideOf(g.lo[cell], g.hi[cell]);
                g.alone[cell] = std::uint8_t((side == 0 ? kUndecided : std::uint8_t(side > 0)) | byClosed);
            }
        }
    }
    if (result == 2 && plan(g, cell, ball.centre, ball.half, within)) result = 6;
    g.state[cell].store(result, std::memory_order_release);
    return result;
}

BoundaryCaps::RangedCells BoundaryCaps::rangedCells(bool fine) const {
    const RangeGrid& g = fine ? fine_ : ranges_;
    RangedCells ranged;
    if (fine ? !fineReady_.load(std::memory_order_acquire) : !g.state) return ranged;
    for (std::size_t c = 0, n = std::size_t(g.dims.x) * g.dims.y * g.dims.z; c < n; ++c) {
        const std::uint8_t state = g.state[c].load(std::memory_order_acquire);
        ranged.boundary += state == 1;
        ranged.winding += state == 4;
        ranged.capped += state == 5;
        ranged.planned += state == 6;
    }
    ranged.closed = g.closedCells.load(std::memory_order_relaxed);
    return ranged;
}

std::size_t BoundaryCaps::memoryBytes() const {
    const auto held = [](const auto& v) { return v.capacity() * sizeof(v[0]); };
    std::size_t total = held(edges_) + held(loopEdges_) + held(loops_) + held(capPositions_) + held(capTriangles_) +
                        held(capLoopOf_) + held(chains_) + held(chainEdges_) + held(treeEdges_) + held(edgeNodes_) +
                        held(leafTris_) + held(nodes_) + (projected_ ? projected_->memoryBytes() : 0);
    for (const RangeGrid* g : {&ranges_, static_cast<const RangeGrid*>(&fine_)}) {
        total += held(g->met) + held(g->capMet) + held(g->constantWinding) + held(g->closedWinding) + held(g->lowestEdge);
        if (g == &fine_ ? !fineReady_.load(std::memory_order_acquire) : !g->state) continue;
        const std::size_t cells = std::size_t(g->dims.x) * g->dims.y * g->dims.z;
        // state, alone, planMisses; near, nearCount, nearLoops; lo, hi
        total += cells * (3 + sizeof(std::unique_ptr<std::uint32_t[]>) + 2 * sizeof(std::uint32_t) + 2 * sizeof(double));
        if (g->visits) total += cells * sizeof(std::uint16_t);
        if (g->blockTried) total += std::size_t(g->blockDims.x) * g->blockDims.y * g->blockDims.z;
        for (std::size_t c = 0; c < cells; ++c) // plans published so far
            if (g->state[c].load(std::memory_order_acquire) == 6)
                total += (std::size_t(g->nearCount[c]) + g->nearLoops[c]) * sizeof(std::uint32_t);
    }
    return total;
}

bool BoundaryCaps::fineCells() const {
    if (fineReady_.load(std::memory_order_acquire)) return true;
    if (fine_.capMet.empty()) return false; // no fine grid (no grid at all)
    std::call_once(fineOnce_, [this] {
        allocateCells(fine_);
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
    if (!cellOf(ranges_, q, cell, at)) return generalizedWindingInside(decide(windingAt(), q, 1.0).term);
    std::uint8_t state = ranges_.state[cell].load(std::memory_order_acquire);
    if (state == 0) state = rangeOf(ranges_, cell, at);
    if ((state == 2 || state == 6) && busy(cell) && fineCells()) {
        // The fine cell, where it has a range or a plan (or the coarse one
        // has none either).
        std::size_t fineCell;
        glm::uvec3 fineAt;
        if (cellOf(fine_, q, fineCell, fineAt)) {
            std::uint8_t fineState = fine_.state[fineCell].load(std::memory_order_acquire);
            if (fineState == 0) fineState = rangeOf(fine_, fineCell, fineAt, state == 6);
            if ((fineState != 2 && fineState != 3) || state == 2)
                return insideIn(fine_, fineCell, fineState, q, windingAt, apart);
        }
    }
    return insideIn(ranges_, cell, state, q, windingAt, apart);
}

template <class Winding>
bool BoundaryCaps::insideIn(const RangeGrid& g, std::size_t cell, std::uint8_t state, const glm::vec3& q,
                            const Winding& windingAt, bool apart) const {
    // A closed count's range, for a query apart from it: -w_caps's range
    // (the count taken off), as state 5.
    const bool closedApart = state == 4 && apart && (g.alone[cell] & kByClosed);
    if (state == 4 && !closedApart && (g.alone[cell] & ~kByClosed) != kUndecided)
        return (g.alone[cell] & ~kByClosed) != 0; // the whole winding number's range: no integer term asked
    const int winding = windingAt();
    if (state == 1 || state == 5 || closedApart) {
        double shift = double(state == 1 ? winding : winding + projected_->winding(q));
        if (closedApart) shift -= double(g.closedWinding[cell]);
        const int side = sideOf(shift + g.lo[cell], shift + g.hi[cell]);
        if (side != 0) return side > 0;
    }
    if (state == 6) {
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
            g.state[cell].store(2, std::memory_order_relaxed);
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

// ------------------------------------------------------------ labels
//
// The tree labels refine: over the loops (each node's surface the loops'
// fans, no chord), then within a loop over halves of its edges. A chain of
// edges running from P to Q, closed by its chord Q -> P, bounds the fan
// (g, b, a) over its edges a -> b and the chord, g the mean of its
// vertices; the fan lies in the node's ball. Where q's ray towards -axis
// misses the ball, the ray crosses no fan, so by the caps' identity (B of a
// closed loop = its cap's crossing count less its cap's winding number,
// caps_tree.h) the chain's per-edge angles sum to the chord's angle
// f(P -> Q) (edgeSolidAngle, exact) less the fan's solid angle, which the
// expansion takes. A chain's fan is a thin lune along the boundary, not a
// cap across the loop: points near a large opening, where the caps' fans
// all meet, are decided by a few chains of the loop near them, the rest of
// the loop by chords. Leaves sum their edges' angles as the per-edge sum
// does.

namespace {
/// Most edges a chain leaf holds.
constexpr std::uint32_t kLeafEdges = 4;
} // namespace

namespace {
/// A chain node's fan: its moments about the node's centre.
void setFan(BoundaryCaps::Node& node, const Moments& m) {
    node.vectorArea = m.vectorArea;
    node.moment = m.moment;
    node.quadrupole = m.quadrupole;
    node.area = m.area;
    node.errorScale = 3.0 * m.second / kFourPi;
}
} // namespace

void BoundaryCaps::buildChains() {
    std::vector<std::uint32_t> order(loops_.size());
    for (std::uint32_t l = 0; l < order.size(); ++l) order[l] = l;
    chains_.reserve(2 * (edges_.size() / 2) / 2 + 2 * loops_.size() + 2);
    buildChainGroup(order, 0, std::uint32_t(order.size()));
}

std::uint32_t BoundaryCaps::buildChainGroup(std::vector<std::uint32_t>& loops, std::uint32_t first,
                                            std::uint32_t last) {
    if (last - first == 1) {
        const CapLoop& loop = loops_[loops[first]];
        const std::uint32_t treeFirst = std::uint32_t(chainEdges_.size() / 2);
        chainEdges_.insert(chainEdges_.end(), loopEdges_.begin() + 2 * std::ptrdiff_t(loop.first),
                          loopEdges_.begin() + 2 * std::ptrdiff_t(loop.first + loop.count));
        return buildChain(loops[first], loop.first, loop.count, treeFirst);
    }
    const std::uint32_t index = std::uint32_t(chains_.size());
    const std::uint32_t treeFirst = std::uint32_t(chainEdges_.size() / 2);
    chains_.emplace_back();
    glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
    glm::dvec3 clo = lo, chi = hi;
    std::vector<std::array<glm::dvec3, 3>> tris;
    for (std::uint32_t l = first; l < last; ++l) {
        const CapLoop& loop = loops_[loops[l]];
        clo = glm::min(clo, loop.centroid);
        chi = glm::max(chi, loop.centroid);
        for (std::uint32_t k = loop.first; k < loop.first + loop.count; ++k) {
            const glm::dvec3 a(loopEdges_[2 * k]), b(loopEdges_[2 * k + 1]);
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
    setFan(node, momentsOf(tris, 0, tris.size(), node.centre));
    finish(node);
    node.chord = false;
    node.loop = kNoLoop;
    const glm::dvec3 extent = chi - clo;
    const int split = extent.x >= extent.y && extent.x >= extent.z ? 0 : extent.y >= extent.z ? 1 : 2;
    const std::uint32_t middle = first + (last - first) / 2;
    std::nth_element(loops.begin() + first, loops.begin() + middle, loops.begin() + last,
                     [&](std::uint32_t x, std::uint32_t y) { return loops_[x].centroid[split] < loops_[y].centroid[split]; });
    node.left = buildChainGroup(loops, first, middle);
    node.right = buildChainGroup(loops, middle, last);
    node.edgeFirst = treeFirst;
    node.edgeCount = std::uint32_t(chainEdges_.size() / 2) - treeFirst;
    chains_[index] = node;
    return index;
}

std::uint32_t BoundaryCaps::buildChain(std::uint32_t loop, std::uint32_t first, std::uint32_t count,
                                       std::uint32_t treeFirst) {
    const std::uint32_t index = std::uint32_t(chains_.size());
    chains_.emplace_back();
    ChainNode node{};
    const bool whole = count == loops_[loop].count;
    glm::dvec3 apex(0.0);
    if (whole) {
        apex = loops_[loop].centroid;
    } else {
        for (std::uint32_t k = first; k < first + count; ++k) apex += glm::dvec3(loopEdges_[2 * k]);
        apex += glm::dvec3(loopEdges_[2 * (first + count - 1) + 1]);
        apex /= double(count + 1);
    }
    std::vector<std::array<glm::dvec3, 3>> tris;
    for (std::uint32_t k = first; k < first + count; ++k) {
        const glm::dvec3 a(loopEdges_[2 * k]), b(loopEdges_[2 * k + 1]);
        tris.push_back({apex, b, a});
        node.radius = std::max({node.radius, glm::length(a - apex), glm::length(b - apex)});
    }
    node.from = glm::dvec3(loopEdges_[2 * first]);
    node.to = glm::dvec3(loopEdges_[2 * (first + count - 1) + 1]);
    node.chord = !whole;
    node.loop = whole ? loop : kNoLoop;
    if (node.chord) tris.push_back({apex, node.from, node.to}); // the chord Q -> P closes the chain
    node.centre = apex;
    setFan(node, momentsOf(tris, 0, tris.size(), apex));
    finish(node);
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
    // steepness (2 area / distance^3 over 4 pi, caps_tree.h); a single
    // loop nearer is near, left to each query, a group nearer is split.
    // Chains (parts of loops) are never reached. No plan where the far
    // range would be wide or the near loops many: the tree from its root
    // does better there.
    const glm::dvec3 p(c);
    std::vector<std::uint32_t> near, loops;
    double value = 0.0, width = 0.0;
    std::uint32_t stack[64];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const std::uint32_t i = stack[--top];
        const ChainNode& n = chains_[i];
        const glm::dvec3 y = n.centre - p;
        const double d2 = glm::dot(y, y), d = std::sqrt(d2);
        const double radius = n.radius * (1.0 + 1e-12), gap = d - radius - half;
        if (!n.chord && gap >= std::max(2.0 * radius, kPlanReach * half)) {
            value -= expansion(n, y, d2, d) / kFourPi;
            width += n.errorScale * remainderFactor(d, d - radius, radius) +
                     2.0 * n.area * half / (kFourPi * gap * gap * gap);
            if (width > kPlanWidth) return false;
            continue;
        }
        if (n.loop != kNoLoop || n.chord) {
            near.push_back(i);
            if (near.size() > kPlanNear) return false;
            continue;
        }
        stack[top++] = n.left;
        stack[top++] = n.right;
    }
    // The loops the near nodes hold.
    for (const std::uint32_t i : near) {
        top = 0;
        stack[top++] = i;
        while (top > 0) {
            const ChainNode& n = chains_[stack[--top]];
            if (n.loop != kNoLoop) {
                loops.push_back(n.loop);
            } else {
                stack[top++] = n.left;
                stack[top++] = n.right;
            }
        }
    }
    // Worth it where the near loops are fewer than the tree from its root
    // takes at the centre (nodes and edges). Within a planned cell that
    // test was passed: a fine cell's near loops lie within the coarse
    // cell's reach (its centre within half the coarse half diagonal), so
    // they are no more than the coarse cell's, and the decide() at the
    // centre (some 2 us of the soup's) is not asked again.
    if (!within && double(near.size()) > kPlanShare * decide(0, c, 1.0).work) return false;
    std::sort(loops.begin(), loops.end());
    // The filling thread owns the cell (state 3).
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

bool BoundaryCaps::takeNode(const ChainNode& n, const glm::dvec3& p, bool fine, double& bound, double& value) const {
    const int a = axisIndex_, s = (a + 1) % 3, t = (a + 2) % 3;
    const glm::dvec3 y = n.centre - p;
    const double d2 = glm::dot(y, y);
    const double reach = n.radius * (1.0 + 1e-12);
    // q's ray towards -axis misses the ball: the fan's crossing count is 0
    const bool misses = y[s] * y[s] + y[t] * y[t] > reach * reach || p[a] < n.centre[a] - reach;
    if (!misses || !(d2 > reach * reach)) return false;
    const double d = std::sqrt(d2), e = d - reach;
    bound = fine ? n.errorScale * remainderFactor(d, e, reach) : n.errorScale * firstOrderFactor(d, e);
    if (!(bound <= kMaxTakenBound)) return false;
    value = fine ? -expansion(n, y, d2, d) : -firstOrderTerm(n.vectorArea, n.moment, n.trace, y, d2, d);
    if (n.chord) value += edgeSolidAngle(a, n.from, n.to, p);
    return true;
}

bool BoundaryCaps::firstCut(int winding, const glm::vec3& q, const std::uint32_t* roots, std::size_t rootCount,
                            double farLo, double farHi, Estimate& out) const {
    const glm::dvec3 p(q);
    const int a = axisIndex_;
    double angles = 0.0, bound = 0.5 * (farHi - farLo), work = 0.0;
    EdgeAngles leafSum;
    bool leaves = false;
    for (std::size_t r = 0; r < rootCount; ++r) {
        // refine()'s open() on a root, its first step: the same tests and
        // terms (not `fine`: the first cut is first order).
        const ChainNode& n = chains_[roots[r]];
        double b, value;
        if (takeNode(n, p, false, b, value)) {
            work += n.chord ? 2.0 : 1.0;
            angles += value;
            bound += b;
            continue;
        }
        if (n.count == 0 && n.edgeCount > kDirectEdges) return false; // refine splits it
        work += double(n.edgeCount);
        leafSum.add(&chainEdges_[2 * std::size_t(n.edgeFirst)], n.edgeCount, a, p);
        leaves = true;
    }
    // As refine() finds its first value (margin 1).
    const double offset = double(winding) - 0.5 - kGeneralizedWindingTie + 0.5 * (farLo + farHi);
    const double value = offset + (angles + (leaves ? leafSum.angle() : 0.0)) / kFourPi;
    if (!(std::fabs(value) > bound + kRoundingSlack)) return false;
    out = {value + 0.5 + kGeneralizedWindingTie, bound + kRoundingSlack, work};
    return true;
}

BoundaryCaps::Estimate BoundaryCaps::decide(int winding, const glm::vec3& q, double margin) const {
    if (!closed_) return {exact(winding, q), 0.0};
    if (chains_.empty()) return {double(winding), 0.0};
    const std::uint32_t root = 0;
    Estimate out;
    if (refine(winding, q, margin, &root, 1, 0.0, 0.0, out)) return out;
    return {exact(winding, q), 0.0, out.work + double(edges_.size() / 2)};
}

bool BoundaryCaps::refine(int winding, const glm::vec3& q, double margin, const std::uint32_t* roots,
                          std::size_t rootCount, double farLo, double farHi, Estimate& out) const {
    struct Taken {
        double bound;
        double value; ///< the node's edges' angles by its chord and expansion
        std::uint32_t node;
    };
    thread_local std::vector<Taken> taken, opening;
    thread_local std::vector<std::uint32_t> stack;
    taken.clear();
    // Decide-or-refine: start from the coarsest cut whose nodes each err by
    // at most kMaxTakenBound, then open, a round at a time, every taken
    // node whose bound is at least kOpenFraction of the largest, until the
    // value lies farther from 1/2 than the summed bounds.
    const glm::dvec3 p(q);
    const int a = axisIndex_;
    // The per-edge angles' sum, in radians: of the taken nodes, and of the
    // leaves' edges (as the per-edge sum takes them, EdgeAngles: one atan2
    // when a label is tried, not one an edge).
    // What stands for the loops not in `roots`: a range of their part.
    const double farBound = 0.5 * (farHi - farLo);
    double angles = 0.0, bound = farBound;
    EdgeAngles leafSum;
    // Work spent, in nodes taken (a chord's angle and an expansion) and
    // edges summed: past the edge count the per-edge sum decides.
    const double budget = double(edges_.size() / 2);
    double work = 0.0;
    bool fine = false;
    // The leaves' angle, taken again (an atan2) only after edges were
    // summed.
    bool leavesChanged = false;
    double leaves = 0.0;
    // Opens the subtree at `index`: nodes q's ray misses and far enough by
    // expansion, the rest down to nodes of at most kDirectEdges edges,
    // whose edges are summed exactly. False once the work exceeds the
    // budget. `expand`: not by its own expansion (a node taken before).
    const auto open = [&](std::uint32_t index, bool expand) {
        stack.clear();
        stack.push_back(index);
        while (!stack.empty()) {
            if (work > budget) return false;
            const std::uint32_t i = stack.back();
            stack.pop_back();
            const ChainNode& n = chains_[i];
            double b, value;
            if (!(expand && i == index) && takeNode(n, p, fine, b, value)) {
                work += n.chord ? 2.0 : 1.0;
                angles += value;
                bound += b;
                taken.push_back({b, value, i});
                continue;
            }
            if (n.count == 0 && n.edgeCount > kDirectEdges) {
                stack.push_back(n.left);
                stack.push_back(n.right);
                continue;
            }
            work += double(n.edgeCount);
            leafSum.add(&chainEdges_[2 * std::size_t(n.edgeFirst)], n.edgeCount, a, p);
            leavesChanged = true;
        }
        return true;
    };
    // value - (1/2 + tie) = offset + angles / 4 pi; the estimate lies
    // within bound + kRoundingSlack of the per-edge sum, so a value farther
    // than that from the threshold has the per-edge sum's label.
    const double offset = double(winding) - 0.5 - kGeneralizedWindingTie + 0.5 * (farLo + farHi);
    bool opened = true;
    for (std::size_t r = 0; r < rootCount && opened; ++r) opened = open(roots[r], false);
    if (opened) {
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
                value = offset + (angles + leaves) / kFourPi;
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
                if (std::fabs(value) <= margin * farBound + kRoundingSlack) break;
                // The bound must shrink by margin * bound / |value|, which
                // takes about the work so far times its square root (a
                // node's first-order bound falls as its radius cubed, but
                // the cut's nodes rise faster than the radius falls, and a
                // taken node costs about three edges of the per-edge sum):
                // where that passes the budget, the per-edge sum is the
                // cheaper.
                if (kGiveUp * work * std::sqrt(margin * bound / std::fabs(value)) > budget) break;
            }
            if (taken.empty() || work > budget) break;
            // Close to the threshold, the nodes opened from here are taken
            // to second order (their bound about R / D of the first
            // order's, for about twice the work; bulk points stop at the
            // first cut). Measured on the generated cases, with 0.01 to 0.2
            // here alike: 1.1-2x the rate within 0.02 of 1/2, 1-1.9x within
            // 0.001, the rest unchanged.
            fine = std::fabs(value) < kFineBelow;
            double largest = 0.0;
            for (const Taken& tk : taken) largest = std::max(largest, tk.bound);
            const double least = kOpenFraction * largest;
            opening.clear();
            std::size_t kept = 0;
            for (const Taken& tk : taken) {
                if (tk.bound >= least) {
                    opening.push_back(tk);
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
                const ChainNode& n = chains_[opening[k].node];
                if (n.count == 0) more = open(n.left, false) && open(n.right, false);
                else more = open(opening[k].node, true); // a leaf: summed exactly
            }
            if (!more) break;
            moved += bound - before;
        }
    }
    out.work = work;
    return false;
}

PackedBoundary packBoundary(const std::vector<glm::vec3>& edges, Axis axis) {
    PackedBoundary packed;
    const glm::ivec3 p = axisPermutation(axis);
    const auto permuted = [&](const glm::dvec3& v) { return glm::vec3(float(v[p.x]), float(v[p.y]), float(v[p.z])); };
    packed.edgeCount = std::uint32_t(edges.size() / 2);
    if (packed.edgeCount == 0) return packed;
    const BoundaryCaps caps(edges.data(), packed.edgeCount, axis);
    const std::vector<glm::vec3>& loopEdges = caps.loopEdges();
    const std::vector<BoundaryCaps::ChainNode>& chains = caps.chains();
    if (!caps.closed() || loopEdges.size() != edges.size() || chains.empty()) {
        for (const glm::vec3& v : edges) packed.data.emplace_back(permuted(glm::dvec3(v)), 0.0f);
        return packed;
    }
    // The nodes in preorder (a node's first child follows it, `skip` is
    // the node after its subtree) and the edges in the order of the leaves,
    // so that every node's edges are one range: the shader walks the tree
    // without a stack and sums a small node's range at once. A group of
    // loops whose expansion would not meet the shader's tolerance even one
    // diagonal of the boundary's box away is left out (its children take
    // its place): a point would only visit it to open it.
    struct Placed {
        std::uint32_t node, skip, first, count;
    };
    std::vector<Placed> placed;
    placed.reserve(chains.size());
    std::vector<glm::vec3> ordered;
    ordered.reserve(loopEdges.size());
    glm::dvec3 boxLo(std::numeric_limits<double>::max()), boxHi(-std::numeric_limits<double>::max());
    for (const glm::vec3& v : loopEdges) {
        boxLo = glm::min(boxLo, glm::dvec3(v));
        boxHi = glm::max(boxHi, glm::dvec3(v));
    }
    const double diagonal = glm::length(boxHi - boxLo);
    const auto visit = [&](const auto& self, std::uint32_t index) -> void {
        const BoundaryCaps::ChainNode& node = chains[index];
        const bool group = !node.chord && node.count == 0 && !chains[node.left].chord;
        const double e = diagonal - node.radius;
        if (group && (e <= 0.0 || node.errorScale * remainderFactor(diagonal, e, node.radius) > kBoundaryNodeTolerance)) {
            self(self, node.left);
            self(self, node.right);
            return;
        }
        const std::size_t at = placed.size();
        placed.push_back({index, 0, std::uint32_t(ordered.size() / 2), 0});
        if (node.count != 0) {
            ordered.insert(ordered.end(), loopEdges.begin() + 2 * std::ptrdiff_t(node.first),
                           loopEdges.begin() + 2 * std::ptrdiff_t(node.first + node.count));
        } else {
            self(self, node.left);
            self(self, node.right);
        }
        placed[at].skip = std::uint32_t(placed.size());
        placed[at].count = std::uint32_t(ordered.size() / 2) - placed[at].first;
    };
    visit(visit, 0); // the tree is balanced: the recursion is about log2(edges) deep
    for (const glm::vec3& v : ordered) packed.data.emplace_back(permuted(glm::dvec3(v)), 0.0f);
    packed.nodeCount = std::uint32_t(placed.size());
    const auto pairIndex = [](int j, int k) {
        if (j == k) return j;
        const int lo = std::min(j, k), hi = std::max(j, k);
        return lo == 0 ? (hi == 1 ? 3 : 4) : 5;
    };
    const auto bits = [](std::uint32_t v) {
        float f;
        const std::int32_t i = std::int32_t(v);
        std::memcpy(&f, &i, 4);
        return f;
    };
    for (const Placed& at : placed) {
        const BoundaryCaps::ChainNode& node = chains[at.node];
        // In the (s, t, r) frame: every index through the permutation.
        const auto M = [&](int i, int j) { return node.moment[std::size_t(3 * p[i] + p[j])]; };
        const auto N = [&](int i, int j, int k) {
            return node.quadrupole[std::size_t(6 * p[i] + pairIndex(p[j], p[k]))];
        };
        const bool leaf = node.count != 0;
        const std::uint32_t flags = (leaf ? kBoundaryNodeLeaf : 0u) | (node.chord ? kBoundaryNodeChord : 0u);
        // Float may round the radius down; the shader's tests of whether
        // q's ray misses the ball round too.
        packed.data.emplace_back(permuted(node.centre), float(node.radius * (1.0 + 1e-5)));
        packed.data.emplace_back(float(node.errorScale), bits(at.skip), bits(at.first), bits(at.count << 2 | flags));
        packed.data.emplace_back(permuted(node.vectorArea), M(0, 0));
        packed.data.emplace_back(M(0, 1), M(0, 2), M(1, 0), M(1, 1));
        packed.data.emplace_back(M(1, 2), M(2, 0), M(2, 1), M(2, 2));
        glm::dvec3 rows(0.0), columns(0.0);
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                rows[i] += N(i, j, j);
                columns[j] += N(i, i, j);
            }
        packed.data.emplace_back(glm::vec3(rows), 0.0f);
        packed.data.emplace_back(glm::vec3(columns), 0.0f);
        float n[20] = {};
        for (int i = 0; i < 3; ++i)
            for (int pair = 0; pair < 6; ++pair) n[6 * i + pair] = float(N(i, kPairs[pair][0], kPairs[pair][1]));
        for (int v = 0; v < 5; ++v) packed.data.emplace_back(n[4 * v], n[4 * v + 1], n[4 * v + 2], n[4 * v + 3]);
        packed.data.emplace_back(permuted(node.chord ? node.from : glm::dvec3(0.0)), 0.0f);
        packed.data.emplace_back(permuted(node.chord ? node.to : glm::dvec3(0.0)), 0.0f);
    }
    return packed;
}

} // namespace vds::detail
