// vds internal: the boundary term of the generalized winding number by
// capping the boundary loops, fast where the boundary is long.
//
// The signed boundary edges of an oriented triangle mesh form a 1-cycle (at
// every vertex as many run out as in), so they split into closed directed
// loops L. Close each with a cap: the fan of triangles (c, b, a) from the
// loop's centroid c over its edges a -> b, whose boundary is L reversed.
// Mesh plus caps is then a closed 2-cycle, whose generalized winding number
// is its signed crossing count along any ray. With C the signed count along
// the ray from q towards -axis (the integer term's ray) and w the solid-angle
// sum over 4 pi:
//
//     GWN_mesh(q) = C_mesh(q) + C_caps(q) - w_caps(q),
//
// so the boundary term is B(q) = C_caps(q) - w_caps(q). C_caps is counted
// with the exact predicates and top-left tie rule of projected_mesh.h, like
// the mesh's own count, so that the two jump together where q's ray passes
// over a boundary edge. w_caps is smooth away from the caps: a tree over the
// cap triangles (Barill et al. 2018, "Fast winding numbers for soups and
// clouds", section 3) takes each node whose sphere (centre c, radius R) lies
// far enough from q by its expansion to first order about c (dipole plus
// quadrupole), and sums the remaining leaves' triangles exactly.
//
// Error of a node taken by expansion, with D = |q - c| > R: Taylor's
// remainder of the kernel K(y) = y / |y|^3 after its linear term, along the
// segment from c - q to x - q (all at distance >= D - R from 0), is
// n . (h^T D^2K h) / 2 for h = x - c. With y unit, D^2K contracted with a
// unit n and h twice is 15 (n.y)(h.y)^2 - 6 (n.h)(h.y) - 3 (n.y) over |y|^4,
// at most 6 (maximise over n: |(15 b^2 - 3) y - 6 b h| with b = h.y, whose
// square 45 b^4 - 18 b^2 + 9 peaks at b^2 = 1). So the node errs by at most
//
//     (1 / 4 pi) * 3 * S / (D - R)^4,   S = sum over its triangles of the
//                                        integral of |x - c|^2 dA,
//
// (S = area * (|g - c|^2 + (sum of squared sides) / 36) for a triangle of
// centroid g). A query takes a node by expansion when that bound is at most
// a tolerance times the solid angle the node subtends (area / D^2, so that
// the bounds sum to about the tolerance times the caps' apparent solid
// angle); the sum of the taken nodes' bounds comes back with the value.
// Labels try a coarse tolerance, then a finer one, and fall back to the
// per-edge sum (boundary_term.h) where the bound could still change the
// answer, so they equal the exact sum's; values take a fine tolerance.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <vds/mesh.h>

#include "projected_mesh.h"

namespace vds::detail {

/// Error bound a tree node may add when taken by its expansion, per unit of
/// the solid angle it subtends: for labels (a first pass; most points lie
/// far from GWN = 1/2, and those that do not are summed again with 1/20 of
/// it, then exactly), and for values (then exactly where the bound exceeds
/// the value's tolerance). Tuned on the bunny, teapot and suzanne.
constexpr double kCapLabelTolerance = 1.0;
constexpr double kCapValueTolerance = 1e-3;

/// One boundary loop and its cap, for the GLSL include's per-loop method.
struct CapLoop {
    glm::dvec3 centroid{0.0};      ///< c: the fan's apex (mean of the loop's vertices, rounded to float)
    glm::dvec3 vectorArea{0.0};    ///< integral of the cap's normal: sum over (c, b, a) of (b - c) x (a - c) / 2
    std::array<double, 9> moment{}; ///< M_ij = integral of n_i (x - c)_j over the cap, row-major
    double radius = 0.0;           ///< R: max |vertex - c|
    double area = 0.0;             ///< sum of the fan triangles' unsigned areas
    glm::vec2 lo{0.0f}, hi{0.0f};  ///< the cap's box across the axis, (s, t)
    std::uint32_t first = 0;       ///< the loop's first edge in `loopEdges()`
    std::uint32_t count = 0;       ///< its edges
};

/// The boundary term of a set of boundary edges by their capped loops. Built
/// once (O(E log E)), then thread safe to query.
class BoundaryCaps {
public:
    /// `edges`: 2 * `edgeCount` points, edge k from [2k] to [2k+1] (copied).
    /// `axis`: the integer term's ray runs towards -axis.
    BoundaryCaps(const glm::vec3* edges, std::size_t edgeCount, Axis axis);

    struct Estimate {
        double term = 0.0;  ///< B(q)
        double bound = 0.0; ///< |B(q) - exact| <= bound; +inf where q lies on a cap (use the exact sum)
    };
    /// B(q) and its error bound, taking nodes whose bound is at most
    /// `nodeTolerance` by expansion. Points are float so that the crossing
    /// count and the solid angles are taken at the same point.
    Estimate estimate(const glm::vec3& q, double nodeTolerance) const;

    /// `winding + B(q)` within `tolerance` of `winding + boundaryTermExact`,
    /// falling back to the per-edge sum where the estimate's bound is larger.
    double generalizedWinding(int winding, const glm::vec3& q, double tolerance) const;

    /// Whether `winding + B(q) > 1/2`, with the per-edge sum's answer: the
    /// estimate decides when it is farther from 1/2 than its bound.
    bool inside(int winding, const glm::vec3& q) const;

    /// False when the edges do not close into loops (not a mesh's boundary):
    /// every query then takes the per-edge sum.
    bool closed() const { return closed_; }
    const std::vector<CapLoop>& loops() const { return loops_; }
    /// The edges in loop order: loop l's edges are [first, first + count),
    /// edge k from [2k] to [2k+1].
    const std::vector<glm::vec3>& loopEdges() const { return loopEdges_; }
    std::size_t edgeCount() const { return edges_.size() / 2; }

private:
    struct Node {
        glm::dvec3 centre;
        double radius;
        double errorScale; ///< 3 S / 4 pi: the bound is errorScale / (D - R)^4
        double area;       ///< unsigned
        glm::dvec3 vectorArea;
        std::array<double, 9> moment;
        double trace;
        std::uint32_t first, count; ///< leaf: cap triangles [first, first + count)
        std::uint32_t left, right;  ///< inner: children (count == 0)
    };
    double exact(int winding, const glm::vec3& q) const;
    std::uint32_t build(std::uint32_t first, std::uint32_t last, std::vector<std::uint32_t>& order,
                        const std::vector<std::array<glm::dvec3, 3>>& tris);

    int axisIndex_;
    bool closed_ = true;
    std::vector<glm::vec3> edges_;
    std::vector<glm::vec3> loopEdges_;
    std::vector<CapLoop> loops_;
    std::vector<glm::vec3> capPositions_;
    std::vector<glm::uvec3> capTriangles_;
    std::vector<std::array<glm::dvec3, 3>> leafTris_; ///< cap triangles in tree order
    std::vector<Node> nodes_;                         ///< [0] is the root
    std::optional<ProjectedMesh> projected_;          ///< the caps, for C_caps
};

} // namespace vds::detail
