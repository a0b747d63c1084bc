// vds_distance_bench: the peers' nearest-surface queries behind one shape,
// each compiled in its own library (CGAL's -frounding-math, Embree's,
// libigl's and fcpw's headers and fcpw's -march=native stay out of the vds code).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include <vds/mesh.h>

namespace vds::peers {

/// A peer's unsigned distance to a mesh, built once, asked on one thread.
class DistancePeer {
public:
    virtual ~DistancePeer() = default;
    /// "CGAL 5.5.1 AABB_tree closest point", as the table prints it.
    virtual std::string name() const = 0;
    /// Unsigned distances of `points` (one thread), `out` holds as many.
    virtual void distances(const std::vector<glm::vec3>& points, double* out) const = 0;
};

/// CGAL's AABB_tree over the triangles (Simple_cartesian<double>, as CGAL's
/// own distance examples build it), with accelerate_distance_queries().
std::unique_ptr<DistancePeer> makeCgalDistance(MeshView mesh);
/// Embree 3's rtcPointQuery over a triangle scene, with the closest point on
/// each candidate triangle in float, as Open3D's RaycastingScene computes it.
std::unique_ptr<DistancePeer> makeEmbreeDistance(MeshView mesh);
/// libigl's igl::AABB over double vertices, squared_distance per point (the
/// search under igl::signed_distance).
std::unique_ptr<DistancePeer> makeLibiglDistance(MeshView mesh);
/// fcpw's vectorized BVH (enoki packets, -march=native), findClosestPoint
/// per point in float.
std::unique_ptr<DistancePeer> makeFcpwDistance(MeshView mesh);

} // namespace vds::peers
