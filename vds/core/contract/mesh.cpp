#include <vds/mesh.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <memory>
#include <sstream>
#include <thread>

#include <glm/geometric.hpp>

#include <vds/detail/parallel.h>
#include <vds/error.h>
#include <vds/rule.h>

namespace vds {
namespace {

bool finite(const glm::vec3& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }

/// "1 boundary edge", "3 boundary edges".
std::string counted(std::size_t n, const char* one, const char* many = nullptr) {
    return std::to_string(n) + " " + (n == 1 ? one : many ? many : std::string(one) + "s");
}

/// A finite position's bits with -0 made +0, so that positions equal as
/// floats have equal keys.
struct PositionKey {
    std::uint32_t bits[3];
    explicit PositionKey(glm::vec3 p) {
        p += glm::vec3(0.0f); // -0 + 0 = +0
        std::memcpy(bits, &p, sizeof bits);
    }
    bool operator==(const PositionKey& o) const {
        return bits[0] == o.bits[0] && bits[1] == o.bits[1] && bits[2] == o.bits[2];
    }
    std::uint64_t hash() const {
        const std::uint64_t h = ((std::uint64_t(bits[0]) << 32) | bits[1]) * 0x9E3779B97F4A7C15ull ^
                                std::uint64_t(bits[2]) * 0xC2B2AE3D27D4EB4Full;
        return (h ^ (h >> 31)) * 0xBF58476D1CE4E5B9ull;
    }
};

/// For each vertex, the first vertex at the same position (equal as floats,
/// so -0 = +0); a vertex with a NaN or infinite coordinate is its own. An
/// open-addressing table, linear probing, at most half full; a slot holds
/// the upper half of the key's hash beside the vertex index, so a probe
/// reads a position only when the hashes agree, and the slots of vertices a
/// little ahead are prefetched: the table's cache misses overlap.
std::vector<std::uint32_t> weldByPosition(const glm::vec3* positions, std::size_t n) {
    std::vector<std::uint32_t> first(n);
    int bits = 1;
    while ((std::size_t(1) << bits) < 2 * n) ++bits;
    const std::size_t mask = (std::size_t(1) << bits) - 1;
    constexpr std::uint64_t kEmpty = ~std::uint64_t(0);
    std::vector<std::uint64_t> table(mask + 1, kEmpty);
    const auto hashOf = [&](std::size_t i) { return PositionKey(positions[i]).hash(); };
    constexpr std::size_t kAhead = 16;
    for (std::size_t i = 0; i < n; ++i) {
        if (i + kAhead < n) __builtin_prefetch(&table[std::size_t(hashOf(i + kAhead) >> (64 - bits))]);
        const glm::vec3 p = positions[i];
        if (!finite(p)) {
            first[i] = std::uint32_t(i);
            continue;
        }
        const PositionKey key(p);
        const std::uint64_t h = key.hash();
        const std::uint64_t tag = h & 0xFFFFFFFF00000000ull;
        for (std::size_t slot = std::size_t(h >> (64 - bits));; slot = (slot + 1) & mask) {
            const std::uint64_t entry = table[slot];
            if (entry == kEmpty) {
                table[slot] = tag | i;
                first[i] = std::uint32_t(i);
                break;
            }
            const auto j = std::uint32_t(entry);
            if ((entry & 0xFFFFFFFF00000000ull) == tag && PositionKey(positions[j]) == key) {
                first[i] = j;
                break;
            }
        }
    }
    return first;
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
    std::size_t boundary = 0, nonManifold = 0, oddNonManifold = 0, inconsistent = 0, duplicates = 0;

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
void countItems(MeshView mesh, const std::vector<std::uint32_t>& weld, std::pair<std::size_t, std::size_t> share,
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
std::pair<Index, Index> groupStarts(std::vector<std::vector<Index>>& edgeAt, std::vector<std::vector<Index>>& cornerAt,
                                    std::size_t nv, unsigned threads) {
    const std::size_t chunks = (nv + kVerticesPerChunk - 1) / kVerticesPerChunk;
    std::vector<std::pair<Index, Index>> chunkStart(chunks + 1); // edges, corners
    parallelFor(threads, chunks, 1, [&](std::size_t c, std::size_t) {
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
    parallelFor(threads, chunks, 1, [&](std::size_t c, std::size_t) {
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
void placeItems(MeshView mesh, const std::vector<std::uint32_t>& weld, std::pair<std::size_t, std::size_t> share,
                Index* edgeNext, Index* cornerNext, Index* edges, std::uint64_t* others) {
    const std::size_t nv = mesh.positionCount;
    for (auto [t, end] = share; t < end; ++t) {
        const glm::uvec3 tri = mesh.triangles[t];
        if (tri.x >= nv || tri.y >= nv || tri.z >= nv) continue;
        std::uint32_t w[3] = {weld[tri.x], weld[tri.y], weld[tri.z]};
        if (w[0] == w[1] || w[1] == w[2] || w[0] == w[2]) continue;
        for (int e = 0; e < 3; ++e) {
            const std::uint32_t a = w[e], b = w[(e + 1) % 3];
            edges[edgeNext[std::min(a, b)]++] = edgeUse<Index>(a, b);
        }
        if (w[0] > w[1]) std::swap(w[0], w[1]);
        if (w[1] > w[2]) std::swap(w[1], w[2]);
        if (w[0] > w[1]) std::swap(w[0], w[1]);
        others[cornerNext[w[0]]++] = (std::uint64_t(w[1]) << 32) | w[2];
    }
}

/// Vertex v's groups, sorted in place and read in runs: its edges' uses
/// (boundary, non-manifold, inconsistent) and its triangles' corner sets
/// (duplicates), into `f`.
template <class Index>
void readGroup(std::size_t v, const std::vector<Index>& edgeEnd, const std::vector<Index>& cornerEnd, Index* edges,
               std::uint64_t* others, Found& f) {
    const auto less = [](auto x, auto y) { return x < y; };
    const std::size_t first = v == 0 ? 0 : std::size_t(edgeEnd[v - 1]);
    Index* group = edges + first;
    const std::size_t n = std::size_t(edgeEnd[v]) - first;
    sortGroup(group, n, less);
    for (std::size_t i = 0; i < n;) {
        std::size_t j = i, forward = 0;
        for (; j < n && (group[j] >> 1) == (group[i] >> 1); ++j) forward += std::size_t(group[j] & 1);
        const std::size_t uses = j - i;
        if (uses == 1) ++f.boundary;
        if (uses > 2) ++f.nonManifold;
        if (uses > 2 && uses % 2 == 1) ++f.oddNonManifold;
        if (uses % 2 == 0 && 2 * forward != uses) ++f.inconsistent;
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
void countByEdges(MeshReport& r, MeshView mesh, const std::vector<std::uint32_t>& weld, unsigned threads) {
    const std::size_t nv = mesh.positionCount, nt = mesh.triangleCount;
    std::unique_ptr<std::atomic<std::uint8_t>[]> used(new std::atomic<std::uint8_t>[nv]());
    // Per thread and vertex: how many edge uses (corner sets) the thread
    // has for the vertex's group; then where it puts the next one.
    std::vector<std::vector<Index>> edgeAt(threads, std::vector<Index>(nv, 0));
    std::vector<std::vector<Index>> cornerAt(threads, std::vector<Index>(nv, 0));
    std::vector<Found> found(threads);
    parallelFor(threads, threads, 1, [&](std::size_t k, std::size_t) {
        countItems(mesh, weld, shareOf(nt, threads, k), used.get(), edgeAt[k].data(), cornerAt[k].data(), found[k]);
    });
    // The bounds of the used vertices' positions: those of the vertices the
    // triangles name, as a twin has its vertex's position.
    Found all;
    for (std::size_t i = 0; i < nv; ++i) {
        if (!used[weld[i]].load(std::memory_order_relaxed))
            ++r.isolatedVertices;
        else if (finite(mesh.positions[i]))
            all.include(mesh.positions[i], mesh.positions[i]);
    }
    r.bounds = all.bounds;
    used.reset();

    const auto [edgeTotal, cornerTotal] = groupStarts(edgeAt, cornerAt, nv, threads);
    // Every item is written below, so the arrays start uninitialised.
    const std::unique_ptr<Index[]> edges(new Index[std::size_t(edgeTotal)]);
    const std::unique_ptr<std::uint64_t[]> others(new std::uint64_t[std::size_t(cornerTotal)]); ///< a triangle's two higher corners: middle << 32 | highest
    parallelFor(threads, threads, 1, [&](std::size_t k, std::size_t) {
        placeItems(mesh, weld, shareOf(nt, threads, k), edgeAt[k].data(), cornerAt[k].data(), edges.get(), others.get());
    });
    const std::vector<Index> edgeEnd = std::move(edgeAt.back()), cornerEnd = std::move(cornerAt.back());
    edgeAt = {};
    cornerAt = {};

    std::vector<Found> groups((nv + kVerticesPerChunk - 1) / kVerticesPerChunk);
    parallelFor(threads, nv, kVerticesPerChunk, [&](std::size_t begin, std::size_t end) {
        for (std::size_t v = begin; v < end; ++v)
            readGroup(v, edgeEnd, cornerEnd, edges.get(), others.get(), groups[begin / kVerticesPerChunk]);
    });

    found.insert(found.end(), groups.begin(), groups.end());
    for (const Found& f : found) {
        r.badIndices += f.badIndices;
        r.degenerateTriangles += f.degenerate;
        r.boundaryEdges += f.boundary;
        r.nonManifoldEdges += f.nonManifold;
        r.oddNonManifoldEdges += f.oddNonManifold;
        r.inconsistentEdges += f.inconsistent;
        r.duplicateTriangles += f.duplicates;
    }
}

} // namespace

std::string MeshReport::summary() const {
    if (triangleCount == 0)
        return "empty: no triangles" +
               (skippedFaces ? " (" + counted(skippedFaces, "face") + " of fewer than 3 vertices skipped)" : "");
    std::ostringstream s;
    if (nonFiniteVertices) s << "non-finite: " << nonFiniteVertices << " vertices with NaN or infinite coordinates, ";
    if (badIndices) s << "invalid: " << badIndices << " indices out of range, ";
    s << (closed() ? "closed" : "open");
    if (!closed()) {
        s << " (";
        if (boundaryEdges) s << counted(boundaryEdges, "boundary edge") << (oddNonManifoldEdges ? ", " : "");
        if (oddNonManifoldEdges) s << counted(oddNonManifoldEdges, "edge") << " shared by an odd number of triangles";
        s << ")";
    }
    if (nonManifoldEdges) s << ", " << counted(nonManifoldEdges, "non-manifold edge");
    if (inconsistentEdges) s << ", " << counted(inconsistentEdges, "inconsistently oriented edge");
    s << ", " << counted(triangleCount, "triangle") << ", " << counted(vertexCount, "vertex", "vertices");
    if (degenerateTriangles) s << ", " << counted(degenerateTriangles, "degenerate triangle");
    if (duplicateTriangles) s << ", " << counted(duplicateTriangles, "duplicate triangle");
    if (isolatedVertices) s << ", " << counted(isolatedVertices, "isolated vertex", "isolated vertices");
    if (skippedFaces) s << ", " << counted(skippedFaces, "face") << " of fewer than 3 vertices skipped";
    return s.str();
}

MeshReport validateMesh(MeshView mesh, unsigned threads) {
    MeshReport r;
    const std::size_t nv = mesh.positionCount, nt = mesh.triangleCount;
    r.vertexCount = nv;
    r.triangleCount = nt;
    r.skippedFaces = mesh.skippedFaces;
    if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
    // Small meshes: one thread pays best. Each thread keeps two counts per
    // vertex, so at most 8.
    threads = unsigned(std::min<std::size_t>({threads, nt / 65536 + 1, 8}));

    for (std::size_t i = 0; i < nv; ++i)
        if (!finite(mesh.positions[i])) ++r.nonFiniteVertices;
    const std::vector<std::uint32_t> weld = weldByPosition(mesh.positions, nv);
    // 32-bit items while vertex indices fit in 31 bits and the edge uses in 32.
    if (nv < (std::size_t(1) << 31) && 3 * nt < (std::size_t(1) << 32))
        countByEdges<std::uint32_t>(r, mesh, weld, threads);
    else
        countByEdges<std::uint64_t>(r, mesh, weld, threads);
    return r;
}

void requireUsable(const MeshReport& report, const std::string& meshName) {
    const std::string who = meshName.empty() ? std::string("mesh") : meshName;
    if (report.triangleCount == 0) throw InvalidMesh(who + ": empty mesh (no triangles)");
    if (report.nonFiniteVertices)
        throw InvalidMesh(who + ": " + std::to_string(report.nonFiniteVertices) +
                          " vertices have NaN or infinite coordinates");
    if (report.badIndices)
        throw InvalidMesh(who + ": " + std::to_string(report.badIndices) + " triangle indices are out of range");
}

bool MeshReport::flat() const {
    for (int a = 0; a < 3; ++a)
        if (!(bounds.hi[a] > bounds.lo[a])) return true;
    return false;
}

std::string openMeshMessage(const MeshReport& report, const std::string& meshName, Rule rule) {
    if (rule == Rule::GeneralizedWinding) return {}; // defined for every usable mesh
    const std::string who = meshName.empty() ? std::string("mesh") : meshName;
    if (!report.closed()) {
        std::string why;
        if (report.boundaryEdges) why = counted(report.boundaryEdges, "boundary edge");
        if (report.oddNonManifoldEdges)
            why += (why.empty() ? "" : ", ") + counted(report.oddNonManifoldEdges, "edge") +
                   " shared by an odd number of triangles";
        return who + " is open (" + why + "): inside is not defined by the " + toString(rule) +
               " rule; the generalized winding number answers for it (--rule generalized-winding), and answering "
               "anyway (--allow-open) counts crossings as for a surface, not a solid";
    }
    if (rule == Rule::Winding && !report.oriented())
        return who + " has " + counted(report.inconsistentEdges, "inconsistently oriented edge") +
               ": inside is not defined by the winding rule; the parity rule and the generalized winding number "
               "(--rule generalized-winding) answer for it";
    return {};
}

std::string openSpriteMessage(const std::string& validation, Rule rule) {
    if (rule == Rule::GeneralizedWinding) return {};
    return "the sprite was baked from a mesh that bounds no solid (" + validation + "): its " + toString(rule) +
           " answers count crossings as for a surface; the generalized winding number answers for it "
           "(--rule generalized-winding)";
}

void requireVolume(const MeshReport& report, const std::string& meshName) {
    if (!report.flat()) return;
    const std::string who = meshName.empty() ? std::string("mesh") : meshName;
    std::string axes;
    for (int a = 0; a < 3; ++a)
        if (!(report.bounds.hi[a] > report.bounds.lo[a])) axes += std::string(axes.empty() ? "" : " and ") + "xyz"[a];
    throw InvalidMesh(who + " is flat (no extent along " + axes +
                      "): it bounds no volume, so no point is inside it by any rule and nothing is baked or written; "
                      "its generalized winding number still measures points off the sheet (between -1/2 and 1/2)");
}

void requireInsideDefined(const MeshReport& report, const std::string& meshName, Rule rule) {
    requireUsable(report, meshName);
    const std::string message = openMeshMessage(report, meshName, rule);
    if (!message.empty()) throw InvalidMesh(message);
}

std::string insideWarning(const MeshReport& report, Rule rule) {
    std::string what;
    if (report.nonManifoldEdges)
        what = counted(report.nonManifoldEdges, "non-manifold edge") + " (more than two triangles on an edge)";
    if (rule == Rule::Parity && report.inconsistentEdges)
        what += (what.empty() ? "" : ", ") + counted(report.inconsistentEdges, "inconsistently oriented edge");
    if (what.empty()) return what;
    return what + "; inside is still defined by the " + toString(rule) + " rule";
}

Box meshBounds(MeshView mesh) {
    Box b;
    bool any = false;
    for (std::size_t t = 0; t < mesh.triangleCount; ++t)
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t i = mesh.triangles[t][k];
            if (i >= mesh.positionCount) continue;
            const glm::vec3& p = mesh.positions[i];
            if (!any) { b.lo = b.hi = p; any = true; }
            b.lo = glm::min(b.lo, p);
            b.hi = glm::max(b.hi, p);
        }
    return b;
}

} // namespace vds
