// vds: a 4-wide bounding volume hierarchy over triangles, for nearest-
// triangle queries (<vds/distance.h>).
//
// Built as a binary tree by the binned surface-area heuristic (Wald, "On
// fast Construction of SAH-based Bounding Volume Hierarchies", 2007: 16
// bins on each axis), then collapsed to four children a node (the child
// with the largest surface opened first) and laid out depth first, so a
// node's first child follows it in memory. A node holds its four
// children's boxes, their oriented slabs and references as structure of
// arrays (one 192-byte, three-cache-line record), so one query tests the
// four box distances in one SIMD step.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include <vds/distance.h>
#include <vds/mesh.h>

namespace vds::detail {

/// One node: children's boxes by axis, their slabs, then their references.
/// A child's slab is a direction n (|n| < 1, the mean normal of its
/// triangles) and the range [slabLo, slabHi] of n . x over its corners:
/// max(slabLo - n . p, n . p - slabHi) bounds the distance from p to the
/// child below. On a curved surface a box is loose by about its size, a
/// slab only by its sagitta (size^2 / 8 radius), which is what lets a cell
/// near the medial axis rule out the nearly equidistant rest of the mesh.
struct alignas(64) BvhNode {
    float lo[3][4];
    float hi[3][4];
    float axis[3][4];
    float slabLo[4];
    float slabHi[4];
    /// >= 0: an inner node's index; kEmptyChild: no child; otherwise a leaf,
    /// ~(block << kLeafBits | (count - 1)): the triangles in slots [4 block,
    /// 4 block + count), lanes of blocks block, block + 1 (each leaf's
    /// triangles from a slot that is a multiple of 4; the slots after its
    /// last, up to the next multiple, are empty).
    std::int32_t child[4];
};
static_assert(sizeof(BvhNode) == 192, "a node is three cache lines, as the header says");
constexpr std::int32_t kEmptyChild = INT32_MIN;
/// Bits of a leaf reference that hold its triangle count less one.
constexpr int kLeafBits = 3;
/// Triangles a leaf holds at most.
constexpr std::uint32_t kLeafTriangles = 1u << kLeafBits;

/// Four planes, one a lane, by component: n . p - w in one SIMD step.
struct alignas(64) Plane4 {
    float x[4], y[4], z[4], w[4];
};

/// Four triangles of a leaf, one a lane, as planes that bound their
/// distance below (lowerBounds in bvh.cpp): the face's plane, and for each
/// edge i (from corner i to corner i + 1) its outward normal in the face's
/// plane (the edge's line: e_i = m_i . p - w) and its direction (the
/// position along it from corner i: t_i = u_i . p - w, in [0, length_i] on
/// the edge). The squared distance to a triangle is h^2 + (0 where every
/// e_i <= 0, else the least over the edges with e_i > 0 of e_i^2 +
/// max(-t_i, t_i - length_i, 0)^2), h the face's plane distance: from outside
/// a convex polygon the nearest point is on an edge whose line separates
/// them. In float, each term less its rounding's bound, it is a lower bound
/// that equals the distance up to that bound. A degenerate or sliver
/// triangle, whose normal double cannot give to float precision, has all
/// planes zero (bound 0: always tested exactly); an empty lane's face plane
/// is (0, -infinity) (bound infinity: never tested).
struct alignas(64) TriangleBlock {
    Plane4 face;
    Plane4 edge[3];
};
/// The rest of a TriangleBlock's triangles, apart from the planes: the
/// edges' directions and lengths, which the bound needs only where the
/// planes alone leave a lane within reach, and the corners (corner, axis,
/// lane), which the exact test reads just after them. A leaf asks for them
/// as it starts, so their cache misses overlap the planes'.
struct alignas(64) ExtentBlock {
    Plane4 along[3];
    float length[3][4];
    float corner[3][3][4];
};

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

class Bvh {
public:
    /// Triangles with valid indices (the caller validated the mesh).
    explicit Bvh(MeshView mesh);

    /// Lowers `state` to the nearest triangle to `p` if one is nearer than
    /// `state.distance2` (the caller's bound: infinity, a band's square, or
    /// the distance to a seed triangle).
    void nearest(const glm::vec3& p, NearestState& state) const;
    /// Appends to `out` the leaves whose boxes come within `reach2` (squared
    /// distance) of the box [lo, hi], packed four to a node as the
    /// hierarchy's own (empty slots kEmptyChild): every triangle that can be
    /// nearer than sqrt(reach2) to a point of the box is in one of them.
    /// Stops, returning false, once `out` holds more than `maxGroups` nodes.
    bool leavesNear(const glm::vec3& lo, const glm::vec3& hi, double reach2, std::vector<BvhNode>& out,
                    std::size_t maxGroups) const;
    /// `nearest` over the leaves `leavesNear` gave only.
    void nearestAmong(const glm::vec3& p, const std::vector<BvhNode>& leaves, NearestState& state) const;
    /// Squared distance from p to the triangle in `slot`.
    double distance2(const glm::vec3& p, std::uint32_t slot) const;
    /// The closest point on the triangle in `slot`, its index the mesh's.
    ClosestPoint closest(const glm::vec3& p, std::uint32_t slot) const;

    std::size_t nodeCount() const { return nodes_.size(); }
    std::size_t triangleCount() const { return triangleCount_; }
    std::size_t memoryBytes() const {
        return nodes_.size() * sizeof(BvhNode) + indices_.size() * sizeof(std::uint32_t) +
               blocks_.size() * (sizeof(TriangleBlock) + sizeof(ExtentBlock));
    }

private:
    void prefetch(std::int32_t node) const;
    void searchLeaf(const glm::vec3& p, float margin, std::int32_t leaf, NearestState& state, float& bound) const;
    void fillSlabs(const std::vector<SlabJob>& jobs, const std::vector<std::uint32_t>& slotOf);
    float slack(const glm::vec3& p) const;
    glm::dvec3 corner(std::uint32_t slot, int c) const {
        const ExtentBlock& e = extents_[slot / 4];
        return {e.corner[c][0][slot % 4], e.corner[c][1][slot % 4], e.corner[c][2][slot % 4]};
    }

    std::vector<BvhNode> nodes_;
    /// A slot's triangle's index in the mesh (kNoTriangle: an empty slot).
    std::vector<std::uint32_t> indices_;
    /// The triangles' lower bounds, four slots a block.
    std::vector<TriangleBlock> blocks_;
    std::vector<ExtentBlock> extents_;
    std::size_t triangleCount_ = 0;
    /// The float plane distances' error bound: kPlaneError times (|p|_1 + 2
    /// max |v|_1 over the vertices).
    float verticesL1_ = 0.0f;
};

} // namespace vds::detail
