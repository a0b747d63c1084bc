// vds: a W-wide bounding volume hierarchy over triangles, for nearest-
// triangle queries (<vds/distance.h>), W chosen when the hierarchy is
// built from what the CPU has: 4 lanes (SSE), 8 (AVX2, the default where
// present) or 16 (AVX-512), so one binary serves each.
//
// Built as a binary tree by the binned surface-area heuristic (Wald, "On
// fast Construction of SAH-based Bounding Volume Hierarchies", 2007: 16
// bins on each axis), then collapsed to W children a node (the child
// with the largest surface opened first) and laid out depth first, so a
// node's first child follows it in memory. A node holds its W
// children's boxes, their oriented slabs and references as structure of
// arrays (12 W floats: 48 W bytes, three cache lines a 4 lanes), so one
// query tests the W box distances in one SIMD step. A leaf's triangles
// fill one block of W lanes (two of 4 at W = 4), tested in one step too.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

#include <glm/vec3.hpp>

#include <vds/distance.h>
#include <vds/mesh.h>

namespace vds::detail {

/// A node's W children, as structure of arrays: 12 W floats, in units of W,
/// lo[3] and hi[3] (boxes by axis), axis[3], slabLo and slabHi (slabs), then
/// the W references (int32, childOf). A child's slab is a direction n (|n|
/// < 1, the mean normal of its triangles) and the range [slabLo, slabHi] of
/// n . x over its corners: max(slabLo - n . p, n . p - slabHi) bounds the
/// distance from p to the child below. On a curved surface a box is loose
/// by about its size, a slab only by its sagitta (size^2 / 8 radius), which
/// is what lets a cell near the medial axis rule out the nearly equidistant
/// rest of the mesh. A reference >= 0 is an inner node's index; kEmptyChild
/// no child; otherwise a leaf, ~(block << kLeafBits | (count - 1)): the
/// triangles in slots [W block, W block + count) (each leaf's from a slot
/// that is a multiple of W; the slots after its last, up to the next
/// multiple, are empty).
struct NodeLanes {
    static constexpr int lo = 0, hi = 3, axis = 6, slabLo = 9, slabHi = 10, child = 11, size = 12;
};

/// Four children gathered from any nodes (Bvh::leavesNear), laid out as a
/// node of width 4 (NodeLanes): three cache lines.
struct alignas(64) BvhNode {
    float lanes[NodeLanes::size * 4];
};
static_assert(sizeof(BvhNode) == 192, "a group is three cache lines, as the header says");
constexpr std::int32_t kEmptyChild = INT32_MIN;
/// Bits of a leaf reference that hold its triangle count less one.
constexpr int kLeafBits = 4;
/// Lanes of the widest search (AVX-512), and the most triangles a leaf holds.
constexpr int kMaxBvhWidth = 16;

/// A box is pruned when its float squared distance exceeds the best squared
/// distance by this relative margin: above the few float roundings of a box
/// distance (4 * 2^-24) and of the bound itself (2^-24).
constexpr double kPruneMargin = 1.0 + 1.0 / (1 << 20);
inline float pruneBound(double distance2) { return float(distance2 * kPruneMargin); }

/// Reference `k` of a node of `width` lanes.
inline std::int32_t childOf(const float* node, int width, int k) {
    std::int32_t reference;
    std::memcpy(&reference, node + NodeLanes::child * width + k, sizeof reference);
    return reference;
}
inline void setChild(float* node, int width, int k, std::int32_t reference) {
    std::memcpy(node + NodeLanes::child * width + k, &reference, sizeof reference);
}

/// A block of W triangles' lower-bound planes (lowerBounds in
/// bvh_search.h), 16 W floats, in units of W: the face's plane, and for
/// each edge i (from corner i to corner i + 1) its outward normal in the
/// face's plane (the edge's line: e_i = m_i . p - w), each plane as x[W],
/// y[W], z[W], w[W], so n . p - w is one SIMD step for W lanes. The squared
/// distance to a triangle is h^2 + (0 where every e_i <= 0, else the least
/// over the edges with e_i > 0 of e_i^2 + max(-t_i, t_i - length_i, 0)^2),
/// h the face's plane distance, t_i the position along edge i: from
/// outside a convex polygon the nearest point is on an edge whose line
/// separates them. In float, each term less its rounding's bound, it is a
/// lower bound that equals the distance up to that bound. A degenerate or
/// sliver triangle, whose normal double cannot give to float precision, has
/// all planes zero (bound 0: always tested exactly); an empty lane's face
/// plane is (0, -infinity) (bound infinity: never tested).
struct PlaneLanes {
    static constexpr int face = 0, edge = 4, size = 16;
};
/// The rest of a block, apart from the planes, 24 W floats in units of W:
/// the edges' directions (planes: t_i = u_i . p - w) and lengths, which the
/// bound needs only where the planes alone leave a lane within reach, and
/// the corners (corner, axis, lane), which the exact test reads just after
/// them. A leaf asks for them as it starts, so their cache misses overlap
/// the planes'.
struct ExtentLanes {
    static constexpr int along = 0, length = 12, corner = 15, size = 24;
};

/// A cache line of floats: the unit the hierarchy's arrays are stored in,
/// so each node and block starts on a line.
struct alignas(64) FloatLine {
    float f[16];
};

/// Whether this CPU can search a hierarchy of `width` lanes: 4 always, 8
/// with AVX2 and FMA, 16 with AVX-512F and VL (x86-64; elsewhere 4 only).
bool bvhWidthAvailable(int width);
/// The width a hierarchy is built with unless told: 8 where the CPU has
/// AVX2, else 4. 16 lanes (AVX-512) are available but not the default: a
/// leaf of up to 16 triangles tests more of them than it saves in steps
/// (measured on the bench meshes, docs/distance.md).
int defaultBvhWidth();

/// The best found so far by a search: squared distance and triangle slot.
struct NearestState {
    double distance2;
    std::uint32_t slot = kNoTriangle; ///< into `Bvh::triangles`
};

/// A child slot whose slab is filled once the triangles are in leaf order:
/// node, slot, and its triangles [begin, end) in the build's order.
struct SlabJob {
    std::uint32_t node, slot, begin, end;
};

class Bvh;
/// A search compiled for one instruction set (bvh_search.h): the nearest
/// triangle to a point over the whole hierarchy, or over leaf groups only.
struct BvhSearch {
    void (*nearest)(const Bvh& bvh, const glm::vec3& p, NearestState& state);
    void (*nearestAmong)(const Bvh& bvh, const glm::vec3& p, const std::vector<BvhNode>& leaves, NearestState& state);
};

class Bvh {
public:
    /// Triangles with valid indices (the caller validated the mesh), W =
    /// `width` lanes (4, 8 or 16, available on this CPU; 0: the default),
    /// the build on `threads` threads (0: one per hardware thread).
    explicit Bvh(MeshView mesh, int width = 0, unsigned threads = 0);
    /// No hierarchy, to be assigned one: it must not be searched.
    Bvh() = default;

    /// Lowers `state` to the nearest triangle to `p` if one is nearer than
    /// `state.distance2` (the caller's bound: infinity, a band's square, or
    /// the distance to a seed triangle).
    void nearest(const glm::vec3& p, NearestState& state) const {
        if (exponent_ == 0 && withinReach(p)) search_.nearest(*this, p, state);
        else nearestAtScale(p, nullptr, state);
    }
    /// Appends to `out` the leaves whose boxes come within `reach2` (squared
    /// distance) of the box [lo, hi], packed four to a group (empty slots
    /// kEmptyChild): every triangle that can be nearer than sqrt(reach2) to
    /// a point of the box is in one of them. Stops, returning false, once
    /// `out` holds more than `maxGroups` groups.
    bool leavesNear(const glm::vec3& lo, const glm::vec3& hi, double reach2, std::vector<BvhNode>& out,
                    std::size_t maxGroups) const;
    /// `nearest` over the leaves `leavesNear` gave only.
    void nearestAmong(const glm::vec3& p, const std::vector<BvhNode>& leaves, NearestState& state) const {
        if (exponent_ == 0 && withinReach(p)) search_.nearestAmong(*this, p, leaves, state);
        else nearestAtScale(p, &leaves, state);
    }
    /// Squared distance from p to the triangle in `slot`.
    double distance2(const glm::vec3& p, std::uint32_t slot) const {
        return exponent_ == 0 ? slotDistance2(p, slot) : slotDistance2(stored(p), slot) * fromStored2_;
    }
    /// The closest point on the triangle in `slot`, its index the mesh's.
    ClosestPoint closest(const glm::vec3& p, std::uint32_t slot) const;

    int width() const { return width_; }
    std::size_t nodeCount() const { return nodeCount_; }
    std::size_t triangleCount() const { return triangleCount_; }
    std::size_t memoryBytes() const {
        return (nodes_.size() + planes_.size() + extents_.size()) * sizeof(FloatLine) +
               indices_.size() * sizeof(std::uint32_t);
    }

    /// The search's view (bvh_search.h): node `i`'s 12 W floats, block
    /// `b`'s planes and extents, the plane distances' rounding bound at p.
    const float* node(std::size_t i) const { return nodes_.data()->f + i * std::size_t(NodeLanes::size * width_); }
    const float* planes(std::size_t b) const { return planes_.data()->f + b * std::size_t(PlaneLanes::size * width_); }
    const float* extents(std::size_t b) const { return extents_.data()->f + b * std::size_t(ExtentLanes::size * width_); }
    float slack(const glm::vec3& p) const;
    /// Squared distance from q, in the hierarchy's own coordinates (the
    /// search's), to the triangle in `slot`.
    double slotDistance2(const glm::vec3& q, std::uint32_t slot) const;

    /// The float search squares distances: it takes points within this of
    /// the origin in the hierarchy's coordinates (a square up to 2^100).
    static constexpr float kReach = 1125899906842624.0f; // 2^50
    static bool withinReach(const glm::vec3& q) {
        return std::abs(q.x) <= kReach && std::abs(q.y) <= kReach && std::abs(q.z) <= kReach;
    }

private:
    /// p in the hierarchy's coordinates: times 2^-exponent_, exact but where
    /// a coordinate falls below float's normal range (then off by less than
    /// 2^-149 of the mesh's size, far inside the stated bound).
    glm::vec3 stored(const glm::vec3& p) const { return glm::vec3(glm::dvec3(p) * toStored_); }
    /// `nearest` or `nearestAmong` (`leaves` set) of a point the search
    /// cannot take as it is: scaled to the hierarchy's coordinates, and past
    /// kReach (every triangle then about equally far) every triangle's
    /// distance in double.
    void nearestAtScale(const glm::vec3& p, const std::vector<BvhNode>* leaves, NearestState& state) const;
    float* node(std::size_t i) { return nodes_.data()->f + i * std::size_t(NodeLanes::size * width_); }
    float* planes(std::size_t b) { return planes_.data()->f + b * std::size_t(PlaneLanes::size * width_); }
    float* extents(std::size_t b) { return extents_.data()->f + b * std::size_t(ExtentLanes::size * width_); }
    void fillSlabs(const std::vector<SlabJob>& jobs, const std::vector<std::uint32_t>& slotOf, unsigned threads);
    glm::dvec3 corner(std::uint32_t slot, int c) const;

    int width_ = 4;
    BvhSearch search_{};
    std::vector<FloatLine> nodes_;
    std::size_t nodeCount_ = 0;
    /// A slot's triangle's index in the mesh (kNoTriangle: an empty slot).
    std::vector<std::uint32_t> indices_;
    /// The triangles' lower bounds, W slots a block.
    std::vector<FloatLine> planes_;
    std::vector<FloatLine> extents_;
    std::size_t triangleCount_ = 0;
    /// The float plane distances' error bound: kPlaneError times (|p|_1 + 2
    /// max |v|_1 over the vertices).
    float verticesL1_ = 0.0f;
    /// The hierarchy holds the mesh times 2^-exponent_, a power of two so
    /// that every distance scales back exactly: 0 for a mesh whose largest
    /// coordinate is within 2^-30..2^30, else that coordinate's exponent
    /// (squares in float would overflow past 2^64, or lose every bit below
    /// 2^-75), so distances are exact at any finite scale, 1e-30 to 1e38.
    int exponent_ = 0;
    double toStored_ = 1.0, fromStored_ = 1.0, fromStored2_ = 1.0;
};

/// The searches of each width, one a translation unit compiled for its
/// instruction set (bvh_sse.cpp, bvh_avx2.cpp, bvh_avx512.cpp).
BvhSearch bvhSearch4();
BvhSearch bvhSearch8();
BvhSearch bvhSearch16();

} // namespace vds::detail
