// vds: exact signed distances to a triangle mesh (<vds/distance.h>): the
// hierarchy (bvh.h) finds the nearest triangle, the exact classifier of the
// same rule gives the sign.
#include <vds/distance.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <glm/common.hpp>

#include <vds/detail/parallel.h>
#include <vds/error.h>
#include <vds/mesh_check.h>

#include <vds/detail/bvh.h>
#include <vds/detail/triangle_distance.h>

namespace vds {

namespace {

/// Points a chunk of a batch: enough to amortise a chunk's classify call.
constexpr std::size_t kChunkPoints = 512;
/// Points a batch needs before it is searched in Morton order (searchOrder):
/// below, sorting costs more than the order saves.
constexpr std::size_t kOrderedBatch = 64;
/// Triangles a hierarchy can reference: a leaf reference holds its first
/// block in 31 - kLeafBits bits, and every block holds at least one
/// triangle (a leaf's triangles fill its blocks from the first lane).
constexpr std::size_t kMaxTriangles = (std::size_t(1) << (31 - detail::kLeafBits)) - 1;

/// Cells a brick has along each axis: the unit of a grid's coherence.
constexpr std::uint32_t kBrick = 8;
/// The same for a full grid, whose bricks gather every leaf within their
/// centre's distance plus their half-diagonal: smaller bricks, shorter lists.
constexpr std::uint32_t kFullGridBrick = 4;
/// Groups of four leaves a brick's list may hold before its cells search the
/// whole hierarchy instead: a group costs each cell one SIMD box test, the
/// hierarchy a few nodes a level (docs/benchmarks.md, exact distances).
constexpr std::size_t kMaxBrickGroups = 1024;

/// Cells between the exact cells of a propagated grid (FarCells::Propagated),
/// on each axis: its bound is 2 (kLatticeStep / 2) cell diagonals.
constexpr std::uint32_t kLatticeStep = 4;
/// Cell diagonals from the surface within which a propagated grid is exact.
constexpr double kExactDiagonals = 1.0;

struct Brick {
    glm::uvec3 lo, hi; ///< cells [lo, hi)
};

/// The exact cells of a propagated grid: every kLatticeStep-th index on
/// each axis and the last.
struct Lattice {
    explicit Lattice(const glm::uvec3& dims) : count((dims - 1u + kLatticeStep - 1u) / kLatticeStep + 1u), last(dims - 1u) {}
    /// The cell index of lattice index m on axis a.
    std::uint32_t cell(std::uint32_t m, int a) const { return std::min(m * kLatticeStep, last[a]); }
    std::size_t index(const glm::uvec3& m) const { return (std::size_t(m.x) * count.y + m.y) * count.z + m.z; }
    std::size_t size() const { return std::size_t(count.x) * count.y * count.z; }
    glm::uvec3 count, last;
};

/// The first point that is not finite after rounding to float, or count.
std::size_t firstNonFinite(const PointsView& points) {
    for (std::size_t k = 0; k < points.count; ++k) {
        const glm::vec3 p = points[k];
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) return k;
    }
    return points.count;
}

void checkBatch(const PointsView& points, const DistanceOptions& options) {
    if (!(options.maxDistance > 0.0))
        throw InvalidArgument("the largest distance to search must be above 0, not " +
                              std::to_string(options.maxDistance));
    const std::size_t bad = firstNonFinite(points);
    if (bad < points.count)
        throw InvalidArgument("point " + std::to_string(bad) + " is not finite (" +
                              std::to_string(points[bad].x) + ", " + std::to_string(points[bad].y) + ", " +
                              std::to_string(points[bad].z) + "): it has no distance");
}

/// Spreads the low 10 bits of v to every third bit (a Morton code's axis).
std::uint64_t spreadBits(std::uint32_t v) {
    std::uint64_t x = v & 0x3ffu;
    x = (x | x << 16) & 0x30000ffull;
    x = (x | x << 8) & 0x300f00full;
    x = (x | x << 4) & 0x30c30c3ull;
    x = (x | x << 2) & 0x9249249ull;
    return x;
}

/// The order a batch is searched in: along a Morton curve over `box` (1024
/// steps an axis, points outside it clamped to its side), so that each
/// point follows one near it, whose nodes and leaves are still in cache and
/// whose nearest triangle bounds its own search from the start. Empty (the
/// given order) for batches too small to gain or too large to index.
std::vector<std::uint32_t> searchOrder(const PointsView& points, const Box& box) {
    if (points.count < kOrderedBatch || points.count > std::numeric_limits<std::uint32_t>::max()) return {};
    const glm::vec3 size = glm::max(box.hi - box.lo, glm::vec3(std::numeric_limits<float>::min()));
    const glm::vec3 scale = 1024.0f / size;
    std::vector<std::uint64_t> keys(points.count);
    for (std::size_t k = 0; k < points.count; ++k) {
        const glm::vec3 at = glm::clamp((points[k] - box.lo) * scale, glm::vec3(0.0f), glm::vec3(1023.0f));
        const std::uint64_t code =
            spreadBits(std::uint32_t(at.x)) | spreadBits(std::uint32_t(at.y)) << 1 | spreadBits(std::uint32_t(at.z)) << 2;
        keys[k] = code << 32 | k;
    }
    std::sort(keys.begin(), keys.end());
    std::vector<std::uint32_t> order(points.count);
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = std::uint32_t(keys[i]);
    return order;
}

} // namespace

struct SignedDistance::Impl {
    /// The hierarchy and the sign's classifier are independent: built at
    /// once, each on threads of its own as well.
    Impl(MeshView mesh, Rule r, std::string flatWhy) : rule(r), bounds(meshBounds(mesh)), flat(std::move(flatWhy)) {
        detail::parallelFor(0, 2, 1, [&](std::size_t part, std::size_t) {
            if (part == 0) bvh = detail::Bvh(mesh);
            else if (flat.empty()) exact.emplace(mesh, Axis::Z);
        });
    }
    Rule rule;
    detail::Bvh bvh;
    Box bounds;
    std::optional<ExactClassifier> exact; ///< none for a flat mesh
    std::string flat;                     ///< why a flat mesh has no sign, else ""

    /// The classifier of the signs; a flat mesh has none: `InvalidMesh`.
    const ExactClassifier& signs() const {
        if (!exact)
            throw InvalidMesh(flat + "; its unsigned distance and closest points are defined, a signed one is not");
        return *exact;
    }

    /// The nearest triangle within `maxDistance`, starting from `seed`'s
    /// distance when one is given.
    detail::NearestState nearest(const glm::vec3& p, double maxDistance, std::uint32_t seed = kNoTriangle) const {
        detail::NearestState state{maxDistance * maxDistance};
        if (seed != kNoTriangle) {
            const double d2 = bvh.distance2(p, seed);
            if (d2 < state.distance2) state = {d2, seed};
        }
        bvh.nearest(p, state);
        return state;
    }
    void fillBrick(const Grid& grid, const Brick& brick, double band, const std::uint8_t* inside, float* cells,
                   std::vector<detail::BvhNode>& leaves) const;
    std::vector<detail::NearestState> latticeTriangles(const Grid& grid, const Lattice& lattice, unsigned threads) const;
    void propagateBrick(const Grid& grid, const Lattice& lattice, const glm::uvec3& m,
                        const detail::NearestState* nearestOf, const std::uint8_t* inside, float* cells) const;
    void propagatedGrid(const Grid& grid, const std::uint8_t* inside, float* cells, unsigned threads) const;
    ClosestPoint closestAt(const glm::vec3& p, double maxDistance) const {
        const detail::NearestState s = nearest(p, maxDistance);
        if (s.slot != kNoTriangle) return bvh.closest(p, s.slot);
        ClosestPoint none;
        none.point = glm::dvec3(std::nan(""));
        none.distance = maxDistance;
        return none;
    }
};

SignedDistance::SignedDistance(MeshView mesh, Rule rule, const std::string& meshName) {
    const MeshReport report = validateMesh(mesh);
    requireUsable(report, meshName);
    // A flat mesh (a sheet) bounds no volume: distances to it, no sign.
    std::string flat;
    try {
        requireVolume(report, meshName);
    } catch (const InvalidMesh& e) {
        flat = e.what();
    }
    if (mesh.triangleCount > kMaxTriangles)
        throw InvalidMesh(meshName + " has " + std::to_string(mesh.triangleCount) +
                          " triangles, more than a distance hierarchy holds (" + std::to_string(kMaxTriangles) + ")");
    impl_ = std::make_unique<Impl>(mesh, rule, std::move(flat));
}

SignedDistance::~SignedDistance() = default;
SignedDistance::SignedDistance(SignedDistance&&) noexcept = default;
SignedDistance& SignedDistance::operator=(SignedDistance&&) noexcept = default;

Rule SignedDistance::rule() const { return impl_->rule; }
const ExactClassifier& SignedDistance::classifier() const { return impl_->signs(); }
bool SignedDistance::hasSign() const { return impl_->exact.has_value(); }
std::size_t SignedDistance::triangleCount() const { return impl_->bvh.triangleCount(); }

std::size_t SignedDistance::memoryBytes() const {
    return impl_->bvh.memoryBytes() + (impl_->exact ? impl_->exact->memoryBytes() : 0);
}

std::string SignedDistance::summary() const {
    return "distance on " + std::to_string(triangleCount()) + " triangles, " + std::to_string(impl_->bvh.nodeCount()) +
           " nodes of " + std::to_string(impl_->bvh.width()) + " lanes, " + (impl_->exact ? std::string("signed by ") + toString(impl_->rule) : std::string("unsigned (flat)"));
}

namespace {

/// Each chunk of a batch in search order (searchOrder): body(begin, end,
/// at), the chunk's points at(begin) ... at(end - 1) by their batch index.
template <class Body>
void inSearchOrder(const PointsView& points, const Box& bounds, unsigned threads, const Body& body) {
    const std::vector<std::uint32_t> order = searchOrder(points, bounds);
    const auto at = [&order](std::size_t i) { return order.empty() ? i : std::size_t(order[i]); };
    detail::parallelFor(threads, points.count, kChunkPoints,
                        [&](std::size_t begin, std::size_t end) { body(begin, end, at); });
}

} // namespace

void SignedDistance::unsignedDistance(const PointsView& points, double* out, const DistanceOptions& options) const {
    checkBatch(points, options);
    inSearchOrder(points, impl_->bounds, options.threads, [&](std::size_t begin, std::size_t end, const auto& at) {
        std::uint32_t seed = kNoTriangle; // the previous point's nearest triangle
        for (std::size_t i = begin; i < end; ++i) {
            const std::size_t k = at(i);
            const detail::NearestState s = impl_->nearest(points[k], options.maxDistance, seed);
            seed = s.slot;
            out[k] = s.slot == kNoTriangle ? options.maxDistance : std::sqrt(s.distance2);
        }
    });
}

void SignedDistance::distance(const PointsView& points, double* out, const DistanceOptions& options) const {
    const ExactClassifier& signs = impl_->signs();
    checkBatch(points, options);
    inSearchOrder(points, impl_->bounds, options.threads, [&](std::size_t begin, std::size_t end, const auto& at) {
        glm::vec3 chunk[kChunkPoints];
        for (std::size_t i = begin; i < end; ++i) chunk[i - begin] = points[at(i)];
        std::uint8_t inside[kChunkPoints];
        ClassifyOptions classify;
        classify.rule = impl_->rule;
        classify.threads = 1;
        signs.classify(PointsView(chunk, end - begin), inside, classify);
        std::uint32_t seed = kNoTriangle;
        for (std::size_t i = begin; i < end; ++i) {
            const detail::NearestState s = impl_->nearest(chunk[i - begin], options.maxDistance, seed);
            seed = s.slot;
            const double d = s.slot == kNoTriangle ? options.maxDistance : std::sqrt(s.distance2);
            out[at(i)] = inside[i - begin] ? -d : d;
        }
    });
}

/// In search order too, but without seeds: a point equidistant from two
/// triangles gets the same one whatever the batch around it.
void SignedDistance::closestPoints(const PointsView& points, ClosestPoint* out, const DistanceOptions& options) const {
    checkBatch(points, options);
    inSearchOrder(points, impl_->bounds, options.threads, [&](std::size_t begin, std::size_t end, const auto& at) {
        for (std::size_t i = begin; i < end; ++i) out[at(i)] = impl_->closestAt(points[at(i)], options.maxDistance);
    });
}

double SignedDistance::distance(const glm::vec3& p) const {
    double d = 0.0;
    distance(PointsView(&p, 1), &d, DistanceOptions{1});
    return d;
}

ClosestPoint SignedDistance::closest(const glm::vec3& p) const {
    ClosestPoint c;
    closestPoints(PointsView(&p, 1), &c, DistanceOptions{1});
    return c;
}


/// One brick of a grid: the leaves that can hold any of its cells' nearest
/// triangle (those within the band, or within the distance of the brick's
/// centre plus its half-diagonal, which bounds every cell's distance) are
/// gathered once; each cell then searches them, starting from the nearest
/// triangle of the cell before it in its column.
void SignedDistance::Impl::fillBrick(const Grid& grid, const Brick& brick, double band, const std::uint8_t* inside,
                                     float* cells, std::vector<detail::BvhNode>& leaves) const {
    const glm::vec3 lo = grid.cellCentre(brick.lo.x, brick.lo.y, brick.lo.z);
    const glm::vec3 hi = grid.cellCentre(brick.hi.x - 1, brick.hi.y - 1, brick.hi.z - 1);
    double reach = band;
    if (band == 0.0) {
        const glm::vec3 centre = (lo + hi) * 0.5f;
        const double radius = std::max(glm::length(glm::dvec3(hi) - glm::dvec3(centre)),
                                       glm::length(glm::dvec3(lo) - glm::dvec3(centre)));
        reach = (std::sqrt(nearest(centre, std::numeric_limits<double>::infinity()).distance2) + radius) * (1.0 + 1e-9);
    }
    leaves.clear();
    const bool useList = bvh.leavesNear(lo, hi, reach * reach, leaves, kMaxBrickGroups);
    const double start2 = band > 0.0 ? band * band : std::numeric_limits<double>::infinity();
    for (std::uint32_t i = brick.lo.x; i < brick.hi.x; ++i)
        for (std::uint32_t j = brick.lo.y; j < brick.hi.y; ++j) {
            std::uint32_t seed = kNoTriangle;
            for (std::uint32_t k = brick.lo.z; k < brick.hi.z; ++k) {
                const glm::vec3 p = grid.cellCentre(i, j, k);
                detail::NearestState s{start2};
                if (seed != kNoTriangle) {
                    const double d2 = bvh.distance2(p, seed);
                    if (d2 < s.distance2) s = {d2, seed};
                }
                if (useList) bvh.nearestAmong(p, leaves, s);
                else bvh.nearest(p, s);
                if (s.slot != kNoTriangle) seed = s.slot;
                const double d = s.slot == kNoTriangle ? band : std::sqrt(s.distance2);
                const std::size_t at = grid.index(i, j, k);
                cells[at] = inside[at] ? -float(d) : float(d);
            }
        }
}

/// The nearest triangle of every lattice cell, exact, each column of the
/// lattice starting from the triangle of the cell before.
std::vector<detail::NearestState> SignedDistance::Impl::latticeTriangles(const Grid& grid, const Lattice& lattice,
                                                                         unsigned threads) const {
    std::vector<detail::NearestState> nearestOf(lattice.size());
    detail::parallelFor(threads, std::size_t(lattice.count.x) * lattice.count.y, 8, [&](std::size_t begin, std::size_t end) {
        for (std::size_t column = begin; column < end; ++column) {
            const std::uint32_t mx = std::uint32_t(column / lattice.count.y), my = std::uint32_t(column % lattice.count.y);
            std::uint32_t seed = kNoTriangle;
            for (std::uint32_t mz = 0; mz < lattice.count.z; ++mz) {
                const glm::vec3 p = grid.cellCentre(lattice.cell(mx, 0), lattice.cell(my, 1), lattice.cell(mz, 2));
                const detail::NearestState s = nearest(p, std::numeric_limits<double>::infinity(), seed);
                nearestOf[lattice.index({mx, my, mz})] = s;
                seed = s.slot;
            }
        }
    });
    return nearestOf;
}

/// The eight lattice cells around a propagated brick: their cell indices
/// (bit a of a corner's number: the high end on axis a), distances and
/// nearest triangles.
struct BrickCorners {
    glm::uvec3 lo, hi; ///< the low and high corners' cells
    glm::dvec3 corner[8];
    double cornerDistance[8];
    std::uint32_t slot[8];
    std::uint32_t central = kNoTriangle; ///< of those, the nearest to the brick's centre
    /// No cell of the brick is nearer the surface than this (1-Lipschitz
    /// from the farthest corner).
    double nearestCell = 0.0;
};

BrickCorners brickCorners(const Grid& grid, const Lattice& lattice, const glm::uvec3& m,
                          const detail::NearestState* nearestOf, const detail::Bvh& bvh) {
    BrickCorners b;
    const glm::uvec3 top = glm::min(m + 1u, lattice.count - 1u);
    b.lo = {lattice.cell(m.x, 0), lattice.cell(m.y, 1), lattice.cell(m.z, 2)};
    b.hi = {lattice.cell(top.x, 0), lattice.cell(top.y, 1), lattice.cell(top.z, 2)};
    double farthest = 0.0;
    for (int c = 0; c < 8; ++c) {
        const glm::uvec3 at(c & 1 ? top.x : m.x, c & 2 ? top.y : m.y, c & 4 ? top.z : m.z);
        b.corner[c] = grid.cellCentre(lattice.cell(at.x, 0), lattice.cell(at.y, 1), lattice.cell(at.z, 2));
        const detail::NearestState& q = nearestOf[lattice.index(at)];
        b.cornerDistance[c] = std::sqrt(q.distance2);
        b.slot[c] = q.slot;
        farthest = std::max(farthest, b.cornerDistance[c]);
    }
    b.nearestCell = farthest - glm::length(b.corner[7] - b.corner[0]);
    const glm::vec3 centre((b.corner[0] + b.corner[7]) * 0.5);
    double best = std::numeric_limits<double>::infinity();
    for (int c = 0; c < 8; ++c) {
        const double d2 = c > 0 && b.slot[c] == b.slot[c - 1] ? best : bvh.distance2(centre, b.slot[c]);
        if (d2 < best) best = d2, b.central = b.slot[c];
    }
    return b;
}

/// The cells between lattice cells m and m + 1 (FarCells::Propagated states
/// the bound). Each takes the nearest of three triangles: its nearest
/// corner's (which makes the bound), the cell's before it in the column
/// (which carries the nearest feature along) and the corners' nearest to the
/// brick's centre; then an exact search where the
/// corners' distances less their distance to the cell (1-Lipschitz) leave
/// it possibly within kExactDiagonals of the surface.
void SignedDistance::Impl::propagateBrick(const Grid& grid, const Lattice& lattice, const glm::uvec3& m,
                                          const detail::NearestState* nearestOf, const std::uint8_t* inside,
                                          float* cells) const {
    const BrickCorners b = brickCorners(grid, lattice, m, nearestOf, bvh);
    const glm::dvec3 step = glm::dvec3(grid.box.hi - grid.box.lo) / glm::dvec3(grid.dims);
    const double exactWithin = kExactDiagonals * glm::length(step);
    glm::uvec3 hi;
    for (int a = 0; a < 3; ++a) hi[a] = m[a] + 1 < lattice.count[a] ? b.hi[a] : grid.dims[a];
    for (std::uint32_t i = b.lo.x; i < hi.x; ++i)
        for (std::uint32_t j = b.lo.y; j < hi.y; ++j) {
            std::uint32_t previous = kNoTriangle;
            for (std::uint32_t k = b.lo.z; k < hi.z; ++k) {
                const glm::vec3 p = grid.cellCentre(i, j, k);
                const int c = (i - b.lo.x > b.hi.x - i ? 1 : 0) | (j - b.lo.y > b.hi.y - j ? 2 : 0) |
                              (k - b.lo.z > b.hi.z - k ? 4 : 0);
                detail::NearestState s{bvh.distance2(p, b.slot[c]), b.slot[c]};
                for (const std::uint32_t other : {previous, b.central})
                    if (other != kNoTriangle && other != s.slot) {
                        const double d2 = bvh.distance2(p, other);
                        if (d2 < s.distance2) s = {d2, other};
                    }
                double below = b.nearestCell; // a lower bound of the cell's distance
                for (int q = 0; q < 8 && below < exactWithin; ++q)
                    below = std::max(below, b.cornerDistance[q] - glm::length(glm::dvec3(p) - b.corner[q]));
                if (below < exactWithin) bvh.nearest(p, s);
                previous = s.slot;
                const double d = std::sqrt(s.distance2);
                const std::size_t at = grid.index(i, j, k);
                cells[at] = inside[at] ? -float(d) : float(d);
            }
        }
}

void SignedDistance::Impl::propagatedGrid(const Grid& grid, const std::uint8_t* inside, float* cells,
                                          unsigned threads) const {
    const Lattice lattice(grid.dims);
    const std::vector<detail::NearestState> nearestOf = latticeTriangles(grid, lattice, threads);
    // One brick from each lattice cell to the next (the last: itself alone).
    const glm::uvec3 bricks = lattice.count;
    detail::parallelFor(threads, lattice.size(), 16, [&](std::size_t begin, std::size_t end) {
        for (std::size_t b = begin; b < end; ++b) {
            const glm::uvec3 m(std::uint32_t(b / (std::size_t(bricks.y) * bricks.z)), std::uint32_t(b / bricks.z % bricks.y),
                               std::uint32_t(b % bricks.z));
            propagateBrick(grid, lattice, m, nearestOf.data(), inside, cells);
        }
    });
}

void SignedDistance::grid(const Grid& grid, float* cells, const DistanceGridOptions& options) const {
    const ExactClassifier& signs = impl_->signs();
    checkGrid(grid);
    if (!std::isfinite(options.band) || options.band < 0.0)
        throw InvalidArgument("the band's half-width must be a finite distance >= 0 (0: the full grid), not " +
                              std::to_string(options.band));
    std::vector<std::uint8_t> inside(grid.cellCount());
    ClassifyOptions classify;
    classify.rule = impl_->rule;
    classify.threads = options.threads;
    signs.occupancy(grid, inside.data(), classify);
    if (options.band == 0.0 && options.far == FarCells::Propagated) {
        impl_->propagatedGrid(grid, inside.data(), cells, options.threads);
        return;
    }
    const std::uint32_t side = options.band > 0.0 ? kBrick : kFullGridBrick;
    const glm::uvec3 bricks = (grid.dims + glm::uvec3(side - 1)) / side;
    const std::size_t count = std::size_t(bricks.x) * bricks.y * bricks.z;
    detail::parallelFor(options.threads, count, 4, [&](std::size_t begin, std::size_t end) {
        std::vector<detail::BvhNode> leaves;
        for (std::size_t b = begin; b < end; ++b) {
            const glm::uvec3 at(std::uint32_t(b / (std::size_t(bricks.y) * bricks.z)),
                                std::uint32_t(b / bricks.z % bricks.y), std::uint32_t(b % bricks.z));
            const Brick brick{at * side, glm::min((at + 1u) * side, grid.dims)};
            impl_->fillBrick(grid, brick, options.band, inside.data(), cells, leaves);
        }
    });
}

ClosestPoint closestPointOnTriangle(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b,
                                    const glm::dvec3& c) {
    const detail::TriangleHit hit = detail::closestOnTriangle(p, a, b, c);
    return {hit.point, std::sqrt(detail::distance2(p, hit.point)), kNoTriangle, hit.feature, hit.index};
}

} // namespace vds
