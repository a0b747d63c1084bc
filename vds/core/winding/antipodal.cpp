// vds: the boundary term of the Antipodal split of the generalized winding
// number (Martens, Trettner & Bessmeltsev, SIGGRAPH 2026, arXiv 2605.01536),
// for sprites, the exact classifier and the voxelizers; see antipodal.h.
#include <vds/detail/antipodal.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstring>
#include <memory>
#include <numeric>
#include <string>

#include <glm/geometric.hpp>

#include <vds/detail/position_weld.h>

#include <vds/error.h>
#include <vds/detail/parallel.h>
#include <vds/detail/pi.h>


namespace vds::detail {

std::vector<glm::vec3> boundaryEdges(MeshView mesh) {
    std::vector<glm::vec3> where;
    const std::vector<std::uint32_t> id = weldPositions(mesh.positions, mesh.positionCount, where);
    // Each edge's uses by its lower id (a counting sort), as (higher id,
    // +1 for low->high or -1 for high->low); a vertex's few uses sorted by
    // the higher id, the net use of each edge is one run's sum, in the order
    // of (low, high).
    const std::size_t ids = where.size();
    std::vector<std::uint32_t> start(ids + 1, 0);
    const auto each = [&](const auto& use) {
        for (std::size_t k = 0; k < mesh.triangleCount; ++k)
            for (int e = 0; e < 3; ++e) {
                const std::uint32_t a = id[mesh.triangles[k][e]], b = id[mesh.triangles[k][(e + 1) % 3]];
                if (a != b) use(std::min(a, b), std::max(a, b), a < b ? 1 : -1);
            }
    };
    each([&](std::uint32_t lo, std::uint32_t, int) { ++start[lo + 1]; });
    std::partial_sum(start.begin(), start.end(), start.begin());
    std::vector<std::pair<std::uint32_t, int>> uses(start.back());
    std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
    each([&](std::uint32_t lo, std::uint32_t hi, int sign) { uses[fill[lo]++] = {hi, sign}; });
    std::vector<glm::vec3> edges;
    for (std::uint32_t lo = 0; lo < ids; ++lo) {
        const auto first = uses.begin() + start[lo], last = uses.begin() + start[lo + 1];
        std::sort(first, last, [](const auto& x, const auto& y) { return x.first < y.first; });
        for (auto run = first; run != last;) {
            int net = 0;
            auto end = run;
            for (; end != last && end->first == run->first; ++end) net += end->second;
            const glm::vec3 a = where[lo], b = where[run->first];
            for (int m = 0; m < std::abs(net); ++m) {
                edges.push_back(net > 0 ? a : b);
                edges.push_back(net > 0 ? b : a);
            }
            run = end;
        }
    }
    return edges;
}

double edgeSolidAngle(int axis, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& q) {
    // axisPermutation(Axis(axis)), inline: this runs once per edge and point.
    const glm::ivec3 p((axis + 1) % 3, (axis + 2) % 3, axis);
    // Float ends and point: these differences are exact in double, so the
    // tests for zero below are exact.
    const glm::dvec3 u = a - q, v = b - q;
    // An end exactly on q's ray (straight in front of q along -axis): the
    // spherical triangle has a vertex at the antipode of the apex, where it
    // is not defined. Take the limit at q moved by (eps, -eps^2) in (s, t),
    // the integer term's tie rule: with u = (0, 0, -h), to first order in
    // eps det = -eps v_t and den = -eps v_s (u', v' the moved vectors; the
    // (|u'| + u'_r) factor is O(eps^2)), so the angle is 2 atan2(-v_t, -v_s);
    // with v on the ray, det = eps u_t and den = -eps u_s. Where the leading
    // det vanishes the eps^2 term (-eps^2 v_s, eps^2 u_s) has the sign of the
    // +0.0 or -0.0 passed to atan2. An edge along q's line adds 0.
    const bool uOnRay = u[p.x] == 0.0 && u[p.y] == 0.0 && u[axis] < 0.0;
    const bool vOnRay = v[p.x] == 0.0 && v[p.y] == 0.0 && v[axis] < 0.0;
    if (uOnRay || vOnRay) {
        const glm::dvec3& other = uOnRay ? v : u;
        if (other[p.x] == 0.0 && other[p.y] == 0.0) return 0.0; // the edge lies along q's line
        return uOnRay ? 2.0 * std::atan2(-v[p.y], -v[p.x]) : 2.0 * std::atan2(u[p.y], -u[p.x]);
    }
    const double lu = glm::length(u), lv = glm::length(v);
    // With w = +axis: det = (u x v) . axis, the cross product across the axis.
    const double det = u[p.x] * v[p.y] - u[p.y] * v[p.x];
    // Van Oosterom & Strackee's denominator |u||v| + u.v + u_r |v| + v_r |u|
    // is (|u| + u_r)(|v| + v_r) + u_s v_s + u_t v_t. Near q's ray (u_r close
    // to -|u|) the factor |u| + u_r cancels; there it is taken as the equal
    // rho^2 / (|u| - u_r), rho^2 = u_s^2 + u_t^2, which does not: so that an
    // edge seen almost straight along the ray still gets its angle to
    // rounding, not to the square root of it.
    const auto towardsApex = [&](const glm::dvec3& w, double length) {
        return w[axis] >= 0.0 ? length + w[axis] : (w[p.x] * w[p.x] + w[p.y] * w[p.y]) / (length - w[axis]);
    };
    const double den = towardsApex(u, lu) * towardsApex(v, lv) + u[p.x] * v[p.x] + u[p.y] * v[p.y];
    if (det == 0.0 && den < 0.0) {
        // q exactly on the edge's sweep (its ray passes over the edge), where
        // the term jumps by 4 pi: take the side of q moved by (eps, -eps^2)
        // in (s, t), as the integer term's tie rule does, so that the two
        // jumps still cancel. There det = eps (u - v)_t + eps^2 (u - v)_s +
        // O(eps^3) -> 0 with that sign while den stays negative: the angle
        // is +-2 pi.
        const glm::dvec3 d = a - b;
        const double side = d[p.y] != 0.0 ? d[p.y] : d[p.x];
        if (side == 0.0) return 0.0; // an edge along the axis
        return side > 0.0 ? 2.0 * kPi : -2.0 * kPi;
    }
    return 2.0 * std::atan2(det, den);
}

namespace {
constexpr std::size_t kEdgeBlock = 16;

/// Edges [first, first + n)'s ends less q, by coordinate (s, t, then the
/// axis: S, T, A), into a block's arrays. The coordinates known when
/// compiled, so that the compiler loads several edges an instruction;
/// inlined into each build of EdgeAngles::add, for its instructions.
template <int S, int T, int A>
__attribute__((always_inline)) inline void edgeEnds(const glm::vec3* edges, std::size_t first, std::size_t n,
                                                    const glm::dvec3& q, double* us, double* ut, double* ua, double* vs,
                                                    double* vt, double* va) {
    const double qs = q[S], qt = q[T], qa = q[A];
    for (std::size_t j = 0; j < n; ++j) {
        const glm::vec3& a = edges[2 * (first + j)];
        const glm::vec3& b = edges[2 * (first + j) + 1];
        // Float ends and point: the differences are exact in double.
        us[j] = double(a[S]) - qs;
        ut[j] = double(a[T]) - qt;
        ua[j] = double(a[A]) - qa;
        vs[j] = double(b[S]) - qs;
        vt[j] = double(b[T]) - qt;
        va[j] = double(b[A]) - qa;
    }
}
} // namespace


VDS_EDGE_CLONES void EdgeAngles::add(const glm::vec3* edges, std::size_t count, int axis, const glm::dvec3& q) {
    alignas(64) double us[kEdgeBlock], ut[kEdgeBlock], ua[kEdgeBlock], vs[kEdgeBlock], vt[kEdgeBlock],
        va[kEdgeBlock], xs[kEdgeBlock], ys[kEdgeBlock], dets[kEdgeBlock];
    for (std::size_t first = 0; first < count; first += kEdgeBlock) {
        const std::size_t n = std::min(kEdgeBlock, count - first);
        switch (axis) {
        case 0: edgeEnds<1, 2, 0>(edges, first, n, q, us, ut, ua, vs, vt, va); break;
        case 1: edgeEnds<2, 0, 1>(edges, first, n, q, us, ut, ua, vs, vt, va); break;
        default: edgeEnds<0, 1, 2>(edges, first, n, q, us, ut, ua, vs, vt, va); break;
        }
        for (std::size_t j = 0; j < n; ++j) {
            // den + i det, both times du dv > 0 (the same angle):
            // |u| + u_r = nu / du is lu + ua (ua >= 0) or
            // rho_u^2 / (lu - ua) = rho_u^2 / (lu + |ua|) (ua < 0).
            const double ru = us[j] * us[j] + ut[j] * ut[j], rv = vs[j] * vs[j] + vt[j] * vt[j];
            const double lu = std::sqrt(ru + ua[j] * ua[j]), lv = std::sqrt(rv + va[j] * va[j]);
            const double mu = lu + std::fabs(ua[j]), mv = lv + std::fabs(va[j]);
            double nu = ru, du = mu, nv = rv, dv = mv;
            if (ua[j] >= 0.0) {
                nu = mu;
                du = 1.0;
            }
            if (va[j] >= 0.0) {
                nv = mv;
                dv = 1.0;
            }
            const double det = us[j] * vt[j] - ut[j] * vs[j], scale = du * dv;
            const double den = nu * nv + (us[j] * vs[j] + ut[j] * vt[j]) * scale, across = det * scale;
            // Scaled to |x| + |y| = 1 (the angle is unchanged), so that the
            // products stay within (1/sqrt 2)^n of 1.
            const double inv = 1.0 / (std::fabs(den) + std::fabs(across));
            xs[j] = den * inv;
            ys[j] = across * inv;
            dets[j] = det;
        }
        bool whole = n == kEdgeBlock;
        for (std::size_t j = 0; j < n; ++j) whole &= dets[j] != 0.0;
        if (whole) {
            // The four products side by side (AngleLanes: products 0 and 1,
            // 2 and 3), lane l taking edges l, l + 4, ...
            AngleLanes low(products_[0], products_[1]), high(products_[2], products_[3]);
            for (std::size_t j = 0; j < kEdgeBlock; j += 4) {
                low.add(xs + j, ys + j);
                high.add(xs + j + 2, ys + j + 2);
            }
            low.store(products_[0], products_[1]);
            high.store(products_[2], products_[3]);
        } else {
            for (std::size_t j = 0; j < n; ++j) {
                if (dets[j] != 0.0) {
                    products_[j & 3].add(xs[j], ys[j]);
                } else {
                    const std::size_t k = first + j;
                    apart_ += edgeSolidAngle(axis, glm::dvec3(edges[2 * k]), glm::dvec3(edges[2 * k + 1]), q);
                }
            }
        }
        // Back to size 1 (the angles are unchanged) before a product of up
        // to 64 factors, each at least 1/sqrt 2 in size, could underflow.
        if (++blocks_ == 16) {
            for (AngleProduct& p : products_) p.rescale();
            blocks_ = 0;
        }
    }
}

double EdgeAngles::angle() const {
    // The four products multiplied into one (each rescaled first; a
    // product on the real axis, which add() cannot take, by its own
    // atan2), then one atan2. Each edge adds 2 atan2(det, den).
    AngleProduct all = products_[0];
    double rest = 0.0;
    for (int k = 1; k < 4; ++k) {
        AngleProduct p = products_[k];
        all.turns += p.turns;
        if (p.im == 0.0) {
            rest += std::atan2(p.im, p.re);
            continue;
        }
        p.rescale();
        all.rescale();
        all.add(p.re, p.im);
    }
    return 2.0 * (std::atan2(all.im, all.re) + 2.0 * kPi * all.turns + rest) + apart_;
}

double boundaryTermExact(const glm::vec3* edges, std::size_t edgeCount, int axis, const glm::dvec3& q) {
    EdgeAngles sum;
    sum.add(edges, edgeCount, axis, q);
    return sum.angle() / kFourPi;
}

} // namespace vds::detail

namespace vds {

std::vector<glm::vec3> meshBoundaryEdges(MeshView mesh) { return detail::boundaryEdges(mesh); }

} // namespace vds
