// vds: closed triangle meshes of simple solids, generated in code.
//
// Tests, benchmarks and `vds eval` build their inputs with these, so that they
// run from a clean clone and any size can be made on demand. Each solid comes
// with its analytic description, to tell how far a point is from the ideal
// surface; the tessellation differs from it by at most `tessellationError`.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include <glm/vec3.hpp>

#include <vds/mesh.h>

namespace vds::solids {

/// Signed distance estimate to an analytic solid: negative inside. Exact for
/// boxes and spheres; for unions/differences it is the usual min/max bound.
struct Solid {
    TriangleMesh mesh;
    float tessellationError = 0.0f; ///< max distance between mesh and ideal surface
    /// Signed distance of `p` to the ideal solid (negative inside).
    float (*signedDistance)(const Solid&, const glm::vec3& p) = nullptr;
    glm::vec3 centre{0.0f};
    glm::vec3 size{0.0f}; ///< box: edge lengths; sphere: (r, inner r or 0, 0); torus: (R, r, 0); knot: (scale, tube r, 0)
    std::vector<glm::vec3> line; ///< torus knot: its centre line, closed
    float distance(const glm::vec3& p) const { return signedDistance(*this, p); }
};

/// Axis-aligned box from `lo` to `hi`, 12 triangles.
Solid box(const glm::vec3& lo, const glm::vec3& hi);
/// UV sphere with `segments` around and `segments/2` rings (>= 8).
Solid sphere(const glm::vec3& centre, float radius, std::uint32_t segments);
/// Torus around the z axis: major radius R, minor radius r.
Solid torus(const glm::vec3& centre, float majorRadius, float minorRadius, std::uint32_t segments);
/// Hollow shell: sphere of `outer` radius with a sphere of `inner` radius cut
/// out (inner surface facing inwards). Two shells in one mesh.
Solid shell(const glm::vec3& centre, float outer, float inner, std::uint32_t segments);
/// Two overlapping boxes in one mesh, each closed and outward facing, not
/// merged: the overlap is crossed twice, so parity calls it outside while
/// non-zero winding calls it inside (the ideal solid is the union).
Solid overlappingBoxes(const glm::vec3& loA, const glm::vec3& hiA, const glm::vec3& loB, const glm::vec3& hiB);

/// A (p, q) torus knot as a closed tube: its centre line winds p times
/// around the z axis and q times around the core of a torus of radii
/// (scale, 0.4 scale) centred at `centre`; the tube's radius is
/// `tubeRadius` (below 0.4 scale: the strands pass 0.8 scale apart for
/// (2, 3), and bend no tighter than 0.76 scale). `segments` rings of
/// `tubeSegments` vertices: 2 * segments * tubeSegments triangles (the
/// benchmark's trefoil, 1800 x 64, has 230,400). The distance is to the
/// centre line as a polyline of `segments` pieces, minus the radius.
Solid torusKnot(const glm::vec3& centre, float scale, std::uint32_t p, std::uint32_t q, float tubeRadius,
                std::uint32_t segments, std::uint32_t tubeSegments);
/// Two cubes of edge `size` in one mesh, the second moved by (size, size, 0):
/// they touch along one vertical edge, which four triangles use. Closed and
/// consistently oriented, so both rules define the union, but not manifold:
/// what users' meshes often look like.
Solid boxesSharingAnEdge(const glm::vec3& lo, float size);

/// Merges several solids' meshes into one (indices rebased).
TriangleMesh merge(const TriangleMesh& a, const TriangleMesh& b);

// Open meshes, for the generalized winding number.

/// A UV sphere of radius 1 at the origin, `rings` x `segments` quads, keeping
/// the quads whose centre (normalized) `keep` accepts: shells with openings,
/// punched holes and the like.
TriangleMesh openSphere(int rings, int segments, const std::function<bool(const glm::vec3&)>& keep);
/// A soup of `count` loose triangles: each a centre uniform in [-1, 1]^3
/// (std::mt19937 seeded `seed`), then its three corners that centre plus
/// `size` times a point uniform in [-1, 1]^3. Every edge is a boundary edge.
TriangleMesh looseTriangles(std::uint32_t count, float size, std::uint32_t seed);
/// `mesh` without the triangles whose centroid `drop` picks.
TriangleMesh without(const TriangleMesh& mesh, bool (*drop)(const glm::vec3& centroid));
/// The unit sphere at the origin (32 segments) without its cap above z = 0.5:
/// a cup, one boundary loop.
TriangleMesh sphereCup();
/// The unit sphere at the origin (32 segments) with three holes: |x| > 0.8
/// (two) and y > 0.7, z > 0.
TriangleMesh sphereWithHoles();
/// Two overlapping spheres (24 segments), each with a hole: self-intersecting and open.
TriangleMesh overlappingShells();
/// A bowl: the half of a unit sphere with y <= 0, its rim the circle of
/// radius 1 exactly in the plane y = 0 (rim vertices have y == 0.0f).
TriangleMesh flatRimBowl(int rings, int segments);
/// The bowl (16 rings, 64 segments) with a disk of radius 0.6 hung inside at
/// y = -0.2: the points just above the rim are inside by the generalized
/// winding rule although they lie outside the box of any sprite of it.
TriangleMesh bowlWithDisk();

} // namespace vds::solids
