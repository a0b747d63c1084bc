// vds: the layer count of the auto axis (sprite/layer_count.h), row by row.
//
// A texel's count is the number of triangles whose projection claims its
// centre (predicates/projected_mesh.h's `claims`). On one row of texel
// centres (t fixed) the centres a triangle claims form one run of
// consecutive texels: the tie rule claims p exactly when p + d, a point
// displaced by a fixed infinitesimal d, lies in the open triangle, and a
// line meets a convex set in an interval. So a triangle adds +1 at its run's
// first texel and -1 past its last in the row's difference array, and a
// prefix sum along the row gives every column's count: the same counts as
// testing every texel of every triangle's box, for two increments and a few
// claim tests a row instead of one claim test a texel.
//
// The run is found from the row's intersection (lo, hi) with the closed
// triangle, computed in double from the float vertices (an error of a few
// units in the last place of double, far below the texels' spacing). A row
// through no vertex crosses the open triangle: centres more than a margin
// inside (lo, hi) are claimed and those more than the margin outside are
// not, so only a centre within the margin of an end takes the exact claim
// test (almost never). A row through a vertex or along an edge takes the
// claim test from both ends of the range widened by the margin. Either way
// every claimed centre lies in the tested range, and the run being
// contiguous, the first and last claimed texels found from the ends bound
// it exactly (whatever the centres' spacing, equal centres included).
//
// Most steps cancel. On a row through no vertex of the mesh, a triangle's
// run is [i(left side), i(right side)), i(e) the first centre at or right of
// side e: the tie rule's displacement points right, so a centre on a side
// belongs to the triangle on its right. i(e) depends on the side alone, not
// on the triangle asking; so where an edge's two triangles lie on either
// side of it in projection (a surface continuing), one's -1 and the other's
// +1 fall on the same texel and cancel, on every such row. Only the other
// edges' steps are computed: the silhouette's, a boundary's, a non-manifold
// edge's, or an edge whose partner is not known by its vertex indices (the
// count is then slower, never different). A smooth closed mesh of a million
// triangles has a few thousand silhouette edges along an axis. A row through
// a vertex takes every triangle's whole run, as above. The crossings in all
// follow from the steps alone: a row's steps sum to 0, so a step of w at
// texel i adds -w i to the row's total.
//
// The centres are found from the even spacing's place of lo and hi, read
// from the centres only where that place lies within the centres' measured
// distance from the even spacing (`Centres`). Each axis's rows are cut into
// bands whose difference arrays stay in a core's cache; a first pass lists
// each triangle in the bands where it has steps to make (its vertices read
// once for the three axes), a second counts each band's steps into its
// arrays and takes the rows' largest sums, bands in parallel. The counts are
// sums and maxima of exact integers: the same for any number of threads.
#include <vds/detail/layer_count.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstring>
#include <limits>
#include <thread>
#include <utility>
#include <vector>

#include <vds/detail/edge_partners.h>
#include <vds/detail/parallel.h>

#include <vds/detail/projected_mesh.h>

namespace vds::detail {
namespace {

// The s range where row t meets the closed triangle (lo > hi: it misses).
void rowSpan(const Triangle& tri, double t, double& lo, double& hi) {
    lo = 1e300;
    hi = -1e300;
    for (int e = 0; e < 3; ++e) {
        const float* a = tri.v[e];
        const float* b = tri.v[(e + 1) % 3];
        const double ta = a[1], tb = b[1];
        if (t < std::min(ta, tb) || t > std::max(ta, tb)) continue;
        if (ta == tb) { // along the row: both ends
            lo = std::min({lo, double(a[0]), double(b[0])});
            hi = std::max({hi, double(a[0]), double(b[0])});
            continue;
        }
        const double f = std::clamp((t - ta) / (tb - ta), 0.0, 1.0);
        const double s = double(a[0]) + f * (double(b[0]) - double(a[0]));
        lo = std::min(lo, s);
        hi = std::max(hi, s);
    }
}

// The texel centres along one axis (increasing, nearly evenly spaced) and
// the searches on them.
struct Centres {
    std::vector<double> padded; ///< -inf, the centres, +inf: every search reads within it
    std::ptrdiff_t n = 0;
    double origin = 0.0, perTexel = 0.0;
    /// How far, in texels, a centre may lie from the even spacing's place
    /// for it, with x's place as computed (`place`); 1 where the spacing
    /// is too uneven to decide anything by it.
    double uneven = 1.0;

    explicit Centres(const std::vector<float>& centres) : n(std::ptrdiff_t(centres.size())) {
        padded.reserve(centres.size() + 2);
        padded.push_back(-std::numeric_limits<double>::infinity());
        padded.insert(padded.end(), centres.begin(), centres.end());
        padded.push_back(std::numeric_limits<double>::infinity());
        origin = centres.front();
        perTexel = n > 1 ? double(n - 1) / (double(centres.back()) - origin) : 0.0;
        if (n < 2 || !(perTexel > 0.0) || !std::isfinite(perTexel)) return;
        // The centres' distance from the even spacing, measured, and the
        // rounding of place(x) (relative 2^-50 of the coordinates, far above
        // double's few ulps).
        double off = 0.0;
        for (std::ptrdiff_t i = 0; i < n; ++i) off = std::max(off, std::fabs(place((*this)[i]) - double(i)));
        const double extent = std::fabs(origin) + std::fabs(double(centres.back()));
        const double slack = off + 0x1p-50 * extent * perTexel + 0x1p-40;
        if (slack < 0.25) uneven = slack;
    }
    std::size_t size() const { return std::size_t(n); }
    /// Centre i, -inf for i = -1, +inf for i = n.
    double operator[](std::ptrdiff_t i) const { return padded[std::size_t(i + 1)]; }
    /// x in texels of the even spacing: centre i near i.
    double place(double x) const { return (x - origin) * perTexel; }
    /// The first centre >= x (std::lower_bound's answer), and the first > x
    /// (`past`, std::upper_bound's): where x lies farther than `uneven`
    /// from every centre's even place, both are the next even place up,
    /// with no centre read; otherwise they are searched from there.
    std::ptrdiff_t first(double x) const { return find(x, [x](double c) { return c < x; }); }
    std::ptrdiff_t past(double x) const { return find(x, [x](double c) { return c <= x; }); }

private:
    /// The number of centres `before` x (a predicate true for a prefix).
    template <class Before>
    std::ptrdiff_t find(double x, const Before& before) const {
        // Clamped to [-1/2, n - 1/2], shifted up by one: > 0, so truncation is floor.
        const double u = std::clamp(place(x), -0.5, double(n) - 0.5) + 1.0;
        std::ptrdiff_t g = std::ptrdiff_t(u);
        const double f = u - double(g);
        if (f > uneven && f < 1.0 - uneven) return g;
        const double* c = padded.data() + 1;
        g = std::clamp<std::ptrdiff_t>(g, 0, n);
        while (g > 0 && before(c[g - 1]) == false) --g;
        while (g < n && before(c[g])) ++g;
        return g;
    }
};

// A triangle's sides as s = s0 + (t - t0) * slope, its vertices sorted by
// t: the long side from the lowest to the highest, the lower side up to the
// middle vertex and the upper side from it. A row strictly between the
// lowest and highest t and through no vertex crosses the long side and one
// short side strictly between their ends (the lower below the middle vertex),
// so its span takes no test of which edges it meets. The slopes' divisions are made once a triangle; the error
// is a few units in the last place of double (the differences of floats are
// exact in double), which the margin of `RowRuns` covers.
struct Sides {
    double tLo, tMid, sLo, sMid, slopeLong, slopeLower, slopeUpper;
    int lo, mid, hi; ///< the vertices (indices into Triangle::v) by t

    explicit Sides(const Triangle& tri) : lo(0), mid(1), hi(2) {
        const auto tOf = [&](int k) { return tri.v[k][1]; };
        if (tOf(mid) < tOf(lo)) std::swap(lo, mid);
        if (tOf(hi) < tOf(mid)) std::swap(mid, hi);
        if (tOf(mid) < tOf(lo)) std::swap(lo, mid);
        const auto slope = [](const float* a, const float* b) {
            return a[1] == b[1] ? 0.0 : (double(b[0]) - double(a[0])) / (double(b[1]) - double(a[1]));
        };
        const float *v0 = tri.v[lo], *v1 = tri.v[mid], *v2 = tri.v[hi];
        tLo = v0[1];
        tMid = v1[1];
        sLo = v0[0];
        sMid = v1[0];
        slopeLong = slope(v0, v2);
        slopeLower = slope(v0, v1);
        slopeUpper = slope(v1, v2);
    }
};

/// The steps a triangle's sides make on a row through none of the mesh's
/// vertices (see the file's comment): which sides' steps are kept (the
/// others cancel against the neighbour's), and which side is on the left.
struct SideSteps {
    bool longLeft;          ///< the long side is the left one (the middle vertex lies right of it)
    bool keepLong, keepLower, keepUpper;
};

struct RowRuns {
    const Centres& s;
    const Centres& t;

    /// The rows [j0, j1) of texel centres within the triangle's t range.
    std::pair<std::ptrdiff_t, std::ptrdiff_t> rows(float tLo, float tHi) const { return {t.first(tLo), t.past(tHi)}; }

    // Calls step(j, i, w) for what the triangle adds on each row j in
    // [rowBegin, rowEnd): w to the counts of texels i and on. A row through
    // a vertex of the mesh (`vertexRow[j]`) takes the triangle's whole run
    // [a, b) (+1 at a, -1 at b); any other row the steps of the sides
    // `kept` keeps, each at the first centre at or right of the side.
    template <class Step>
    void forEach(const Triangle& tri, const SideSteps& kept, std::ptrdiff_t rowBegin, std::ptrdiff_t rowEnd,
                 const std::uint8_t* vertexRow, const Step& step) const {
        const Box2 box = boxOf(tri);
        const auto [j0, j1] = rows(box.lo[1], box.hi[1]);
        rowBegin = std::max(rowBegin, j0);
        rowEnd = std::min(rowEnd, j1);
        if (rowBegin >= rowEnd) return;
        // What the double intersection may err by, with a wide margin
        // (a few double ulps of the coordinates, taken as 2^-40 of them).
        const double tol =
            0x1p-40 * 3.0 * std::max({std::fabs(tri.v[0][0]), std::fabs(tri.v[1][0]), std::fabs(tri.v[2][0])});
        const Sides sides(tri);
        const auto run = [&](std::ptrdiff_t j, std::ptrdiff_t a, std::ptrdiff_t b) {
            step(j, a, 1);
            step(j, b, -1);
        };
        // Rows below the middle vertex meet the lower side, the others the
        // upper side: two loops, no branch a row on which.
        const std::ptrdiff_t middle = std::clamp(t.first(sides.tMid), rowBegin, rowEnd);
        for (std::ptrdiff_t j = rowBegin; j < middle; ++j) {
            if (vertexRow[j])
                interior(tri, j, sides.sLo, sides.tLo, sides.slopeLower, sides, tol, run);
            else
                sideSteps(tri, j, sides.lo, sides.mid, sides.sLo, sides.tLo, sides.slopeLower, kept.keepLower, sides,
                          kept, tol, step);
        }
        for (std::ptrdiff_t j = middle; j < rowEnd; ++j) {
            if (vertexRow[j])
                interior(tri, j, sides.sMid, sides.tMid, sides.slopeUpper, sides, tol, run);
            else
                sideSteps(tri, j, sides.mid, sides.hi, sides.sMid, sides.tMid, sides.slopeUpper, kept.keepUpper, sides,
                          kept, tol, step);
        }
    }

    // Row j (through no vertex of the mesh) crosses the long side and the
    // short side from vertex `p` up to `q` (s0 + (t - t0) * slope) strictly
    // inside both: the run is [the left side's index, the right side's).
    template <class Step>
    void sideSteps(const Triangle& tri, std::ptrdiff_t j, int p, int q, double s0, double t0, double slope,
                   bool keepShort, const Sides& sides, const SideSteps& kept, double tol, const Step& step) const {
        const double row = t[j];
        if (kept.keepLong) {
            const double x = sides.sLo + (row - sides.tLo) * sides.slopeLong;
            step(j, sideIndex(tri.v[sides.lo], tri.v[sides.hi], row, x, tol), kept.longLeft ? 1 : -1);
        }
        if (keepShort) {
            const double x = s0 + (row - t0) * slope;
            step(j, sideIndex(tri.v[p], tri.v[q], row, x, tol), kept.longLeft ? -1 : 1);
        }
    }

    // The first centre of row `row` at or right of the side from p up to q
    // (x: where it crosses the row, within tol): the centres more than tol
    // from x are decided by x, the others by the exact orientation. A centre
    // on the side belongs to the triangle on its right (the tie rule's
    // displacement points right), whichever triangle asks.
    std::ptrdiff_t sideIndex(const float* p, const float* q, double row, double x, double tol) const {
        std::ptrdiff_t a = s.first(x - tol);
        const std::ptrdiff_t b = s.first(x + tol);
        float c[3] = {0.0f, float(row), 0.0f};
        for (; a < b; ++a) {
            c[0] = float(s[a]);
            if (orient2d(p, q, c) <= 0) break;
        }
        return a;
    }

    // Row j's run, the short side given as s0 + (t - t0) * slope.
    template <class Emit>
    void interior(const Triangle& tri, std::ptrdiff_t j, double s0, double t0, double slope, const Sides& sides,
                  double tol, const Emit& emit) const {
        const double row = t[j];
        std::ptrdiff_t a, b;
        if (row == double(tri.v[0][1]) || row == double(tri.v[1][1]) || row == double(tri.v[2][1])) {
            // Through a vertex (or along an edge): the ends by the claim test.
            double lo, hi;
            rowSpan(tri, row, lo, hi);
            if (lo > hi) return;
            a = s.first(lo - tol);
            b = s.past(hi + tol);
            narrow(tri, float(row), a, b, false, false);
        } else {
            // Through the interior: a centre farther than tol inside
            // (lo, hi) lies in the open triangle, one farther outside
            // outside the closed one; only an end within tol of lo or
            // hi takes the claim test.
            const double x = sides.sLo + (row - sides.tLo) * sides.slopeLong, y = s0 + (row - t0) * slope;
            const double lo = std::min(x, y), hi = std::max(x, y);
            a = s.first(lo - tol);
            b = s.past(hi + tol);
            if (a >= b) return;
            const bool sureA = s[a] > lo + tol && s[a] < hi - tol, sureB = s[b - 1] > lo + tol && s[b - 1] < hi - tol;
            if (!(sureA && sureB)) narrow(tri, float(row), a, b, sureA, sureB);
        }
        if (a < b) emit(j, a, b);
    }

    // Narrows [a, b), which holds the row's run, to the run; `sureA` says
    // texel a is known claimed, `sureB` texel b - 1.
    void narrow(const Triangle& tri, float row, std::ptrdiff_t& a, std::ptrdiff_t& b, bool sureA, bool sureB) const {
        float c[3] = {0.0f, row, 0.0f};
        for (; !sureA && a < b; ++a) {
            c[0] = float(s[a]);
            if (claims(tri, c)) break;
        }
        for (; !sureB && b > a; --b) {
            c[0] = float(s[b - 1]);
            if (claims(tri, c)) break;
        }
    }
};

// One axis's texel centres and its rows cut into bands.
struct AxisRows {
    glm::ivec3 perm;
    Centres s, t;
    std::size_t bandRows = 1, bands = 0;

    AxisRows(const SpriteGrid& grid, std::size_t rowsPerBand)
        : perm(axisPermutation(grid.axis)), s(centres(grid, true)), t(centres(grid, false)), bandRows(rowsPerBand),
          bands((t.size() + rowsPerBand - 1) / rowsPerBand) {}

    // The texel centres along s or t, as the baker's `texelCentre` rounds
    // them (a baking grid is axis-aligned: s follows i alone, t follows j alone).
    static std::vector<float> centres(const SpriteGrid& grid, bool alongS) {
        const glm::ivec3 p = axisPermutation(grid.axis);
        std::vector<float> at(alongS ? grid.width : grid.height);
        for (std::uint32_t k = 0; k < at.size(); ++k)
            at[k] = alongS ? grid.texelCentre(k, 0, 0.0f)[p.x] : grid.texelCentre(0, k, 0.0f)[p.y];
        return at;
    }
};

// One band of rows at a time: the rows' difference arrays (a run +1 at its
// first texel, -1 past its last; a side's step its weight), small enough to
// stay in the core's cache, and the texels each row's steps touch (the
// counts are 0 outside them: the steps of a row sum to 0).
class Band {
public:
    Band(std::size_t rows, std::size_t width)
        : diff_(rows * (width + 1), 0), lo_(rows, std::uint32_t(width)), hi_(rows, 0), stride_(width + 1) {}

    /// Adds w to the counts of texels i and on of the row.
    void step(std::size_t row, std::uint32_t i, std::int32_t w) {
        diff_[row * stride_ + i] += w;
        lo_[row] = std::min(lo_[row], i);
        hi_[row] = std::max(hi_[row], i);
    }
    /// The most runs over one texel of rows [0, rows), the differences then
    /// cleared.
    std::int32_t most(std::size_t rows) {
        std::int32_t best = 0;
        for (std::size_t r = 0; r < rows; ++r) {
            if (lo_[r] < hi_[r]) best = std::max(best, rowMost(diff_.data() + r * stride_, lo_[r], hi_[r]));
            lo_[r] = std::uint32_t(stride_ - 1);
            hi_[r] = 0;
        }
        return best;
    }

private:
    // The row's largest prefix sum over [lo, hi); clears [lo, hi] (the
    // row's differences sum to 0 there).
    static std::int32_t rowMost(std::int32_t* diff, std::uint32_t lo, std::uint32_t hi) {
        std::int32_t running = 0, best = 0;
        std::uint32_t i = lo;
        for (; i + 4 <= hi; i += 4) { // four texels a step: the sums within the step do not wait on `running`
            const std::int32_t* d = diff + i;
            const std::int32_t p1 = d[0], p2 = p1 + d[1], p3 = p2 + d[2], p4 = p3 + d[3];
            best = std::max(best, running + std::max(std::max(p1, p2), std::max(p3, p4)));
            running += p4;
        }
        for (; i < hi; ++i) best = std::max(best, running += diff[i]);
        std::fill(diff + lo, diff + hi + 1, 0);
        return best;
    }

    std::vector<std::int32_t> diff_;
    std::vector<std::uint32_t> lo_, hi_;
    std::size_t stride_;
};

// Texels of difference array a band holds (256 KB of counts: a core's
// cache holds it beside the mesh data streaming through), and the most
// bands an axis is cut into (the triangle lists are per band and chunk).
constexpr std::size_t kBandTexels = std::size_t(1) << 16;
constexpr std::size_t kMaxBands = 256;
// Triangles (vertices) a chunk of the passes over them.
constexpr std::size_t kChunk = std::size_t(1) << 16;

std::size_t rowsPerBand(std::uint32_t width, std::uint32_t height) {
    const std::size_t byCache = std::max<std::size_t>(1, kBandTexels / (std::size_t(width) + 1));
    return std::max(byCache, (std::size_t(height) + kMaxBands - 1) / kMaxBands);
}

// The edges' partners (kNoPartner, kSameWay: <vds/detail/edge_partners.h>)
// are validation's where it found them, by vertices welded by position. An
// edge without one (a boundary, a non-manifold edge, an edge of a triangle
// with a repeated vertex) keeps its steps, which costs time, not exactness.

// Sorts a vertex's few edges (insertion: most vertices have about six).
void sortFew(std::uint64_t* items, std::size_t n) {
    if (n > 16) {
        std::sort(items, items + n);
        return;
    }
    for (std::size_t i = 1; i < n; ++i) {
        const std::uint64_t v = items[i];
        std::size_t j = i;
        for (; j > 0 && v < items[j - 1]; --j) items[j] = items[j - 1];
        items[j] = v;
    }
}

// The partners by vertex index, where validation's were not given: a
// counting sort of the edges by their lower vertex and a
// sort of each vertex's few edges by the higher one. Each thread sorts the
// edges of its own range of lower vertices, reading every triangle: no
// counts are shared, and the triangles stream while the counts and edges
// are written at random.
LargeVector<std::uint32_t> edgePartners(MeshView mesh, unsigned threads) {
    const std::size_t nt = mesh.triangleCount, nv = mesh.positionCount;
    LargeVector<std::uint32_t> partner(3 * nt, kNoPartner);
    if (nt >= kSameWay / 3) return partner; // half-edges and partners must fit their bits
    const auto ends = [&](std::size_t h) {
        const glm::uvec3 tri = mesh.triangles[h / 3];
        return std::make_pair(tri[int(h % 3)], tri[int((h + 1) % 3)]);
    };
    const unsigned ranges = std::max(1u, std::min(threads ? threads : std::thread::hardware_concurrency(), 8u));
    // Calls f(lower, higher, half-edge) for the edges whose lower vertex
    // is in range r.
    const auto forRange = [&](std::size_t r, const auto& f) {
        const std::size_t lo = nv * r / ranges, hi = nv * (r + 1) / ranges;
        for (std::size_t t = 0; t < nt; ++t) {
            const glm::uvec3 tri = mesh.triangles[t];
            for (int e = 0; e < 3; ++e) {
                const std::uint32_t u = tri[e], v = tri[(e + 1) % 3], m = std::min(u, v);
                if (u != v && m >= lo && m < hi && std::max(u, v) < nv)
                    f(m, std::max(u, v), std::uint32_t(3 * t + std::size_t(e)));
            }
        }
    };
    std::vector<std::uint32_t> start(nv + 1, 0);
    detail::parallelFor(ranges, ranges, 1, [&](std::size_t r, std::size_t) {
        forRange(r, [&](std::uint32_t m, std::uint32_t, std::uint32_t) { ++start[m + 1]; });
    });
    for (std::size_t v = 0; v < nv; ++v) start[v + 1] += start[v];
    std::vector<std::uint64_t> items(start[nv]); ///< higher vertex << 32 | half-edge
    std::vector<std::uint32_t> next(start.begin(), start.end() - 1);
    detail::parallelFor(ranges, ranges, 1, [&](std::size_t r, std::size_t) {
        forRange(r, [&](std::uint32_t m, std::uint32_t other, std::uint32_t h) {
            items[next[m]++] = (std::uint64_t(other) << 32) | h;
        });
    });
    detail::parallelFor(threads, nv, kChunk, [&](std::size_t begin, std::size_t end) {
        for (std::size_t v = begin; v < end; ++v) {
            std::uint64_t* group = items.data() + start[v];
            const std::size_t n = start[v + 1] - start[v];
            sortFew(group, n);
            for (std::size_t i = 0, j; i < n; i = j) {
                for (j = i + 1; j < n && (group[j] >> 32) == (group[i] >> 32);) ++j;
                if (j - i != 2) continue;
                const auto h1 = std::uint32_t(group[i]), h2 = std::uint32_t(group[i + 1]);
                if (h1 / 3 == h2 / 3) continue;
                const std::uint32_t same = ends(h1).first == ends(h2).first ? kSameWay : 0;
                partner[h1] = h2 / 3 | same;
                partner[h2] = h1 / 3 | same;
            }
        }
    });
    return partner;
}

// Each triangle's facing along each axis, two bits an axis (axis a at bit
// 2a): 1 counter-clockwise in projection, 2 clockwise, 0 parallel
// (<vds/detail/edge_partners.h>). Validation's, where given, with the few it
// left undecided decided here by the exact predicate; otherwise all found here.
LargeVector<std::uint8_t> facings(MeshView mesh, const std::vector<glm::ivec3>& perms, unsigned threads,
                                  const LargeVector<std::uint8_t>& found) {
    const bool given = found.size() == mesh.triangleCount;
    LargeVector<std::uint8_t> facing = given ? found : LargeVector<std::uint8_t>(mesh.triangleCount, 0);
    detail::parallelFor(threads, mesh.triangleCount, kChunk, [&](std::size_t begin, std::size_t end) {
        for (std::size_t k = begin; k < end; ++k) {
            // Given: eight triangles a word, skipped where no pair of bits is
            // kFacesUndecided (both set).
            std::uint64_t word = 0;
            if (given && k % 8 == 0 && k + 8 <= end) {
                std::memcpy(&word, facing.data() + k, 8);
                if ((word & (word >> 1) & 0x1515151515151515ull) == 0) {
                    k += 7;
                    continue;
                }
            }
            std::uint8_t bits = facing[k];
            const glm::uvec3 tri = mesh.triangles[k];
            const glm::vec3* p[3] = {&mesh.positions[tri.x], &mesh.positions[tri.y], &mesh.positions[tri.z]};
            for (std::size_t a = 0; a < 3; ++a) {
                if (given && ((bits >> (2 * a)) & 3) != kFacesUndecided) continue;
                float v[3][2];
                for (int c = 0; c < 3; ++c) v[c][0] = (*p[c])[perms[a].x], v[c][1] = (*p[c])[perms[a].y];
                const int o = orient2d(v[0], v[1], v[2]);
                bits = std::uint8_t((bits & ~(3u << (2 * a))) | unsigned(o > 0 ? 1 : o < 0 ? 2 : 0) << (2 * a));
            }
            facing[k] = bits;
        }
    });
    return facing;
}

// What the listing and the bands share of one count.
struct Mesh3 {
    MeshView mesh;
    const LargeVector<std::uint32_t>& partner;
    LargeVector<std::uint8_t> facing;

    int facingOf(std::size_t t, std::size_t axis) const { return (facing[t] >> (2 * axis)) & 3; }
    /// The bits e of triangle t's edges whose steps along `axis` cancel
    /// against the partner's on every row through no vertex: the partner
    /// lies on the other side of the edge in projection (same facing where
    /// the edge runs the two ways, opposite facings where it runs one way),
    /// both crossable. Their first centre at or right of the edge is the
    /// same, one's run ending where the other's starts. Bit 3a + e: axis a.
    unsigned cancelling(std::size_t t) const {
        unsigned bits = 0;
        for (unsigned e = 0; e < 3; ++e) {
            const std::uint32_t p = partner[3 * t + e];
            if (p == kNoPartner) continue;
            const unsigned f = facing[t], g = facing[p & ~kSameWay];
            for (unsigned a = 0; a < 3; ++a) {
                const unsigned fa = (f >> (2 * a)) & 3, ga = (g >> (2 * a)) & 3;
                if (fa != 0 && ga != 0 && ((p & kSameWay) ? ga != fa : ga == fa)) bits |= 1u << (3 * a + e);
            }
        }
        return bits;
    }
    /// Which of the projected triangle's sides keep their steps, given its
    /// cancelling edges (the projection may have swapped corners 1 and 2).
    static SideSteps kept(const Triangle& tri, const Sides& sides, unsigned cancel) {
        const auto corner = [&](int k) { return (tri.flags & kEntering) && k != 0 ? 3 - k : k; };
        const auto keeps = [&](int a, int b) {
            const int sum = corner(a) + corner(b); // corners 0,1: edge 0; 1,2: edge 1; 2,0: edge 2
            return !((cancel >> (sum == 1 ? 0 : sum == 3 ? 1 : 2)) & 1u);
        };
        return {orient2d(tri.v[sides.lo], tri.v[sides.hi], tri.v[sides.mid]) < 0, keeps(sides.lo, sides.hi),
                keeps(sides.lo, sides.mid), keeps(sides.mid, sides.hi)};
    }
};

// The rows of an axis that some vertex's t equals (where sides meet and
// their steps may not cancel), and how many precede each row.
struct VertexRows {
    std::vector<std::uint8_t> at;
    std::vector<std::uint32_t> before; ///< size rows + 1
    std::vector<double> values;        ///< the rows' centres, increasing

    VertexRows(MeshView mesh, const Centres& t, int coordinate, unsigned threads)
        : at(t.size(), 0), before(t.size() + 1, 0) {
        std::vector<std::atomic<std::uint8_t>> marks(t.size());
        detail::parallelFor(threads, mesh.positionCount, kChunk, [&](std::size_t begin, std::size_t end) {
            for (std::size_t v = begin; v < end; ++v) {
                const float x = mesh.positions[v][coordinate];
                for (std::ptrdiff_t j = t.first(x); j < t.n && t[j] == double(x); ++j) // equal centres: each row
                    marks[std::size_t(j)].store(1, std::memory_order_relaxed);
            }
        });
        for (std::size_t j = 0; j < at.size(); ++j) {
            at[j] = marks[j].load(std::memory_order_relaxed);
            before[j + 1] = before[j] + at[j];
            const double centre = t[std::ptrdiff_t(j)];
            if (at[j] && (values.empty() || values.back() != centre)) values.push_back(centre);
        }
    }
    /// Whether a row through a vertex lies within [lo, hi].
    bool anyWithin(float lo, float hi) const {
        const auto it = std::lower_bound(values.begin(), values.end(), double(lo));
        return it != values.end() && *it <= double(hi);
    }
    /// Whether a row through a vertex lies in rows [begin, end).
    bool anyIn(std::ptrdiff_t begin, std::ptrdiff_t end) const {
        return before[std::size_t(end)] > before[std::size_t(begin)];
    }
};

struct Axes {
    std::vector<AxisRows> rows;
    std::vector<VertexRows> vertexRows;
    std::size_t bandRows, bands;
};

// First pass: each chunk of triangles lists, for each axis and band, its
// triangles with steps to make there: those with an edge that does not
// cancel, and the others only in bands holding a row through a vertex.
std::vector<std::vector<std::uint32_t>> listTriangles(const Mesh3& m, const Axes& axes, unsigned threads) {
    const MeshView mesh = m.mesh;
    const std::size_t chunks = (mesh.triangleCount + kChunk - 1) / kChunk, bands = axes.bands;
    std::vector<std::vector<std::uint32_t>> lists(chunks * 3 * bands);
    detail::parallelFor(threads, mesh.triangleCount, kChunk, [&](std::size_t begin, std::size_t end) {
        const std::size_t chunk = begin / kChunk;
        for (std::size_t k = begin; k < end; ++k) {
            const unsigned cancel = m.cancelling(k);
            const glm::uvec3 tri = mesh.triangles[k];
            const glm::vec3 &p0 = mesh.positions[tri.x], &p1 = mesh.positions[tri.y], &p2 = mesh.positions[tri.z];
            const glm::vec3 lo = glm::min(glm::min(p0, p1), p2), hi = glm::max(glm::max(p0, p1), p2);
            for (std::size_t a = 0; a < 3; ++a) {
                const VertexRows& vertexRows = axes.vertexRows[a];
                const bool silent = ((cancel >> (3 * a)) & 7u) == 7u;
                if (m.facingOf(k, a) == 0 || (silent && vertexRows.values.empty())) continue;
                const int c = axes.rows[a].perm.y;
                if (silent && !vertexRows.anyWithin(lo[c], hi[c])) continue;
                const Centres& t = axes.rows[a].t;
                const std::ptrdiff_t j0 = t.first(lo[c]), j1 = t.past(hi[c]);
                if (j0 >= j1) continue; // between two rows of centres
                const std::size_t rows = axes.bandRows;
                for (std::size_t b = std::size_t(j0) / rows, last = std::size_t(j1 - 1) / rows; b <= last; ++b) {
                    const std::ptrdiff_t from = std::max(j0, std::ptrdiff_t(b * rows));
                    const std::ptrdiff_t to = std::min(j1, std::ptrdiff_t((b + 1) * rows));
                    if (!silent || vertexRows.anyIn(from, to))
                        lists[(chunk * 3 + a) * bands + b].push_back(std::uint32_t(k));
                }
            }
        }
    });
    return lists;
}

} // namespace

std::array<LayerCount, 3> countLayers(MeshView mesh, const std::array<SpriteGrid, 3>& grids, unsigned threads,
                                      const MeshFinds& finds) {
    std::uint32_t width = 1, height = 1;
    for (const SpriteGrid& g : grids) {
        width = std::max(width, g.width);
        height = std::max(height, g.height);
    }
    Axes axes;
    axes.bandRows = rowsPerBand(width, height);
    axes.bands = (std::size_t(height) + axes.bandRows - 1) / axes.bandRows;
    std::vector<glm::ivec3> perms;
    for (const SpriteGrid& g : grids) {
        axes.rows.emplace_back(g, axes.bandRows);
        perms.push_back(axes.rows.back().perm);
        axes.vertexRows.emplace_back(mesh, axes.rows.back().t, perms.back().y, threads);
    }
    const bool given = finds.partners.size() == 3 * mesh.triangleCount;
    const LargeVector<std::uint32_t> own = given ? LargeVector<std::uint32_t>() : edgePartners(mesh, threads);
    const Mesh3 m{mesh, given ? finds.partners : own, facings(mesh, perms, threads, finds.facings)};
    const std::vector<std::vector<std::uint32_t>> lists = listTriangles(m, axes, threads);
    // Second pass: each band of each axis, its triangles' steps into the
    // band's difference arrays, then its rows' largest counts. A step of w
    // at texel i adds w (n - i) to the row's n texels, and a row's steps sum
    // to 0: the crossings in all are the sum of -w i.
    const std::size_t bands = axes.bands, tasks = 3 * bands, chunks = lists.size() / tasks;
    std::vector<std::pair<std::int32_t, std::int64_t>> found(tasks);
    std::atomic<std::size_t> next{0};
    const unsigned hardware = detail::ThreadPool::hardwareThreads();
    const unsigned bandThreads = unsigned(std::min<std::size_t>(threads ? threads : hardware, tasks));
    detail::parallelFor(bandThreads, bandThreads, 1, [&](std::size_t, std::size_t) {
        Band band(axes.bandRows, width);
        for (std::size_t task; (task = next.fetch_add(1)) < tasks;) {
            const std::size_t a = task / bands, b = task % bands;
            const AxisRows& axis = axes.rows[a];
            if (b >= axis.bands) continue;
            const RowRuns runs{axis.s, axis.t};
            const std::ptrdiff_t first = std::ptrdiff_t(b * axes.bandRows);
            const std::ptrdiff_t end = std::min<std::ptrdiff_t>(first + std::ptrdiff_t(axes.bandRows), axis.t.n);
            std::int64_t claimed = 0;
            for (std::size_t chunk = 0; chunk < chunks; ++chunk)
                for (std::uint32_t k : lists[(chunk * 3 + a) * bands + b]) {
                    const Triangle tri = projectTriangle(mesh, k, axis.perm);
                    if (tri.flags & kParallel) continue;
                    const SideSteps kept = Mesh3::kept(tri, Sides(tri), (m.cancelling(k) >> (3 * a)) & 7u);
                    const auto step = [&](std::ptrdiff_t j, std::ptrdiff_t i, std::int32_t w) {
                        band.step(std::size_t(j - first), std::uint32_t(i), w);
                        claimed -= std::int64_t(w) * i;
                    };
                    runs.forEach(tri, kept, first, end, axes.vertexRows[a].at.data(), step);
                }
            found[task] = {band.most(std::size_t(end - first)), claimed};
        }
    });
    std::array<LayerCount, 3> counts{};
    for (std::size_t task = 0; task < tasks; ++task) {
        LayerCount& c = counts[task / bands];
        c.most = std::max(c.most, std::uint32_t(found[task].first));
        c.total += std::uint64_t(found[task].second);
    }
    return counts;
}

} // namespace vds::detail
