// vds: a 4-wide bounding volume hierarchy over triangles, for nearest-
// triangle queries (<vds/distance.h>).
//
// Built as a binary tree by the binned surface-area heuristic (Wald, "On
// fast Construction of SAH-based Bounding Volume Hierarchies", 2007: 16
// bins on each axis), then collapsed to four children a node (the child
// with the largest surface opened first) and laid out depth first, so a
// node's first child follows it in memory. A node holds its four
// children's boxes as structure of arrays (one 128-byte, two-cache-line
// record), so one query tests the four box distances in one SIMD step.
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
    /// ~(first << 2 | (count - 1)), triangles [first, first + count) of
    /// `Bvh::triangles`.
    std::int32_t child[4];
};
constexpr std::int32_t kEmptyChild = INT32_MIN;
/// Triangles a leaf holds at most (two bits of the reference).
constexpr std::uint32_t kLeafTriangles = 4;

/// A triangle as stored in leaf order: its corners and its index in the mesh.
struct BvhTriangle {
    glm::vec3 a, b, c;
    std::uint32_t index;
};

/// Four planes of one triangle, by component (lanes: its face, then the
/// outward in-plane normals of edges ab, bc, ca), so that one SIMD step
/// gives the four signed distances s = n . p - w. With h = |s_face| and e =
/// the largest edge distance, h^2 + max(e, 0)^2 is a lower bound of the
/// squared distance to the triangle, equal to it when the closest point is
/// on the face or an edge (the plane distance, then the in-plane distance
/// to a convex polygon bounded by its edge lines). A degenerate or sliver
/// triangle, whose normal double cannot give to float precision, has all
/// four planes zero: its bound is 0, so it is always tested exactly.
struct alignas(64) TriangleBound {
    float x[4], y[4], z[4], w[4];
};

/// The best found so far by a search: squared distance and triangle slot.
struct NearestState {
    double distance2;
    std::uint32_t slot = kNoTriangle; ///< into `Bvh::triangles`
};

/// A child slot whose slab is filled once the triangles are in leaf order:
/// node, slot, and its triangles [begin, end).
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
    std::size_t triangleCount() const { return triangles_.size(); }
    std::size_t memoryBytes() const {
        return nodes_.size() * sizeof(BvhNode) + triangles_.size() * (sizeof(BvhTriangle) + sizeof(TriangleBound));
    }

private:
    void prefetch(std::int32_t node) const;
    void searchLeaf(const glm::vec3& p, float margin, std::int32_t leaf, NearestState& state, float& bound) const;
    void fillSlabs(const std::vector<SlabJob>& jobs);
    float slack(const glm::vec3& p) const;

    std::vector<BvhNode> nodes_;
    std::vector<BvhTriangle> triangles_;
    /// Each triangle's planes (leaf order): a lower bound of its distance in
    /// float, less `slack`, turns most triangles of a leaf away before the
    /// exact double test.
    std::vector<TriangleBound> bounds_;
    /// The float plane distances' error bound: kPlaneError times (|p|_1 + 2
    /// max |v|_1 over the vertices).
    float verticesL1_ = 0.0f;
};

} // namespace vds::detail
