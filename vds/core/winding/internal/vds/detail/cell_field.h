// vds internal: the boundary term over one cell of the grids of bounds
// (bound_ranges.h) as the chain nodes near the cell's column, refined at
// each query (ChainLabels::refine), plus the rest interpolated from a
// lattice of its values with a bound on the error: the chain tree's far
// part, some half of a label's nodes, becomes a polynomial.
//
// Why the rest is smooth. B is the per-edge sum (antipodal.h): edge e's
// angle a_e is the solid angle of the strip swept from e towards +axis,
// over 4 pi, harmonic off that strip. Call an edge near where its
// projection along the axis comes within `margin` of the cell's footprint
// (at any height), and a chain node near where its ball's does: the
// tree is cut into far nodes and near ones (whole subtrees of near edges,
// split where no query in the cell could take them, as
// ChainLabels::frontier splits). Every far edge's strip keeps `margin`
// away from the cell, so S = sum of a_e over the far edges is harmonic
// over the cell, and
// B(q) = the near nodes' per-edge sum at q + S(q) exactly.
//
// S's derivatives. A strip's solid angle has as gradient the Biot-Savart
// integral over the strip's border: its edge and the two rays from its
// ends towards +axis (the top at infinity adds nothing). Along a loop the
// rays of consecutive far edges cancel, so S's gradient is the integral
// over the far edges and one ray at each vertex where the loop passes
// between a near and a far edge (a junction, `margin` from the footprint
// too). For a unit h, with (h . grad)^(k-1) 1/r = (k-1)! P_(k-1)(cos) / r^k
// up to sign and |grad (P_n(cos) / r^(n+1))| <= sqrt 2 (n + 1) / r^(n+2)
// (|sin P_n'(cos)| <= sqrt(n (n + 1))), the k-th derivative along h is
//
//     |D^k S [h, ..., h]| <= sqrt 2 k! / (4 pi) * integral of |dx| / r^(k+1)
//
// over those curves: an edge at distance d adds at most length / d^(k+1)
// (a far node small against its distance, its length / d^(k+1) with d
// its ball's), a ray at distance rho across the axis at most the
// integral over a whole line, pi / (2 rho^3) for k = 3.
//
// The interpolation. S is sampled at the 5 x 5 x 5 nodes of the cell
// (widened against the rounding of a point's cell index), s apart (a
// quarter of its side), and taken in each octant by the tensor product
// of quadratic interpolation along each axis at its 3 x 3 x 3 nodes.
// Along one axis quadratic interpolation at -s, 0, s errs by at most
// max|f'''| / 6 * max|x (x^2 - s^2)| = 0.0642 s^3 max|f'''|,
// and its Lebesgue constant is 5/4; the tensor product's error is at most
// e_1 + (5/4) e_2 + (5/4)^2 e_3 (f - IxIyIz f = (f - Ix f) + Ix (f - Iy f)
// + IxIy (f - Iz f)), and the samples' own errors (the chain tree's bound,
// ChainLabels::sumOver) add (5/4)^3 times their largest.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

namespace vds::detail {

class ChainLabels;

/// B over one box as its near chain nodes, refined at each query, plus
/// the rest interpolated. Built once (by one thread), then read only.
class CellField {
public:
    /// Over the box [lo, hi] (a cell, widened by its rounding slack), the
    /// near nodes those of `labels`' chain tree within `margin` of its
    /// footprint across the axis. False where the error would reach
    /// `limit`, the near nodes `nearLimit`, or the tree is empty.
    bool build(const ChainLabels& labels, const glm::dvec3& lo, const glm::dvec3& hi, double margin, double limit,
               std::size_t nearLimit);
    /// S(q) for q in the box, within error() of the far nodes' per-edge sum.
    double rest(const glm::vec3& q) const;
    double error() const { return error_; }
    /// What building it took, built or not: the chain nodes and edges its
    /// cut and bound visited, its samples' nodes taken and edges summed.
    double work() const { return work_; }
    /// The chain nodes whose edges are not in S (refine() from them).
    const std::vector<std::uint32_t>& nearNodes() const { return near_; }
    std::size_t memoryBytes() const { return sizeof(*this) + near_.capacity() * sizeof(std::uint32_t); }

private:
    /// The cut of the tree into near nodes (near_) and far ones (`far`).
    void split(const ChainLabels& labels, const glm::dvec3& lo, const glm::dvec3& hi, double margin,
               std::vector<std::uint32_t>& far);
    /// The bound on S's third derivative along any direction over the box,
    /// from the far nodes' edges and the junctions' rays.
    double thirdBound(const ChainLabels& labels, const std::vector<std::uint32_t>& far, const glm::dvec3& lo,
                      const glm::dvec3& hi);

    /// S at node (i, j, k) of the 5 x 5 x 5 lattice over the box, a
    /// quarter of its sides apart: [25 i + 5 j + k]. Each octant of the
    /// box takes its 3 x 3 x 3 nodes.
    std::array<double, 125> values_{};
    glm::dvec3 lo_{0.0};
    glm::dvec3 inverse_{0.0}; ///< 1 / the nodes' spacing
    double error_ = 0.0;
    double work_ = 0.0;
    std::vector<std::uint32_t> near_;
};

} // namespace vds::detail
