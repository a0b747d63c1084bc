// vds: triangle meshes as plain data, and the report of their validation
// (validation itself and its messages: <vds/mesh_check.h>).
//
// The core of the library takes triangles as a view over caller-owned arrays;
// `TriangleMesh` is the owning form the loaders (<vds/mesh_io.h>) and tests
// produce.
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
    std::size_t skippedFaces = 0;      ///< faces of fewer than 3 vertices the file held, left out of `triangles`
};

/// A non-owning view of an indexed triangle mesh. The arrays must outlive every
/// call that receives the view; nothing is copied unless a call says so.
struct MeshView {
    const glm::vec3* positions = nullptr;  ///< `positionCount` points
    std::size_t positionCount = 0;
    const glm::uvec3* triangles = nullptr; ///< `triangleCount` index triples
    std::size_t triangleCount = 0;
    std::size_t skippedFaces = 0;          ///< as `TriangleMesh::skippedFaces`, passed on to `MeshReport`

    MeshView() = default;
    MeshView(const glm::vec3* p, std::size_t np, const glm::uvec3* t, std::size_t nt)
        : positions(p), positionCount(np), triangles(t), triangleCount(nt) {}
    MeshView(const TriangleMesh& m) // NOLINT: implicit on purpose, a mesh is a view of itself
        : positions(m.positions.data()), positionCount(m.positions.size()),
          triangles(m.triangles.data()), triangleCount(m.triangles.size()), skippedFaces(m.skippedFaces) {}
};

/// Axis-aligned box, `lo <= hi` componentwise when not empty.
struct Box {
    glm::vec3 lo{0.0f};
    glm::vec3 hi{0.0f};
};

/// What validation found. Counts are of undirected edges after welding
/// vertices at equal positions: exact duplicates are one vertex, and so are
/// `-0` and `+0` (positions compared as floats, as the winding code and the
/// STL reader compare them), so a mesh whose loader duplicated vertices is
/// judged by its geometry, not by its index buffer, and every count of one
/// mesh agrees. A vertex with a NaN or infinite coordinate is welded to none.
///
/// Which rule defines inside: a ray from a point crosses the surface; across
/// an edge used by an even number of triangles the count of crossings changes
/// by an even number, so the parity of the count, and whether a point is
/// inside by the parity rule, does not depend on the ray (`closed()`). The
/// winding rule needs more: every edge used as often in one direction as in
/// the other (`oriented()`). Neither needs a manifold mesh: two solids that
/// touch along an edge (four triangles on it) bound a solid by both rules.
struct MeshReport {
    std::size_t vertexCount = 0;
    std::size_t triangleCount = 0;
    std::size_t boundaryEdges = 0;       ///< edges used by one triangle: holes, the mesh is open
    std::size_t nonManifoldEdges = 0;    ///< edges used by three or more triangles
    std::size_t oddNonManifoldEdges = 0; ///< of those, edges used by 3, 5, ... triangles: open like boundary edges
    std::size_t inconsistentEdges = 0;   ///< edges used an even number of times, more often in one direction: orientation conflicts
    /// Closed connected parts (vertices joined by triangles, no edge at
    /// fault) whose triangles face inward: a negative signed volume. The
    /// parity and winding rules count such a part inside (its winding
    /// number is -1), the generalized winding number outside.
    std::size_t insideOutParts = 0;
    /// The generalized winding number's boundary: edge uses that do not
    /// cancel, an edge counted by how many more times it is used one way than
    /// the other (boundary edges once, an inconsistently oriented edge twice).
    /// The count of `ExactClassifier::boundaryEdgeCount()` and of a sprite's
    /// `boundaryEdges`.
    std::size_t windingBoundaryEdges = 0;
    std::size_t degenerateTriangles = 0; ///< repeated vertex or zero area
    std::size_t duplicateTriangles = 0;  ///< triangles on the same three vertices as an earlier one, either orientation
    std::size_t isolatedVertices = 0;    ///< vertices no triangle uses (nor any vertex at the same position)
    std::size_t nonFiniteVertices = 0;   ///< NaN or infinite coordinates
    std::size_t badIndices = 0;          ///< triangles with an index >= vertex count
    std::size_t skippedFaces = 0;        ///< faces of fewer than 3 vertices the file held (`TriangleMesh::skippedFaces`)
    Box bounds;                          ///< of the vertices used by triangles (finite ones)
    /// Every vertex the triangles use lies within 1e-6 of the box's diagonal
    /// of the plane of the largest triangle (rounding's reach for float
    /// positions on a tilted plane).
    bool coplanar = false;

    /// True when every edge is used by an even number of triangles: the parity
    /// rule defines inside. Non-manifold edges used by 4, 6, ... triangles are
    /// allowed.
    bool closed() const { return boundaryEdges == 0 && oddNonManifoldEdges == 0; }
    /// True when closed and every edge is used as often in each direction:
    /// the winding rule defines inside too.
    bool oriented() const { return closed() && inconsistentEdges == 0; }
    /// True when closed but the rules disagree: orientation conflicts, or a
    /// part turned inside out.
    bool misoriented() const { return closed() && (inconsistentEdges > 0 || insideOutParts > 0); }
    /// The one word for the mesh (CLI, Python, a sprite's status):
    /// "closed" (every rule answers alike), "mis-oriented" or "open".
    const char* status() const { return !closed() ? "open" : misoriented() ? "mis-oriented" : "closed"; }
    /// True when every edge is used by at most two triangles.
    bool manifold() const { return nonManifoldEdges == 0; }
    /// True when the mesh is a flat sheet, which bounds no volume (nothing is
    /// inside it by any rule): its box has no extent along some axis, or all
    /// its triangles lie in one tilted plane (`coplanar`), which a sprite sees
    /// edge-on from some direction.
    bool flat() const;
    /// True when nothing at all would stop a bake (finite, non-empty, valid indices).
    bool usable() const { return triangleCount > 0 && nonFiniteVertices == 0 && badIndices == 0; }
    /// One line, e.g. "closed, 5856 triangles, 2930 vertices", "closed but
    /// mis-oriented (12 inconsistently oriented edges, 1 inside-out part; 24
    /// edges in the generalized winding number's boundary), ..." or "open (12
    /// boundary edges), ..., 3 duplicate triangles, 1 isolated vertex, 2 faces
    /// of fewer than 3 vertices skipped"; every count that is not zero is named.
    std::string summary() const;
};

/// "24 edges in the generalized winding number's boundary": the words for
/// `MeshReport::windingBoundaryEdges` wherever that count is shown.
std::string windingBoundaryText(std::size_t edges);

/// Bounding box of the vertices referenced by triangles.
Box meshBounds(MeshView mesh);

/// A mesh's boundary edges as `Sprite::boundaryEdges` (<vds/sprite.h>) holds them (edge k
/// runs from `[2k]` to `[2k+1]`, mesh coordinates; see there), for bakers
/// outside vds::core such as `bakeToGpu`. Empty for a mesh whose every edge
/// is used equally often each way. O(triangles log triangles).
std::vector<glm::vec3> meshBoundaryEdges(MeshView mesh);

} // namespace vds
