// vds: the distance hierarchy's build and nearest-triangle search (bvh.h).
#include <vds/detail/bvh.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <vds/detail/triangle_distance.h>

namespace vds::detail {

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr int kBins = 16;
/// Below this depth of the binary tree the surface-area heuristic decides;
/// past it, median splits, so the depth (and the search's stack) stays
/// bounded by kSahDepth + log2(triangles) whatever the input.
constexpr int kSahDepth = 48;
/// The search's stack: three entries a level at most over
/// kSahDepth + 32 levels.
constexpr int kStackEntries = 3 * (kSahDepth + 32) + 4;
/// A box is pruned when its float squared distance exceeds the best squared
/// distance by this relative margin: above the few float roundings of a box
/// distance (4 * 2^-24) and of the bound itself (2^-24).
constexpr double kPruneMargin = 1.0 + 1.0 / (1 << 20);
/// A float plane distance n . p - w (a triangle's face, edge or edge
/// direction plane, TriangleBlock) is within kPlaneError (|p|_1 + 2 max |v|_1) of
/// the exact signed distance to the plane: the unit normal's rounding to
/// float (sqrt(3) 2^-24 relative), the offset's (2^-24) and four float
/// roundings of the dot product (4 2^-24), with a factor of 2 to spare.
constexpr float kPlaneError = 1e-6f;
/// A triangle gets planes only where |ab x ac| >= kMinSine |ab| |ac|: then
/// the double cross product of its float corners' differences (off by
/// about 2^-52 |ab| |ac| at worst) gives its normal, and so its edges'
/// normals, to 2^-32 relative, far inside kPlaneError's spare.
constexpr double kMinSine = 1.0 / (1 << 20);

struct Aabb {
    glm::vec3 lo{kInf}, hi{-kInf};
    void grow(const glm::vec3& p) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    void grow(const Aabb& b) {
        lo = glm::min(lo, b.lo);
        hi = glm::max(hi, b.hi);
    }
    float area() const {
        const glm::vec3 e = glm::max(hi - lo, glm::vec3(0.0f));
        return e.x * e.y + e.y * e.z + e.z * e.x;
    }
};

struct Prim {
    Aabb box;
    glm::vec3 centroid;
    std::uint32_t index;
};

struct BuildNode {
    Aabb box;
    std::uint32_t left = 0, right = 0; ///< children (inner)
    std::uint32_t first = 0, count = 0; ///< prims (leaf: count > 0)
    std::uint32_t begin = 0, end = 0; ///< the prims below it, leaf or inner
    bool leaf() const { return count > 0; }
};

/// The binned SAH split of prims [first, first + count): the prims of the
/// left side first, and their count (0: no split worth a node found).
class BinaryBuilder {
public:
    explicit BinaryBuilder(std::vector<Prim>& prims) : prims_(prims) {}

    std::uint32_t build(std::uint32_t first, std::uint32_t count, int depth) {
        const std::uint32_t self = std::uint32_t(nodes.size());
        nodes.emplace_back();
        Aabb box, centroids;
        for (std::uint32_t k = first; k < first + count; ++k) {
            box.grow(prims_[k].box);
            centroids.grow(prims_[k].centroid);
        }
        nodes[self].box = box;
        nodes[self].begin = first;
        nodes[self].end = first + count;
        if (count <= kLeafTriangles) {
            nodes[self].first = first;
            nodes[self].count = count;
            return self;
        }
        std::uint32_t leftCount = depth < kSahDepth ? sahSplit(first, count, centroids) : 0;
        if (leftCount == 0 || leftCount == count) leftCount = medianSplit(first, count, centroids);
        const std::uint32_t left = build(first, leftCount, depth + 1);
        const std::uint32_t right = build(first + leftCount, count - leftCount, depth + 1);
        nodes[self].left = left;
        nodes[self].right = right;
        return self;
    }

    std::vector<BuildNode> nodes;

private:
    static int binOf(float c, float lo, float scale) {
        return std::min(kBins - 1, std::max(0, int((c - lo) * scale)));
    }

    std::uint32_t sahSplit(std::uint32_t first, std::uint32_t count, const Aabb& centroids) {
        float bestCost = std::numeric_limits<float>::infinity();
        int bestAxis = -1, bestBin = 0;
        for (int a = 0; a < 3; ++a) {
            const float extent = centroids.hi[a] - centroids.lo[a];
            if (!(extent > 0.0f)) continue;
            const float scale = float(kBins) / extent;
            Aabb bins[kBins];
            std::uint32_t counts[kBins] = {};
            for (std::uint32_t k = first; k < first + count; ++k) {
                const int b = binOf(prims_[k].centroid[a], centroids.lo[a], scale);
                bins[b].grow(prims_[k].box);
                ++counts[b];
            }
            float rightCost[kBins];
            Aabb right;
            std::uint32_t rightCount = 0;
            for (int b = kBins - 1; b > 0; --b) {
                right.grow(bins[b]);
                rightCount += counts[b];
                rightCost[b] = right.area() * float(rightCount);
            }
            Aabb left;
            std::uint32_t leftCount = 0;
            for (int b = 0; b < kBins - 1; ++b) {
                left.grow(bins[b]);
                leftCount += counts[b];
                const float cost = left.area() * float(leftCount) + rightCost[b + 1];
                if (leftCount > 0 && leftCount < count && cost < bestCost) {
                    bestCost = cost;
                    bestAxis = a;
                    bestBin = b;
                }
            }
        }
        if (bestAxis < 0) return 0;
        const float lo = centroids.lo[bestAxis];
        const float scale = float(kBins) / (centroids.hi[bestAxis] - lo);
        const auto mid = std::partition(prims_.begin() + first, prims_.begin() + first + count, [&](const Prim& p) {
            return binOf(p.centroid[bestAxis], lo, scale) <= bestBin;
        });
        return std::uint32_t(mid - (prims_.begin() + first));
    }

    /// Half the prims by centroid along the longest extent (by index when
    /// every centroid is the same point).
    std::uint32_t medianSplit(std::uint32_t first, std::uint32_t count, const Aabb& centroids) {
        const glm::vec3 e = centroids.hi - centroids.lo;
        const int a = e.x >= e.y && e.x >= e.z ? 0 : (e.y >= e.z ? 1 : 2);
        const std::uint32_t half = count / 2;
        std::nth_element(prims_.begin() + first, prims_.begin() + first + half, prims_.begin() + first + count,
                         [a](const Prim& l, const Prim& r) { return l.centroid[a] < r.centroid[a]; });
        return half;
    }

    std::vector<Prim>& prims_;
};

std::int32_t leafReference(std::uint32_t block, std::uint32_t count) {
    return ~std::int32_t(block << kLeafBits | (count - 1));
}

/// The four-wide tree of a binary one, depth first.
class Collapser {
public:
    Collapser(const std::vector<BuildNode>& binary, std::vector<BvhNode>& nodes, const std::vector<std::uint32_t>& slotOf)
        : binary_(binary), nodes_(nodes), slotOf_(slotOf) {}

    std::uint32_t emit(std::uint32_t b) {
        const std::uint32_t self = std::uint32_t(nodes_.size());
        nodes_.emplace_back();
        std::uint32_t kids[4];
        int n = 0;
        if (binary_[b].leaf()) {
            kids[n++] = b;
        } else {
            kids[n++] = binary_[b].left;
            kids[n++] = binary_[b].right;
        }
        while (n < 4) { // open the inner child with the largest surface
            int widest = -1;
            for (int k = 0; k < n; ++k)
                if (!binary_[kids[k]].leaf() &&
                    (widest < 0 || binary_[kids[k]].box.area() > binary_[kids[widest]].box.area()))
                    widest = k;
            if (widest < 0) break;
            const BuildNode& open = binary_[kids[widest]];
            kids[widest] = open.left;
            kids[n++] = open.right;
        }
        for (int k = 0; k < 4; ++k) {
            const bool used = k < n;
            const Aabb box = used ? binary_[kids[k]].box : Aabb{};
            for (int a = 0; a < 3; ++a) {
                nodes_[self].lo[a][k] = box.lo[a];
                nodes_[self].hi[a][k] = box.hi[a];
            }
            for (int a = 0; a < 3; ++a) nodes_[self].axis[a][k] = 0.0f;
            nodes_[self].slabLo[k] = nodes_[self].slabHi[k] = 0.0f;
            if (used) slabs.push_back({self, std::uint32_t(k), binary_[kids[k]].begin, binary_[kids[k]].end});
            std::int32_t reference = kEmptyChild;
            if (used && binary_[kids[k]].leaf())
                reference = leafReference(slotOf_[binary_[kids[k]].first] / 4, binary_[kids[k]].count);
            else if (used) reference = std::int32_t(emit(kids[k]));
            nodes_[self].child[k] = reference;
        }
        return self;
    }

    std::vector<SlabJob> slabs;

private:
    const std::vector<BuildNode>& binary_;
    std::vector<BvhNode>& nodes_;
    const std::vector<std::uint32_t>& slotOf_; ///< of each triangle in the build's order
};

/// Lower bounds of the squared distances from p to the four children of
/// `node`: the larger of the box's and the slab's, the slab's less `slack`
/// (its float rounding); infinity for an empty slot.
inline void boxDistances(const BvhNode& node, const glm::vec3& p, float slack, float d2[4]) {
#if defined(__SSE2__)
    const __m128 zero = _mm_setzero_ps();
    __m128 sum = zero, along = zero;
    for (int a = 0; a < 3; ++a) {
        const __m128 q = _mm_set1_ps(p[a]);
        const __m128 below = _mm_sub_ps(_mm_load_ps(node.lo[a]), q);
        const __m128 above = _mm_sub_ps(q, _mm_load_ps(node.hi[a]));
        const __m128 d = _mm_max_ps(_mm_max_ps(below, above), zero);
        sum = _mm_add_ps(sum, _mm_mul_ps(d, d));
        along = _mm_add_ps(along, _mm_mul_ps(_mm_load_ps(node.axis[a]), q));
    }
    const __m128 off = _mm_max_ps(_mm_sub_ps(_mm_load_ps(node.slabLo), along),
                                  _mm_sub_ps(along, _mm_load_ps(node.slabHi)));
    const __m128 s = _mm_max_ps(_mm_sub_ps(off, _mm_set1_ps(slack)), zero);
    _mm_storeu_ps(d2, _mm_max_ps(sum, _mm_mul_ps(s, s)));
#else
    for (int k = 0; k < 4; ++k) {
        float sum = 0.0f, along = 0.0f;
        for (int a = 0; a < 3; ++a) {
            const float d = std::max(std::max(node.lo[a][k] - p[a], p[a] - node.hi[a][k]), 0.0f);
            sum += d * d;
            along += node.axis[a][k] * p[a];
        }
        const float s = std::max(std::max(node.slabLo[k] - along, along - node.slabHi[k]) - slack, 0.0f);
        d2[k] = std::max(sum, s * s);
    }
#endif
}

float pruneBound(double distance2) { return float(distance2 * kPruneMargin); }

void setPlane(Plane4& plane, int lane, const glm::dvec3& unit, const glm::dvec3& on) {
    const glm::vec3 rounded(unit);
    plane.x[lane] = rounded.x;
    plane.y[lane] = rounded.y;
    plane.z[lane] = rounded.z;
    plane.w[lane] = float(glm::dot(glm::dvec3(rounded), on));
}

/// Lane `lane` of `block` and `extents`: the planes of triangle abc and its
/// edges' extents (TriangleBlock), zero where it is too thin.
void setLane(TriangleBlock& block, ExtentBlock& extents, int lane, const glm::vec3& a, const glm::vec3& b,
             const glm::vec3& c) {
    const glm::dvec3 v[3] = {glm::dvec3(a), glm::dvec3(b), glm::dvec3(c)};
    const glm::dvec3 n = glm::cross(v[1] - v[0], v[2] - v[0]);
    const double length = glm::length(n);
    if (!(length >= kMinSine * glm::length(v[1] - v[0]) * glm::length(v[2] - v[0])) || !(length > 0.0)) return;
    const glm::dvec3 unit = n / length;
    setPlane(block.face, lane, unit, v[0]);
    for (int e = 0; e < 3; ++e) { // outward: (b - a) x n points away from c
        const glm::dvec3 edge = v[(e + 1) % 3] - v[e];
        const glm::dvec3 outward = glm::cross(edge, unit);
        setPlane(block.edge[e], lane, outward / glm::length(outward), v[e]);
        setPlane(extents.along[e], lane, edge / glm::length(edge), v[e]);
        // The far corner's position along the rounded direction, rounded up:
        // a longer edge only lowers the bound.
        const glm::dvec3 u(extents.along[e].x[lane], extents.along[e].y[lane], extents.along[e].z[lane]);
        extents.length[e][lane] = std::nextafter(float(glm::dot(u, edge)), kInf);
    }
}

/// An empty block: every lane's bound infinity until set.
TriangleBlock emptyBlock() {
    TriangleBlock block{};
    for (float& w : block.face.w) w = -kInf;
    return block;
}

#if defined(__SSE2__)
inline __m128 planeDistance(const Plane4& q, __m128 x, __m128 y, __m128 z) {
    return _mm_sub_ps(_mm_add_ps(_mm_add_ps(_mm_mul_ps(_mm_load_ps(q.x), x), _mm_mul_ps(_mm_load_ps(q.y), y)),
                                 _mm_mul_ps(_mm_load_ps(q.z), z)),
                      _mm_load_ps(q.w));
}
#endif

/// Lower bounds of the squared distances from p to the four triangles of
/// `block` into out[0..3] (TriangleBlock): each plane distance is within
/// `slack` of the exact one, so each term is taken less `slack`, and an
/// edge counts wherever its e may be > 0 (e > -slack), the triangle is
/// certainly outside only where some e > slack.
inline void lowerBounds(const TriangleBlock& block, const ExtentBlock& extents, const glm::vec3& p, float slack,
                        float bound, float* out) {
#if defined(__SSE2__)
    const __m128 x = _mm_set1_ps(p.x), y = _mm_set1_ps(p.y), z = _mm_set1_ps(p.z), s = _mm_set1_ps(slack);
    const __m128 zero = _mm_setzero_ps(), sign = _mm_set1_ps(-0.0f), inf = _mm_set1_ps(kInf);
    const __m128 h = _mm_max_ps(_mm_sub_ps(_mm_andnot_ps(sign, planeDistance(block.face, x, y, z)), s), zero);
    __m128 e[3], farthest = zero;
    for (int i = 0; i < 3; ++i) {
        e[i] = planeDistance(block.edge[i], x, y, z);
        farthest = _mm_max_ps(farthest, _mm_sub_ps(e[i], s));
    }
    // The planes alone first (h^2 + the largest e^2): where they leave no
    // lane within `bound`, the block ends here.
    const __m128 h2 = _mm_mul_ps(h, h);
    const __m128 planes = _mm_add_ps(h2, _mm_mul_ps(farthest, farthest));
    if (_mm_movemask_ps(_mm_cmple_ps(planes, _mm_set1_ps(bound))) == 0) {
        _mm_storeu_ps(out, planes);
        return;
    }
    __m128 inPlane = inf, outside = zero;
    for (int i = 0; i < 3; ++i) {
        const __m128 t = planeDistance(extents.along[i], x, y, z);
        const __m128 g = _mm_max_ps(_mm_xor_ps(t, sign), _mm_sub_ps(t, _mm_load_ps(extents.length[i])));
        const __m128 es = _mm_max_ps(_mm_sub_ps(e[i], s), zero), gs = _mm_max_ps(_mm_sub_ps(g, s), zero);
        const __m128 term = _mm_add_ps(_mm_mul_ps(es, es), _mm_mul_ps(gs, gs));
        const __m128 counts = _mm_cmpgt_ps(e[i], _mm_xor_ps(s, sign));
        inPlane = _mm_min_ps(inPlane, _mm_or_ps(_mm_and_ps(counts, term), _mm_andnot_ps(counts, inf)));
        outside = _mm_or_ps(outside, _mm_cmpgt_ps(e[i], s));
    }
    _mm_storeu_ps(out, _mm_max_ps(planes, _mm_add_ps(h2, _mm_and_ps(outside, inPlane))));
#else
    (void)bound;
    for (int k = 0; k < 4; ++k) {
        const auto distance = [&](const Plane4& q) { return q.x[k] * p.x + q.y[k] * p.y + q.z[k] * p.z - q.w[k]; };
        const float h = std::max(std::abs(distance(block.face)) - slack, 0.0f);
        float inPlane = kInf;
        bool outside = false;
        for (int i = 0; i < 3; ++i) {
            const float e = distance(block.edge[i]), t = distance(extents.along[i]);
            const float es = std::max(e - slack, 0.0f);
            const float gs = std::max(std::max(-t, t - extents.length[i][k]) - slack, 0.0f);
            if (e > -slack) inPlane = std::min(inPlane, es * es + gs * gs);
            outside = outside || e > slack;
        }
        out[k] = h * h + (outside ? inPlane : 0.0f);
    }
#endif
}

} // namespace

Bvh::Bvh(MeshView mesh) {
    std::vector<Prim> prims;
    prims.reserve(mesh.triangleCount);
    for (std::size_t t = 0; t < mesh.triangleCount; ++t) {
        const glm::uvec3 v = mesh.triangles[t];
        Prim prim;
        for (int c = 0; c < 3; ++c) prim.box.grow(mesh.positions[v[c]]);
        prim.centroid = (prim.box.lo + prim.box.hi) * 0.5f;
        prim.index = std::uint32_t(t);
        prims.push_back(prim);
    }
    BinaryBuilder builder(prims);
    builder.build(0, std::uint32_t(prims.size()), 0);
    // Each leaf's triangles from a multiple of 4: its lanes fill whole blocks.
    std::vector<std::uint32_t> slotOf(prims.size());
    std::uint32_t slots = 0;
    for (const BuildNode& b : builder.nodes) // leaves in the build's order: depth first, left first
        if (b.leaf()) {
            slots = (slots + 3u) & ~3u;
            for (std::uint32_t k = 0; k < b.count; ++k) slotOf[b.first + k] = slots++;
        }
    slots = (slots + 3u) & ~3u;
    nodes_.reserve(builder.nodes.size() / 2 + 1);
    Collapser collapser(builder.nodes, nodes_, slotOf);
    collapser.emit(0);
    triangleCount_ = prims.size();
    indices_.assign(slots, kNoTriangle);
    blocks_.assign(slots / 4, emptyBlock());
    extents_.assign(slots / 4, ExtentBlock{});
    for (std::size_t k = 0; k < prims.size(); ++k) {
        const glm::uvec3 v = mesh.triangles[prims[k].index];
        const glm::vec3 corners[3] = {mesh.positions[v.x], mesh.positions[v.y], mesh.positions[v.z]};
        const std::uint32_t slot = slotOf[k];
        const int lane = int(slot % 4);
        indices_[slot] = prims[k].index;
        blocks_[slot / 4].face.w[lane] = 0.0f;
        setLane(blocks_[slot / 4], extents_[slot / 4], lane, corners[0], corners[1], corners[2]);
        for (int c = 0; c < 3; ++c) {
            for (int a = 0; a < 3; ++a) extents_[slot / 4].corner[c][a][lane] = corners[c][a];
            verticesL1_ = std::max(verticesL1_, std::abs(corners[c].x) + std::abs(corners[c].y) + std::abs(corners[c].z));
        }
    }
    fillSlabs(collapser.slabs, slotOf);
}

/// Each child's slab: its triangles' area-weighted mean normal, shrunk so
/// that its float length stays below 1 (a longer one would overstate the
/// bound), and the range of n . x over their corners in double, rounded
/// outward to float. A child whose normals cancel keeps the zero slab,
/// which bounds nothing.
void Bvh::fillSlabs(const std::vector<SlabJob>& jobs, const std::vector<std::uint32_t>& slotOf) {
    for (const SlabJob& job : jobs) {
        glm::dvec3 sum(0.0);
        for (std::uint32_t k = job.begin; k < job.end; ++k) {
            const glm::dvec3 a = corner(slotOf[k], 0);
            sum += glm::cross(corner(slotOf[k], 1) - a, corner(slotOf[k], 2) - a);
        }
        const double length = glm::length(sum);
        if (!(length > 0.0)) continue;
        const glm::vec3 n(sum * ((1.0 - 1e-6) / length));
        double lo = std::numeric_limits<double>::infinity(), hi = -lo;
        for (std::uint32_t k = job.begin; k < job.end; ++k)
            for (int c = 0; c < 3; ++c) {
                const double w = glm::dot(glm::dvec3(n), corner(slotOf[k], c));
                lo = std::min(lo, w);
                hi = std::max(hi, w);
            }
        BvhNode& node = nodes_[job.node];
        for (int a = 0; a < 3; ++a) node.axis[a][job.slot] = n[a];
        // One more float step each way covers the double sum's rounding.
        node.slabLo[job.slot] = std::nextafter(float(lo), -kInf);
        node.slabHi[job.slot] = std::nextafter(float(hi), kInf);
        node.slabLo[job.slot] = std::nextafter(node.slabLo[job.slot], -kInf);
        node.slabHi[job.slot] = std::nextafter(node.slabHi[job.slot], kInf);
    }
}

float Bvh::slack(const glm::vec3& p) const {
    return kPlaneError * (std::abs(p.x) + std::abs(p.y) + std::abs(p.z) + 2.0f * verticesL1_);
}

double Bvh::distance2(const glm::vec3& p, std::uint32_t slot) const {
    const glm::dvec3 q(p);
    const glm::dvec3 d = q - closestOnTriangle(q, corner(slot, 0), corner(slot, 1), corner(slot, 2)).point;
    return d.x * d.x + d.y * d.y + d.z * d.z;
}

ClosestPoint Bvh::closest(const glm::vec3& p, std::uint32_t slot) const {
    const glm::dvec3 q(p);
    const TriangleHit hit = closestOnTriangle(q, corner(slot, 0), corner(slot, 1), corner(slot, 2));
    const glm::dvec3 d = q - hit.point;
    return {hit.point, std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z), indices_[slot], hit.feature, hit.index};
}

/// Asks for a pushed node's lines, which arrive while the nodes popped
/// before it are searched.
void Bvh::prefetch(std::int32_t node) const {
#if defined(__SSE2__)
    const char* at = reinterpret_cast<const char*>(&nodes_[std::size_t(node)]);
    for (std::size_t line = 0; line < sizeof(BvhNode); line += 64) _mm_prefetch(at + line, _MM_HINT_T0);
#else
    (void)node;
#endif
}

void Bvh::nearest(const glm::vec3& p, NearestState& state) const {
    struct Entry {
        float distance2;
        std::int32_t node;
    };
    Entry stack[kStackEntries];
    int top = 0;
    stack[top++] = {0.0f, 0};
    float bound = pruneBound(state.distance2);
    const float margin = slack(p);
    while (top > 0) {
        const Entry e = stack[--top];
        if (e.distance2 > bound) continue;
        const BvhNode& node = nodes_[std::size_t(e.node)];
        float d2[4];
        boxDistances(node, p, margin, d2);
        int order[4], n = 0;
        for (int k = 0; k < 4; ++k) {
            if (node.child[k] == kEmptyChild || d2[k] > bound) continue;
            int at = n++; // insertion by distance, nearest first
            while (at > 0 && d2[order[at - 1]] > d2[k]) {
                order[at] = order[at - 1];
                --at;
            }
            order[at] = k;
        }
        // Leaves now, nearest first, so the bound tightens before the inner
        // children are pushed (farthest first: the nearest is popped next).
        for (int i = 0; i < n; ++i) {
            const std::int32_t ref = node.child[order[i]];
            if (ref < 0 && d2[order[i]] <= bound) searchLeaf(p, margin, ref, state, bound);
        }
        for (int i = n - 1; i >= 0; --i) {
            const std::int32_t ref = node.child[order[i]];
            if (ref >= 0 && d2[order[i]] <= bound) {
                stack[top++] = {d2[order[i]], ref};
                prefetch(ref);
            }
        }
    }
}

/// The leaf's triangles' lower bounds first, then the exact test of each
/// whose bound is still within `bound`, the lowest bound first: the bound is
/// the distance itself (less the slack) where the closest point is on a face
/// or an edge, so few triangles of a leaf get the exact test.
void Bvh::searchLeaf(const glm::vec3& p, float margin, std::int32_t leaf, NearestState& state, float& bound) const {
    const std::uint32_t code = std::uint32_t(~leaf);
    const std::uint32_t block = code >> kLeafBits, first = 4 * block, count = (code & (kLeafTriangles - 1)) + 1;
    float below[(kLeafTriangles + 3) / 4 * 4];
#if defined(__SSE2__)
    // The extents and corners, read after the planes if at all, asked for
    // now: their latency overlaps the planes'.
    for (std::uint32_t b = 0; 4 * b < count; ++b) {
        const char* at = reinterpret_cast<const char*>(&extents_[block + b]);
        for (std::size_t line = 0; line < sizeof(ExtentBlock); line += 64) _mm_prefetch(at + line, _MM_HINT_T0);
    }
#endif
    for (std::uint32_t b = 0; 4 * b < count; ++b)
        lowerBounds(blocks_[block + b], extents_[block + b], p, margin, bound, below + 4 * b);
    for (std::uint32_t tested = 0; tested < count; ++tested) {
        std::uint32_t next = 0;
        for (std::uint32_t i = 1; i < count; ++i)
            if (below[i] < below[next]) next = i;
        if (below[next] > bound) return;
        below[next] = kInf;
        const double t2 = distance2(p, first + next);
        if (t2 < state.distance2) {
            state.distance2 = t2;
            state.slot = first + next;
            bound = pruneBound(t2);
        }
    }
}

bool Bvh::leavesNear(const glm::vec3& lo, const glm::vec3& hi, double reach2, std::vector<BvhNode>& out,
                     std::size_t maxGroups) const {
    const float bound = pruneBound(reach2);
    int slot = 4; // the next free slot of out.back()
    const auto keep = [&](const BvhNode& node, int k) {
        if (slot == 4) {
            out.emplace_back();
            BvhNode& fresh = out.back();
            for (int a = 0; a < 3; ++a)
                for (int s = 0; s < 4; ++s) {
                    fresh.lo[a][s] = kInf;
                    fresh.hi[a][s] = -kInf;
                    fresh.axis[a][s] = 0.0f;
                }
            std::fill(fresh.slabLo, fresh.slabLo + 4, 0.0f);
            std::fill(fresh.slabHi, fresh.slabHi + 4, 0.0f);
            std::fill(fresh.child, fresh.child + 4, kEmptyChild);
            slot = 0;
        }
        BvhNode& into = out.back();
        for (int a = 0; a < 3; ++a) {
            into.lo[a][slot] = node.lo[a][k];
            into.hi[a][slot] = node.hi[a][k];
            into.axis[a][slot] = node.axis[a][k];
        }
        into.slabLo[slot] = node.slabLo[k];
        into.slabHi[slot] = node.slabHi[k];
        into.child[slot++] = node.child[k];
    };
    std::int32_t stack[kStackEntries];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const BvhNode& node = nodes_[std::size_t(stack[--top])];
        for (int k = 0; k < 4; ++k) {
            if (node.child[k] == kEmptyChild) continue;
            float d2 = 0.0f; // box to box: the gap along each axis
            for (int a = 0; a < 3; ++a) {
                const float gap = std::max(std::max(node.lo[a][k] - hi[a], lo[a] - node.hi[a][k]), 0.0f);
                d2 += gap * gap;
            }
            if (d2 > bound) continue;
            if (node.child[k] >= 0) stack[top++] = node.child[k];
            else keep(node, k);
        }
        if (out.size() > maxGroups) return false;
    }
    return true;
}

void Bvh::nearestAmong(const glm::vec3& p, const std::vector<BvhNode>& leaves, NearestState& state) const {
    float bound = pruneBound(state.distance2);
    const float margin = slack(p);
    for (const BvhNode& group : leaves) {
        float d2[4];
        boxDistances(group, p, margin, d2);
        for (int k = 0; k < 4; ++k)
            if (d2[k] <= bound && group.child[k] != kEmptyChild) searchLeaf(p, margin, group.child[k], state, bound);
    }
}

} // namespace vds::detail
