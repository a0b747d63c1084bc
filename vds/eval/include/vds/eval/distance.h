// vds: the distance of a point to a triangle mesh's surface,
// exact (closest point on each nearby triangle, Ericson, "Real-Time Collision
// Detection", 2005, section 5.1.5), found through a uniform grid of the
// triangles' boxes searched in growing rings.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include <vds/mesh.h>

namespace vds::eval {

/// Used by `vds eval` and `vds::eval::compare` to measure how far wrong
/// answers lie from the surface.
class SurfaceDistance {
public:
    /// Copies the triangles (those with valid indices). Thread safe to query.
    explicit SurfaceDistance(MeshView mesh);
    /// Distance of `p` to the nearest triangle, mesh units.
    double distance(const glm::vec3& p) const;

private:
    std::vector<glm::dvec3> corners_; // 3 per triangle
    glm::dvec3 lo_{0.0}, cell_{1.0};
    glm::ivec3 dims_{1};
    std::vector<std::uint32_t> offsets_, refs_;
};

/// Distance from p to the triangle (a, b, c).
double pointTriangleDistance(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c);

} // namespace vds::eval
