// vds: the distance hierarchy's build and nearest-triangle search (bvh.h).
#include <vds/detail/bvh.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstddef>
#include <limits>

#include <glm/geometric.hpp>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <vds/detail/parallel.h>
#include <vds/detail/triangle_distance.h>

namespace vds::detail {

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr int kBins = 16;
/// Below this depth of the binary tree the surface-area heuristic decides;
/// past it, median splits, so the depth (and the search's stack) stays
/// bounded by kSahDepth + log2(triangles) whatever the input.
constexpr int kSahDepth = 48;
static_assert(kSahDepth + 32 == 80, "bvh_search.h sizes its stack for this depth");
/// The leavesNear walk's stack: W - 1 entries a level at most.
constexpr int kStackEntries = (kMaxBvhWidth - 1) * (kSahDepth + 32) + 4;
/// A float plane distance n . p - w (a triangle's face, edge or edge
/// direction plane, PlaneLanes) is within kPlaneError (|p|_1 + 2 max |v|_1) of
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

/// A box grown by prims in the build's inner loops: two SSE steps a prim.
/// It reads four floats from each corner (the fourth is the next member of
/// the prim, a lane never read back).
struct PrimBounds {
#if defined(__SSE2__)
    __m128 lo = _mm_set1_ps(kInf), hi = _mm_set1_ps(-kInf);
    void grow(const glm::vec3& l, const glm::vec3& h) {
        lo = _mm_min_ps(lo, _mm_loadu_ps(&l.x));
        hi = _mm_max_ps(hi, _mm_loadu_ps(&h.x));
    }
    Aabb box() const {
        float l[4], h[4];
        _mm_storeu_ps(l, lo);
        _mm_storeu_ps(h, hi);
        Aabb b;
        b.lo = {l[0], l[1], l[2]};
        b.hi = {h[0], h[1], h[2]};
        return b;
    }
#else
    Aabb b;
    void grow(const glm::vec3& l, const glm::vec3& h) {
        b.grow(l);
        b.grow(h);
    }
    Aabb box() const { return b; }
#endif
};
static_assert(offsetof(Prim, centroid) == sizeof(Aabb) && sizeof(Prim) >= sizeof(Aabb) + 16,
              "PrimBounds reads a fourth float past each corner and the centroid, inside the prim");

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
    /// Leaves of at most `leafTriangles` (<= kMaxBvhWidth); subtrees of at
    /// most `taskPrims` prims left to `tasks` (0: none), to be built apart.
    BinaryBuilder(std::vector<Prim>& prims, std::uint32_t leafTriangles, std::uint32_t taskPrims = 0)
        : prims_(prims), leafTriangles_(leafTriangles), taskPrims_(taskPrims) {}

    /// A subtree left for later: its root's node here, prims and depth.
    struct Task {
        std::uint32_t node, first, count;
        int depth;
    };

    std::uint32_t build(std::uint32_t first, std::uint32_t count, int depth) {
        const std::uint32_t self = std::uint32_t(nodes.size());
        nodes.emplace_back();
        if (count <= taskPrims_ && count > leafTriangles_) {
            tasks.push_back({self, first, count, depth});
            return self;
        }
        PrimBounds boxes, centres;
        for (std::uint32_t k = first; k < first + count; ++k) {
            boxes.grow(prims_[k].box.lo, prims_[k].box.hi);
            centres.grow(prims_[k].centroid, prims_[k].centroid);
        }
        const Aabb box = boxes.box(), centroids = centres.box();
        nodes[self].box = box;
        nodes[self].begin = first;
        nodes[self].end = first + count;
        if (count <= leafTriangles_) {
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
    std::vector<Task> tasks;

private:
    static int binOf(float c, float lo, float scale) {
        return std::min(kBins - 1, std::max(0, int((c - lo) * scale)));
    }

    std::uint32_t sahSplit(std::uint32_t first, std::uint32_t count, const Aabb& centroids) {
        // The three axes' bins in one pass over the prims.
        PrimBounds bins[3][kBins];
        std::uint32_t counts[3][kBins] = {};
        float scale[3];
        for (int a = 0; a < 3; ++a) {
            const float extent = centroids.hi[a] - centroids.lo[a];
            scale[a] = extent > 0.0f ? float(kBins) / extent : 0.0f;
        }
        for (std::uint32_t k = first; k < first + count; ++k)
            for (int a = 0; a < 3; ++a) {
                const int b = binOf(prims_[k].centroid[a], centroids.lo[a], scale[a]);
                bins[a][b].grow(prims_[k].box.lo, prims_[k].box.hi);
                ++counts[a][b];
            }
        float bestCost = std::numeric_limits<float>::infinity();
        int bestAxis = -1, bestBin = 0;
        for (int a = 0; a < 3; ++a) {
            if (!(scale[a] > 0.0f)) continue;
            float rightCost[kBins];
            Aabb right;
            std::uint32_t rightCount = 0;
            for (int b = kBins - 1; b > 0; --b) {
                right.grow(bins[a][b].box());
                rightCount += counts[a][b];
                rightCost[b] = right.area() * float(rightCount);
            }
            Aabb left;
            std::uint32_t leftCount = 0;
            for (int b = 0; b < kBins - 1; ++b) {
                left.grow(bins[a][b].box());
                leftCount += counts[a][b];
                const float cost = left.area() * float(leftCount) + rightCost[b + 1];
                if (leftCount > 0 && leftCount < count && cost < bestCost) {
                    bestCost = cost;
                    bestAxis = a;
                    bestBin = b;
                }
            }
        }
        if (bestAxis < 0) return 0;
        const float lo = centroids.lo[bestAxis], by = scale[bestAxis];
        const auto mid = std::partition(prims_.begin() + first, prims_.begin() + first + count, [&](const Prim& p) {
            return binOf(p.centroid[bestAxis], lo, by) <= bestBin;
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
    std::uint32_t leafTriangles_;
    std::uint32_t taskPrims_;
};

/// Prims a subtree built on a thread of its own holds at most: enough tasks
/// to share among `threads`, each worth a thread's start.
std::uint32_t taskPrims(std::size_t prims, unsigned threads) {
    if (threads == 0) threads = ThreadPool::hardwareThreads();
    if (threads <= 1) return 0;
    return std::uint32_t(std::max<std::size_t>(4096, prims / (8 * std::size_t(threads))));
}

/// The binary tree over `prims`, depth first from the root (node 0): the
/// top levels on this thread, the subtrees below them on `threads`, each
/// into nodes of its own, appended after (their prims are disjoint ranges).
std::vector<BuildNode> buildBinary(std::vector<Prim>& prims, std::uint32_t leafTriangles, unsigned threads) {
    BinaryBuilder top(prims, leafTriangles, taskPrims(prims.size(), threads));
    top.build(0, std::uint32_t(prims.size()), 0);
    std::vector<std::vector<BuildNode>> subtrees(top.tasks.size());
    parallelFor(threads, top.tasks.size(), 1, [&](std::size_t begin, std::size_t end) {
        for (std::size_t t = begin; t < end; ++t) {
            BinaryBuilder builder(prims, leafTriangles);
            builder.build(top.tasks[t].first, top.tasks[t].count, top.tasks[t].depth);
            subtrees[t] = std::move(builder.nodes);
        }
    });
    std::vector<BuildNode> nodes = std::move(top.nodes);
    for (std::size_t t = 0; t < subtrees.size(); ++t) {
        // Subtree node i > 0 goes to offset + i - 1; its root to the task's node.
        const std::uint32_t offset = std::uint32_t(nodes.size());
        const auto place = [&](std::uint32_t i) { return i == 0 ? top.tasks[t].node : offset + i - 1; };
        for (std::size_t i = 0; i < subtrees[t].size(); ++i) {
            BuildNode b = subtrees[t][i];
            if (!b.leaf()) b.left = place(b.left), b.right = place(b.right);
            if (i == 0) nodes[top.tasks[t].node] = b;
            else nodes.push_back(b);
        }
    }
    return nodes;
}

std::int32_t leafReference(std::uint32_t block, std::uint32_t count) {
    return ~std::int32_t(block << kLeafBits | (count - 1));
}

/// The W-wide tree of a binary one, depth first, into lines of floats.
class Collapser {
public:
    Collapser(const std::vector<BuildNode>& binary, std::vector<FloatLine>& lines, int width,
              const std::vector<std::uint32_t>& slotOf)
        : binary_(binary), lines_(lines), width_(width), slotOf_(slotOf) {}

    std::uint32_t emit(std::uint32_t b) {
        const std::uint32_t self = count++;
        lines_.resize(std::size_t(count) * linesPerNode());
        std::uint32_t kids[kMaxBvhWidth];
        const int n = gather(b, kids);
        for (int k = 0; k < width_; ++k) {
            const bool used = k < n;
            const Aabb box = used ? binary_[kids[k]].box : Aabb{};
            float* node = at(self);
            for (int a = 0; a < 3; ++a) {
                node[(NodeLanes::lo + a) * width_ + k] = box.lo[a];
                node[(NodeLanes::hi + a) * width_ + k] = box.hi[a];
                node[(NodeLanes::axis + a) * width_ + k] = 0.0f;
            }
            node[NodeLanes::slabLo * width_ + k] = node[NodeLanes::slabHi * width_ + k] = 0.0f;
            if (used) slabs.push_back({self, std::uint32_t(k), binary_[kids[k]].begin, binary_[kids[k]].end});
            std::int32_t reference = kEmptyChild;
            if (used && binary_[kids[k]].leaf())
                reference = leafReference(slotOf_[binary_[kids[k]].first] / std::uint32_t(width_), binary_[kids[k]].count);
            else if (used) reference = std::int32_t(emit(kids[k]));
            setChild(at(self), width_, k, reference);
        }
        return self;
    }

    std::vector<SlabJob> slabs;
    std::uint32_t count = 0; ///< nodes emitted

private:
    std::size_t linesPerNode() const { return std::size_t(NodeLanes::size * width_) / 16; }
    float* at(std::uint32_t node) { return lines_[node * linesPerNode()].f; }

    /// The children of binary node b: its two, then the inner child with
    /// the largest surface opened until there are W.
    int gather(std::uint32_t b, std::uint32_t* kids) const {
        int n = 0;
        if (binary_[b].leaf()) {
            kids[n++] = b;
        } else {
            kids[n++] = binary_[b].left;
            kids[n++] = binary_[b].right;
        }
        while (n < width_) {
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
        return n;
    }

    const std::vector<BuildNode>& binary_;
    std::vector<FloatLine>& lines_;
    int width_;
    const std::vector<std::uint32_t>& slotOf_; ///< of each triangle in the build's order
};

/// Lane `lane` of the plane at `plane` (x, y, z, w, each `width` lanes):
/// the unit normal rounded to float, and its offset through `on` in double.
void setPlane(float* plane, int width, int lane, const glm::dvec3& unit, const glm::dvec3& on) {
    const glm::vec3 rounded(unit);
    plane[lane] = rounded.x;
    plane[width + lane] = rounded.y;
    plane[2 * width + lane] = rounded.z;
    plane[3 * width + lane] = float(glm::dot(glm::dvec3(rounded), on));
}

/// Lane `lane` of a block's planes and extents (PlaneLanes, ExtentLanes):
/// triangle abc's planes and its edges' extents, zero where it is too thin,
/// and its corners.
void setLane(float* planes, float* extents, int width, int lane, const glm::vec3* corners) {
    for (int c = 0; c < 3; ++c)
        for (int a = 0; a < 3; ++a) extents[(ExtentLanes::corner + 3 * c + a) * width + lane] = corners[c][a];
    planes[(PlaneLanes::face + 3) * width + lane] = 0.0f;
    const glm::dvec3 v[3] = {glm::dvec3(corners[0]), glm::dvec3(corners[1]), glm::dvec3(corners[2])};
    const glm::dvec3 n = glm::cross(v[1] - v[0], v[2] - v[0]);
    const double length = glm::length(n);
    if (!(length >= kMinSine * glm::length(v[1] - v[0]) * glm::length(v[2] - v[0])) || !(length > 0.0)) return;
    const glm::dvec3 unit = n / length;
    setPlane(planes + PlaneLanes::face * width, width, lane, unit, v[0]);
    for (int e = 0; e < 3; ++e) { // outward: (b - a) x n points away from c
        const glm::dvec3 edge = v[(e + 1) % 3] - v[e];
        const glm::dvec3 outward = glm::cross(edge, unit);
        setPlane(planes + (PlaneLanes::edge + 4 * e) * width, width, lane, outward / glm::length(outward), v[e]);
        float* along = extents + (ExtentLanes::along + 4 * e) * width;
        setPlane(along, width, lane, edge / glm::length(edge), v[e]);
        // The far corner's position along the rounded direction, rounded up:
        // a longer edge only lowers the bound.
        const glm::dvec3 u(along[lane], along[width + lane], along[2 * width + lane]);
        extents[(ExtentLanes::length + e) * width + lane] = std::nextafter(float(glm::dot(u, edge)), kInf);
    }
}

/// Each block's planes all zero but the face's offsets, -infinity: every
/// lane's bound infinity (an empty slot) until set.
void clearBlocks(std::vector<FloatLine>& planes, int width) {
    const std::size_t floats = std::size_t(PlaneLanes::size * width);
    float* all = planes.data()->f;
    std::fill(all, all + planes.size() * 16, 0.0f);
    for (std::size_t block = 0; block * floats < planes.size() * 16; ++block)
        std::fill_n(all + block * floats + (PlaneLanes::face + 3) * width, width, -kInf);
}

} // namespace

bool bvhWidthAvailable(int width) {
    if (width == 4) return true;
#if (defined(__x86_64__) || defined(__i386__)) && defined(__GNUC__)
    if (width == 8) return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
    if (width == 16) return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl");
#endif
    return false;
}

int defaultBvhWidth() {
    static const int width = bvhWidthAvailable(8) ? 8 : 4;
    return width;
}

namespace {

/// Bvh::exponent_ for a mesh whose largest coordinate magnitude is `largest`.
int scaleExponent(float largest) {
    constexpr float kLow = 1.0f / float(1 << 30), kHigh = float(1 << 30);
    if (!(largest > 0.0f) || (largest >= kLow && largest <= kHigh)) return 0;
    return std::ilogb(largest);
}

} // namespace

Bvh::Bvh(MeshView mesh, int width, unsigned threads) : width_(width == 0 ? defaultBvhWidth() : width) {
    assert(bvhWidthAvailable(width_));
    search_ = width_ == 16 ? bvhSearch16() : width_ == 8 ? bvhSearch8() : bvhSearch4();
    std::vector<float> largest(mesh.positionCount);
    parallelFor(threads, largest.size(), 4096, [&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) {
            const glm::vec3 a = glm::abs(mesh.positions[i]);
            largest[i] = std::max(a.x, std::max(a.y, a.z));
        }
    });
    exponent_ = scaleExponent(largest.empty() ? 0.0f : *std::max_element(largest.begin(), largest.end()));
    toStored_ = std::ldexp(1.0, -exponent_);
    fromStored_ = std::ldexp(1.0, exponent_);
    fromStored2_ = fromStored_ * fromStored_;
    std::vector<glm::vec3> scaled;
    if (exponent_ != 0) {
        scaled.resize(mesh.positionCount);
        parallelFor(threads, scaled.size(), 4096, [&](std::size_t begin, std::size_t end) {
            for (std::size_t i = begin; i < end; ++i) scaled[i] = stored(mesh.positions[i]);
        });
        mesh.positions = scaled.data();
    }
    std::vector<Prim> prims(mesh.triangleCount);
    parallelFor(threads, prims.size(), 4096, [&](std::size_t begin, std::size_t end) {
        for (std::size_t t = begin; t < end; ++t) {
            const glm::uvec3 v = mesh.triangles[t];
            Prim& prim = prims[t];
            for (int c = 0; c < 3; ++c) prim.box.grow(mesh.positions[v[c]]);
            prim.centroid = (prim.box.lo + prim.box.hi) * 0.5f;
            prim.index = std::uint32_t(t);
        }
    });
    // Leaves of up to W triangles (8 at W = 4: two blocks), one SIMD step each.
    const std::vector<BuildNode> binary = buildBinary(prims, std::uint32_t(std::max(width_, 8)), threads);
    // Each leaf's triangles from a multiple of W: its lanes fill whole blocks.
    const std::uint32_t w = std::uint32_t(width_);
    std::vector<std::uint32_t> slotOf(prims.size());
    std::uint32_t slots = 0;
    for (const BuildNode& b : binary) // leaves in the build's order
        if (b.leaf()) {
            slots = (slots + w - 1) / w * w;
            for (std::uint32_t k = 0; k < b.count; ++k) slotOf[b.first + k] = slots++;
        }
    slots = (slots + w - 1) / w * w;
    Collapser collapser(binary, nodes_, width_, slotOf);
    collapser.emit(0);
    nodeCount_ = collapser.count;
    triangleCount_ = prims.size();
    indices_.assign(slots, kNoTriangle);
    planes_.assign(std::size_t(slots) * PlaneLanes::size / 16, FloatLine{});
    extents_.assign(std::size_t(slots) * ExtentLanes::size / 16, FloatLine{});
    clearBlocks(planes_, width_);
    largest.assign(prims.size(), 0.0f);
    parallelFor(threads, prims.size(), 4096, [&](std::size_t begin, std::size_t end) {
        for (std::size_t k = begin; k < end; ++k) {
            const glm::uvec3 v = mesh.triangles[prims[k].index];
            const glm::vec3 corners[3] = {mesh.positions[v.x], mesh.positions[v.y], mesh.positions[v.z]};
            const std::uint32_t slot = slotOf[k];
            indices_[slot] = prims[k].index;
            setLane(planes(slot / w), extents(slot / w), width_, int(slot % w), corners);
            for (const glm::vec3& c : corners)
                largest[k] = std::max(largest[k], std::abs(c.x) + std::abs(c.y) + std::abs(c.z));
        }
    });
    for (const float l : largest) verticesL1_ = std::max(verticesL1_, l);
    fillSlabs(collapser.slabs, slotOf, threads);
}

glm::dvec3 Bvh::corner(std::uint32_t slot, int c) const {
    const std::uint32_t w = std::uint32_t(width_);
    const float* e = extents(slot / w) + (ExtentLanes::corner + 3 * c) * width_ + slot % w;
    return {e[0], e[width_], e[2 * width_]};
}

/// Each child's slab: its triangles' area-weighted mean normal, shrunk so
/// that its float length stays below 1 (a longer one would overstate the
/// bound), and the range of n . x over their corners in double, rounded
/// outward to float. A child whose normals cancel keeps the zero slab,
/// which bounds nothing.
void Bvh::fillSlabs(const std::vector<SlabJob>& jobs, const std::vector<std::uint32_t>& slotOf, unsigned threads) {
    parallelFor(threads, jobs.size(), 256, [&](std::size_t first, std::size_t last) {
        for (std::size_t j = first; j < last; ++j) {
            const SlabJob& job = jobs[j];
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
            float* node = this->node(job.node);
            for (int a = 0; a < 3; ++a) node[(NodeLanes::axis + a) * width_ + int(job.slot)] = n[a];
            // Two more float steps each way cover the double sum's rounding.
            float& slabLo = node[NodeLanes::slabLo * width_ + int(job.slot)];
            float& slabHi = node[NodeLanes::slabHi * width_ + int(job.slot)];
            slabLo = std::nextafter(std::nextafter(float(lo), -kInf), -kInf);
            slabHi = std::nextafter(std::nextafter(float(hi), kInf), kInf);
        }
    });
}

float Bvh::slack(const glm::vec3& p) const {
    return kPlaneError * (std::abs(p.x) + std::abs(p.y) + std::abs(p.z) + 2.0f * verticesL1_);
}

double Bvh::slotDistance2(const glm::vec3& p, std::uint32_t slot) const {
    const glm::dvec3 q(p);
    const glm::dvec3 d = q - closestOnTriangle(q, corner(slot, 0), corner(slot, 1), corner(slot, 2)).point;
    return d.x * d.x + d.y * d.y + d.z * d.z;
}

ClosestPoint Bvh::closest(const glm::vec3& p, std::uint32_t slot) const {
    const glm::dvec3 q(exponent_ == 0 ? p : stored(p));
    const TriangleHit hit = closestOnTriangle(q, corner(slot, 0), corner(slot, 1), corner(slot, 2));
    const glm::dvec3 d = q - hit.point;
    return {hit.point * fromStored_, std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z) * fromStored_, indices_[slot],
            hit.feature, hit.index};
}

void Bvh::nearestAtScale(const glm::vec3& p, const std::vector<BvhNode>* leaves, NearestState& state) const {
    const glm::vec3 q = stored(p);
    state.distance2 *= toStored_ * toStored_;
    if (!withinReach(q)) {
        for (std::uint32_t slot = 0; slot < indices_.size(); ++slot) {
            if (indices_[slot] == kNoTriangle) continue;
            const double d2 = slotDistance2(q, slot);
            if (d2 < state.distance2) state = {d2, slot};
        }
    } else if (leaves) {
        search_.nearestAmong(*this, q, *leaves, state);
    } else {
        search_.nearest(*this, q, state);
    }
    state.distance2 *= fromStored2_;
}

namespace {

/// Appends child k of `node` (`width` lanes) to the groups of `out`, a new
/// group of empty slots where the last is full (slot == 4).
void keepChild(const float* node, int width, int k, std::vector<BvhNode>& out, int& slot) {
    if (slot == 4) {
        out.emplace_back();
        float* fresh = out.back().lanes;
        std::fill(fresh, fresh + NodeLanes::size * 4, 0.0f);
        std::fill_n(fresh + NodeLanes::lo * 4, 12, kInf);
        std::fill_n(fresh + NodeLanes::hi * 4, 12, -kInf);
        for (int s = 0; s < 4; ++s) setChild(fresh, 4, s, kEmptyChild);
        slot = 0;
    }
    float* into = out.back().lanes;
    for (int row = 0; row < NodeLanes::child; ++row) into[row * 4 + slot] = node[row * width + k];
    setChild(into, 4, slot++, childOf(node, width, k));
}

} // namespace

bool Bvh::leavesNear(const glm::vec3& boxLo, const glm::vec3& boxHi, double reach2, std::vector<BvhNode>& out,
                     std::size_t maxGroups) const {
    const glm::vec3 lo = stored(boxLo), hi = stored(boxHi); // the hierarchy's coordinates
    const float bound = pruneBound(reach2 * toStored_ * toStored_);
    int slot = 4; // the next free slot of out.back()
    std::int32_t stack[kStackEntries];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const float* node = this->node(std::size_t(stack[--top]));
        for (int k = 0; k < width_; ++k) {
            const std::int32_t reference = childOf(node, width_, k);
            if (reference == kEmptyChild) continue;
            float d2 = 0.0f; // box to box: the gap along each axis
            for (int a = 0; a < 3; ++a) {
                const float gap = std::max(std::max(node[(NodeLanes::lo + a) * width_ + k] - hi[a],
                                                    lo[a] - node[(NodeLanes::hi + a) * width_ + k]),
                                           0.0f);
                d2 += gap * gap;
            }
            if (d2 > bound) continue;
            if (reference >= 0) stack[top++] = reference;
            else keepChild(node, width_, k, out, slot);
        }
        if (out.size() > maxGroups) return false;
    }
    return true;
}

} // namespace vds::detail
