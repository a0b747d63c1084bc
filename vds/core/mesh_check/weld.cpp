// vds: the library's one weld, positions equal as floats (weld.h).
#include <vds/detail/weld.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>
#include <vector>

#include <vds/detail/parallel.h>

namespace vds::detail {
namespace {


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

/// Vertices at least for the weld to take more than one thread: below it
/// the threads' start outweighs their share.
constexpr std::size_t kWeldParallelVertices = std::size_t(1) << 16;
/// The most parts of the weld (the threads it takes).
constexpr std::size_t kMaxWeldParts = 8;
/// Vertices a chunk of the weld's hashing.
constexpr std::size_t kWeldChunk = std::size_t(1) << 14;

} // namespace

// The keys are split by their hash's low bits into parts (a power of two,
// at most the threads): chunks of vertices in parallel hash their keys and
// list each vertex under its part, in index order; then a thread a part
// takes its list, so the first found at a position is the lowest vertex,
// for any number of threads. A part is an open-addressing table, linear
// probing, at most half full; a slot holds the upper half of the key's hash
// beside the vertex index, so a probe reads a position only when the hashes
// agree, and the slots of vertices a little ahead are prefetched: the
// table's cache misses overlap.
LargeVector<std::uint32_t> weldByPosition(const glm::vec3* positions, std::size_t n, unsigned threads,
                                          std::size_t& notFinite) {
    std::size_t parts = 1;
    while (n >= kWeldParallelVertices && 2 * parts <= std::min<std::size_t>(threads, kMaxWeldParts)) parts *= 2;
    const std::size_t chunks = (n + kWeldChunk - 1) / kWeldChunk;
    LargeVector<std::uint32_t> first(n);
    // Written before read, by the threads: their first touches fault in parallel.
    const LargeArray<std::uint64_t> hashes = largeArray<std::uint64_t>(n);
    std::vector<std::size_t> at((parts + 1) * chunks + 1, 0); // per part and chunk, its place in `order`
    std::vector<std::size_t> notFiniteIn(chunks, 0);
    parallelFor(threads, n, kWeldChunk, [&](std::size_t begin, std::size_t end) {
        // Counted here, written once: neighbouring chunks' counts share cache lines.
        std::size_t count[kMaxWeldParts + 1] = {};
        for (std::size_t i = begin; i < end; ++i) {
            first[i] = std::uint32_t(i);
            const std::uint64_t h = PositionKey(positions[i]).hash();
            hashes[i] = h;
            ++count[finitePosition(positions[i]) ? h & (parts - 1) : kMaxWeldParts];
        }
        const std::size_t chunk = begin / kWeldChunk;
        for (std::size_t part = 0; part < parts; ++part) at[1 + part * chunks + chunk] = count[part];
        notFiniteIn[chunk] = count[kMaxWeldParts];
    });
    notFinite = std::accumulate(notFiniteIn.begin(), notFiniteIn.end(), std::size_t(0));
    std::partial_sum(at.begin(), at.end(), at.begin());
    const LargeArray<std::uint32_t> order = largeArray<std::uint32_t>(n - notFinite);
    parallelFor(threads, n, kWeldChunk, [&](std::size_t begin, std::size_t end) {
        const std::size_t chunk = begin / kWeldChunk;
        std::size_t next[kMaxWeldParts];
        for (std::size_t part = 0; part < parts; ++part) next[part] = at[part * chunks + chunk];
        for (std::size_t i = begin; i < end; ++i)
            if (finitePosition(positions[i])) order[next[hashes[i] & (parts - 1)]++] = std::uint32_t(i);
    });
    parallelFor(unsigned(parts), parts, 1, [&](std::size_t part, std::size_t) {
        const std::size_t from = at[part * chunks], to = at[(part + 1) * chunks];
        int bits = 1;
        while ((std::size_t(1) << bits) < 2 * (to - from) + 2) ++bits;
        const std::size_t mask = (std::size_t(1) << bits) - 1;
        constexpr std::uint64_t kEmpty = ~std::uint64_t(0);
        LargeVector<std::uint64_t> table(mask + 1, kEmpty);
        constexpr std::size_t kAhead = 16;
        for (std::size_t k = from; k < to; ++k) {
            if (k + kAhead < to) __builtin_prefetch(&table[std::size_t(hashes[order[k + kAhead]] >> (64 - bits))]);
            const std::uint32_t i = order[k];
            const std::uint64_t h = hashes[i], tag = h & 0xFFFFFFFF00000000ull;
            for (std::size_t slot = std::size_t(h >> (64 - bits));; slot = (slot + 1) & mask) {
                const std::uint64_t entry = table[slot];
                if (entry == kEmpty) {
                    table[slot] = tag | i;
                    break;
                }
                const auto j = std::uint32_t(entry);
                if ((entry & 0xFFFFFFFF00000000ull) == tag && PositionKey(positions[j]) == PositionKey(positions[i])) {
                    first[i] = j;
                    break;
                }
            }
        }
    });
    return first;
}

std::vector<std::uint32_t> weldPositions(const glm::vec3* positions, std::size_t n, std::vector<glm::vec3>& where) {
    std::size_t notFinite = 0;
    const LargeVector<std::uint32_t> first = weldByPosition(positions, n, 1, notFinite);
    // Ids in the order of each position's first vertex: a vertex is its
    // position's first exactly when it is its own.
    std::vector<std::uint32_t> id(n);
    where.clear();
    for (std::size_t v = 0; v < n; ++v) {
        if (first[v] == v) {
            id[v] = std::uint32_t(where.size());
            where.push_back(positions[v]);
        } else {
            id[v] = id[first[v]];
        }
    }
    return id;
}

} // namespace vds::detail
