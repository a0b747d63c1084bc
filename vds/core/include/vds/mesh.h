// vds: triangle meshes as plain data, and their validation.
//
// The core of the library takes triangles as a view over caller-owned arrays;
// `TriangleMesh` is the owning form the loaders and tests produce. OpenMesh is
// used only by the file loader (<vds/mesh_io.h>).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace vds {

/// An owning indexed triangle mesh. Triangles are counter-clockwise seen from
/// outside (outward normals by the right-hand rule), indices into `positions`.
struct TriangleMesh {
    std::vector<glm::vec3> positions;  ///< vertex positions, mesh coordinates
    std::vector<glm::uvec3> triangles; ///< three vertex indices per triangle
    std::string name;                  ///< where it came from (file name), may be empty
};

/// A non-owning view of an indexed triangle mesh. The arrays must outlive every
/// call that receives the view; nothing is copied unless a call says so.
struct MeshView {
    const glm::vec3* positions = nullptr;  ///< `positionCount` points
    std::size_t positionCount = 0;
    const glm::uvec3* triangles = nullptr; ///< `triangleCount` index triples
    std::size_t triangleCount = 0;

    MeshView() = default;
    MeshView(const glm::vec3* p, std::size_t np, const glm::uvec3* t, std::size_t nt)
        : positions(p), positionCount(np), triangles(t), triangleCount(nt) {}
    MeshView(const TriangleMesh& m) // NOLINT: implicit on purpose, a mesh is a view of itself
        : positions(m.positions.data()), positionCount(m.positions.size()),
          triangles(m.triangles.data()), triangleCount(m.triangles.size()) {}
};

/// Axis-aligned box, `lo <= hi` componentwise when not empty.
struct Box {
    glm::vec3 lo{0.0f};
    glm::vec3 hi{0.0f};
};

/// What validation found. Counts are of undirected edges after welding
/// vertices with bitwise-equal positions, so a mesh whose loader duplicated
/// vertices is judged by its geometry, not by its index buffer.
struct MeshReport {
    std::size_t vertexCount = 0;
    std::size_t triangleCount = 0;
    std::size_t boundaryEdges = 0;       ///< edges used by one triangle: the mesh is open
    std::size_t nonManifoldEdges = 0;    ///< edges used by three or more triangles
    std::size_t inconsistentEdges = 0;   ///< edges used twice in the same direction: orientation flips
    std::size_t degenerateTriangles = 0; ///< repeated vertex or zero area
    std::size_t nonFiniteVertices = 0;   ///< NaN or infinite coordinates
    std::size_t badIndices = 0;          ///< triangle indices >= vertex count
    Box bounds;                          ///< of the vertices used by triangles (finite ones)

    /// True when the mesh bounds a solid: closed, manifold, consistently oriented.
    bool closed() const { return boundaryEdges == 0 && nonManifoldEdges == 0 && inconsistentEdges == 0; }
    /// True when nothing at all would stop a bake (finite, non-empty, valid indices).
    bool usable() const { return triangleCount > 0 && nonFiniteVertices == 0 && badIndices == 0; }
    /// One line, e.g. "closed, 5856 triangles" or "open: 12 boundary edges, ...".
    std::string summary() const;
};

/// Validates a mesh. Cost O(n log n) in the triangle count; never throws for
/// bad geometry (it counts it), only for allocation failure.
MeshReport validateMesh(MeshView mesh);

/// Throws `InvalidMesh` with a one-line reason if `report` is not `usable()`.
void requireUsable(const MeshReport& report, const std::string& meshName);

/// Bounding box of the vertices referenced by triangles.
Box meshBounds(MeshView mesh);

} // namespace vds
