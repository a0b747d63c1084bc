// vds internal: the boundary term of the Antipodal split of the generalized
// winding number (Martens, Trettner & Bessmeltsev 2026), shared by the exact
// classifier, sprites and the voxelizers (the per-edge sum: the reference;
// boundary_caps.h makes it fast).
//
// GWN(q) = integer term + boundary term. The integer term is the signed
// count of surface crossings on the ray from q towards -axis (what a
// sprite's column and the exact classifier count). The boundary term sums,
// over the boundary edges a -> b, the signed solid angle of the spherical
// triangle (+axis, a - q, b - q), over 4 pi. It is smooth except on the
// boundary curve and on the curve's sweep towards +axis (the points whose
// ray towards -axis passes over the curve), where it jumps by -+1 exactly
// as the integer term jumps by +-1.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <vds/detail/solid_angle.h>
#include <vds/mesh.h>
#include <vds/detail/pi.h>
#include <vds/rule.h>

namespace vds::detail {

/// The mesh's boundary edges as endpoint pairs: edge k runs from `[2k]` to
/// `[2k+1]`. Edges whose uses do not cancel after welding vertices with
/// equal positions (by value: -0 and +0 alike); an edge used n times more one way than the
/// other appears |n| times, oriented as the majority of its uses run (so
/// non-manifold edges count by their unbalanced orientation).
std::vector<glm::vec3> boundaryEdges(MeshView mesh);

// solidAngle(u, v, w): <vds/detail/solid_angle.h>, shared with the contract's validation.

/// One edge's solid angle (+axis, a - q, b - q). On the edge's sweep, where
/// it jumps, it takes the side of the integer term's tie rule (q moved by
/// (eps, -eps^2) in the texture's (s, t)), so that a ray exactly over the
/// boundary still gets a consistent sum; an edge along the axis adds 0.
double edgeSolidAngle(int axis, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& q);

// On x86-64 with GCC, the loops that find many edges' angles at once
// (EdgeAngles::add, the column sweep's) are built twice, for AVX2 (four
// edges an instruction) and for the baseline (two), and the loader picks
// the one the machine runs (docs/benchmarks.md). The same IEEE operations either way (no fused
// multiply-add: -ffp-contract=off), so the same values.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__linux__)
#define VDS_EDGE_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define VDS_EDGE_CLONES
#endif

/// A running product re + i im of factors x + i y, each |x| + |y| = 1
/// (an angle in (-pi, pi), the argument of x + i y, without an atan2
/// each): its argument atan2(im, re) plus 2 pi turns is the angles' sum. A
/// step with y > 0 (an angle in (0, pi)) that takes the product from
/// Im >= 0 to Im < 0 crossed the negative real axis (a step of less than pi
/// crosses from above only there; both right of the imaginary axis is the
/// rounding of a step at +0); y < 0 alike, from below; y = 0, x = 1 leaves
/// it as it is. "Im >= 0" is its sign bit clear, as atan2 reads +0 and -0.
/// No branch on the factor. Each multiply errs by some 1e-16 relative, so
/// n angles sum to within some n * 1e-16 of their atan2s' sum; rescale()
/// (the angle unchanged) before some 64 factors, each at least 1/sqrt 2
/// in size, could underflow the product.
struct AngleProduct {
    double re = 1.0, im = 0.0;
    int turns = 0;
    void add(double x, double y) {
        const double r = re * x - im * y, i = re * y + im * x;
        const bool left = (re < 0.0) | (r < 0.0);
        const bool above = !std::signbit(im), after = !std::signbit(i);
        turns += int((y > 0.0) & above & !after & left) - int((y < 0.0) & !above & after & left);
        re = r;
        im = i;
    }
    void rescale() {
        const double size = std::fabs(re) + std::fabs(im);
        re /= size;
        im /= size;
    }
    double angle() const { return std::atan2(im, re) + 2.0 * kPi * turns; }
};

/// Two AngleProducts side by side, a lane each (GCC's vectors: SSE2's
/// width, which an AVX2 build merges two at a time), each lane's steps
/// exactly AngleProduct::add's, so the same values. Inlined into the
/// builds of the loops that use it (VDS_EDGE_CLONES), for their
/// instructions.
struct AngleLanes {
    typedef double Lanes __attribute__((vector_size(16)));
    typedef std::int64_t Masks __attribute__((vector_size(16)));
    Lanes re, im;
    Masks turns;
    AngleLanes(const AngleProduct& a, const AngleProduct& b) : re{a.re, b.re}, im{a.im, b.im}, turns{0, 0} {}
    /// Factor x[l] + i y[l] into lane l.
    __attribute__((always_inline)) void add(const double* x2, const double* y2) {
        Lanes x, y;
        std::memcpy(&x, x2, sizeof x);
        std::memcpy(&y, y2, sizeof y);
        const Lanes zero = {0.0, 0.0};
        const Masks none = {0, 0};
        const Lanes r = re * x - im * y, i = re * y + im * x;
        Masks imBits, iBits;
        std::memcpy(&imBits, &im, sizeof imBits);
        std::memcpy(&iBits, &i, sizeof iBits);
        // Masks are -1 (true) or 0: left, above = !signbit(im), after =
        // !signbit(i); a turn up where y > 0, above, not after, left; down
        // where y < 0, not above, after, left.
        const Masks left = (re < zero) | (r < zero);
        const Masks above = imBits >= none, after = iBits >= none;
        turns -= (y > zero) & above & ~after & left; // -(-1): +1
        turns += (y < zero) & ~above & after & left;
        re = r;
        im = i;
    }
    /// Back into the products (their turns added to).
    void store(AngleProduct& a, AngleProduct& b) const {
        a.re = re[0];
        a.im = im[0];
        a.turns += int(turns[0]);
        b.re = re[1];
        b.im = im[1];
        b.turns += int(turns[1]);
    }
};

/// A sum of edge angles (+axis, a - q, b - q) as the per-edge sum takes
/// them: each edge's angle is twice the argument of den + i det, Van
/// Oosterom & Strackee's (edgeSolidAngle: den = (|u| + u_r)(|v| + v_r) +
/// u_s v_s + u_t v_t, the factor |u| + u_r taken as rho^2 / (|u| - u_r)
/// where u_r < 0, so that it does not cancel), scaled to |x| + |y| = 1 so
/// that products of many stay in range, and multiplied into one of four
/// running products, their turns counted, one atan2 at the end. The
/// factors are found a block of edges at a time with no branch on the
/// edge (|u| + u_r's two forms selected, the division folded into the
/// scale both parts share), so that the compiler takes several edges per
/// instruction; the products then wait only on each other. An edge with
/// det = 0 (q on its sweep, an end on q's ray) is taken by edgeSolidAngle.
/// Each multiply errs by some 1e-16 relative, so n edges sum to within
/// some n * 1e-16 of their atan2s' sum.
class EdgeAngles {
public:
    /// Adds the angles of edges 0 .. count - 1 of `edges` (2 points each,
    /// edge k from [2k] to [2k + 1]), seen from q, `axis` the view axis.
    void add(const glm::vec3* edges, std::size_t count, int axis, const glm::dvec3& q);
    /// The edges' angles summed (each 2 atan2(det, den)), in radians.
    double angle() const;

private:
    AngleProduct products_[4];
    double apart_ = 0.0;  ///< the edges with det = 0, by edgeSolidAngle
    unsigned blocks_ = 0; ///< blocks taken since the products were last rescaled
};

/// The boundary term at `q` by the per-edge sum: `edges` holds 2 *
/// `edgeCount` points (mesh coordinates), `axis` the index (0..2) of the
/// view axis. O(edgeCount): each edge's angle as `edgeSolidAngle` gives
/// it, summed by `EdgeAngles` (to some 1e-16 an edge).
double boundaryTermExact(const glm::vec3* edges, std::size_t edgeCount, int axis, const glm::dvec3& q);


/// Values within this of 1/2 are ties, and ties are outside. The per-edge
/// sum errs by some 1e-15 per edge, so a value this close to 1/2 cannot be
/// told from 1/2; and 1/2 is what a flat sheet's points have (seen from its
/// plane a flat sheet subtends a half sphere on one side and nothing on the
/// other; the tie rule takes one side): they lie on the surface, not inside.
using vds::kGeneralizedWindingTie; // <vds/rule.h>: one predicate, public for callers that show the values

/// The label of a generalized winding number computed by the per-edge sum.
using vds::generalizedWindingInside;

} // namespace vds::detail
