// libigl's AABB tree (igl::AABB, the tree under igl::signed_distance and
// igl::point_mesh_squared_distance), header-only from a libigl checkout
// named by VDS_LIBIGL_DIR: squared_distance per point over double vertices,
// as libigl's own examples hold a mesh (Eigen::MatrixXd, Eigen::MatrixXi).
#include "distance_peer.h"

#include <cmath>
#include <string>

#include <Eigen/Core>
#include <igl/AABB.h>

namespace vds::peers {

namespace {

class LibiglDistance final : public DistancePeer {
public:
    explicit LibiglDistance(MeshView mesh) : vertices_(mesh.positionCount, 3), faces_(mesh.triangleCount, 3) {
        for (std::size_t v = 0; v < mesh.positionCount; ++v)
            for (int a = 0; a < 3; ++a) vertices_(Eigen::Index(v), a) = mesh.positions[v][a];
        for (std::size_t f = 0; f < mesh.triangleCount; ++f)
            for (int a = 0; a < 3; ++a) faces_(Eigen::Index(f), a) = int(mesh.triangles[f][a]);
        tree_.init(vertices_, faces_);
    }
    std::string name() const override { return "libigl AABB squared_distance"; }
    void distances(const std::vector<glm::vec3>& points, double* out) const override {
        Eigen::RowVector3d closest;
        int face = -1;
        for (std::size_t k = 0; k < points.size(); ++k) {
            const Eigen::RowVector3d p(points[k].x, points[k].y, points[k].z);
            out[k] = std::sqrt(tree_.squared_distance(vertices_, faces_, p, face, closest));
        }
    }

private:
    Eigen::MatrixXd vertices_;
    Eigen::MatrixXi faces_;
    igl::AABB<Eigen::MatrixXd, 3> tree_;
};

} // namespace

std::unique_ptr<DistancePeer> makeLibiglDistance(MeshView mesh) { return std::make_unique<LibiglDistance>(mesh); }

} // namespace vds::peers
