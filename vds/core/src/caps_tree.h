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
// remainder of the kernel K(y) = y / |y|^3 after its linear term, for the
// point x = c + h, is the integral over t in [0, 1] of
// (1 - t) n . D^2K(c - q + t h)[h, h] dt. With y unit, D^2K contracted with a
// unit n and h twice is 15 (n.y)(h.y)^2 - 6 (n.h)(h.y) - 3 (n.y) over |y|^4,
// at most 6 (maximise over n: |(15 b^2 - 3) y - 6 b h| with b = h.y, whose
// square 45 b^4 - 18 b^2 + 9 peaks at b^2 = 1), and |c - q + t h| >=
// D - t |h| >= D - t R. The integral of 6 (1 - t) / (D - t R)^4 is
// (D + 2e) / (D^3 e^2) with e = D - R, and |h|^2 integrates to S, so the
// node errs by at most
//
//     (1 / 4 pi) * S * (D + 2e) / (D^3 e^2),   S = sum over its triangles of
//                                              the integral of |x - c|^2 dA,
//
// (S = area * (|g - c|^2 + (sum of squared sides) / 36) for a triangle of
// centroid g); that is 3 S / (4 pi e^4) (the kernel taken at D - R all along)
// times (D + 2e) e^2 / (3 D^3): 1/6 of it at D = 2R. Values take a node by
// expansion when that bound is at most a tolerance times the solid angle the
// node subtends (area / D^2, so that the bounds sum to about the tolerance
// times the caps' apparent solid angle); the sum of the taken nodes' bounds
// comes back with the value, and values fall back to the per-edge sum
// (antipodal.h) where it exceeds their tolerance. Labels refine
// greedily: from the coarsest cut whose nodes each err by at most 1/4, the
// node with the largest bound is opened (its children, or a leaf's
// triangles summed exactly) until the value lies farther from the label's
// threshold (1/2 plus the tie, antipodal.h) than the summed bounds, and the
// per-edge sum decides where it never does or once the tree's work passes a
// quarter of that sum's; so labels equal the per-edge sum's.
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
/// the solid angle it subtends, for values (then exactly where the bound
/// exceeds the value's tolerance).
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
    /// tree is refined greedily until the value is farther from 1/2 than its
    /// bound.
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
        double errorScale; ///< 3 S / 4 pi: the bound is errorScale (D + 2e) / (3 D^3 e^2), e = D - R
        double area;       ///< unsigned
        glm::dvec3 vectorArea;
        std::array<double, 9> moment;
        double trace;
        std::uint32_t first, count; ///< leaf: cap triangles [first, first + count)
        std::uint32_t left, right;  ///< inner: children (count == 0)
    };
    double exact(int winding, const glm::vec3& q) const;
    /// `unsignedMoments[node]`: the integral of |n| (x - centre) dA, for the
    /// parent's moments from its children's.
    std::uint32_t build(std::uint32_t first, std::uint32_t last, std::vector<std::uint32_t>& order,
                        const std::vector<std::array<glm::dvec3, 3>>& tris,
                        std::vector<glm::dvec3>& unsignedMoments);

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
