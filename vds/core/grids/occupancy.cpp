// vds: occupancy grids by column sweeps (see <vds/occupancy.h>). The sprite
// sweep is the VPT of Trapp & Döllner 2008 (section 3.2) evaluated for a
// whole column of points at once; the exact sweep applies the exact
// classifier's predicates and tie rule (projected_mesh.h) to a column of
// cell centres at once, in the manner of the Antipodal method's dense-grid
// path (Martens, Trettner & Bessmeltsev 2026: signed crossings along the
// axis, then a prefix sum).
#include <vds/occupancy.h>

#include <algorithm>
#include <cassert>
#include <chrono>
#include <cmath>
#include <cstring>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <vds/error.h>
#include <vds/mesh_check.h>
#include <vds/detail/aligned_axes.h>
#include <vds/detail/column_boundary.h>
#include <vds/detail/parallel.h>
#include <vds/detail/pi.h>
#include <vds/detail/sweep_plan.h>
#include <vds/detail/tree_walk.h>

#include <vds/detail/boundary_caps.h>
#include <vds/detail/sprite_winding.h>
#include <vds/detail/antipodal.h>
#include <vds/detail/projected_mesh.h>
#include <vds/detail/vpt.h>

namespace vds {
namespace {

using detail::ColumnBoundary;
using detail::kFourPi;
using detail::kPi;
using detail::Split;

std::vector<float> centres(const Grid& grid, int axis) {
    std::vector<float> c(grid.dims[axis]);
    for (std::uint32_t k = 0; k < grid.dims[axis]; ++k)
        c[k] = grid.cellCoordinate(axis, k);
    return c;
}


/// Slack on a bracket's ends: they and the per-edge sum each err by some
/// 1e-15 an edge; a bracket decides only when it clears the label's
/// threshold by more than this.
constexpr double kBracketSlack = 1e-9;
/// Runs of one integer term this short are labelled cell by cell (by the
/// capped loops), which is cheaper than brackets of O(boundary edges) each.
constexpr std::uint32_t kShortRun = 8;
/// How far from the threshold, in multiples of its bound, the value of a
/// cell that labels a run after it is refined: the rest of that distance is
/// what the boundary term may drift along the run.
constexpr double kReachMargin = 2.0;
/// Most cells labelled alone after a run came out empty.
constexpr std::uint32_t kMaxAlone = 16;
/// The slower way is timed again once the cheaper has spent this many of
/// the slower's mean column times since: it bounds the share of time spent
/// probing the slower way at about 1 / kProbe (tuning: docs/benchmarks.md).
constexpr std::size_t kProbe = 64;


} // namespace

detail::SweepPlan detail::planSweep(const SpriteGrid& sg, const Grid& grid, unsigned threads) {
    SweepPlan plan;
    if (!sweepsByColumns(sg)) return plan;
    // s, t and r on world axes u, v and a, in any order and sign (a sprite
    // turned by quarter turns or mirrored across its axis), depth growing along a.
    const glm::ivec3 p = *alignedAxes(sg);
    const int a = p.z;
    plan.aligned = true;
    plan.a = a;
    plan.u = p.x;
    plan.v = p.y;
    plan.n = grid.dims[a];
    plan.step = a == 2 ? 1 : a == 1 ? grid.dims.z : std::size_t(grid.dims.y) * grid.dims.z;
    plan.columns = std::size_t(grid.dims[plan.u]) * grid.dims[plan.v];
    const std::vector<float> along = centres(grid, a), acrossU = centres(grid, plan.u),
                             acrossV = centres(grid, plan.v);
    // toTexture adds only exact zeros to a slice's depth: one depth a slice.
    plan.depth.resize(plan.n);
    glm::vec3 probe = sg.position;
    for (std::uint32_t k = 0; k < plan.n; ++k) {
        probe[a] = along[k];
        plan.depth[k] = sg.toTexture(probe).z;
    }
    plan.firstSlice = std::uint32_t(std::lower_bound(plan.depth.begin(), plan.depth.end(), 0.0f) - plan.depth.begin());
    plan.endSlice = std::uint32_t(std::upper_bound(plan.depth.begin(), plan.depth.end(), 1.0f) - plan.depth.begin());
    plan.texels.assign(plan.columns, -1);
    if (plan.firstSlice >= plan.endSlice) return plan;
    detail::parallelFor(threads, plan.columns, 4096, [&](std::size_t begin, std::size_t end) {
        for (std::size_t column = begin; column < end; ++column) {
            glm::vec3 world;
            world[plan.u] = acrossU[column / grid.dims[plan.v]];
            world[plan.v] = acrossV[column % grid.dims[plan.v]];
            world[a] = along[plan.firstSlice];
            plan.texels[column] = std::int32_t(columnOf(sg, sg.toTexture(world))); // exactly as Sprite::contains
        }
    });
    return plan;
}

void occupancy(const Sprite& sprite, const Grid& grid, std::uint8_t* cells, const ClassifyOptions& options) {
    const detail::BoundaryCapsCache caps; // this call's
    detail::occupancyOfSprite(sprite, caps, grid, cells, options);
}

void detail::occupancyOfSprite(const Sprite& sprite, const BoundaryCapsCache& caps, const Grid& grid,
                               std::uint8_t* cells, const ClassifyOptions& options) {
    checkGrid(grid);
    detail::requireBoundaryKnown(sprite, options.rule);
    assert(cells);
    const bool boundaryTerm = detail::needsBoundaryTerm(sprite, options.rule);
    const detail::SweepPlan plan = detail::planSweep(sprite.grid, grid, options.threads);
    if (!plan.aligned || boundaryTerm) {
        // A rotated sprite, or the GWN of an open one: each cell on its own,
        // the same answers as classify (the sprite's boundary caps for the GWN).
        const glm::ivec3 p = axisPermutation(sprite.grid.axis);
        const int a = p.z, u = p.x, v = p.y;
        const std::uint32_t n = grid.dims[a];
        const std::size_t step = a == 2 ? 1 : a == 1 ? grid.dims.z : std::size_t(grid.dims.y) * grid.dims.z;
        const BoundaryCaps* built = boundaryTerm ? &caps.get(sprite, options.threads) : nullptr;
        detail::parallelFor(options.threads, std::size_t(grid.dims[u]) * grid.dims[v], 64, [&](std::size_t begin, std::size_t end) {
            std::vector<glm::vec3> points(n);
            std::vector<std::uint8_t> labels(n);
            for (std::size_t column = begin; column < end; ++column) {
                glm::uvec3 c(0u);
                c[u] = std::uint32_t(column / grid.dims[v]);
                c[v] = std::uint32_t(column % grid.dims[v]);
                for (std::uint32_t k = 0; k < n; ++k) {
                    c[a] = k;
                    points[k] = grid.cellCentre(c.x, c.y, c.z);
                }
                const ClassifyOptions one{options.rule, 1};
                if (boundaryTerm)
                    detail::classifyGeneralizedWinding(sprite, built, &points[0].x, n, sizeof(glm::vec3), labels.data(), one);
                else
                    classify(sprite, PointsView(points.data(), n), labels.data(), one, {QueryLayout::Offsets});
                c[a] = 0;
                std::uint8_t* out = cells + grid.index(c.x, c.y, c.z);
                for (std::uint32_t k = 0; k < n; ++k) out[k * step] = labels[k];
            }
        });
        return;
    }
    const std::uint32_t n = plan.n, firstValid = plan.firstSlice, endValid = plan.endSlice;
    const std::vector<float>& depth = plan.depth;
    const float* crossings = sprite.crossings.data();
    detail::parallelFor(options.threads, plan.columns, 64, [&](std::size_t begin, std::size_t end) {
        for (std::size_t column = begin; column < end; ++column) {
            const glm::uvec3 c = plan.firstCell(column, grid);
            std::uint8_t* out = cells + grid.index(c.x, c.y, c.z);
            const auto fill = [&](std::uint32_t from, std::uint32_t to, std::uint8_t label) {
                if (from >= to) return;
                if (plan.step == 1) std::memset(out + from, label, to - from);
                else for (std::uint32_t k = from; k < to; ++k) out[k * plan.step] = label;
            };
            const std::int32_t texel = plan.texels[column];
            if (texel < 0) {
                fill(0, n, 0);
                continue;
            }
            fill(0, firstValid, 0);
            // Each crossing counts for the cells whose depth lies strictly behind it.
            const float* e = crossings + sprite.offsets[std::size_t(texel)];
            const float* last = crossings + sprite.offsets[std::size_t(texel) + 1];
            int winding = 0;
            std::uint32_t filled = firstValid;
            for (; e != last && filled < endValid; ++e) {
                const auto from = std::uint32_t(
                    std::upper_bound(depth.begin() + filled, depth.begin() + endValid, std::fabs(*e)) - depth.begin());
                fill(filled, from, insideByRule(winding, options.rule) ? 1 : 0);
                filled = from;
                winding += crossingEnters(*e) ? 1 : -1;
            }
            fill(filled, endValid, insideByRule(winding, options.rule) ? 1 : 0);
            fill(endValid, n, 0);
        }
    });
}

void SpriteClassifier::sweep(const Grid& grid, std::uint8_t* cells, const ClassifyOptions& options) const {
    const detail::BoundaryCapsCache callCaps; // a moved-from classifier's: this call's alone
    detail::occupancyOfSprite(sprite_, *(caps_ ? &caps_->cache : &callCaps), grid, cells, options);
}

void occupancy(MeshView mesh, const Grid& grid, std::uint8_t* cells, const ClassifyOptions& options) {
    checkGrid(grid);
    assert(cells);
    const MeshReport report = validateMesh(mesh);
    requireUsable(report, "mesh");
    const std::vector<glm::vec3> edges = options.rule == Rule::GeneralizedWinding && !report.oriented()
                                             ? detail::boundaryEdges(mesh)
                                             : std::vector<glm::vec3>();
    const detail::ProjectedMesh projected(mesh, Axis::Z); // (s, t, r) = (x, y, z)
    detail::sweepExact(projected, edges, grid, cells, options);
}

namespace {

/// detail::sweepExact's columns from one thread: each column's crossings
/// (its cells' crossing counts), then its labels by the rule; for the
/// generalized winding number either cell by cell by the capped loops or
/// by brackets of the boundary term (ColumnBoundary), timed against each
/// other.
class ColumnSweep {
public:
    ColumnSweep(const detail::ProjectedMesh& projected, const std::vector<glm::vec3>& edges, const std::vector<float>& zs,
                const detail::BoundaryCaps* caps, const ClassifyOptions& options, detail::SweepWay way)
        : projected_(projected), edges_(edges), zs_(zs), caps_(caps), options_(options), way_(way),
          n_(std::uint32_t(zs.size())), integer_(caps ? n_ : 0), terms_(integer_.size()), known_(integer_.size()),
          height_(double(zs.back()) - double(zs.front())) {}

    /// Labels the column at (x, y) into out[0, n); `local`: its place in
    /// this thread's range.
    void column(float x, float y, std::uint8_t* out, std::size_t local) {
        q_[0] = x;
        q_[1] = y;
        out_ = out;
        crossings();
        if (!caps_) {
            fillByRule();
            return;
        }
        integerTerms();
        // Which way labels a column faster depends on the boundary:
        // brackets cost O(edges) a split, the capped loops a tree query a
        // cell (cheap for small holes, dear beside a large cap). Both give
        // the same labels, so each range of columns times both (its first
        // two columns) and takes the cheaper, timing the other way again
        // once the cheaper has spent kProbe of the other's columns since.
        const bool useBrackets = way_ == detail::SweepWay::Timed ? (local < 2 ? local == 0 : timedWay())
                                                                 : way_ == detail::SweepWay::Brackets;
        const auto started = std::chrono::steady_clock::now();
        const auto record = [&](int timed) {
            const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
            secondsSpent_[timed] += seconds;
            ++columnsTimed_[timed];
            sinceProbe_ = timed == int(cheaper_) ? sinceProbe_ + seconds : 0.0;
        };
        if (!useBrackets ||
            !bracket_.reset(edges_, caps_->closed() ? caps_ : nullptr, double(q_[0]), double(q_[1]), height_)) {
            byCells();
            if (!useBrackets) record(0);
            return;
        }
        byBrackets();
        record(1);
    }

private:
    /// Whether the next column takes the brackets (SweepWay::Timed, after
    /// the first two columns): the way with the lower mean time a column,
    /// but the other once the cheaper has spent kProbe times the other's
    /// mean since the other was last timed, so probing costs at most about
    /// 1 / kProbe of the time whatever the ratio of the two.
    bool timedWay() {
        // A way not timed yet (its first column fell back) counts as free, so it is tried.
        const double mean[2] = {columnsTimed_[0] ? secondsSpent_[0] / double(columnsTimed_[0]) : 0.0,
                                columnsTimed_[1] ? secondsSpent_[1] / double(columnsTimed_[1]) : 0.0};
        cheaper_ = mean[1] <= mean[0];
        const bool probe = sinceProbe_ >= double(kProbe) * mean[cheaper_ ? 0 : 1];
        return probe != cheaper_;
    }
    /// The column's crossings as (first cell the crossing is in front of,
    /// +-1), in order.
    void crossings();
    /// The column's labels by the rule, from its crossings alone.
    void fillByRule();
    /// The integer term of every cell.
    void integerTerms();
    /// Cell k by the capped loops.
    void cell(std::uint32_t k) { out_[k] = caps_->inside(integer_[k], glm::vec3(q_[0], q_[1], zs_[k])) ? 1 : 0; }
    /// Cell by cell, each estimate labelling the cells after it as far as
    /// the boundary term provably stays on one side of the threshold
    /// (BoundaryCaps::Reach).
    void byCells();
    /// Each run of cells with one integer term by brackets of the boundary
    /// term, halved until they decide; short or undecided runs cell by cell.
    void byBrackets();
    /// The split at cell k; false where it is ill-conditioned.
    bool split(std::uint32_t k) {
        if (!known_[k]) known_[k] = bracket_.at(double(zs_[k]), terms_[k]) ? 1 : 2;
        return known_[k] == 1;
    }
    /// Labels cells [k0, k1] (one integer term) by their brackets.
    void decideRun(std::uint32_t k0, std::uint32_t k1);

    const detail::ProjectedMesh& projected_;
    const std::vector<glm::vec3>& edges_;
    const std::vector<float>& zs_;
    const detail::BoundaryCaps* caps_;
    const ClassifyOptions& options_;
    const detail::SweepWay way_;
    const std::uint32_t n_;
    float q_[3] = {0.0f, 0.0f, 0.0f};
    std::uint8_t* out_ = nullptr;
    std::vector<std::pair<std::uint32_t, int>> events_;
    // For the generalized winding number: each cell's integer term, and
    // the column's boundary term split by monotony, memoized per cell.
    std::vector<int> integer_;
    std::vector<Split> terms_;
    std::vector<std::uint8_t> known_;
    ColumnBoundary bracket_;
    const double height_;
    double secondsSpent_[2] = {0.0, 0.0}; ///< on the columns timed, [0]: cell by cell, [1]: brackets
    std::size_t columnsTimed_[2] = {0, 0};
    bool cheaper_ = true;      ///< brackets the cheaper way, as last timed
    double sinceProbe_ = 0.0;  ///< seconds on the cheaper way since the other was timed
};

void ColumnSweep::crossings() {
    float* q = q_;
    events_.clear();
    const detail::CellGrid::Found found = projected_.grid.find(q);
    for (const detail::CellEntry* e = found.begin; e != found.end; ++e) {
        if (!detail::CellGrid::mayHold(*e, found.sub)) continue;
        const detail::Triangle& t = projected_.tris[e->triangle];
        if (!detail::claims(t, q)) continue;
        // The crossing lies strictly in front of (q, z) iff orient3d < 0,
        // false then true as z grows: the first such cell, by bisection.
        std::uint32_t lo = 0, hi = n_;
        while (lo < hi) {
            const std::uint32_t mid = lo + (hi - lo) / 2;
            q[2] = zs_[mid];
            if (detail::orient3d(t.v[0], t.v[1], t.v[2], q) < 0) hi = mid;
            else lo = mid + 1;
        }
        if (lo < n_) events_.emplace_back(lo, (t.flags & detail::kEntering) ? 1 : -1);
    }
    std::sort(events_.begin(), events_.end());
}

void ColumnSweep::fillByRule() {
    int winding = 0;
    std::uint32_t filled = 0;
    for (const auto& [k, delta] : events_) {
        if (k > filled) std::memset(out_ + filled, insideByRule(winding, options_.rule) ? 1 : 0, k - filled);
        filled = std::max(filled, k);
        winding += delta;
    }
    std::memset(out_ + filled, insideByRule(winding, options_.rule) ? 1 : 0, n_ - filled);
}

void ColumnSweep::integerTerms() {
    std::size_t next = 0;
    int w = 0;
    for (std::uint32_t k = 0; k < n_; ++k) {
        for (; next < events_.size() && events_[next].first <= k; ++next) w += events_[next].second;
        integer_[k] = w;
    }
}

void ColumnSweep::byCells() {
    // Where runs come out empty (coarse grids, cells beside the boundary)
    // the next cells are labelled alone for a while, twice as long each
    // time, so that the reach is not paid for nothing.
    const double threshold = 0.5 + detail::kGeneralizedWindingTie;
    std::uint32_t alone = 0, backoff = 1;
    for (std::uint32_t k = 0; k < n_;) {
        if (alone > 0) {
            cell(k++);
            --alone;
            continue;
        }
        const glm::vec3 at(q_[0], q_[1], zs_[k]);
        const detail::BoundaryCaps::Estimate e = caps_->decide(integer_[k], at, kReachMargin);
        out_[k] = e.term > threshold ? 1 : 0;
        // No run unless the room left could hold at least the next cell at
        // the steepness found.
        const double room = std::fabs(e.term - threshold) - e.bound;
        const double step = k + 1 < n_ ? double(zs_[k + 1]) - double(zs_[k]) : 0.0;
        const detail::BoundaryCaps::Reach reach =
            room > 0.0 && step > 0.0 ? caps_->reach(at, room / step) : detail::BoundaryCaps::Reach{};
        std::uint32_t j = k + 1;
        for (; j < n_; ++j) {
            const double v = double(integer_[j] - integer_[k]) + e.term;
            const double move = double(zs_[j]) - double(zs_[k]);
            if (!(std::fabs(v - threshold) > e.bound + reach.drift(move))) break;
            out_[j] = v > threshold ? 1 : 0;
        }
        if (j == k + 1) {
            alone = backoff;
            backoff = std::min(2 * backoff, kMaxAlone);
        } else {
            backoff = 1;
        }
        k = j;
    }
}

void ColumnSweep::byBrackets() {
    std::fill(known_.begin(), known_.end(), 0);
    for (std::uint32_t k0 = 0; k0 < n_;) {
        std::uint32_t k1 = k0;
        while (k1 + 1 < n_ && integer_[k1 + 1] == integer_[k0]) ++k1;
        if (k1 - k0 + 1 < kShortRun) {
            for (std::uint32_t k = k0; k <= k1; ++k) cell(k);
        } else {
            decideRun(k0, k1);
        }
        k0 = k1 + 1;
    }
}

void ColumnSweep::decideRun(std::uint32_t k0, std::uint32_t k1) {
    const double threshold = 0.5 + detail::kGeneralizedWindingTie;
    if (!split(k0) || !split(k1)) {
        for (std::uint32_t k = k0; k <= k1; ++k) cell(k);
        return;
    }
    // One or two cells: the split's value, or the capped loops where it is
    // too close to call.
    const double error = bracket_.error() + kBracketSlack;
    if (k1 - k0 <= 1) {
        for (const std::uint32_t k : {k0, k1}) {
            const Split& t = terms_[k];
            const double value = double(integer_[k]) + t.up + t.down + t.smooth;
            if (std::fabs(value - threshold) > error) out_[k] = value > threshold ? 1 : 0;
            else cell(k);
        }
        return;
    }
    const Split& t0 = terms_[k0];
    const Split& t1 = terms_[k1];
    // The fans' part: their mean at the ends, less (plus) the error and
    // how far they may move over half the run.
    const double fans = 0.5 * (t0.smooth + t1.smooth),
                 spread = error + 0.5 * bracket_.drift() * (double(zs_[k1]) - double(zs_[k0]));
    const double lo = double(integer_[k0]) + t0.up + t1.down + fans - spread,
                 hi = double(integer_[k0]) + t1.up + t0.down + fans + spread;
    if (lo > threshold || hi < threshold) {
        std::memset(out_ + k0, lo > threshold ? 1 : 0, k1 - k0 + 1);
        return;
    }
    // Where the ends lie on either side of the threshold, cut beside the
    // crossing their line predicts (the halves then mostly decide at
    // once); else halve, the halves sharing the middle cell (one new split
    // a cut).
    const double v0 = double(integer_[k0]) + t0.up + t0.down + t0.smooth,
                 v1 = double(integer_[k0]) + t1.up + t1.down + t1.smooth;
    if ((v0 - threshold) * (v1 - threshold) < 0.0) {
        const double at = (threshold - v0) / (v1 - v0) * double(k1 - k0);
        const std::uint32_t m = k0 + std::min(k1 - k0 - 1, std::uint32_t(std::max(0.0, at)));
        decideRun(k0, m);
        decideRun(m + 1, k1);
        return;
    }
    const std::uint32_t mid = k0 + (k1 - k0) / 2;
    decideRun(k0, mid);
    decideRun(mid, k1);
}

} // namespace

void detail::sweepExact(const ProjectedMesh& projected, const std::vector<glm::vec3>& edges, const Grid& grid,
                        std::uint8_t* cells, const ClassifyOptions& options, SweepWay way, const BoundaryCaps* built) {
    assert(projected.axis == Axis::Z);
    // The generalized winding number of a mesh with boundary: each cell's
    // crossing count plus the boundary term at its centre, by the boundary's
    // capped loops (the labels of the exact per-edge sum).
    const std::size_t edgeCount = options.rule == Rule::GeneralizedWinding ? edges.size() / 2 : 0;
    std::optional<detail::BoundaryCaps> own;
    const detail::ProjectedSurface surface(projected);
    if (edgeCount > 0 && !built) own.emplace(edges.data(), edgeCount, Axis::Z, &grid.box, &surface);
    const detail::BoundaryCaps* caps = edgeCount == 0 ? nullptr : built ? built : &*own;
    const std::vector<float> xs = centres(grid, 0), ys = centres(grid, 1), zs = centres(grid, 2);
    const std::uint32_t n = grid.dims.z;
    const std::size_t columns = std::size_t(grid.dims.x) * grid.dims.y;
    detail::parallelFor(options.threads, columns, 256, [&](std::size_t begin, std::size_t end) {
        ColumnSweep sweep(projected, edges, zs, caps, options, way);
        std::size_t local = 0;
        for (std::size_t column = begin; column < end; ++column, ++local)
            sweep.column(xs[column / grid.dims.y], ys[column % grid.dims.y], cells + column * n, local);
    });
}

void packLabels(const std::uint8_t* cells, std::size_t count, std::uint8_t* bits) {
    const std::size_t whole = count / 8;
    for (std::size_t b = 0; b < whole; ++b) {
        const std::uint8_t* c = cells + 8 * b;
        bits[b] = std::uint8_t((c[0] != 0) << 7 | (c[1] != 0) << 6 | (c[2] != 0) << 5 | (c[3] != 0) << 4 |
                               (c[4] != 0) << 3 | (c[5] != 0) << 2 | (c[6] != 0) << 1 | (c[7] != 0));
    }
    if (count % 8) {
        std::uint8_t last = 0;
        for (std::size_t k = 0; k < count % 8; ++k) last |= std::uint8_t((cells[8 * whole + k] != 0) << (7 - k));
        bits[whole] = last;
    }
}

} // namespace vds
