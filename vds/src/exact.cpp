// vds: exact point-in-solid classification and the CPU baker.
//
// Trapp & Döllner 2008, section 3.2 (the parity test: count the surface
// crossings of a ray in front of the point) and section 4.1 (the LDI: every
// crossing of every texel's ray), evaluated on the triangles themselves.
//
// Predicates. Coordinates are floats, permuted to (s,t,r) by the view axis (a
// cyclic permutation: orientations keep their sign) and read as doubles,
// which is exact. Two signs decide everything:
//  - orient2d(a,b,c) in (s,t), twice the projected signed area. It is the r
//    component of the normal (b-a)x(c-a): < 0 means the triangle faces the
//    viewer (the ray enters there); 0 means it is parallel to the axis and is
//    never crossed.
//  - orient3d(a,b,c,p) = det[a-p; b-p; c-p] = orient2d(a,b,c) * (r_plane - p.r),
//    r_plane being the plane's depth at p's (s,t) (multilinearity of det).
//    With (a,b,c) counter-clockwise in projection, the crossing lies strictly
//    in front of p iff orient3d < 0.
// Each is evaluated in double first and accepted when it exceeds Shewchuk's
// forward error bound (Shewchuk 1997, "Adaptive Precision Floating-Point
// Arithmetic and Fast Robust Geometric Predicates", ccwerrboundA and
// o3derrboundA; valid here: no double overflow or underflow is possible from
// float inputs). Otherwise it is evaluated exactly: the determinant is
// expanded into monomials of the input coordinates; a product of two floats
// is exact in double (at most 48 significant bits, exponents within range) and
// a product of three is exactly the pair (x, fma(xy, z, -x)) with x = fl(xy*z)
// (Two-Product; the exact product is a multiple of 2^-447, far above double's
// smallest subnormal, so the error term is representable). The 6 (orient2d)
// or 48 (orient3d) doubles are summed exactly by Grow-Expansion (Shewchuk,
// theorem 10), which yields a non-overlapping expansion sorted by magnitude:
// its sign is that of its last non-zero component.
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
// of the cell; triangles stored in cell order. The brute-force path applies
// the same predicates to every triangle.
#include <vds/exact.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cassert>
#include <cmath>
#include <exception>
#include <limits>
#include <mutex>
#include <numeric>
#include <string>
#include <system_error>
#include <thread>

#include <vds/error.h>
#include <vds/parallel.h>

#include "bake_common.h"

namespace vds {
namespace {

// ---- Exact predicates -----------------------------------------------------

constexpr double kEpsilon = 0x1p-53; // half an ulp of 1.0: the rounding unit
constexpr double kOrient2dBound = (3.0 + 16.0 * kEpsilon) * kEpsilon;
constexpr double kOrient3dBound = (7.0 + 56.0 * kEpsilon) * kEpsilon;

int signOf(double x) { return (x > 0.0) - (x < 0.0); }

// Knuth's Two-Sum: x + y == a + b exactly, x = fl(a + b).
inline void twoSum(double a, double b, double& x, double& y) {
    x = a + b;
    const double bv = x - a;
    const double av = x - bv;
    y = (a - av) + (b - bv);
}

// An exact sum of doubles as a Shewchuk expansion (Grow-Expansion with zero
// elimination): components non-overlapping, in increasing magnitude.
class ExactSum {
public:
    void add(double b) {
        assert(count_ < kCapacity);
        double q = b;
        int kept = 0;
        for (int i = 0; i < count_; ++i) {
            double sum, error;
            twoSum(q, parts_[i], sum, error);
            q = sum;
            if (error != 0.0) parts_[kept++] = error;
        }
        if (q != 0.0 || kept == 0) parts_[kept++] = q;
        count_ = kept;
    }
    // x * y * z exactly, for floats x, y, z: x*y is exact in double.
    void addProduct(double sign, float x, float y, float z) {
        const double xy = double(x) * double(y);
        const double hi = xy * double(z);
        const double lo = std::fma(xy, double(z), -hi);
        add(sign * hi);
        add(sign * lo);
    }
    int sign() const { return count_ == 0 ? 0 : signOf(parts_[count_ - 1]); }

private:
    static constexpr int kCapacity = 64;
    double parts_[kCapacity];
    int count_ = 0;
};

int orient2dExact(const float* a, const float* b, const float* c) {
    // Expanded: a.s*b.t - a.t*b.s + b.s*c.t - b.t*c.s + c.s*a.t - c.t*a.s;
    // each product of two floats is exact in double.
    ExactSum sum;
    sum.add(double(a[0]) * double(b[1]));
    sum.add(-(double(a[1]) * double(b[0])));
    sum.add(double(b[0]) * double(c[1]));
    sum.add(-(double(b[1]) * double(c[0])));
    sum.add(double(c[0]) * double(a[1]));
    sum.add(-(double(c[1]) * double(a[0])));
    return sum.sign();
}

/// Sign of (b-a) x (c-a) in (s,t) = coordinates [0], [1]: > 0 counter-clockwise.
int orient2d(const float* a, const float* b, const float* c) {
    const double left = (double(a[0]) - double(c[0])) * (double(b[1]) - double(c[1]));
    const double right = (double(a[1]) - double(c[1])) * (double(b[0]) - double(c[0]));
    const double det = left - right;
    double magnitude;
    if (left > 0.0) {
        if (right <= 0.0) return signOf(det);
        magnitude = left + right;
    } else if (left < 0.0) {
        if (right >= 0.0) return signOf(det);
        magnitude = -left - right;
    } else {
        return signOf(det);
    }
    const double bound = kOrient2dBound * magnitude;
    if (det >= bound || -det >= bound) return signOf(det);
    return orient2dExact(a, b, c);
}

// det[a-p; b-p; c-p] = det[a;b;c] - det[p;b;c] - det[a;p;c] - det[a;b;p].
void addDet3(ExactSum& sum, double sign, const float* u, const float* v, const float* w) {
    sum.addProduct(sign, u[0], v[1], w[2]);
    sum.addProduct(-sign, u[0], v[2], w[1]);
    sum.addProduct(-sign, u[1], v[0], w[2]);
    sum.addProduct(sign, u[1], v[2], w[0]);
    sum.addProduct(sign, u[2], v[0], w[1]);
    sum.addProduct(-sign, u[2], v[1], w[0]);
}

int orient3dExact(const float* a, const float* b, const float* c, const float* p) {
    ExactSum sum;
    addDet3(sum, 1.0, a, b, c);
    addDet3(sum, -1.0, p, b, c);
    addDet3(sum, -1.0, a, p, c);
    addDet3(sum, -1.0, a, b, p);
    return sum.sign();
}

/// Sign of det[a-p; b-p; c-p] over (s,t,r): for a, b, c counter-clockwise in
/// (s,t), > 0 when p lies below the plane (smaller r), < 0 above it.
int orient3d(const float* a, const float* b, const float* c, const float* p) {
    const double adx = double(a[0]) - p[0], bdx = double(b[0]) - p[0], cdx = double(c[0]) - p[0];
    const double ady = double(a[1]) - p[1], bdy = double(b[1]) - p[1], cdy = double(c[1]) - p[1];
    const double adz = double(a[2]) - p[2], bdz = double(b[2]) - p[2], cdz = double(c[2]) - p[2];
    const double bdxcdy = bdx * cdy, cdxbdy = cdx * bdy;
    const double cdxady = cdx * ady, adxcdy = adx * cdy;
    const double adxbdy = adx * bdy, bdxady = bdx * ady;
    const double det = adz * (bdxcdy - cdxbdy) + bdz * (cdxady - adxcdy) + cdz * (adxbdy - bdxady);
    const double permanent = (std::fabs(bdxcdy) + std::fabs(cdxbdy)) * std::fabs(adz) +
                             (std::fabs(cdxady) + std::fabs(adxcdy)) * std::fabs(bdz) +
                             (std::fabs(adxbdy) + std::fabs(bdxady)) * std::fabs(cdz);
    const double bound = kOrient3dBound * permanent;
    if (det > bound || -det > bound) return signOf(det);
    return orient3dExact(a, b, c, p);
}

// ---- Triangles and their projections --------------------------------------

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

Box2 boxOf(const Triangle& t) {
    Box2 b;
    for (int a = 0; a < 2; ++a) {
        b.lo[a] = std::min({t.v[0][a], t.v[1][a], t.v[2][a]});
        b.hi[a] = std::max({t.v[0][a], t.v[1][a], t.v[2][a]});
    }
    return b;
}

bool isTopLeft(const float* a, const float* b) { return b[1] < a[1] || (b[1] == a[1] && b[0] < a[0]); }

/// Whether the projection of `tri` claims the point q (its (s,t) in q[0],
/// q[1]) under the top-left rule. `tri` must not be parallel. A first pass
/// evaluates the three edges as orient2d's filter does (q as the pivot) and
/// decides whenever every sign it needs passes the error bound; the rest go
/// through the full predicate, edge by edge.
bool claims(const Triangle& tri, const float* q) {
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
int crossingInFront(const Triangle& tri, const float* q) {
    if (orient3d(tri.v[0], tri.v[1], tri.v[2], q) >= 0) return 0;
    return (tri.flags & kEntering) ? 1 : -1;
}

/// Grid cells per crossable triangle. On UV spheres of 0.1M and 1M triangles
/// (random queries) 0.25 to 2 run at the same speed, memory latency bound;
/// 0.5 gives ~6.6 cell entries and ~11 candidates per query, 4 of them read.
constexpr double kCellsPerTriangle = 0.5;

/// One triangle listed in a grid cell, with its box clipped to the cell and
/// rounded outwards to 1/256 of the cell: most candidates are rejected
/// without reading the triangle.
struct CellEntry {
    std::uint32_t triangle;
    std::uint8_t lo[2], hi[2];
};

/// A uniform grid over the (s,t) boxes of the crossable triangles. Points and
/// boxes are located by one monotone function (`fine`), so a point in a
/// triangle's closed box always finds the triangle, whatever the rounding.
class CellGrid {
public:
    /// Chooses bounds and cell counts for these boxes.
    void layout(const std::vector<Box2>& boxes);
    /// Lists the triangles of every cell; `boxes[k]` is triangle k's box
    /// (the boxes given to `layout`, in any order).
    void fill(const std::vector<Box2>& boxes);

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

    float lo_[2] = {1.0f, 1.0f}, hi_[2] = {0.0f, 0.0f}; // empty until laid out
    double extent_[2] = {0.0, 0.0};
    float scale_[2] = {0.0f, 0.0f};
    std::uint32_t dims_[2] = {1, 1};
    std::vector<std::size_t> offsets_;
    std::vector<CellEntry> entries_;
};

void CellGrid::setDims(std::uint32_t s, std::uint32_t t) {
    dims_[0] = s;
    dims_[1] = t;
    for (int a = 0; a < 2; ++a)
        scale_[a] = float(std::min(double(dims_[a]) * kSub / extent_[a], double(std::numeric_limits<float>::max())));
}

std::uint64_t CellGrid::countEntries(const std::vector<Box2>& boxes) const {
    std::uint64_t count = 0;
    for (const Box2& b : boxes)
        count += std::uint64_t(fine(b.hi[0], 0) / kSub - fine(b.lo[0], 0) / kSub + 1) *
                 (fine(b.hi[1], 1) / kSub - fine(b.lo[1], 1) / kSub + 1);
    return count;
}

void CellGrid::layout(const std::vector<Box2>& boxes) {
    if (boxes.empty()) return;
    lo_[0] = lo_[1] = std::numeric_limits<float>::max();
    hi_[0] = hi_[1] = -std::numeric_limits<float>::max();
    std::vector<float> widths(boxes.size()), heights(boxes.size());
    for (std::size_t k = 0; k < boxes.size(); ++k) {
        const Box2& b = boxes[k];
        for (int a = 0; a < 2; ++a) {
            lo_[a] = std::min(lo_[a], b.lo[a]);
            hi_[a] = std::max(hi_[a], b.hi[a]);
        }
        widths[k] = b.hi[0] - b.lo[0];
        heights[k] = b.hi[1] - b.lo[1];
    }
    // A crossable triangle has a projected area, so both extents are > 0.
    for (int a = 0; a < 2; ++a) extent_[a] = double(hi_[a]) - double(lo_[a]);
    // About kCellsPerTriangle cells per triangle, shaped like the median
    // triangle's box, so that long thin triangles get long thin cells.
    const auto median = [](std::vector<float>& v) {
        std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2), v.end());
        return double(v[v.size() / 2]);
    };
    const double width = median(widths), height = median(heights);
    const double aspect = width > 0.0 && height > 0.0 ? width / height : 1.0;
    const double cells = kCellsPerTriangle * double(boxes.size()) + 16.0;
    const double s = std::sqrt(cells * extent_[0] / (extent_[1] * aspect));
    constexpr double kMaxDim = 1 << 15;
    const auto dim = [&](double d) { return std::uint32_t(std::clamp(std::ceil(d), 1.0, kMaxDim)); };
    setDims(dim(s), dim(cells / s));
    // Boxes spanning many cells (long thin triangles across the grid): coarsen
    // until the entries stay linear in the triangle count.
    const std::uint64_t maxEntries = 16 * std::uint64_t(boxes.size()) + 1024;
    while ((dims_[0] > 1 || dims_[1] > 1) && countEntries(boxes) > maxEntries)
        setDims((dims_[0] + 1) / 2, (dims_[1] + 1) / 2);
}

void CellGrid::fill(const std::vector<Box2>& boxes) {
    if (boxes.empty()) return;
    const std::size_t cellCount = std::size_t(dims_[0]) * dims_[1];
    offsets_.assign(cellCount + 1, 0);
    for (const Box2& b : boxes)
        for (std::uint32_t j = fine(b.lo[1], 1) / kSub, j1 = fine(b.hi[1], 1) / kSub; j <= j1; ++j)
            for (std::uint32_t i = fine(b.lo[0], 0) / kSub, i1 = fine(b.hi[0], 0) / kSub; i <= i1; ++i)
                ++offsets_[std::size_t(j) * dims_[0] + i + 1];
    std::partial_sum(offsets_.begin(), offsets_.end(), offsets_.begin());
    entries_.resize(offsets_.back());
    std::vector<std::size_t> next(offsets_.begin(), offsets_.end() - 1);
    for (std::size_t k = 0; k < boxes.size(); ++k) {
        const std::uint32_t lo[2] = {fine(boxes[k].lo[0], 0), fine(boxes[k].lo[1], 1)};
        const std::uint32_t hi[2] = {fine(boxes[k].hi[0], 0), fine(boxes[k].hi[1], 1)};
        for (std::uint32_t j = lo[1] / kSub; j <= hi[1] / kSub; ++j)
            for (std::uint32_t i = lo[0] / kSub; i <= hi[0] / kSub; ++i) {
                CellEntry e;
                e.triangle = std::uint32_t(k);
                e.lo[0] = std::uint8_t(i == lo[0] / kSub ? lo[0] % kSub : 0);
                e.hi[0] = std::uint8_t(i == hi[0] / kSub ? hi[0] % kSub : kSub - 1);
                e.lo[1] = std::uint8_t(j == lo[1] / kSub ? lo[1] % kSub : 0);
                e.hi[1] = std::uint8_t(j == hi[1] / kSub ? hi[1] % kSub : kSub - 1);
                entries_[next[std::size_t(j) * dims_[0] + i]++] = e;
            }
    }
}

// ---- The projected triangles, indexed --------------------------------------

struct ProjectedMesh {
    Axis axis;
    glm::ivec3 perm;
    /// Crossable triangles first (`crossable` of them, sorted by grid cell
    /// for locality), then the parallel ones.
    std::vector<Triangle> tris;
    std::size_t crossable = 0;
    CellGrid grid;

    ProjectedMesh(MeshView mesh, Axis viewAxis);

    void toViewSpace(const glm::vec3& p, float* q) const {
        q[0] = p[perm.x];
        q[1] = p[perm.y];
        q[2] = p[perm.z];
    }

    int winding(const glm::vec3& p) const {
        float q[3];
        toViewSpace(p, q);
        const CellGrid::Found found = grid.find(q);
        int w = 0;
        for (const CellEntry* e = found.begin; e != found.end; ++e) {
            if (!CellGrid::mayHold(*e, found.sub)) continue;
            const Triangle& t = tris[e->triangle];
            if (claims(t, q)) w += crossingInFront(t, q);
        }
        return w;
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

ProjectedMesh::ProjectedMesh(MeshView mesh, Axis viewAxis) : axis(viewAxis), perm(axisPermutation(viewAxis)) {
    const std::size_t n = mesh.triangleCount;
    if (n > std::numeric_limits<std::uint32_t>::max()) throw InvalidMesh("mesh has more than 2^32 - 1 triangles");
    std::vector<Triangle> all(n);
    std::vector<std::uint32_t> crossing; // indices into `all`
    std::vector<Box2> boxes;             // of `crossing`
    for (std::size_t k = 0; k < n; ++k) {
        Triangle& t = all[k];
        for (int c = 0; c < 3; ++c) toViewSpace(mesh.positions[mesh.triangles[k][c]], t.v[c]);
        t.index = std::uint32_t(k);
        const int o = orient2d(t.v[0], t.v[1], t.v[2]);
        t.flags = o == 0 ? kParallel : o < 0 ? kEntering : 0;
        if (o < 0) std::swap(t.v[1], t.v[2]);
        for (int e = 0; e < 3; ++e)
            if (isTopLeft(t.v[e], t.v[(e + 1) % 3])) t.flags |= kTopLeft0 << e;
        if (o != 0) {
            crossing.push_back(std::uint32_t(k));
            boxes.push_back(boxOf(t));
        }
    }
    crossable = crossing.size();
    grid.layout(boxes);

    // Crossable triangles first, in the order of their boxes' centre cells,
    // so that the candidates of one query lie close together in memory.
    std::vector<std::pair<std::size_t, std::uint32_t>> order(crossable);
    for (std::size_t k = 0; k < crossable; ++k) {
        const Box2& b = boxes[k];
        const float centre[2] = {0.5f * b.lo[0] + 0.5f * b.hi[0], 0.5f * b.lo[1] + 0.5f * b.hi[1]};
        order[k] = {grid.cellIndex(centre), std::uint32_t(k)};
    }
    std::sort(order.begin(), order.end());
    tris.reserve(n);
    std::vector<Box2> sortedBoxes(crossable);
    for (std::size_t k = 0; k < crossable; ++k) {
        tris.push_back(all[crossing[order[k].second]]);
        sortedBoxes[k] = boxes[order[k].second];
    }
    for (const Triangle& t : all)
        if (t.flags & kParallel) tris.push_back(t);
    grid.fill(sortedBoxes);
}

} // namespace

// ---- The classifier -------------------------------------------------------

struct ExactClassifier::Impl : ProjectedMesh {
    using ProjectedMesh::ProjectedMesh;
};

ExactClassifier::ExactClassifier(MeshView mesh, Axis axis) {
    requireUsable(validateMesh(mesh), "mesh");
    impl_ = std::make_unique<Impl>(mesh, axis);
}

ExactClassifier::~ExactClassifier() = default;
ExactClassifier::ExactClassifier(ExactClassifier&&) noexcept = default;
ExactClassifier& ExactClassifier::operator=(ExactClassifier&&) noexcept = default;

Axis ExactClassifier::axis() const {
    assert(impl_ && "use of a moved-from ExactClassifier");
    return impl_->axis;
}

int ExactClassifier::winding(const glm::vec3& p) const {
    assert(impl_ && "use of a moved-from ExactClassifier");
    return impl_->winding(p);
}

namespace {
// Each crossing is +1 or -1, so the crossing count and the winding number
// have the same parity.
bool inside(int winding, Rule rule) { return rule == Rule::Parity ? (winding & 1) != 0 : winding != 0; }
} // namespace

bool ExactClassifier::contains(const glm::vec3& p, Rule rule) const { return inside(winding(p), rule); }

bool ExactClassifier::containsBruteForce(const glm::vec3& p, Rule rule) const {
    assert(impl_ && "use of a moved-from ExactClassifier");
    return inside(impl_->windingBruteForce(p), rule);
}

void ExactClassifier::classify(const glm::vec3* points, std::size_t count, std::uint8_t* labels,
                               const ClassifyOptions& options) const {
    assert(impl_ && "use of a moved-from ExactClassifier");
    assert((points && labels) || count == 0);
    const Impl& impl = *impl_;
    parallelFor(options.threads, count, 4096, [&](std::size_t begin, std::size_t end) {
        for (std::size_t k = begin; k < end; ++k) labels[k] = inside(impl.winding(points[k]), options.rule) ? 1 : 0;
    });
}

// ---- The CPU baker --------------------------------------------------------

namespace {

struct Crossing {
    float depth;
    std::uint32_t triangle;
    bool entering;
};

/// Depth of the plane of `tri` at q, in LDI texture space: the barycentric
/// coordinates of q in (s,t) (invariant under the grid's affine map) weight
/// the vertices' texture depths `r`. q is in the closed triangle, so the
/// result is kept within the vertices' depth range despite rounding.
float planeDepth(const Triangle& tri, const float* q, const std::array<float, 3>& r) {
    double weight[3], total = 0.0;
    for (int k = 0; k < 3; ++k) {
        const float* a = tri.v[(k + 1) % 3];
        const float* b = tri.v[(k + 2) % 3];
        const double w = (double(b[0]) - a[0]) * (double(q[1]) - a[1]) - (double(b[1]) - a[1]) * (double(q[0]) - a[0]);
        weight[k] = std::max(w, 0.0);
        total += weight[k];
    }
    double depth = total > 0.0 ? (weight[0] * r[0] + weight[1] * r[1] + weight[2] * r[2]) / total
                               : (double(r[0]) + r[1] + r[2]) / 3.0;
    depth = std::clamp(depth, double(std::min({r[0], r[1], r[2]})), double(std::max({r[0], r[1], r[2]})));
    return std::clamp(float(depth), 0.0f, 1.0f);
}

} // namespace

Sprite bakeCpu(MeshView mesh, const BakeOptions& options) {
    const detail::BakeSetup setup = detail::prepareBake(mesh, options);
    const SpriteGrid& grid = setup.grid;
    const auto report = [&](const std::string& message) {
        if (options.progress) options.progress(message);
    };
    report("cpu bake: indexing " + std::to_string(mesh.triangleCount) + " triangles");
    const ProjectedMesh projected(mesh, options.axis);

    // Texture-space depth of every vertex, as the GL bakers' vertex stage computes it.
    std::vector<std::array<float, 3>> vertexDepth(projected.crossable);
    for (std::size_t k = 0; k < projected.crossable; ++k)
        for (int c = 0; c < 3; ++c) {
            glm::vec3 world;
            for (int a = 0; a < 3; ++a) world[projected.perm[a]] = projected.tris[k].v[c][a];
            vertexDepth[k][std::size_t(c)] = grid.toTexture(world).z;
        }

    const std::uint32_t width = grid.width, height = grid.height;
    const unsigned threads = std::max(1u, std::thread::hardware_concurrency());
    report("cpu bake: casting " + std::to_string(width) + "x" + std::to_string(height) + " rays on " +
           std::to_string(threads) + " threads");
    std::vector<std::uint32_t> offsets(std::size_t(width) * height + 1, 0);
    std::vector<std::vector<float>> rows(height);
    parallelFor(threads, height, 1, [&](std::size_t row, std::size_t) {
        std::vector<Crossing> column;
        std::vector<float>& out = rows[row];
        for (std::uint32_t i = 0; i < width; ++i) {
            float q[3];
            projected.toViewSpace(grid.texelCentre(i, std::uint32_t(row), 0.0f), q);
            column.clear();
            const CellGrid::Found found = projected.grid.find(q);
            for (const CellEntry* e = found.begin; e != found.end; ++e) {
                if (!CellGrid::mayHold(*e, found.sub)) continue;
                const Triangle& t = projected.tris[e->triangle];
                if (claims(t, q))
                    column.push_back({planeDepth(t, q, vertexDepth[e->triangle]), t.index, (t.flags & kEntering) != 0});
            }
            std::sort(column.begin(), column.end(), [](const Crossing& a, const Crossing& b) {
                return a.depth < b.depth || (a.depth == b.depth && a.triangle < b.triangle);
            });
            for (const Crossing& c : column) out.push_back(encodeCrossing(c.depth, c.entering));
            offsets[row * width + i + 1] = std::uint32_t(column.size());
        }
    });

    std::uint64_t total = 0;
    for (const auto& r : rows) total += r.size();
    if (total > std::numeric_limits<std::uint32_t>::max())
        throw OutOfMemory("cpu bake: " + std::to_string(total) + " crossings exceed the sprite's 2^32 - 1 limit");
    std::partial_sum(offsets.begin(), offsets.end(), offsets.begin());
    std::vector<float> crossings;
    crossings.reserve(std::size_t(total));
    for (auto& r : rows) {
        crossings.insert(crossings.end(), r.begin(), r.end());
        std::vector<float>().swap(r);
    }
    report("cpu bake: " + std::to_string(total) + " crossings");
    return detail::assembleSprite(setup, options, mesh, std::move(offsets), std::move(crossings));
}

} // namespace vds
