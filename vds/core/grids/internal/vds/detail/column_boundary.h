// vds internal: the generalized winding number's boundary term along one
// grid column, bracketed for the exact occupancy sweep (grids/occupancy.cpp).
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

#include <glm/vec3.hpp>

#include <vds/detail/antipodal.h>
#include <vds/detail/boundary_caps.h>
#include <vds/detail/pi.h>
#include <vds/detail/tree_walk.h>

namespace vds::detail {

// The boundary term along one grid column (x, y fixed, z the axis), split by
// monotony, for the generalized winding number's column sweep.
//
// Edge e's term is 2 atan2(det, den) with det = (u x v)_z, u = a - q,
// v = b - q: det does not depend on q's z, and den = g(u) g(v) + u_x v_x +
// u_y v_y with g(w) = |w| + w_z. As q rises, w_z = a_z - q_z falls and g
// (derivative w_z / |w| + 1 >= 0 in w_z) falls with it, so den falls; with
// det > 0 the angle atan2(det, den) rises as den falls, with det < 0 it
// falls. So B+(z), the sum over the edges with det > 0, is non-decreasing
// in z, B-(z), the rest, non-increasing, and on [z0, z1]
//
//     B+(z0) + B-(z1) <= B(z) <= B+(z1) + B-(z0).
//
// Edges with det = 0 whose projection the column meets (u_x v_x + u_y v_y
// <= 0: over the edge, or through an end) step at one depth by the tie
// rule; columns with such an edge are labelled cell by cell instead, and so
// are runs whose ends the column passes almost over an edge (see `at`).
//
// With the boundary's chain tree (boundary_caps.h), a node whose ball the
// column passes beside (at every depth, so its fan's crossing count is 0)
// stands for its edges by its chord, an edge like the others, and its fan,
// taken by expansion: F(z), within the expansions' bounds E of the fans'
// own, which move by at most G a unit of depth. On [z0, z1] (length L)
// then, for the fans' part,
//
//     (F(z0) + F(z1)) / 2 - E - G L / 2 <= . <= (F(z0) + F(z1)) / 2 + E + G L / 2,
//
// so a split costs the column's cut (chords and fans where the boundary is
// far, edges where it is near), not every edge.
/// The far nodes' fans along one column (x, y): each node's first-order
/// expansion (firstOrderSolidAngle) is, at depth z, with w = c_z - z,
///
///     (A . y + trace - 3 y M y / d^2) / d^3,   d^2 = r^2 + w^2,
///
/// y = c - q, r the column's distance from c; A . y and y M y are a line
/// and a parabola in w whose coefficients depend on the column alone. So
/// the column's nodes are set up once (add) as those coefficients, a field
/// a vector, and a depth costs a few multiplies, a square root and a
/// division a node, over every node at once (sum: no pointer chasing, no
/// branch; cloned for AVX2).
class ColumnFans {
public:
    void clear() {
        for (std::vector<double>* v : {&cz_, &r2_, &c0_, &c1_, &m0_, &m1_, &m2_}) v->clear();
    }
    std::size_t size() const { return cz_.size(); }
    void add(const detail::CapsNode& n, double x, double y) {
        const double ux = n.centre.x - x, uy = n.centre.y - y;
        const std::array<double, 9>& m = n.moment;
        cz_.push_back(n.centre.z);
        r2_.push_back(ux * ux + uy * uy);
        c0_.push_back(n.vectorArea.x * ux + n.vectorArea.y * uy + n.trace);
        c1_.push_back(n.vectorArea.z);
        m0_.push_back(3.0 * (m[0] * ux * ux + (m[1] + m[3]) * ux * uy + m[4] * uy * uy));
        m1_.push_back(3.0 * ((m[2] + m[6]) * ux + (m[5] + m[7]) * uy));
        m2_.push_back(3.0 * m[8]);
    }
    /// The nodes' first-order solid angles summed at depth z.
    VDS_EDGE_CLONES double sum(double z) const {
        const double *__restrict cz = cz_.data(), *r2 = r2_.data(), *c0 = c0_.data(), *c1 = c1_.data(),
                                 *m0 = m0_.data(), *m1 = m1_.data(), *m2 = m2_.data();
        double total = 0.0;
        for (std::size_t k = 0; k < cz_.size(); ++k) {
            const double w = cz[k] - z, d2 = r2[k] + w * w, inv2 = 1.0 / d2;
            total += (c0[k] + c1[k] * w - (m0[k] + (m1[k] + m2[k] * w) * w) * inv2) * inv2 / std::sqrt(d2);
        }
        return total;
    }

private:
    std::vector<double> cz_, r2_, c0_, c1_, m0_, m1_, m2_;
};

/// The boundary term at one depth of a column, split as ColumnBoundary
/// brackets it.
struct Split {
    double up = 0.0, down = 0.0, smooth = 0.0;
};

class ColumnBoundary {
public:
    /// The column's terms: with `caps` (closed loops), by its chain tree
    /// (see the comment above `at`), else every edge. False when the column
    /// meets an edge's projection (no bracket).
    bool reset(const std::vector<glm::vec3>& edges, const detail::BoundaryCaps* caps, double x, double y,
               double height) {
        ups_.clear();
        downs_.clear();
        far_.clear();
        error_ = 0.0;
        drift_ = 0.0;
        x_ = x;
        y_ = y;
        if (caps == nullptr || caps->chains().empty()) {
            for (std::size_t k = 0; k + 1 < edges.size(); k += 2)
                if (!addEdge(glm::dvec3(edges[k]), glm::dvec3(edges[k + 1]))) return false;
            return true;
        }
        const std::vector<detail::BoundaryCaps::ChainNode>& nodes = caps->chains();
        const std::vector<glm::vec3>& loopEdges = caps->loopEdges();
        const bool bracketed = detail::walkTree(0, [&](std::uint32_t index, detail::TreeStack& stack) {
            const detail::BoundaryCaps::ChainNode& n = nodes[index];
            const double dx = n.centre.x - x, dy = n.centre.y - y;
            const double rho = std::sqrt(dx * dx + dy * dy), e = rho - n.radius * (1.0 + 1e-12);
            if (e > 0.0) {
                // The column passes beside the ball at every depth: the
                // fan's crossing count is 0 all along, its expansion errs
                // by at most the bound at the closest approach, and its
                // solid angle moves by at most 2 area / e^3 a unit of depth
                // (the gradient of n . (x - q) / |x - q|^3 has norm at most
                // 2 / |x - q|^3).
                const double bound = detail::firstOrderBound(n, n.radius * (1.0 + 1e-12) + e);
                const double drift = 2.0 * n.area / (e * e * e) / kFourPi;
                if (bound <= kFarBound && drift * height <= kFarDrift) {
                    far_.add(n, x, y);
                    error_ += bound;
                    drift_ += drift;
                    return !n.chord || addEdge(n.from, n.to);
                }
            }
            if (n.count == 0) {
                stack.push(n.left);
                stack.push(n.right);
                return true;
            }
            for (std::uint32_t k = n.first; k < n.first + n.count; ++k)
                if (!addEdge(glm::dvec3(loopEdges[2 * k]), glm::dvec3(loopEdges[2 * k + 1]))) return false;
            return true;
        });
        if (!bracketed) return false;
        // The expansions' bounds, and rounding: the fans' float sums.
        error_ = error_ * (1.0 + 1e-9) + 1e-12 * double(far_.size());
        return true;
    }

    /// B at depth z as (B+, B-, F): B+ non-decreasing, B- non-increasing
    /// in z, F the far nodes' fans by expansion, within `error()` of
    /// theirs, which move by at most `drift()` a unit of depth; each over
    /// 4 pi. False where some edge's angle is ill-conditioned there (its
    /// denominator cancelling to within 1e-6 of its parts: the column
    /// passes almost over the edge).
    ///
    /// Without an atan2 per edge: the angles of one sign are summed as the
    /// argument of the product of the complex numbers den + i |det|, each
    /// in (0, pi) (AngleProduct, its turns counted; the column's edges
    /// of each sign are kept apart, as det's sign is the column's). The
    /// factors are found a block of edges at a time, with no branch on the
    /// edge (columnFactors). The
    /// products err by some 1e-16 an edge relative, so the sums stay well
    /// within kBracketSlack.
    bool at(double z, Split& split) const {
        // Two products a sign, alternating, so that consecutive multiplies
        // do not wait on each other.
        detail::AngleProduct up[2], down[2];
        if (!product(ups_, z, up) || !product(downs_, z, down)) return false;
        const double fans = far_.sum(z);
        // Each edge adds 2 atan2(det, den); over 4 pi.
        split.up = (up[0].angle() + up[1].angle()) / (2.0 * kPi);
        split.down = -(down[0].angle() + down[1].angle()) / (2.0 * kPi);
        split.smooth = -fans / kFourPi;
        return true;
    }
    double error() const { return error_; }
    double drift() const { return drift_; }

private:
    /// A node is taken by its fan's expansion where that errs by at most
    /// this anywhere along the column,
    static constexpr double kFarBound = 1e-4;
    /// and its fan's solid angle (over 4 pi) moves by at most this over the
    /// column's height; else its edges or children are taken (tuning:
    /// docs/benchmarks.md).
    static constexpr double kFarDrift = 1.0;
    static constexpr std::size_t kBlock = 16;
    /// The column's edges, a field a vector (so that a block of them loads
    /// as vectors): ends a, b less the column's (x, y), their depths, the
    /// cross product det (the edge's turn about the column, never 0) and
    /// dot product `across` of their (x, y) parts.
    struct Terms {
        std::vector<double> ux, uy, vx, vy, az, bz, det, across;
        std::size_t size() const { return ux.size(); }
        void clear() {
            for (std::vector<double>* v : {&ux, &uy, &vx, &vy, &az, &bz, &det, &across}) v->clear();
        }
    };
    /// Edges first .. first + n - 1 of `terms` at depth z: each edge's den +
    /// i det (EdgeAngles' factor, both times the positive du dv that
    /// apex's division would take) scaled to |x| + |y| = 1. False where
    /// some edge's denominator cancels to within 1e-6 of its parts.
    VDS_EDGE_CLONES static bool columnFactors(const Terms& terms, std::size_t first, std::size_t n, double z,
                                              double* __restrict xs, double* __restrict ys) {
        // Whether each edge's denominator cancels, as a double a lane (an
        // int reduction of double compares would keep the loop scalar).
        alignas(64) double cancels[kBlock];
        const double *__restrict ux = terms.ux.data() + first, *uy = terms.uy.data() + first, *vx = terms.vx.data() + first,
                     *vy = terms.vy.data() + first, *az = terms.az.data() + first, *bz = terms.bz.data() + first,
                     *det = terms.det.data() + first, *across = terms.across.data() + first;
        for (std::size_t j = 0; j < n; ++j) {
            // apex(w) = |w| + w_z = nw / dw: w_z >= 0: (|w| + w_z) / 1, else
            // rho^2 / (|w| + |w_z|).
            const double uz = az[j] - z, vz = bz[j] - z;
            const double ru = ux[j] * ux[j] + uy[j] * uy[j], rv = vx[j] * vx[j] + vy[j] * vy[j];
            const double mu = std::sqrt(ru + uz * uz) + std::fabs(uz), mv = std::sqrt(rv + vz * vz) + std::fabs(vz);
            double nu = ru, du = mu, nv = rv, dv = mv;
            if (uz >= 0.0) {
                nu = mu;
                du = 1.0;
            }
            if (vz >= 0.0) {
                nv = mv;
                dv = 1.0;
            }
            const double scale = du * dv, product = nu * nv, along = across[j] * scale;
            const double den = product + along, turn = det[j] * scale, size = std::fabs(den) + std::fabs(turn);
            cancels[j] = across[j] < 0.0 && size < 1e-6 * (product - along) ? 1.0 : 0.0;
            const double inv = 1.0 / size;
            xs[j] = den * inv;
            ys[j] = turn * inv;
        }
        for (std::size_t j = 0; j < n; ++j)
            if (cancels[j] != 0.0) return false;
        return true;
    }
    /// The angles of `terms` (all of one sign: det's, |det| taken) at depth
    /// z multiplied into `sums` (two products, alternating, so that
    /// consecutive multiplies do not wait on each other); false where some
    /// edge's denominator cancels (see columnFactors).
    static bool product(const Terms& terms, double z, detail::AngleProduct (&sums)[2]) {
        alignas(64) double xs[kBlock], ys[kBlock];
        const std::size_t count = terms.size();
        for (std::size_t first = 0; first < count; first += kBlock) {
            const std::size_t n = std::min(kBlock, count - first);
            if (!columnFactors(terms, first, n, z, xs, ys)) return false;
            std::size_t j = 0;
            for (; j + 1 < n; j += 2) {
                sums[0].add(xs[j], std::fabs(ys[j]));
                sums[1].add(xs[j + 1], std::fabs(ys[j + 1]));
            }
            if (j < n) sums[0].add(xs[j], std::fabs(ys[j]));
            // At most 32 factors a product between rescales.
            if ((first / kBlock) % 4 == 3) {
                sums[0].rescale();
                sums[1].rescale();
            }
        }
        return true;
    }
    /// Adds edge a -> b; false where its projection meets the column.
    bool addEdge(const glm::dvec3& a, const glm::dvec3& b) {
        const double ux = a.x - x_, uy = a.y - y_, vx = b.x - x_, vy = b.y - y_;
        const double det = ux * vy - uy * vx, across = ux * vx + uy * vy;
        if (det == 0.0) return across > 0.0; // else adds 0 all along the column
        // The sign of det, so of the edge's angle, is the column's: the
        // edges of each sign kept apart.
        Terms& terms = det > 0.0 ? ups_ : downs_;
        terms.ux.push_back(ux);
        terms.uy.push_back(uy);
        terms.vx.push_back(vx);
        terms.vy.push_back(vy);
        terms.az.push_back(a.z);
        terms.bz.push_back(b.z);
        terms.det.push_back(det);
        terms.across.push_back(across);
        return true;
    }
    Terms ups_, downs_; ///< the column's edges with det > 0, det < 0
    ColumnFans far_;
    double error_ = 0.0, drift_ = 0.0, x_ = 0.0, y_ = 0.0;
};

} // namespace vds::detail
