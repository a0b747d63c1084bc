// vds internal: what the parts of the winding engine (caps_tree.h) share:
// the moments of a fan of triangles about a centre, the error factor of
// their expansion to first order (to second: chain_tree.h), and the
// constants more than one part bounds by.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <vds/detail/chain_tree.h>
#include <vds/detail/pi.h> // kPi, kFourPi

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

} // namespace vds::detail::caps
