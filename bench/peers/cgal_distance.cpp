// CGAL's AABB tree (Alliez, Tayeb & Wormser, CGAL's "3D Fast Intersection
// and Distance Computation" package): the closest point on the triangles,
// searched with the tree's distance acceleration (a kd-tree of sample
// points gives the first bound).
#include "distance_peer.h"

#include <vector>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/version.h>

namespace vds::peers {

namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using Point = Kernel::Point_3;
using Triangle = Kernel::Triangle_3;
using Iterator = std::vector<Triangle>::const_iterator;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, Iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

std::vector<Triangle> toTriangles(MeshView mesh) {
    std::vector<Triangle> out;
    out.reserve(mesh.triangleCount);
    const auto point = [&](std::uint32_t v) {
        const glm::vec3& p = mesh.positions[v];
        return Point(p.x, p.y, p.z);
    };
    for (std::size_t f = 0; f < mesh.triangleCount; ++f) {
        const glm::uvec3& t = mesh.triangles[f];
        out.emplace_back(point(t.x), point(t.y), point(t.z));
    }
    return out;
}

class CgalDistance final : public DistancePeer {
public:
    explicit CgalDistance(MeshView mesh) : triangles_(toTriangles(mesh)), tree_(triangles_.begin(), triangles_.end()) {
        tree_.accelerate_distance_queries();
        tree_.squared_distance(Point(0.0, 0.0, 0.0)); // builds now, not in the first timed query
    }
    std::string name() const override { return "CGAL " CGAL_VERSION_STR " AABB_tree"; }
    void distances(const std::vector<glm::vec3>& points, double* out) const override {
        for (std::size_t k = 0; k < points.size(); ++k) {
            const glm::vec3& p = points[k];
            out[k] = std::sqrt(tree_.squared_distance(Point(p.x, p.y, p.z)));
        }
    }

private:
    std::vector<Triangle> triangles_; // before tree_, which points into it
    Tree tree_;
};

} // namespace

std::unique_ptr<DistancePeer> makeCgalDistance(MeshView mesh) { return std::make_unique<CgalDistance>(mesh); }

} // namespace vds::peers
