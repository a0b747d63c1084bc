#include <vds/mesh_check.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <memory>
#include <numeric>
#include <sstream>
#include <thread>

#include <glm/geometric.hpp>

#include <vds/detail/edge_partners.h>
#include <vds/detail/large_vector.h>
#include <vds/detail/parallel.h>
#include <vds/detail/pi.h>
#include <vds/detail/solid_angle.h>
#include <vds/detail/weld.h>
#include <vds/error.h>
#include <vds/rule.h>

namespace vds {
namespace {

/// A vertex index a vertex (or triangle): the arrays of the size of the mesh.
using Indices = detail::LargeVector<std::uint32_t>;
using detail::finitePosition;
using detail::weldByPosition;

/// For each welded vertex, the part it belongs to (vertices joined by
/// triangles), named by one of its vertices: union-find, halving paths.
Indices connectedParts(MeshView mesh, const Indices& weld) {
    Indices parent(mesh.positionCount);
    std::iota(parent.begin(), parent.end(), 0u);
    const auto root = [&](std::uint32_t v) {
        while (parent[v] != v) v = parent[v] = parent[parent[v]];
        return v;
    };
    for (std::size_t t = 0; t < mesh.triangleCount; ++t) {
        const glm::uvec3 tri = mesh.triangles[t];
        if (tri.x >= mesh.positionCount || tri.y >= mesh.positionCount || tri.z >= mesh.positionCount) continue;
        const std::uint32_t a = root(weld[tri.x]), b = root(weld[tri.y]), c = root(weld[tri.z]);
        const std::uint32_t low = std::min({a, b, c});
        parent[a] = parent[b] = parent[c] = low;
    }
    for (std::size_t v = 0; v < parent.size(); ++v) parent[v] = root(std::uint32_t(v));
    return parent;
}

/// Sorts a short run in place (most groups hold a handful of items).
template <class Item, class Less> void sortGroup(Item* items, std::size_t n, const Less& less) {
    if (n > 24) {
        std::sort(items, items + n, less);
        return;
    }
    for (std::size_t i = 1; i < n; ++i) {
        const Item v = items[i];
        std::size_t j = i;
        for (; j > 0 && less(v, items[j - 1]); --j) items[j] = items[j - 1];
        items[j] = v;
    }
}

/// One use of an undirected edge, kept in the group of its lower vertex: the
/// higher vertex, shifted left by one, and whether the use runs lower ->
/// higher in the low bit.
template <class Index> Index edgeUse(std::uint32_t a, std::uint32_t b) {
    return a < b ? (Index(b) << 1) | 1 : Index(a) << 1;
}

/// What one thread finds in its share of the triangles, or of the vertices.
struct Found {
    std::size_t badIndices = 0, degenerate = 0;
    bool anyBounds = false;
    Box bounds; ///< of the positions `include`d
    std::size_t boundary = 0, nonManifold = 0, oddNonManifold = 0, inconsistent = 0, duplicates = 0, unpaired = 0;

    void include(const glm::vec3& lo, const glm::vec3& hi) {
        bounds.lo = anyBounds ? glm::min(bounds.lo, lo) : lo;
        bounds.hi = anyBounds ? glm::max(bounds.hi, hi) : hi;
        anyBounds = true;
    }
};

/// The triangles [nt k / threads, nt (k + 1) / threads): thread k's share.
std::pair<std::size_t, std::size_t> shareOf(std::size_t nt, unsigned threads, std::size_t k) {
    return std::make_pair(nt * k / threads, nt * (k + 1) / threads);
}

/// countByEdges' first pass, thread k's share: checks its triangles (into
/// `f`), marks their welded vertices `used`, and counts per vertex the edge
/// uses and corner sets that go to the vertex's group.
template <class Index>
void countItems(MeshView mesh, const Indices& weld, std::pair<std::size_t, std::size_t> share,
                std::atomic<std::uint8_t>* used, Index* edgeCount, Index* cornerCount, Found& f) {
    const std::size_t nv = mesh.positionCount;
    for (auto [t, end] = share; t < end; ++t) {
        const glm::uvec3 tri = mesh.triangles[t];
        if (tri.x >= nv || tri.y >= nv || tri.z >= nv) {
            ++f.badIndices;
            continue;
        }
        const std::uint32_t w[3] = {weld[tri.x], weld[tri.y], weld[tri.z]};
        for (std::uint32_t v : w) used[v].store(1, std::memory_order_relaxed);
        const glm::vec3 &a = mesh.positions[tri.x], &b = mesh.positions[tri.y], &c = mesh.positions[tri.z];
        const glm::vec3 n = glm::cross(b - a, c - a);
        const bool collapsed = w[0] == w[1] || w[1] == w[2] || w[0] == w[2];
        if (collapsed || glm::dot(n, n) == 0.0f) ++f.degenerate;
        if (collapsed) continue; // the edges of a collapsed triangle mean nothing
        ++edgeCount[std::min(w[0], w[1])];
        ++edgeCount[std::min(w[1], w[2])];
        ++edgeCount[std::min(w[2], w[0])];
        ++cornerCount[std::min({w[0], w[1], w[2]})];
    }
}

constexpr std::size_t kVerticesPerChunk = 1 << 14;

/// Counts to where each thread starts in each group (afterwards the last
/// thread's entries are where the groups end): the totals of chunks of
/// vertices, their running sums, then each chunk's own, chunks in
/// parallel. Returns the totals (edge uses, corner sets).
template <class Index>
std::pair<Index, Index> groupStarts(std::vector<detail::LargeVector<Index>>& edgeAt,
                                    std::vector<detail::LargeVector<Index>>& cornerAt,
                                    std::size_t nv, unsigned threads) {
    const std::size_t chunks = (nv + kVerticesPerChunk - 1) / kVerticesPerChunk;
    std::vector<std::pair<Index, Index>> chunkStart(chunks + 1); // edges, corners
    detail::parallelFor(threads, chunks, 1, [&](std::size_t c, std::size_t) {
        Index e = 0, t = 0;
        for (std::size_t v = c * kVerticesPerChunk, end = std::min(nv, v + kVerticesPerChunk); v < end; ++v)
            for (unsigned k = 0; k < threads; ++k) {
                e += edgeAt[k][v];
                t += cornerAt[k][v];
            }
        chunkStart[c + 1] = {e, t};
    });
    for (std::size_t c = 0; c < chunks; ++c) {
        chunkStart[c + 1].first += chunkStart[c].first;
        chunkStart[c + 1].second += chunkStart[c].second;
    }
    detail::parallelFor(threads, chunks, 1, [&](std::size_t c, std::size_t) {
        auto [e, t] = chunkStart[c];
        for (std::size_t v = c * kVerticesPerChunk, end = std::min(nv, v + kVerticesPerChunk); v < end; ++v)
            for (unsigned k = 0; k < threads; ++k) {
                const Index edgeCount = edgeAt[k][v], cornerCount = cornerAt[k][v];
                edgeAt[k][v] = e;
                cornerAt[k][v] = t;
                e += edgeCount;
                t += cornerCount;
            }
    });
    return chunkStart[chunks];
}

/// countByEdges' second pass, thread k's share: each edge use and corner
/// set into its group, at the thread's next place there.
template <class Index>
void placeItems(MeshView mesh, const Indices& weld, std::pair<std::size_t, std::size_t> share,
                Index* edgeNext, Index* cornerNext, Index* edges, std::uint64_t* others, std::uint32_t* owners) {
    const std::size_t nv = mesh.positionCount;
    for (auto [t, end] = share; t < end; ++t) {
        const glm::uvec3 tri = mesh.triangles[t];
        if (tri.x >= nv || tri.y >= nv || tri.z >= nv) continue;
        std::uint32_t w[3] = {weld[tri.x], weld[tri.y], weld[tri.z]};
        if (w[0] == w[1] || w[1] == w[2] || w[0] == w[2]) continue;
        for (int e = 0; e < 3; ++e) {
            const std::uint32_t a = w[e], b = w[(e + 1) % 3];
            const Index at = edgeNext[std::min(a, b)]++;
            edges[at] = edgeUse<Index>(a, b);
            if (owners) owners[at] = std::uint32_t(3 * t + std::size_t(e));
        }
        if (w[0] > w[1]) std::swap(w[0], w[1]);
        if (w[1] > w[2]) std::swap(w[1], w[2]);
        if (w[0] > w[1]) std::swap(w[0], w[1]);
        others[cornerNext[w[0]]++] = (std::uint64_t(w[1]) << 32) | w[2];
    }
}

/// Where validation also finds the edges' partners (edge_partners.h):
/// beside each edge use, its half-edge (`owners`), sorted with it; an edge
/// used exactly twice, by two triangles, pairs them.
struct Partners {
    std::uint32_t* owners = nullptr; ///< none: no partners asked
    std::uint32_t* partners = nullptr;

    template <class Index> void sort(Index* group, std::uint32_t* owner, std::size_t n) const {
        // On the stack for the usual handful; a rare crowded vertex takes the heap.
        constexpr std::size_t kFew = 32;
        std::uint64_t few[kFew];
        thread_local std::vector<std::uint64_t> many;
        if (n > kFew) many.resize(n);
        std::uint64_t* keys = n > kFew ? many.data() : few;
        for (std::size_t i = 0; i < n; ++i) keys[i] = (std::uint64_t(group[i]) << 32) | owner[i];
        sortGroup(keys, n, [](std::uint64_t x, std::uint64_t y) { return x < y; });
        for (std::size_t i = 0; i < n; ++i) {
            group[i] = Index(keys[i] >> 32);
            owner[i] = std::uint32_t(keys[i]);
        }
    }
    void pair(const std::uint32_t* owner, bool sameWay) const {
        const std::uint32_t h1 = owner[0], h2 = owner[1];
        if (h1 / 3 == h2 / 3) return;
        partners[h1] = h2 / 3 | (sameWay ? detail::kSameWay : 0);
        partners[h2] = h1 / 3 | (sameWay ? detail::kSameWay : 0);
    }
};

/// Vertex v's groups, sorted in place and read in runs: its edges' uses
/// (boundary, non-manifold, inconsistent, unpaired) and its triangles'
/// corner sets (duplicates), into `f`; an edge used an odd number of times
/// marks its part open (`openPart[part[v]]`).
template <class Index>
void readGroup(std::size_t v, const detail::LargeVector<Index>& edgeEnd, const detail::LargeVector<Index>& cornerEnd,
               Index* edges, std::uint64_t* others, Found& f, const Indices& part, std::atomic<std::uint8_t>* openPart,
               const Partners& partners) {
    const auto less = [](auto x, auto y) { return x < y; };
    const std::size_t first = v == 0 ? 0 : std::size_t(edgeEnd[v - 1]);
    Index* group = edges + first;
    const std::size_t n = std::size_t(edgeEnd[v]) - first;
    if (partners.owners)
        partners.sort(group, partners.owners + first, n);
    else
        sortGroup(group, n, less);
    for (std::size_t i = 0; i < n;) {
        std::size_t j = i, forward = 0;
        for (; j < n && (group[j] >> 1) == (group[i] >> 1); ++j) forward += std::size_t(group[j] & 1);
        const std::size_t uses = j - i;
        if (uses == 1) ++f.boundary;
        if (uses > 2) ++f.nonManifold;
        if (uses > 2 && uses % 2 == 1) ++f.oddNonManifold;
        if (uses % 2 == 0 && 2 * forward != uses) ++f.inconsistent;
        f.unpaired += 2 * forward > uses ? 2 * forward - uses : uses - 2 * forward;
        if (uses % 2 == 1) openPart[part[v]].store(1, std::memory_order_relaxed);
        if (uses == 2 && partners.owners) partners.pair(partners.owners + first + i, (group[i] & 1) == (group[i + 1] & 1));
        i = j;
    }
    const std::size_t firstSet = v == 0 ? 0 : std::size_t(cornerEnd[v - 1]);
    std::uint64_t* sets = others + firstSet;
    const std::size_t m = std::size_t(cornerEnd[v]) - firstSet;
    sortGroup(sets, m, less);
    for (std::size_t i = 1; i < m; ++i) f.duplicates += sets[i] == sets[i - 1];
}

/// The counts of `validateMesh` but for the vertices, `weld` given. Each
/// thread takes a share of the triangles: it checks them and counts, per
/// vertex, the edge uses and corner sets it will put in the vertex's group
/// (the group of an edge's, or a triangle's, lowest welded vertex). Running
/// sums of those counts say where each thread puts each item, and a second
/// pass puts them there: a counting sort by lowest vertex. Then every group,
/// a handful of items, is sorted in place and read in runs. `Index` holds a
/// vertex index shifted left by one and any position in the arrays of items.
template <class Index>
void countByEdges(MeshReport& r, MeshView mesh, const Indices& weld, unsigned threads, Indices& part,
                  std::atomic<std::uint8_t>* openPart, Indices* partnersOut) {
    const std::size_t nv = mesh.positionCount, nt = mesh.triangleCount;
    std::unique_ptr<std::atomic<std::uint8_t>[]> used(new std::atomic<std::uint8_t>[nv]());
    // Per thread and vertex: how many edge uses (corner sets) the thread
    // has for the vertex's group; then where it puts the next one.
    // Zeroed by the task that counts into them: fresh pages fault (and the
    // kernel clears them) on every thread at once, not on this one.
    std::vector<detail::LargeVector<Index>> edgeAt(threads), cornerAt(threads);
    std::vector<Found> found(threads);
    // The parts (union-find, serial) are found beside the first pass: task
    // 0, taken first, while the other threads count the shares; only the
    // groups' reading needs them.
    detail::parallelFor(threads, threads + 1, 1, [&](std::size_t task, std::size_t) {
        if (task == 0) {
            part = connectedParts(mesh, weld);
            return;
        }
        const std::size_t k = task - 1;
        edgeAt[k].assign(nv, 0);
        cornerAt[k].assign(nv, 0);
        countItems(mesh, weld, shareOf(nt, threads, k), used.get(), edgeAt[k].data(), cornerAt[k].data(), found[k]);
    });
    // The bounds of the used vertices' positions: those of the vertices the
    // triangles name, as a twin has its vertex's position.
    Found all;
    for (std::size_t i = 0; i < nv; ++i) {
        if (!used[weld[i]].load(std::memory_order_relaxed))
            ++r.isolatedVertices;
        else if (finitePosition(mesh.positions[i]))
            all.include(mesh.positions[i], mesh.positions[i]);
    }
    r.bounds = all.bounds;
    used.reset();

    const auto [edgeTotal, cornerTotal] = groupStarts(edgeAt, cornerAt, nv, threads);
    // Every item is written below, so the arrays start uninitialised.
    const detail::LargeArray<Index> edges = detail::largeArray<Index>(std::size_t(edgeTotal));
    /// A triangle's two higher corners: middle << 32 | highest.
    const detail::LargeArray<std::uint64_t> others = detail::largeArray<std::uint64_t>(std::size_t(cornerTotal));
    const detail::LargeArray<std::uint32_t> owners =
        partnersOut ? detail::largeArray<std::uint32_t>(std::size_t(edgeTotal)) : detail::LargeArray<std::uint32_t>();
    if (partnersOut) {
        partnersOut->resize(3 * nt); // unset: filled by the threads
        detail::parallelFor(threads, 3 * nt, kVerticesPerChunk * 16, [&](std::size_t begin, std::size_t end) {
            std::fill(partnersOut->begin() + std::ptrdiff_t(begin), partnersOut->begin() + std::ptrdiff_t(end),
                      detail::kNoPartner);
        });
    }
    const Partners partners{owners.get(), partnersOut ? partnersOut->data() : nullptr};
    detail::parallelFor(threads, threads, 1, [&](std::size_t k, std::size_t) {
        placeItems(mesh, weld, shareOf(nt, threads, k), edgeAt[k].data(), cornerAt[k].data(), edges.get(), others.get(),
                   owners.get());
    });
    const detail::LargeVector<Index> edgeEnd = std::move(edgeAt.back()), cornerEnd = std::move(cornerAt.back());
    edgeAt = {};
    cornerAt = {};

    std::vector<Found> groups((nv + kVerticesPerChunk - 1) / kVerticesPerChunk);
    detail::parallelFor(threads, nv, kVerticesPerChunk, [&](std::size_t begin, std::size_t end) {
        for (std::size_t v = begin; v < end; ++v)
            readGroup(v, edgeEnd, cornerEnd, edges.get(), others.get(), groups[begin / kVerticesPerChunk], part, openPart,
                      partners);
    });

    found.insert(found.end(), groups.begin(), groups.end());
    for (const Found& f : found) {
        r.badIndices += f.badIndices;
        r.degenerateTriangles += f.degenerate;
        r.boundaryEdges += f.boundary;
        r.nonManifoldEdges += f.nonManifold;
        r.oddNonManifoldEdges += f.oddNonManifold;
        r.inconsistentEdges += f.inconsistent;
        r.windingBoundaryEdges += f.unpaired;
        r.duplicateTriangles += f.duplicates;
    }
}

/// Each triangle's part, numbered densely: that of its first corner's
/// welded vertex (valid indices only).
struct TriangleParts {
    MeshView mesh;
    const Indices& weld;
    const Indices& part;
    Indices dense; ///< per part's root vertex, its number
    std::size_t count = 0;            ///< parts

    TriangleParts(MeshView m, const Indices& w, const Indices& p)
        : mesh(m), weld(w), part(p), dense(p.size(), 0) {
        for (std::size_t v = 0; v < part.size(); ++v)
            if (part[v] == v) dense[v] = std::uint32_t(count++);
    }
    std::uint32_t operator[](std::size_t t) const { return dense[part[weld[mesh.triangles[t].x]]]; }
};

/// What one pass over the triangles finds for `countInsideOutParts` and
/// `allInOnePlane`, chunk by chunk of triangles in parallel.
struct TriangleSums {
    /// Per part (numbered densely), the signed volume about the box's centre
    /// and the sum of its magnitudes; only the closed parts' are summed.
    std::vector<double> volume, magnitude;
    /// The largest area of a valid triangle (finite), and the first
    /// triangle of that area.
    double largest = 0.0;
    std::size_t largestTriangle = 0;
};

/// Triangles a chunk of `sumTriangles`; parts at most for which each chunk
/// keeps its own sums (otherwise the triangles are one chunk). The chunks
/// are fixed, not one per thread, and their sums added in order: the same
/// rounding for any number of threads.
constexpr std::size_t kSumChunk = std::size_t(1) << 16;
constexpr std::size_t kChunkedParts = 256;

/// The triangle's corners in double; false if an index is out of range.
bool cornersOf(MeshView mesh, std::size_t t, glm::dvec3 (&c)[3]) {
    const glm::uvec3 tri = mesh.triangles[t];
    const std::size_t n = mesh.positionCount;
    if (tri.x >= n || tri.y >= n || tri.z >= n) return false;
    for (int k = 0; k < 3; ++k) c[k] = glm::dvec3(mesh.positions[tri[k]]);
    return true;
}

bool finiteCorners(const glm::dvec3 (&c)[3]) {
    return std::isfinite(c[0].x + c[0].y + c[0].z + c[1].x + c[1].y + c[1].z + c[2].x + c[2].y + c[2].z);
}

/// Shewchuk's forward error bound of orient2d evaluated in double (1997,
/// ccwerrboundA; predicates/predicates.h evaluates the same in the room
/// above, with its exact fallback).
constexpr double kOrientBound = (3.0 + 16.0 * 0x1p-53) * 0x1p-53;

/// The triangle's facings along x, y and z (<vds/detail/edge_partners.h>):
/// each component of (c1 - c0) x (c2 - c0) is the orientation of the
/// corners projected along its axis, formed as orient2d forms it from
/// float coordinates: its sign where it exceeds the bound, undecided
/// otherwise.
std::uint8_t facingsOf(const glm::dvec3 (&c)[3]) {
    const glm::dvec3 u = c[1] - c[0], v = c[2] - c[0];
    std::uint8_t bits = 0;
    for (int a = 0; a < 3; ++a) {
        const int s = (a + 1) % 3, t = (a + 2) % 3;
        const double left = u[s] * v[t], right = u[t] * v[s], det = left - right;
        const double bound = kOrientBound * (std::fabs(left) + std::fabs(right));
        // Both products exactly zero: a factor is (a difference of floats
        // rounds to zero only when exact), so the orientation is: parallel.
        const std::uint8_t f = det > bound                   ? detail::kFacesPlus
                               : -det > bound                ? detail::kFacesMinus
                               : left == 0.0 && right == 0.0 ? 0
                                                             : detail::kFacesUndecided;
        bits |= std::uint8_t(f << (2 * a));
    }
    return bits;
}

/// The sums of `TriangleSums`, the volume counted only where `closed[part]`.
TriangleSums sumTriangles(MeshView mesh, const TriangleParts& partOf, const std::vector<std::uint8_t>& closed,
                          const Box& bounds, unsigned threads, std::uint8_t* facings) {
    const std::size_t parts = partOf.count;
    const glm::dvec3 centre = (glm::dvec3(bounds.lo) + glm::dvec3(bounds.hi)) * 0.5;
    const std::size_t nt = mesh.triangleCount;
    const std::size_t chunk = parts <= kChunkedParts ? kSumChunk : std::max<std::size_t>(1, nt);
    const std::size_t chunks = std::max<std::size_t>(1, (nt + chunk - 1) / chunk);
    std::vector<TriangleSums> found(chunks);
    detail::parallelFor(threads, nt, chunk, [&](std::size_t begin, std::size_t end) {
        TriangleSums& f = found[begin / chunk];
        f.volume.assign(parts, 0.0);
        f.magnitude.assign(parts, 0.0);
        glm::dvec3 c[3] = {glm::dvec3(0.0), glm::dvec3(0.0), glm::dvec3(0.0)};
        for (std::size_t t = begin; t < end; ++t) {
            if (!cornersOf(mesh, t, c)) continue;
            const glm::dvec3 n = glm::cross(c[1] - c[0], c[2] - c[0]);
            if (facings) facings[t] = facingsOf(c);
            // sqrt is monotone: only a triangle whose squared area reaches
            // the largest's, less rounding, can be larger.
            const double squared = glm::dot(n, n);
            if (squared >= f.largest * f.largest * (1.0 - 1e-9)) {
                const double area = glm::length(n);
                if (std::isfinite(area) && area > f.largest) f.largest = area, f.largestTriangle = t;
            }
            const std::uint32_t p = partOf[t];
            if (!finiteCorners(c) || !closed[p]) continue;
            const double v = glm::dot(c[0] - centre, glm::cross(c[1] - centre, c[2] - centre));
            f.volume[p] += v;
            f.magnitude[p] += std::abs(v);
        }
    });
    TriangleSums all = std::move(found[0]);
    all.volume.resize(parts, 0.0);
    all.magnitude.resize(parts, 0.0);
    for (std::size_t k = 1; k < chunks; ++k) {
        const TriangleSums& f = found[k];
        for (std::size_t p = 0; p < parts; ++p) {
            all.volume[p] += f.volume[p];
            all.magnitude[p] += f.magnitude[p];
        }
        if (f.largest > all.largest) all.largest = f.largest, all.largestTriangle = f.largestTriangle;
    }
    return all;
}

/// Whether every vertex the (valid) triangles use lies within 1e-6 of the
/// box's diagonal of the plane of the largest triangle (`MeshReport::coplanar`).
bool allInOnePlane(MeshView mesh, const Box& bounds, const TriangleSums& sums) {
    constexpr double kPlaneTolerance = 1e-6;
    if (sums.largest == 0.0) return true; // every triangle degenerate: no plane, no volume
    glm::dvec3 c[3] = {glm::dvec3(0.0), glm::dvec3(0.0), glm::dvec3(0.0)};
    cornersOf(mesh, sums.largestTriangle, c);
    const glm::dvec3 normal = glm::cross(c[1] - c[0], c[2] - c[0]) / sums.largest, origin = c[0];
    const double reach = kPlaneTolerance * glm::length(glm::dvec3(bounds.hi) - glm::dvec3(bounds.lo));
    for (std::size_t t = 0; t < mesh.triangleCount; ++t) {
        if (!cornersOf(mesh, t, c)) continue;
        for (int k = 0; k < 3; ++k) {
            const double off = glm::dot(c[k] - origin, normal);
            if (!(std::abs(off) <= reach)) return false;
        }
    }
    return true;
}

/// Closed parts (no edge at fault) turned inside out, from the parts' sums.
/// A part whose signed volume is negative beyond rounding (below -1e-6 of
/// the sum of its triangles' magnitudes, about the box's centre: a flat
/// part is not) encloses a region on its triangles' front side; it is
/// inside out where the winding number of the closed parts there is
/// negative, and a cavity (a reversed sphere inside an outward one: winding
/// 0) where it is not. The point asked lies off the centroid of the part's
/// largest triangle, a thousandth of its size along its normal; its winding
/// number is the closed parts' solid angles summed (an integer, rounded),
/// the candidates of the largest volume first while the work stays within
/// kProbeBudget triangle-point pairs (a part left unasked is not counted).
std::size_t countInsideOutParts(MeshView mesh, const TriangleParts& partOf,
                                const std::vector<std::uint8_t>& closed, const TriangleSums& sums) {
    constexpr double kRounding = 1e-6, kOffset = 1e-3;
    constexpr std::size_t kProbeBudget = std::size_t(1) << 27;
    std::vector<std::uint32_t> candidates;
    for (std::size_t p = 0; p < sums.volume.size(); ++p)
        if (sums.magnitude[p] > 0.0 && closed[p] && sums.volume[p] < -kRounding * sums.magnitude[p])
            candidates.push_back(std::uint32_t(p));
    if (candidates.empty()) return 0;
    std::sort(candidates.begin(), candidates.end(),
              [&](std::uint32_t a, std::uint32_t b) { return sums.volume[a] < sums.volume[b]; });
    candidates.resize(std::min(candidates.size(), std::max<std::size_t>(1, kProbeBudget / std::max<std::size_t>(1, mesh.triangleCount))));
    // Each candidate's largest triangle: the first of the largest area.
    std::vector<double> largest(sums.volume.size(), 0.0);
    std::vector<std::size_t> largestTriangle(sums.volume.size(), 0);
    glm::dvec3 c[3] = {glm::dvec3(0.0), glm::dvec3(0.0), glm::dvec3(0.0)};
    for (std::size_t t = 0; t < mesh.triangleCount; ++t) {
        if (!cornersOf(mesh, t, c) || !finiteCorners(c)) continue;
        const std::uint32_t p = partOf[t];
        const double area = glm::length(glm::cross(c[1] - c[0], c[2] - c[0]));
        if (area > largest[p]) largest[p] = area, largestTriangle[p] = t;
    }
    std::vector<glm::dvec3> probes;
    for (std::uint32_t p : candidates) {
        cornersOf(mesh, largestTriangle[p], c);
        const glm::dvec3 normal = glm::cross(c[1] - c[0], c[2] - c[0]);
        const double size = glm::length(normal);
        probes.push_back((c[0] + c[1] + c[2]) / 3.0 + normal / size * (kOffset * std::sqrt(size)));
    }
    std::vector<double> angle(probes.size(), 0.0);
    for (std::size_t t = 0; t < mesh.triangleCount; ++t) {
        if (!cornersOf(mesh, t, c) || !finiteCorners(c) || !closed[partOf[t]]) continue;
        for (std::size_t k = 0; k < probes.size(); ++k)
            angle[k] += detail::solidAngle(c[0] - probes[k], c[1] - probes[k], c[2] - probes[k]);
    }
    std::size_t count = 0;
    for (double a : angle) count += std::lround(a / detail::kFourPi) < 0;
    return count;
}

} // namespace

namespace {

MeshReport validate(MeshView mesh, unsigned threads, detail::MeshFinds* finds) {
    MeshReport r;
    const std::size_t nv = mesh.positionCount, nt = mesh.triangleCount;
    r.vertexCount = nv;
    r.triangleCount = nt;
    r.skippedFaces = mesh.skippedFaces;
    if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
    // Small meshes: one thread pays best. Each thread keeps two counts per
    // vertex, so at most 8.
    threads = unsigned(std::min<std::size_t>({threads, nt / 65536 + 1, 8}));

    const Indices weld = weldByPosition(mesh.positions, nv, threads, r.nonFiniteVertices);
    Indices part; // found by countByEdges, beside its first pass
    std::unique_ptr<std::atomic<std::uint8_t>[]> openPart(new std::atomic<std::uint8_t>[nv]());
    // 32-bit items while vertex indices fit in 31 bits and the edge uses in 32.
    // Partners (their half-edges and flag in 32 bits) with 32-bit items only.
    if (nv < (std::size_t(1) << 31) && 3 * nt < (std::size_t(1) << 31))
        countByEdges<std::uint32_t>(r, mesh, weld, threads, part, openPart.get(), finds ? &finds->partners : nullptr);
    else if (nv < (std::size_t(1) << 31) && 3 * nt < (std::size_t(1) << 32))
        countByEdges<std::uint32_t>(r, mesh, weld, threads, part, openPart.get(), nullptr);
    else
        countByEdges<std::uint64_t>(r, mesh, weld, threads, part, openPart.get(), nullptr);
    const TriangleParts partOf(mesh, weld, part);
    std::vector<std::uint8_t> closed(partOf.count, 0);
    for (std::size_t v = 0; v < nv; ++v)
        if (part[v] == v) closed[partOf.dense[v]] = !openPart[v].load(std::memory_order_relaxed);
    if (finds) finds->facings.assign(nt, 0);
    const TriangleSums sums =
        sumTriangles(mesh, partOf, closed, r.bounds, threads, finds ? finds->facings.data() : nullptr);
    r.insideOutParts = countInsideOutParts(mesh, partOf, closed, sums);
    r.coplanar = allInOnePlane(mesh, r.bounds, sums);
    return r;
}

} // namespace

MeshReport validateMesh(MeshView mesh, unsigned threads) { return validate(mesh, threads, nullptr); }

MeshReport detail::validateMesh(MeshView mesh, unsigned threads, MeshFinds& finds) {
    finds = MeshFinds();
    return validate(mesh, threads, &finds);
}

MeshValidation::MeshValidation(MeshView mesh, unsigned threads) : finds_(std::make_unique<Finds>()) {
    report_ = validate(mesh, threads, finds_.get());
}
MeshValidation::~MeshValidation() = default;
MeshValidation::MeshValidation(MeshValidation&&) noexcept = default;
MeshValidation& MeshValidation::operator=(MeshValidation&&) noexcept = default;

} // namespace vds
