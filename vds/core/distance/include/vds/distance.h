// vds: distance to the border — the unsigned and signed distance of points
// to a triangle mesh, the closest point and the triangle (and feature of it)
// it lies on, and signed distance grids over a `Grid`.
//
// The shape beside `Classifier` (<vds/classify.h>): built once from a mesh
// and a `Rule`, then asked for many points (a `PointsView`, float or double,
// any stride) into caller-owned arrays, with one options struct. The sign is
// the classifier's: `SignedDistance` holds an `ExactClassifier` of the same
// mesh and asks it, so a distance is negative exactly where that classifier
// says inside by the rule (see `distance`).
//
// Unsigned distance: a W-wide bounding volume hierarchy over the triangles,
// W the SIMD lanes the CPU has, chosen at run time (8 with AVX2, else 4;
// binned surface-area heuristic, built on threads; nodes of 48 W bytes in
// depth-first order, the W children's box and slab distances in one SIMD
// step), searched nearest box first; a leaf's triangles, W to a SIMD step,
// are first bounded below in float by their face and edge planes and their
// edges' extents (the distance itself up to rounding), and only where that
// bound does not rule a triangle out is the closest point on it computed in
// double (Ericson, "Real-Time Collision Detection", 2005, 5.1.5). A batch
// is searched in Morton order, each point from the nearest triangle of the
// one before: the same answers as one point a call, with far fewer cache
// misses.
//
// Error bound. Points are rounded to float first (as every classifier does,
// <vds/classify.h>), and the distance is that of the float point. The box
// tests prune only boxes whose distance exceeds the best found by a margin
// of 2^-20 relative (more than float rounding of a box distance can make),
// and a triangle's float bound is lowered by its rounding's bound first,
// so no triangle that could be nearest is skipped. The closest point on a
// triangle is a convex combination of its corners computed in double, so
// the distance returned is within 2^-45 * L of the exact distance from the
// float point to the triangles, L = the largest coordinate magnitude of the
// point and the mesh (measured against a brute-force reference by another
// formula in tests/core/distance/distance_test.cpp; far below float
// precision). At any finite scale: the hierarchy holds a mesh whose largest
// coordinate lies outside 2^-30..2^30 scaled by a power of two (exact), so
// squares in float neither overflow nor vanish, and a point more than 2^50
// times the mesh's size away is measured against every triangle in double
// (tested from 2^-100 to 2^125, and 1e30 away from a unit mesh).
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>

#include <glm/vec3.hpp>

#include <vds/classify.h>
#include <vds/enum_names.h>
#include <vds/exact.h>
#include <vds/grid.h>
#include <vds/mesh.h>
#include <vds/rule.h>
#include <vds/sprite.h>

namespace vds {

/// Where on its triangle a closest point lies.
enum class Feature : std::uint8_t {
    Face,   ///< inside the triangle
    Edge,   ///< on edge `index`: from corner index to corner (index + 1) % 3
    Vertex, ///< at corner `index`
};

template <> struct EnumNames<Feature> {
    static constexpr const char* kind = "feature";
    static constexpr EnumName<Feature> table[] = {
        {"face", Feature::Face}, {"edge", Feature::Edge}, {"vertex", Feature::Vertex}};
};

/// No triangle: a search bounded by `DistanceOptions::maxDistance` found none.
constexpr std::uint32_t kNoTriangle = 0xffffffffu;

/// The nearest point of the surface to a query point.
struct ClosestPoint {
    glm::dvec3 point{0.0};  ///< on the surface, mesh coordinates
    double distance = 0.0;  ///< unsigned, mesh units (|query - point|)
    std::uint32_t triangle = kNoTriangle; ///< index into the mesh's triangles
    Feature feature = Feature::Face;
    std::uint8_t index = 0; ///< the edge or corner of `feature` (0 for Face)
};

/// The one options struct of every distance call.
struct DistanceOptions {
    unsigned threads = 0; ///< CPU threads, 0: one per hardware thread
    /// Search no farther: a point farther than this from every triangle gets
    /// distance `maxDistance` (signed as its label) and no triangle. Cheaper
    /// for points far away; > 0 (infinity: no bound).
    double maxDistance = std::numeric_limits<double>::infinity();
};

/// How a full distance grid (band 0) answers its cells far from the surface.
enum class FarCells : std::uint8_t {
    /// Every cell exact (the nearest float to `distance` of its centre).
    Exact,
    /// A closest-feature transform: the grid's cells at every 4th index on
    /// each axis (and its last) are exact; every other cell c takes d', the
    /// distance to the nearest of three triangles: the nearest triangle of
    /// the nearest such corner q, the previous cell's in its column, and of
    /// the 8 corners' the one nearest the brick's centre. d' is a distance to
    /// a triangle of the mesh, so d' >= d, and d' <= d(q) + |c - q| <=
    /// d + 2 |c - q| (distance is 1-Lipschitz), |c - q| at most two cell
    /// diagonals. Where max over the 8 of d(q) - |c - q| (a lower bound
    /// of d) is below one cell diagonal the cell is searched exactly,
    /// so every cell nearer the surface than that is exact, as in `Exact`;
    /// farther ones are within 4 cell diagonals of exact (plus the float
    /// rounding of the cell; in practice within a cell), the sign exact
    /// everywhere. Many times faster than `Exact` on round solids
    /// (docs/benchmarks.md, exact distances).
    Propagated,
};

/// Options of a signed distance grid.
struct DistanceGridOptions {
    unsigned threads = 0; ///< CPU threads, 0: one per hardware thread
    /// Narrow band half-width in mesh units: cells farther than this from
    /// the surface get exactly -band (inside) or +band (outside). 0: the
    /// full grid, its far cells as `far` says. Must be finite and >= 0.
    double band = 0.0;
    /// The full grid's far cells (band 0 only; a band is always exact).
    FarCells far = FarCells::Exact;
};

/// Exact distances to one mesh, signed by one rule. Read-only once built:
/// queries may run from any number of threads at once.
class SignedDistance {
public:
    /// Copies the triangles and builds the hierarchy (O(n log n); about 240
    /// bytes a triangle at 8 lanes, 210 at 4) and the exact classifier along
    /// z (100-200 more), the two at once, on the library's threads. Throws
    /// `InvalidMesh` (naming `meshName`) for a mesh that is empty, not
    /// finite or has bad indices. A flat mesh (a sheet: it bounds no volume)
    /// is built without the classifier: `unsignedDistance`, `closestPoints`
    /// and `closest` answer it, while `distance`, `grid` and `classifier`
    /// throw `InvalidMesh` saying why (`hasSign()` is false). Like
    /// `ExactClassifier`, any other mesh is answered by any
    /// rule: on an open mesh parity and winding count crossings as for a
    /// surface, and only Rule::GeneralizedWinding means inside; callers that
    /// want to refuse it check `requireInsideDefined` first (the CLI does).
    SignedDistance(MeshView mesh, Rule rule, const std::string& meshName = "mesh");
    ~SignedDistance();
    SignedDistance(SignedDistance&&) noexcept;
    SignedDistance& operator=(SignedDistance&&) noexcept;

    Rule rule() const;
    /// False for a flat mesh: distances to it, but no sign (see above).
    bool hasSign() const;
    /// The classifier the signs come from.
    const ExactClassifier& classifier() const;
    std::size_t triangleCount() const;
    /// Bytes the queries read (hierarchy, triangles and the classifier).
    std::size_t memoryBytes() const;
    /// One line, e.g. "distance on 5856 triangles, 1953 nodes of 8 lanes, signed by
    /// winding" (lanes: the SIMD width the CPU lent the search, 4, 8 or 16).
    std::string summary() const;

    /// Signed distances: `out[k]` = -d where the classifier says point k is
    /// inside by `rule()`, +d elsewhere, d the unsigned distance (so
    /// `std::signbit(out[k])` is the label, also on the surface, where d is
    /// -0.0 inside). `out` holds `points.count` doubles, caller-owned.
    /// Throws `InvalidArgument` naming the first point that is not finite
    /// (after rounding to float) or a bad `options.maxDistance`; nothing is
    /// written then.
    void distance(const PointsView& points, double* out, const DistanceOptions& options = {}) const;
    /// Unsigned distances, as `distance` without the sign (no classifier).
    void unsignedDistance(const PointsView& points, double* out, const DistanceOptions& options = {}) const;
    /// The closest point of each point (`points.count` entries); throws as `distance`.
    void closestPoints(const PointsView& points, ClosestPoint* out, const DistanceOptions& options = {}) const;

    /// One point (rounded to float like a batch); throws as `distance`.
    double distance(const glm::vec3& p) const;
    ClosestPoint closest(const glm::vec3& p) const;

    /// The signed distance of every cell centre of `grid` (`Grid::cellCentre`,
    /// index order `Grid::index`) as float: `cells` holds `grid.cellCount()`
    /// floats. Each cell's distance is the nearest float to `distance` of its
    /// centre, and its sign the label `occupancy` of the same classifier
    /// gives (one sweep a column). Cells go by bricks (8^3 cells, 4^3 for a
    /// full grid): the leaves that can hold a brick's nearest triangles are
    /// gathered once, and each cell starts from the nearest triangle of the
    /// cell before it; in band mode a brick no leaf comes near is filled
    /// without a search. A full grid with `FarCells::Propagated` is a
    /// closest-feature transform instead, within the bound that enum states.
    /// Throws like `checkGrid` and `InvalidArgument` for a bad band.
    void grid(const Grid& grid, float* cells, const DistanceGridOptions& options = {}) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

/// Closest point on the triangle (a, b, c) to p, in double (Ericson 5.1.5);
/// a degenerate triangle (a segment or a point) answers as its edges do.
/// The one copy the hierarchy and `SignedDistance` use.
ClosestPoint closestPointOnTriangle(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b,
                                    const glm::dvec3& c);

/// The distance grid of `mesh` for a sprite: cubic cells, `resolution`
/// along the longest side of `box` (the baked box) grown by two cells on
/// every side, so that the band of a clip or a lens reaches past the
/// surface there; signed by `rule` (`SignedDistance` above), on `threads` threads
/// (0: all). Throws `InvalidArgument` for a resolution below 4 or above
/// `kMaxDistanceResolution`, and as `SignedDistance` above does for the mesh.
SpriteDistance bakeDistance(const TriangleMesh& mesh, const Box& box, std::uint32_t resolution, Rule rule,
                            unsigned threads = 0);

/// The grid `bakeDistance` fills, without the distances: for callers that
/// fill it themselves (a slab at a time, to report progress). Throws as
/// `bakeDistance` does for the resolution and the box.
Grid spriteDistanceGrid(const Box& box, std::uint32_t resolution);

} // namespace vds
