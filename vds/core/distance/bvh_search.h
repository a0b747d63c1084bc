// vds: the distance hierarchy's search (bvh.h), written once over a SIMD
// vector of L float lanes and compiled once per instruction set: bvh_sse.cpp
// (L = 4, or 1 without SSE), bvh_avx2.cpp (8) and bvh_avx512.cpp (16), each
// of which includes this file after switching its instruction set on, and
// every header this file needs before it (and says which by defining
// VDS_BVH_AVX2 or VDS_BVH_AVX512: GCC's target pragma does not define the
// instruction set's own macros). Everything here has internal
// linkage, so each of them keeps its own copy, compiled for its own
// instructions, and no function compiled for AVX can stand in for one a
// plain SSE machine runs.
//
// The search is nearest box first: a node's W box and slab distances in
// W / L SIMD steps, then its leaves, nearest first, then its inner children
// pushed farthest first. A leaf's triangles are first bounded below in float
// by their planes (PlaneLanes, ExtentLanes) in W / L steps, and only those
// whose bound is still within reach get the exact test in double
// (Bvh::slotDistance2), the lowest bound first.
#pragma once

#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include <glm/vec3.hpp>

#if defined(__SSE2__)
#include <immintrin.h>
#endif

#include <vds/detail/bvh.h>

namespace vds::detail {
namespace {

constexpr float kSearchInf = std::numeric_limits<float>::infinity();
/// The search's stack: W - 1 entries a level at most, over the binary
/// build's depth bound (kSahDepth + 32 levels, bvh.cpp).
constexpr int kStackEntries = (kMaxBvhWidth - 1) * (48 + 32) + 4;
/// One float lane: the search where no SIMD is known.
struct Scalar {
    static constexpr int lanes = 1;
    using F = float;
    using M = bool;
    static F loadLanes(const float* p) { return *p; }
    static void store(float* p, F a) { *p = a; }
    static F set(float a) { return a; }
    static F add(F a, F b) { return a + b; }
    static F sub(F a, F b) { return a - b; }
    static F mul(F a, F b) { return a * b; }
    static F max(F a, F b) { return a > b ? a : b; }
    static F min(F a, F b) { return a < b ? a : b; }
    static F abs(F a) { return a < 0.0f ? -a : a; }
    static F neg(F a) { return -a; }
    static M gt(F a, F b) { return a > b; }
    static M le(F a, F b) { return a <= b; }
    static M either(M a, M b) { return a || b; }
    static M none() { return false; }
    static F select(M m, F a, F b) { return m ? a : b; }
    static bool any(M m) { return m; }
};

#if defined(__SSE2__)
struct Sse {
    static constexpr int lanes = 4;
    using F = __m128;
    using M = __m128;
    static F loadLanes(const float* p) { return _mm_load_ps(p); }
    static void store(float* p, F a) { _mm_storeu_ps(p, a); }
    static F set(float a) { return _mm_set1_ps(a); }
    static F add(F a, F b) { return _mm_add_ps(a, b); }
    static F sub(F a, F b) { return _mm_sub_ps(a, b); }
    static F mul(F a, F b) { return _mm_mul_ps(a, b); }
    static F max(F a, F b) { return _mm_max_ps(a, b); }
    static F min(F a, F b) { return _mm_min_ps(a, b); }
    static F abs(F a) { return _mm_andnot_ps(_mm_set1_ps(-0.0f), a); }
    static F neg(F a) { return _mm_xor_ps(a, _mm_set1_ps(-0.0f)); }
    static M gt(F a, F b) { return _mm_cmpgt_ps(a, b); }
    static M le(F a, F b) { return _mm_cmple_ps(a, b); }
    static M either(M a, M b) { return _mm_or_ps(a, b); }
    static M none() { return _mm_setzero_ps(); }
    static F select(M m, F a, F b) { return _mm_or_ps(_mm_and_ps(m, a), _mm_andnot_ps(m, b)); }
    static bool any(M m) { return _mm_movemask_ps(m) != 0; }
};
/// Four lanes: the groups of leavesNear are nodes of width 4.
using Four = Sse;
#else
using Four = Scalar;
#endif

#if defined(__AVX2__) || defined(VDS_BVH_AVX2)
struct Avx {
    static constexpr int lanes = 8;
    using F = __m256;
    using M = __m256;
    static F loadLanes(const float* p) { return _mm256_load_ps(p); }
    static void store(float* p, F a) { _mm256_storeu_ps(p, a); }
    static F set(float a) { return _mm256_set1_ps(a); }
    static F add(F a, F b) { return _mm256_add_ps(a, b); }
    static F sub(F a, F b) { return _mm256_sub_ps(a, b); }
    static F mul(F a, F b) { return _mm256_mul_ps(a, b); }
    static F max(F a, F b) { return _mm256_max_ps(a, b); }
    static F min(F a, F b) { return _mm256_min_ps(a, b); }
    static F abs(F a) { return _mm256_andnot_ps(_mm256_set1_ps(-0.0f), a); }
    static F neg(F a) { return _mm256_xor_ps(a, _mm256_set1_ps(-0.0f)); }
    static M gt(F a, F b) { return _mm256_cmp_ps(a, b, _CMP_GT_OQ); }
    static M le(F a, F b) { return _mm256_cmp_ps(a, b, _CMP_LE_OQ); }
    static M either(M a, M b) { return _mm256_or_ps(a, b); }
    static M none() { return _mm256_setzero_ps(); }
    static F select(M m, F a, F b) { return _mm256_blendv_ps(b, a, m); }
    static bool any(M m) { return _mm256_movemask_ps(m) != 0; }
};
#endif

#if defined(__AVX512F__) || defined(VDS_BVH_AVX512)
struct Avx512 {
    static constexpr int lanes = 16;
    using F = __m512;
    using M = __mmask16;
    static F loadLanes(const float* p) { return _mm512_load_ps(p); }
    static void store(float* p, F a) { _mm512_storeu_ps(p, a); }
    static F set(float a) { return _mm512_set1_ps(a); }
    static F add(F a, F b) { return _mm512_add_ps(a, b); }
    static F sub(F a, F b) { return _mm512_sub_ps(a, b); }
    static F mul(F a, F b) { return _mm512_mul_ps(a, b); }
    // The zero-masked forms: GCC 12's plain ones read an undefined vector
    // that -Wmaybe-uninitialized reports.
    static F max(F a, F b) { return _mm512_maskz_max_ps(0xffff, a, b); }
    static F min(F a, F b) { return _mm512_maskz_min_ps(0xffff, a, b); }
    static F abs(F a) { return _mm512_abs_ps(a); }
    static F neg(F a) {
        return _mm512_castsi512_ps(_mm512_xor_si512(_mm512_castps_si512(a), _mm512_set1_epi32(INT32_MIN)));
    }
    static M gt(F a, F b) { return _mm512_cmp_ps_mask(a, b, _CMP_GT_OQ); }
    static M le(F a, F b) { return _mm512_cmp_ps_mask(a, b, _CMP_LE_OQ); }
    static M either(M a, M b) { return M(a | b); }
    static M none() { return 0; }
    static F select(M m, F a, F b) { return _mm512_mask_blend_ps(m, b, a); }
    static bool any(M m) { return m != 0; }
};
#endif

/// Lower bounds of the squared distances from p to the `width` children of
/// `node` (NodeLanes) into d2: the larger of the box's and the slab's, the
/// slab's less `slack` (its float rounding); infinity for an empty slot.
template <class V, int width>
inline void boxDistances(const float* node, const glm::vec3& p, float slack, float* d2) {
    using F = typename V::F;
    const F zero = V::set(0.0f), s = V::set(slack);
    const F q[3] = {V::set(p.x), V::set(p.y), V::set(p.z)};
    for (int c = 0; c < width; c += V::lanes) {
        const float* at = node + c;
        F sum = zero, along = zero;
        for (int a = 0; a < 3; ++a) {
            const F below = V::sub(V::loadLanes(at + (NodeLanes::lo + a) * width), q[a]);
            const F above = V::sub(q[a], V::loadLanes(at + (NodeLanes::hi + a) * width));
            const F d = V::max(V::max(below, above), zero);
            sum = V::add(sum, V::mul(d, d));
            along = V::add(along, V::mul(V::loadLanes(at + (NodeLanes::axis + a) * width), q[a]));
        }
        const F off = V::max(V::sub(V::loadLanes(at + NodeLanes::slabLo * width), along),
                             V::sub(along, V::loadLanes(at + NodeLanes::slabHi * width)));
        const F out = V::max(V::sub(off, s), zero);
        V::store(d2 + c, V::max(sum, V::mul(out, out)));
    }
}

/// n . p - w of the plane at `plane` (x, y, z, w, each `width` lanes).
template <class V, int width>
inline typename V::F planeDistance(const float* plane, const typename V::F* q) {
    return V::sub(V::add(V::add(V::mul(V::loadLanes(plane), q[0]), V::mul(V::loadLanes(plane + width), q[1])),
                         V::mul(V::loadLanes(plane + 2 * width), q[2])),
                  V::loadLanes(plane + 3 * width));
}

/// Lower bounds of the squared distances from p to the `width` triangles of
/// a block (its planes and extents) into out (PlaneLanes): each plane
/// distance is within `slack` of the exact one, so each term is taken less
/// `slack`, and an edge counts wherever its e may be > 0 (e > -slack), the
/// triangle is certainly outside only where some e > slack.
template <class V, int width>
inline void lowerBounds(const float* planes, const float* extents, const glm::vec3& p, float slack, float bound,
                        float* out) {
    using F = typename V::F;
    const F q[3] = {V::set(p.x), V::set(p.y), V::set(p.z)};
    const F s = V::set(slack), zero = V::set(0.0f), inf = V::set(kSearchInf), reach = V::set(bound);
    for (int c = 0; c < width; c += V::lanes) {
        const float* plane = planes + c;
        const F h = V::max(V::sub(V::abs(planeDistance<V, width>(plane + PlaneLanes::face * width, q)), s), zero);
        F e[3], farthest = zero;
        for (int i = 0; i < 3; ++i) {
            e[i] = planeDistance<V, width>(plane + (PlaneLanes::edge + 4 * i) * width, q);
            farthest = V::max(farthest, V::sub(e[i], s));
        }
        // The planes alone first (h^2 + the largest e^2): where they leave no
        // lane within `bound`, the lanes end here.
        const F h2 = V::mul(h, h);
        const F alone = V::add(h2, V::mul(farthest, farthest));
        if (!V::any(V::le(alone, reach))) {
            V::store(out + c, alone);
            continue;
        }
        const float* extent = extents + c;
        F inPlane = inf;
        typename V::M outside = V::none();
        for (int i = 0; i < 3; ++i) {
            const F t = planeDistance<V, width>(extent + (ExtentLanes::along + 4 * i) * width, q);
            const F g = V::max(V::neg(t), V::sub(t, V::loadLanes(extent + (ExtentLanes::length + i) * width)));
            const F es = V::max(V::sub(e[i], s), zero), gs = V::max(V::sub(g, s), zero);
            const F term = V::add(V::mul(es, es), V::mul(gs, gs));
            inPlane = V::min(inPlane, V::select(V::gt(e[i], V::neg(s)), term, inf));
            outside = V::either(outside, V::gt(e[i], s));
        }
        V::store(out + c, V::max(alone, V::add(h2, V::select(outside, inPlane, zero))));
    }
}

inline void prefetchLines(const void* at, std::size_t bytes) {
#if defined(__SSE2__)
    for (std::size_t line = 0; line < bytes; line += 64) _mm_prefetch(static_cast<const char*>(at) + line, _MM_HINT_T0);
#else
    (void)at;
    (void)bytes;
#endif
}

/// The search over nodes and blocks of `width` lanes (the hierarchy's) in
/// steps of V::lanes.
template <class V, int width>
struct Search {
    /// The leaf's triangles' lower bounds first, then the exact test of each
    /// whose bound is still within `bound`, the lowest bound first: the bound
    /// is the distance itself (less the slack) where the closest point is on
    /// a face or an edge, so few triangles of a leaf get the exact test.
    static void leaf(const Bvh& bvh, const glm::vec3& p, float margin, std::int32_t reference, NearestState& state,
                     float& bound) {
        const std::uint32_t code = std::uint32_t(~reference);
        const std::uint32_t block = code >> kLeafBits, count = (code & ((1u << kLeafBits) - 1)) + 1;
        const std::uint32_t first = std::uint32_t(width) * block, blocks = (count + std::uint32_t(width) - 1) / width;
        // The extents and corners, read after the planes if at all, asked
        // for now: their latency overlaps the planes'.
        for (std::uint32_t b = 0; b < blocks; ++b)
            prefetchLines(bvh.extents(block + b), sizeof(float) * ExtentLanes::size * std::size_t(width));
        alignas(64) float below[2 * kMaxBvhWidth];
        for (std::uint32_t b = 0; b < blocks; ++b)
            lowerBounds<V, width>(bvh.planes(block + b), bvh.extents(block + b), p, margin, bound, below + width * b);
        for (std::uint32_t tested = 0; tested < count; ++tested) {
            std::uint32_t next = 0;
            for (std::uint32_t i = 1; i < count; ++i)
                if (below[i] < below[next]) next = i;
            if (below[next] > bound) return;
            below[next] = kSearchInf;
            const double t2 = bvh.slotDistance2(p, first + next);
            if (t2 < state.distance2) {
                state.distance2 = t2;
                state.slot = first + next;
                bound = pruneBound(t2);
            }
        }
    }

    static void nearest(const Bvh& bvh, const glm::vec3& p, NearestState& state) {
        struct Entry {
            float distance2;
            std::int32_t node;
        };
        Entry stack[kStackEntries];
        int top = 0;
        stack[top++] = {0.0f, 0};
        float bound = pruneBound(state.distance2);
        const float margin = bvh.slack(p);
        while (top > 0) {
            const Entry e = stack[--top];
            if (e.distance2 > bound) continue;
            const float* node = bvh.node(std::size_t(e.node));
            alignas(64) float d2[width];
            boxDistances<V, width>(node, p, margin, d2);
            std::int32_t child[width];
            int order[width], n = 0;
            for (int k = 0; k < width; ++k) {
                child[k] = childOf(node, width, k);
                if (child[k] == kEmptyChild || d2[k] > bound) continue;
                int at = n++; // insertion by distance, nearest first
                while (at > 0 && d2[order[at - 1]] > d2[k]) {
                    order[at] = order[at - 1];
                    --at;
                }
                order[at] = k;
            }
            // Leaves now, nearest first, so the bound tightens before the
            // inner children are pushed (farthest first: the nearest is
            // popped next).
            // Their planes asked for first, so the misses of all overlap.
            for (int i = 0; i < n; ++i)
                if (child[order[i]] < 0)
                    prefetchLines(bvh.planes(std::uint32_t(~child[order[i]]) >> kLeafBits),
                                  sizeof(float) * PlaneLanes::size * std::size_t(width));
            for (int i = 0; i < n; ++i)
                if (child[order[i]] < 0 && d2[order[i]] <= bound) leaf(bvh, p, margin, child[order[i]], state, bound);
            for (int i = n - 1; i >= 0; --i)
                if (child[order[i]] >= 0 && d2[order[i]] <= bound) {
                    stack[top++] = {d2[order[i]], child[order[i]]};
                    prefetchLines(bvh.node(std::size_t(child[order[i]])), sizeof(float) * NodeLanes::size * std::size_t(width));
                }
        }
    }

    static void nearestAmong(const Bvh& bvh, const glm::vec3& p, const std::vector<BvhNode>& leaves,
                             NearestState& state) {
        float bound = pruneBound(state.distance2);
        const float margin = bvh.slack(p);
        for (const BvhNode& group : leaves) {
            alignas(64) float d2[4];
            boxDistances<Four, 4>(group.lanes, p, margin, d2);
            for (int k = 0; k < 4; ++k) {
                const std::int32_t reference = childOf(group.lanes, 4, k);
                if (d2[k] <= bound && reference != kEmptyChild) leaf(bvh, p, margin, reference, state, bound);
            }
        }
    }

    static BvhSearch table() { return {&nearest, &nearestAmong}; }
    static_assert(width % V::lanes == 0, "whole SIMD steps a node");
};

} // namespace
} // namespace vds::detail
