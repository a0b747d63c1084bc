// vds internal: the boundary term of the Antipodal split of the generalized
// winding number (Martens, Trettner & Bessmeltsev 2026), shared by the exact
// classifier, sprites and the voxelizers, and a grid that makes it cheap.
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
#include <vector>

#include <glm/vec3.hpp>

#include <vds/mesh.h>
#include <vds/sprite.h>

namespace vds::detail {

/// The mesh's boundary edges as endpoint pairs: edge k runs from `[2k]` to
/// `[2k+1]`. Edges whose uses do not cancel after welding vertices with
/// bitwise-equal positions; an edge used n times more one way than the
/// other appears |n| times, oriented as the majority of its uses run (so
/// non-manifold edges count by their unbalanced orientation).
std::vector<glm::vec3> boundaryEdges(MeshView mesh);

/// Signed solid angle of the triangle (u, v, w) seen from the origin (Van
/// Oosterom & Strackee), in double.
double solidAngle(const glm::dvec3& u, const glm::dvec3& v, const glm::dvec3& w);

/// One edge's solid angle (+axis, a - q, b - q). On the edge's sweep, where
/// it jumps, it takes the side of the integer term's tie rule (q moved by
/// (eps, -eps^2) in the texture's (s, t)), so that a ray exactly over the
/// boundary still gets a consistent sum; an edge along the axis adds 0.
double edgeSolidAngle(int axis, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& q);

/// The boundary term at `q` by the per-edge sum: `edges` holds 2 *
/// `edgeCount` points (mesh coordinates), `axis` the index (0..2) of the
/// view axis. O(edgeCount).
double boundaryTermExact(const glm::vec3* edges, std::size_t edgeCount, int axis, const glm::dvec3& q);

/// A coarse grid of boundary-term values with trilinear interpolation where
/// that is provably within `tolerance`, and the exact sum elsewhere.
///
/// Cubic cells of edge h over a box. A cell is *exact* when (a) its
/// footprint across the axis meets the projection of a boundary edge at or
/// below the cell's top (the sweep, where the term jumps, may cross it), or
/// (b) the interpolation bound below exceeds `tolerance`. Elsewhere the term
/// is smooth in the cell, and trilinear interpolation of its values at the
/// cell's corners errs by at most (h_x^2 + h_y^2 + h_z^2) / 8 times the
/// largest second derivative in the cell. The gradient of the GWN away from
/// the surface is the Biot-Savart integral of its boundary curve, (1/4 pi)
/// \oint (x - q) x dl / |x - q|^3, and so is the boundary term's off the
/// sweep; its second derivatives are bounded by (1/2 pi) \oint |dl| / |x -
/// q|^3. Edges are gathered in chunks of nearby edges (bounding sphere, total
/// length L_c), each contributing at most L_c / (distance - radius)^3, so
/// error <= 3 h^2 / (16 pi) * sum_c L_c / d_c^3 <= tolerance, d_c the least
/// distance from the cell to chunk c. The stored corner values are rounded
/// to float (relative 6e-8) on top. Thread safe to query.
class BoundaryGrid {
public:
    /// `edges`: 2 * edgeCount points, kept by pointer (must outlive the grid).
    BoundaryGrid(const glm::vec3* edges, std::size_t edgeCount, int axis, const Box& box, std::uint32_t cells,
                 double tolerance, unsigned threads);

    /// The boundary term at `q`, within `tolerance` of `boundaryTermExact`.
    double at(const glm::dvec3& q) const;

    /// Fraction of cells that evaluate exactly.
    double exactFraction() const;
    std::size_t nodeCount() const { return values_.size(); }

private:
    const glm::vec3* edges_;
    std::size_t edgeCount_;
    int axis_;
    glm::dvec3 lo_;
    double h_;
    glm::ivec3 dims_;               ///< cells along x, y, z
    std::vector<std::uint8_t> exact_; ///< per cell, x fastest
    std::vector<float> values_;     ///< per node, (dims + 1), x fastest
};

/// Default grid: cells along the box's longest side, and the tolerance on
/// the boundary term (labels differ from the exact sum's only for points
/// whose GWN is within this of 1/2).
constexpr std::uint32_t kBoundaryGridCells = 48;
constexpr double kBoundaryGridTolerance = 1e-3;

/// Signed count of a column's crossings strictly in front of depth r.
inline int columnWinding(const float* begin, const float* end, float r) {
    int winding = 0;
    for (const float* e = begin; e != end; ++e) {
        if (!(std::fabs(*e) < r)) break;
        winding += crossingEnters(*e) ? 1 : -1;
    }
    return winding;
}

/// The point the column's count belongs to: the centre of texel `column` at
/// texture depth r, in the mesh coordinates of the bake.
glm::dvec3 columnPoint(const SpriteGrid& grid, std::ptrdiff_t column, float r);

/// Throws `InvalidArgument` when `sprite` cannot answer `rule`: the
/// generalized winding number of an open sprite read from a version-1 file,
/// which has no boundary edges.
void requireBoundaryKnown(const Sprite& sprite, Rule rule);

/// True when the sprite answers Rule::GeneralizedWinding with a boundary
/// term (it has boundary edges); otherwise the rule reads as Winding.
inline bool needsBoundaryTerm(const Sprite& sprite, Rule rule) {
    return rule == Rule::GeneralizedWinding && !sprite.boundaryEdges.empty();
}

/// Batch GWN labels for a sprite with boundary edges (sprite.cpp's
/// `classify` hands over to it). With `grid` null, the evaluation follows
/// `options.boundary`.
void classifyGeneralizedWinding(const Sprite& sprite, const float* xyz, std::size_t count, std::size_t strideBytes,
                                std::uint8_t* labels, const ClassifyOptions& options,
                                const BoundaryGrid* grid = nullptr);

/// The grid a sprite's batch should use for `count` points, or none (exact
/// sums) by `mode`; Auto builds one when the batch is large enough to repay it.
bool useBoundaryGrid(BoundaryEvaluation mode, std::size_t count, std::size_t edgeCount);

} // namespace vds::detail
