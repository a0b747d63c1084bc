// vds internal: a mesh's triangles projected along the view axis, with the
// top-left tie rule and a uniform grid over their projections; the shared
// machinery of the exact classifier (exact_classifier.cpp) and the CPU baker
// (cpu_bake.cpp).
//
// Tie rule. Projected triangles are taken counter-clockwise (swapped when
// clockwise; the facing is kept separately). A point on an edge's line is
// claimed iff the edge is a top edge (horizontal, running towards -s: the
// interior lies below, at lower t) or a left edge (running towards -t), the
// rasterizers' top-left rule with t pointing up, like texture rows. For a
// counter-clockwise triangle with edge vector e and a point p on its line,
// orient2d(a, b, p + d) = e.s*d.t - e.t*d.s, so with d = (eps, -eps^2) this
// is > 0 exactly for top and left edges: the rule claims p iff p + d, a point
// displaced infinitesimally, lies in the open triangle. Hence every point is
// claimed by exactly the triangles that contain a generic nearby point, and:
//  - on the interior of an edge shared by triangles on opposite sides of it in
//    projection (a sheet continuing), exactly one claims it, with either facing;
//  - at a vertex whose fan covers its neighbourhood once in projection,
//    exactly one triangle of the fan claims it;
//  - where the projection folds (silhouette edges and vertices, fans that are
//    not simple in projection) the count is that of the nearby generic ray:
//    0 or 2 at a fold, in general n with signed sum equal to the fan's
//    projected winding. Parity and winding of a closed mesh thus stay those of
//    a nearby generic ray. Depth is compared at p itself; the displacement
//    does not change a non-zero orient3d sign, and a zero one is not counted.
// GL rasterizers apply such a rule to vertices snapped to sub-texel
// precision, so at a texel centre within snapping distance of an edge a GL
// bake may pick the other triangle of a shared edge (same count and facing),
// and at a silhouette within that distance see 0 crossings where this sees 2
// or the reverse.
//
// Acceleration: a uniform grid over the triangles' (s,t) boxes, cells shaped
// like the median box, each entry carrying its box rounded outwards to 1/256
// of the cell and its triangle's least vertex depth, a cell's entries nearest
// first; triangles stored in cell order. The brute-force path applies
// the same predicates to every triangle.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include <vds/mesh.h>
#include <vds/grid.h>
#include <vds/axis.h>
#include <vds/classify.h>

#include <vds/detail/predicates.h>

namespace vds::detail {

constexpr std::uint32_t kEntering = 1;  // faces the viewer: the ray enters the solid
constexpr std::uint32_t kParallel = 2;  // zero projected area: never crossed
constexpr std::uint32_t kTopLeft0 = 4;  // edge e (v[e] -> v[e+1]) is top or left: kTopLeft0 << e

struct Triangle {
    float v[3][3];        ///< vertices as (s,t,r); counter-clockwise in (s,t) unless parallel
    std::uint32_t index;  ///< in the mesh: orders equal-depth crossings
    std::uint32_t flags;
};

/// Bounding box of a projected triangle in (s,t).
struct Box2 {
    float lo[2], hi[2];
};

inline Box2 boxOf(const Triangle& t) {
    Box2 b;
    for (int a = 0; a < 2; ++a) {
        b.lo[a] = std::min({t.v[0][a], t.v[1][a], t.v[2][a]});
        b.hi[a] = std::max({t.v[0][a], t.v[1][a], t.v[2][a]});
    }
    return b;
}

/// Triangle k of `mesh` in view space ((s,t,r) = the coordinates `perm`
/// picks), counter-clockwise unless parallel, with its facing and top-left
/// flags: the one projection of the exact classifier, the CPU baker and the
/// layer count (inline: the layer count projects millions a second).
inline Triangle projectTriangle(MeshView mesh, std::size_t k, const glm::ivec3& perm) {
    const auto isTopLeft = [](const float* a, const float* b) { return b[1] < a[1] || (b[1] == a[1] && b[0] < a[0]); };
    Triangle t;
    for (int c = 0; c < 3; ++c) {
        const glm::vec3& p = mesh.positions[mesh.triangles[k][c]];
        t.v[c][0] = p[perm.x];
        t.v[c][1] = p[perm.y];
        t.v[c][2] = p[perm.z];
    }
    t.index = std::uint32_t(k);
    const int o = orient2d(t.v[0], t.v[1], t.v[2]);
    t.flags = o == 0 ? kParallel : o < 0 ? kEntering : 0;
    if (o < 0) std::swap(t.v[1], t.v[2]);
    for (int e = 0; e < 3; ++e)
        if (isTopLeft(t.v[e], t.v[(e + 1) % 3])) t.flags |= kTopLeft0 << e;
    return t;
}
/// Whether the projection of `tri` claims the point q (its (s,t) in q[0],
/// q[1]) under the top-left rule. `tri` must not be parallel. A first pass
/// evaluates the three edges as orient2d's filter does (q as the pivot) and
/// decides whenever every sign it needs passes the error bound; the rest go
/// through the full predicate, edge by edge.
inline bool claims(const Triangle& tri, const float* q) {
    double ds[3], dt[3];
    for (int k = 0; k < 3; ++k) {
        ds[k] = double(tri.v[k][0]) - double(q[0]);
        dt[k] = double(tri.v[k][1]) - double(q[1]);
    }
    bool outside = false, inside = true;
    for (int e = 0; e < 3; ++e) {
        const int f = (e + 1) % 3;
        const double left = ds[e] * dt[f], right = dt[e] * ds[f];
        const double det = left - right, bound = kOrient2dBound * (std::fabs(left) + std::fabs(right));
        outside |= det < -bound;
        inside &= det > bound;
    }
    if (outside) return false;
    if (inside) return true;
    for (int e = 0; e < 3; ++e) {
        const int o = orient2d(tri.v[e], tri.v[(e + 1) % 3], q);
        if (o < 0 || (o == 0 && !(tri.flags & (kTopLeft0 << e)))) return false;
    }
    return true;
}

/// Contribution of a claimed triangle to the winding of q: +1 entering, -1
/// leaving, 0 unless the crossing lies strictly in front of q (smaller r).
inline int crossingInFront(const Triangle& tri, const float* q) {
    if (orient3d(tri.v[0], tri.v[1], tri.v[2], q) >= 0) return 0;
    return (tri.flags & kEntering) ? 1 : -1;
}

/// Grid cells per crossable triangle. On UV spheres of 0.1M and 1M triangles
/// (random queries) 0.25 to 2 run at the same speed, memory latency bound;
/// 0.5 gives ~6.6 cell entries and ~11 candidates per query, 4 of them read.
constexpr double kCellsPerTriangle = 0.5;

/// One triangle listed in a grid cell, with its box clipped to the cell and
/// rounded outwards to 1/256 of the cell, and its nearest vertex depth: most
/// candidates are rejected without reading the triangle. A cell lists its
/// entries by `depthLo`, ascending: a query stops at the first entry wholly
/// behind it.
struct CellEntry {
    std::uint32_t triangle;
    std::uint8_t lo[2], hi[2];
    float depthLo; ///< the least r of the triangle's vertices
};

/// A uniform grid over the (s,t) boxes of the crossable triangles. Points and
/// boxes are located by one monotone function (`fine`), so a point in a
/// triangle's closed box always finds the triangle, whatever the rounding.
class CellGrid {
public:
    /// Chooses bounds and cell counts for these boxes.
    void layout(const std::vector<Box2>& boxes);
    /// Lists the triangles of every cell, by `depthLo[k]` ascending;
    /// `boxes[k]` is triangle k's box (the boxes given to `layout`, in any
    /// order), `depthLo[k]` its least vertex r.
    void fill(const std::vector<Box2>& boxes, const std::vector<float>& depthLo);

    /// Row-major cell of a point within the bounds.
    std::size_t cellIndex(const float* q) const {
        return std::size_t(fine(q[1], 1) / kSub) * dims_[0] + fine(q[0], 0) / kSub;
    }

    struct Found {
        const CellEntry* begin = nullptr;
        const CellEntry* end = nullptr;
        std::uint8_t sub[2] = {0, 0}; ///< q's position in the cell, 1/256ths
    };
    /// The entries of q's cell; none outside the bounds (or for NaN).
    Found find(const float* q) const {
        if (!(q[0] >= lo_[0] && q[0] <= hi_[0] && q[1] >= lo_[1] && q[1] <= hi_[1])) return {};
        const std::uint32_t s = fine(q[0], 0), t = fine(q[1], 1);
        const std::size_t cell = std::size_t(t / kSub) * dims_[0] + s / kSub;
        return {entries_.data() + offsets_[cell], entries_.data() + offsets_[cell + 1],
                {std::uint8_t(s % kSub), std::uint8_t(t % kSub)}};
    }
    /// Asks the cache for the cell offsets `find(q)` will read.
    void prefetch(const float* q) const {
        if (q[0] >= lo_[0] && q[0] <= hi_[0] && q[1] >= lo_[1] && q[1] <= hi_[1])
            __builtin_prefetch(offsets_.data() + cellIndex(q));
    }
    static bool mayHold(const CellEntry& e, const std::uint8_t* sub) {
        return sub[0] >= e.lo[0] && sub[0] <= e.hi[0] && sub[1] >= e.lo[1] && sub[1] <= e.hi[1];
    }

private:
    static constexpr std::uint32_t kSub = 256;
    /// Position in 1/256ths of a cell, clamped to the grid. For x >= lo_ the
    /// float operations are monotone in x.
    std::uint32_t fine(float x, int k) const {
        const float f = (x - lo_[k]) * scale_[k];
        const std::uint32_t n = dims_[k] * kSub; // <= 2^23: exact in float
        return f < float(n) ? std::uint32_t(f) : n - 1;
    }
    void setDims(std::uint32_t s, std::uint32_t t);
    std::uint64_t countEntries(const std::vector<Box2>& boxes) const;

public:
    std::size_t memoryBytes() const {
        return offsets_.size() * sizeof(std::size_t) + entries_.size() * sizeof(CellEntry);
    }

private:

    float lo_[2] = {1.0f, 1.0f}, hi_[2] = {0.0f, 0.0f}; // empty until laid out
    double extent_[2] = {0.0, 0.0};
    float scale_[2] = {0.0f, 0.0f};
    std::uint32_t dims_[2] = {1, 1};
    std::vector<std::size_t> offsets_;
    std::vector<CellEntry> entries_;
};

struct ProjectedMesh {
    Axis axis;
    glm::ivec3 perm;
    /// Crossable triangles first (`crossable` of them, sorted by grid cell
    /// for locality), then the parallel ones.
    std::vector<Triangle> tris;
    std::size_t crossable = 0;
    CellGrid grid;

    ProjectedMesh(MeshView mesh, Axis viewAxis);
    std::size_t memoryBytes() const { return tris.size() * sizeof(Triangle) + grid.memoryBytes(); }

    void toViewSpace(const glm::vec3& p, float* q) const {
        q[0] = p[perm.x];
        q[1] = p[perm.y];
        q[2] = p[perm.z];
    }

    int winding(const glm::vec3& p) const {
        float q[3];
        toViewSpace(p, q);
        return winding(grid.find(q), q);
    }
    /// The winding of view-space point q, from its cell's entries `found`.
    /// A claimed crossing's depth lies between its triangle's least and
    /// greatest vertex r, so a triangle whose least r is >= q's is not
    /// strictly in front, and one whose every vertex r is < q's is, with no
    /// orient3d; the entries run by least r, so the first of the former ends
    /// the scan.
    int winding(const CellGrid::Found& found, const float* q) const {
        int w = 0;
        crossings(found, q, [&](const Triangle&, int crossing) { w += crossing; });
        return w;
    }
    /// Calls visit(triangle, +1 or -1) for each crossing `winding` counts.
    template <class Visit>
    void crossings(const CellGrid::Found& found, const float* q, Visit&& visit) const {
        for (const CellEntry* e = found.begin; e != found.end; ++e) {
            if (e->depthLo >= q[2]) break;
            if (!CellGrid::mayHold(*e, found.sub)) continue;
            const Triangle& t = tris[e->triangle];
            if (!claims(t, q)) continue;
            const int crossing = t.v[0][2] < q[2] && t.v[1][2] < q[2] && t.v[2][2] < q[2]
                                     ? ((t.flags & kEntering) ? 1 : -1)
                                     : crossingInFront(t, q);
            if (crossing != 0) visit(t, crossing);
        }
    }

    int windingBruteForce(const glm::vec3& p) const {
        float q[3];
        toViewSpace(p, q);
        if (!(std::isfinite(q[0]) && std::isfinite(q[1]) && std::isfinite(q[2]))) return 0;
        int w = 0;
        for (const Triangle& t : tris)
            if (!(t.flags & kParallel) && claims(t, q)) w += crossingInFront(t, q);
        return w;
    }
};

class BoundaryCaps;

/// How the exact sweep labels the columns of a mesh with boundary under
/// Rule::GeneralizedWinding: both ways give the same labels; Timed times
/// both on a few columns of each range and takes the cheaper.
enum class SweepWay { Timed, CellByCell, Brackets };

/// The exact column sweep of `occupancy(mesh, ...)` (<vds/occupancy.h>) on
/// a mesh projected along z; `edges` (2 points an edge) its boundary for
/// Rule::GeneralizedWinding (ignored for the other rules).
/// `caps`: the boundary's capped loops already built over `edges` with this
/// mesh as their surface (an ExactClassifier's), so that a grid swept a
/// slab at a time builds them once; none: built for this call.
void sweepExact(const ProjectedMesh& projected, const std::vector<glm::vec3>& edges, const Grid& grid,
                std::uint8_t* cells, const ClassifyOptions& options, SweepWay way = SweepWay::Timed,
                const BoundaryCaps* caps = nullptr);

} // namespace vds::detail
