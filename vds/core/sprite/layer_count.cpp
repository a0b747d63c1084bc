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
// claim test at both ends of the range widened by one texel. Either way
// every claimed centre lies in the tested range, and the run being
// contiguous, the first and last claimed texels found from the ends bound
// it exactly.
#include "sprite/layer_count.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <memory>
#include <utility>
#include <vector>

#include <vds/detail/parallel.h>

#include "predicates/projected_mesh.h"

namespace vds::detail {
namespace {

// Texels that the double intersection may be off by, at most: it errs by a
// few units in the last place of double, and the texel centres, being
// distinct floats, lie at least one float ulp (2^29 double ulps) apart.
constexpr std::ptrdiff_t kWiden = 1;

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

// The triangle's three edges as s = s0 + (t - t0) * slope, for rows through
// no vertex: the slope's one division is made once a triangle instead of
// once a row. Its error is a few units in the last place of double, as
// rowSpan's (the differences of floats are exact in double), so the same
// margin covers both.
struct Edges {
    double t0[3], tLo[3], tHi[3], s0[3], slope[3];

    explicit Edges(const Triangle& tri) {
        for (int e = 0; e < 3; ++e) {
            const float* a = tri.v[e];
            const float* b = tri.v[(e + 1) % 3];
            t0[e] = a[1];
            s0[e] = a[0];
            tLo[e] = std::min(a[1], b[1]);
            tHi[e] = std::max(a[1], b[1]);
            slope[e] = a[1] == b[1] ? 0.0 : (double(b[0]) - double(a[0])) / (double(b[1]) - double(a[1]));
        }
    }
    /// rowSpan for a row t equal to no vertex's t: it crosses two edges
    /// strictly between their ends, or none.
    void span(double t, double& lo, double& hi) const {
        lo = 1e300;
        hi = -1e300;
        for (int e = 0; e < 3; ++e) {
            if (!(t > tLo[e] && t < tHi[e])) continue;
            const double s = s0[e] + (t - t0[e]) * slope[e];
            lo = std::min(lo, s);
            hi = std::max(hi, s);
        }
    }
};

// The texel centres along one axis (increasing, nearly evenly spaced) and
// the binary searches on them, started from the even spacing's guess.
struct Centres {
    std::vector<float> at;
    double origin = 0.0, perTexel = 0.0;

    explicit Centres(std::vector<float> centres) : at(std::move(centres)) {
        origin = at.front();
        perTexel = at.size() > 1 ? double(at.size() - 1) / (double(at.back()) - double(at.front())) : 0.0;
    }
    std::ptrdiff_t guess(double x) const {
        const double g = (x - origin) * perTexel;
        return std::ptrdiff_t(std::clamp(g, 0.0, double(at.size())));
    }
    /// The first centre >= x (std::lower_bound's answer).
    std::ptrdiff_t first(double x) const {
        std::ptrdiff_t g = guess(x);
        while (g > 0 && double(at[std::size_t(g - 1)]) >= x) --g;
        while (g < std::ptrdiff_t(at.size()) && double(at[std::size_t(g)]) < x) ++g;
        return g;
    }
    /// The first centre > x (std::upper_bound's answer).
    std::ptrdiff_t past(double x) const {
        std::ptrdiff_t g = guess(x);
        while (g > 0 && double(at[std::size_t(g - 1)]) > x) --g;
        while (g < std::ptrdiff_t(at.size()) && double(at[std::size_t(g)]) <= x) ++g;
        return g;
    }
};

// One triangle's run of claimed texels [a, b) on a row.
struct Run {
    std::uint32_t row, a, b;
};

struct RowCounts {
    const Centres& s;
    const Centres& t;

    // Appends the triangle's runs to `out`.
    void add(const Triangle& tri, std::vector<Run>& out) const {
        const Box2 box = boxOf(tri);
        const std::ptrdiff_t j0 = t.first(box.lo[1]), j1 = t.past(box.hi[1]);
        if (j0 >= j1) return; // between two rows of centres
        // What the double intersection may err by, with a wide margin
        // (a few double ulps of the coordinates, taken as 2^-40 of them).
        const double tol = 0x1p-40 * 3.0 * std::max({std::fabs(tri.v[0][0]), std::fabs(tri.v[1][0]), std::fabs(tri.v[2][0])});
        const Edges edges(tri);
        for (std::ptrdiff_t j = j0; j < j1; ++j) {
            const float row = t.at[std::size_t(j)];
            std::ptrdiff_t a, b;
            if (row == tri.v[0][1] || row == tri.v[1][1] || row == tri.v[2][1]) {
                // Through a vertex (or along an edge): the ends by the claim test.
                double lo, hi;
                rowSpan(tri, double(row), lo, hi);
                if (lo > hi) continue;
                a = s.first(lo) - kWiden;
                b = s.past(hi) + kWiden;
                a = std::max<std::ptrdiff_t>(a, 0);
                b = std::min<std::ptrdiff_t>(b, std::ptrdiff_t(s.at.size()));
                narrow(tri, row, a, b, false, false);
            } else {
                // Through the interior: a centre farther than tol inside
                // (lo, hi) lies in the open triangle, one farther outside
                // outside the closed one; only an end within tol of lo or
                // hi takes the claim test.
                double lo, hi;
                edges.span(double(row), lo, hi);
                if (lo > hi) continue;
                a = s.first(lo - tol);
                b = s.past(hi + tol);
                const auto inside = [&](std::ptrdiff_t i) {
                    const double c = s.at[std::size_t(i)];
                    return c > lo + tol && c < hi - tol;
                };
                narrow(tri, row, a, b, a < b && inside(a), a < b && inside(b - 1));
            }
            if (a < b) out.push_back({std::uint32_t(j), std::uint32_t(a), std::uint32_t(b)});
        }
    }

    // Narrows [a, b), which holds the row's run, to the run; `sureA` says
    // texel a is known claimed, `sureB` texel b - 1.
    void narrow(const Triangle& tri, float row, std::ptrdiff_t& a, std::ptrdiff_t& b, bool sureA, bool sureB) const {
        float c[3] = {0.0f, row, 0.0f};
        for (; !sureA && a < b; ++a) {
            c[0] = s.at[std::size_t(a)];
            if (claims(tri, c)) break;
        }
        for (; !sureB && b > a; --b) {
            c[0] = s.at[std::size_t(b - 1)];
            if (claims(tri, c)) break;
        }
    }
};

// The most runs over one texel of a row. A row of few runs (a small
// mesh's triangles span many rows, so its rows hold a few dozen runs over
// thousands of texels) sorts its runs' ends: the count is largest just after
// a start, where it is the starts up to there less the ends up to there. A
// row of many runs sums its difference array over the texels they touch.
class RowMost {
public:
    explicit RowMost(std::uint32_t width) : diff_(std::size_t(width) + 1), width_(width) {}

    std::int32_t most(const std::pair<std::uint32_t, std::uint32_t>* runs, std::size_t k, std::uint64_t& claimed) {
        if (k == 0) return 0;
        std::uint32_t lo = width_, hi = 0; // the row's texels that runs touch
        for (std::size_t r = 0; r < k; ++r) {
            claimed += runs[r].second - runs[r].first;
            lo = std::min(lo, runs[r].first);
            hi = std::max(hi, runs[r].second);
        }
        return k * kSortedPerTexel < hi - lo ? byEnds(runs, k) : bySum(runs, k, lo, hi);
    }

private:
    // A sort of k ends costs about what a sum over this many texels a run does.
    static constexpr std::size_t kSortedPerTexel = 16;

    std::int32_t byEnds(const std::pair<std::uint32_t, std::uint32_t>* runs, std::size_t k) {
        starts_.resize(k);
        ends_.resize(k);
        for (std::size_t r = 0; r < k; ++r) {
            starts_[r] = runs[r].first;
            ends_[r] = runs[r].second;
        }
        std::sort(starts_.begin(), starts_.end());
        std::sort(ends_.begin(), ends_.end());
        std::size_t ended = 0;
        std::int32_t best = 0;
        for (std::size_t r = 0; r < k; ++r) { // runs [a, b): b <= x has ended at x
            while (ended < k && ends_[ended] <= starts_[r]) ++ended;
            best = std::max(best, std::int32_t(r + 1 - ended));
        }
        return best;
    }
    std::int32_t bySum(const std::pair<std::uint32_t, std::uint32_t>* runs, std::size_t k, std::uint32_t lo, std::uint32_t hi) {
        for (std::size_t r = 0; r < k; ++r) {
            ++diff_[runs[r].first];
            --diff_[runs[r].second];
        }
        std::int32_t running = 0, best = 0;
        std::uint32_t i = lo;
        for (; i + 4 <= hi; i += 4) { // four texels a step: the sums within the step do not wait on `running`
            const std::int32_t* d = diff_.data() + i;
            const std::int32_t p1 = d[0], p2 = p1 + d[1], p3 = p2 + d[2], p4 = p3 + d[3];
            best = std::max(best, running + std::max(std::max(p1, p2), std::max(p3, p4)));
            running += p4;
        }
        for (; i < hi; ++i) best = std::max(best, running += diff_[i]);
        std::fill(diff_.begin() + lo, diff_.begin() + hi + 1, 0); // the row's differences sum to 0
        return best;
    }

    std::vector<std::int32_t> diff_;
    std::vector<std::uint32_t> starts_, ends_;
    std::uint32_t width_;
};

} // namespace

// The runs and their buckets, kept from one axis's count to the next: their
// pages are then faulted in once (tens of MB for a million triangles), not
// once an axis, and the chunks' vectors keep their capacity.
struct LayerCounter::Buffers {
    std::vector<std::vector<Run>> runs;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> byRow;
};

LayerCounter::LayerCounter() : buffers_(std::make_unique<Buffers>()) {}
LayerCounter::~LayerCounter() = default;

LayerCount LayerCounter::count(MeshView mesh, const SpriteGrid& grid, unsigned threads) {
    const glm::ivec3 perm = axisPermutation(grid.axis);
    // Texel centres along s and t, as the baker's `texelCentre` rounds them
    // (a baking grid is axis-aligned: s follows i alone, t follows j alone).
    std::vector<float> sAt(grid.width), tAt(grid.height);
    for (std::uint32_t i = 0; i < grid.width; ++i) sAt[i] = grid.texelCentre(i, 0, 0.0f)[perm.x];
    for (std::uint32_t j = 0; j < grid.height; ++j) tAt[j] = grid.texelCentre(0, j, 0.0f)[perm.y];
    const Centres s(std::move(sAt)), t(std::move(tAt));
    const RowCounts rows{s, t};
    // The runs, chunk by chunk of triangles, then bucketed by row: each row's
    // difference array is then small enough to stay in the core's cache.
    constexpr std::size_t kChunk = 4096;
    std::vector<std::vector<Run>>& runs = buffers_->runs;
    runs.resize((mesh.triangleCount + kChunk - 1) / kChunk);
    for (auto& chunk : runs) chunk.clear();
    parallelFor(threads, mesh.triangleCount, kChunk, [&](std::size_t begin, std::size_t end) {
        std::vector<Run>& out = runs[begin / kChunk];
        for (std::size_t k = begin; k < end; ++k) {
            const Triangle tri = projectTriangle(mesh, k, perm);
            if (!(tri.flags & kParallel)) rows.add(tri, out);
        }
    });
    std::vector<std::uint32_t> start(std::size_t(grid.height) + 1, 0);
    for (const auto& chunk : runs)
        for (const Run& r : chunk) ++start[r.row + 1];
    for (std::size_t j = 0; j < grid.height; ++j) start[j + 1] += start[j];
    std::vector<std::pair<std::uint32_t, std::uint32_t>>& byRow = buffers_->byRow;
    byRow.resize(start.back());
    {
        std::vector<std::uint32_t> next(start.begin(), start.end() - 1);
        for (const auto& chunk : runs)
            for (const Run& r : chunk) byRow[next[r.row]++] = {r.a, r.b};
    }
    std::atomic<std::uint32_t> most{0};
    std::atomic<std::uint64_t> total{0};
    parallelFor(threads, grid.height, 64, [&](std::size_t begin, std::size_t end) {
        RowMost row(grid.width);
        std::int32_t best = 0;
        std::uint64_t claimed = 0;
        for (std::size_t j = begin; j < end; ++j)
            best = std::max(best, row.most(byRow.data() + start[j], start[j + 1] - start[j], claimed));
        total.fetch_add(claimed);
        std::uint32_t seen = most.load();
        while (std::uint32_t(best) > seen && !most.compare_exchange_weak(seen, std::uint32_t(best))) {
        }
    });
    return {most.load(), total.load()};
}

} // namespace vds::detail
