// vds internal: what the parts of the winding engine (boundary_caps.h)
// share: an estimate of the boundary term, the moments of a fan of
// triangles about a centre, a node's expansion to first and second order
// and the error factor of the first (of the second: chain_tree.h), the
// rounding slack of a grid's cells, and the constants more than one part
// bounds by.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <vds/detail/chain_tree.h>
#include <vds/detail/pi.h> // kPi, kFourPi

namespace vds::detail {

/// The boundary term B at a point and its error bound (CapsValueTree,
/// ChainLabels, BoundaryCaps).
struct CapsEstimate {
    double term = 0.0;  ///< B(q)
    double bound = 0.0; ///< |B(q) - exact| <= bound; +inf where q lies on a cap (use the exact sum)
    /// ChainLabels::decide: nodes taken and edges summed (the per-edge sum
    /// adds its edges), the cost in edges' angles of the per-edge sum.
    double work = 0.0;
};

} // namespace vds::detail

namespace vds::detail::caps {

constexpr std::uint32_t kLeafTriangles = 4;
/// Rounding slack on the estimate: the solid angles and the expansion are
/// summed in double, some 1e-15 each.
constexpr double kRoundingSlack = 1e-9;
/// A node to be opened that holds at most this many edges has them summed
/// at once: with the per-edge sum a block of edges per instruction
/// (EdgeAngles), 16 edges cost about as much as two nodes taken (tuning:
/// docs/benchmarks.md).
constexpr std::uint32_t kDirectEdges = 16;

struct Moments {
    glm::dvec3 vectorArea{0.0};
    std::array<double, 9> moment{};
    std::array<double, 18> quadrupole{}; ///< N_ijk, see Node::quadrupole
    double area = 0.0;
    double second = 0.0; ///< S: the integral of |x - centre|^2 dA
};


// Sum over triangles of their vector areas, first and second moments about
// `centre` and unsigned areas. A flat triangle's integral of (x - c)(x - c)^T
// is its area / 12 times (sum of v v^T over its corners v, taken from c,
// plus s s^T, s the sum of the corners).
template <class Tris>
inline Moments momentsOf(const Tris& tris, std::size_t first, std::size_t last, const glm::dvec3& centre) {
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
// costs about as much again as the rest), values to second order (their
// tolerance is tight; docs/benchmarks.md).
inline double firstOrderFactor(double d, double e) { return (d + 2.0 * e) / (3.0 * d * d * d * e * e); }

/// A surface's integral of n . (x - q) / |x - q|^3 dA by its expansion to
/// first order about c, at y = c - q (|y| = d): vector area A, first
/// moments M_ij (row-major) and their trace.
inline double firstOrderTerm(const glm::dvec3& vectorArea, const std::array<double, 9>& M, double trace,
                             const glm::dvec3& y, double d2, double d) {
    const double inv2 = 1.0 / d2, inv3 = inv2 / d;
    const double yMy = y.x * (M[0] * y.x + M[1] * y.y + M[2] * y.z) + y.y * (M[3] * y.x + M[4] * y.y + M[5] * y.z) +
                       y.z * (M[6] * y.x + M[7] * y.y + M[8] * y.z);
    return (vectorArea.x * y.x + vectorArea.y * y.y + vectorArea.z * y.z + trace - 3.0 * yMy * inv2) * inv3;
}

/// A node's surface integral by the expansion to first order.
inline double firstOrderTerm(const CapsNode& n, const glm::dvec3& y, double d2, double d) {
    return firstOrderTerm(n.vectorArea, n.moment, n.trace, y, d2, d);
}

/// A node's integral of n . (x - q) / |x - q|^3 dA by its Taylor expansion
/// about its centre to second order, at y = c - q (|y| = d): with
/// K_i(y) = y_i / d^3, the terms are A . K, M_ij dK_i/dy_j and
/// N_ijk d2K_i/dy_j dy_k / 2, where dK_i/dy_j = delta_ij / d^3 - 3 y_i y_j / d^5
/// and d2K_i/dy_j dy_k = -3 (delta_ij y_k + delta_ik y_j + delta_jk y_i) / d^5
/// + 15 y_i y_j y_k / d^7. Inline: taken once a node by the walks of the
/// labels and values.
inline double secondOrderTerm(const CapsNode& n, const glm::dvec3& y, double d2, double d) {
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
    return firstOrderTerm(n, y, d2, d) + second * inv3;
}

/// A node's moments of a fan, and the scale of its error bounds.
inline void setMoments(CapsNode& node, const Moments& m) {
    node.vectorArea = m.vectorArea;
    node.moment = m.moment;
    node.quadrupole = m.quadrupole;
    node.errorScale = 3.0 * m.second / kFourPi;
    node.area = m.area;
}

/// The sums a node's expansion reads, from its moments: the trace of M and
/// the row and column sums of N.
inline void finishNode(CapsNode& node) {
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

/// The slack a grid's cells are widened by against the rounding of a
/// point's cell index, for a grid of extent `extent`: 1e-7 of its longest
/// side (an index is found to a few ulps of a float).
inline double cellSlack(const glm::dvec3& extent) { return 1e-7 * std::max({extent.x, extent.y, extent.z}); }

} // namespace vds::detail::caps

namespace vds::detail {

/// A node's fan's solid angle seen from q by its expansion to first order
/// (over 4 pi: in B's units, as the bound below).
inline double firstOrderSolidAngle(const CapsNode& n, const glm::dvec3& q) {
    const glm::dvec3 y = n.centre - q;
    const double d2 = y.x * y.x + y.y * y.y + y.z * y.z;
    return caps::firstOrderTerm(n, y, d2, std::sqrt(d2));
}

/// The bound on firstOrderSolidAngle's error at distance `distance` >
/// radius from the node's centre, which falls as the distance grows.
inline double firstOrderBound(const CapsNode& n, double distance) {
    return n.errorScale * caps::firstOrderFactor(distance, distance - n.radius);
}

} // namespace vds::detail
