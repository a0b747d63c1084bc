// fcpw ("Fastest Closest Points in the West", Sawhney): its vectorized
// bounding volume hierarchy (enoki packets as wide as the machine's widest
// float SIMD, -march=native as fcpw's own build sets it) over one triangle
// object, built by the surface-area heuristic, asked one point at a time
// with findClosestPoint, in float.
#include "distance_peer.h"

#include <memory>
#include <string>
#include <vector>

#include <fcpw/fcpw.h>

namespace vds::peers {

namespace {

class FcpwDistance final : public DistancePeer {
public:
    explicit FcpwDistance(MeshView mesh) {
        std::vector<fcpw::Vector3> positions(mesh.positionCount);
        for (std::size_t k = 0; k < mesh.positionCount; ++k)
            positions[k] = fcpw::Vector3(mesh.positions[k].x, mesh.positions[k].y, mesh.positions[k].z);
        std::vector<fcpw::Vector3i> triangles(mesh.triangleCount);
        for (std::size_t k = 0; k < mesh.triangleCount; ++k)
            triangles[k] = fcpw::Vector3i(int(mesh.triangles[k].x), int(mesh.triangles[k].y), int(mesh.triangles[k].z));
        scene_.setObjectCount(1);
        scene_.setObjectVertices(positions, 0);
        scene_.setObjectTriangles(triangles, 0);
        scene_.build(fcpw::AggregateType::Bvh_SurfaceArea, true);
    }

    std::string name() const override {
        return "fcpw " + std::to_string(FCPW_SIMD_WIDTH) + "-wide leaves, " +
               std::to_string(FCPW_MBVH_BRANCHING_FACTOR) + "-wide nodes";
    }

    void distances(const std::vector<glm::vec3>& points, double* out) const override {
        for (std::size_t k = 0; k < points.size(); ++k) {
            fcpw::Interaction<3> hit;
            scene_.findClosestPoint(fcpw::Vector3(points[k].x, points[k].y, points[k].z), hit);
            out[k] = double(hit.d);
        }
    }

private:
    fcpw::Scene<3> scene_;
};

} // namespace

std::unique_ptr<DistancePeer> makeFcpwDistance(MeshView mesh) { return std::make_unique<FcpwDistance>(mesh); }

} // namespace vds::peers
