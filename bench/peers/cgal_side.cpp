// CGAL::Side_of_triangle_mesh (CGAL's Polygon Mesh Processing package):
// parity of the crossings of a ray cast through an AABB tree, decided with
// exact predicates; a ray that meets an edge or a vertex is thrown away and
// another one, in a random direction, is cast instead.
#include "cgal_side.h"

#include <stdexcept>
#include <vector>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/version.h>

namespace vds::peers {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using SurfaceMesh = CGAL::Surface_mesh<Point>;
using Side = CGAL::Side_of_triangle_mesh<SurfaceMesh, Kernel>;

SurfaceMesh toSurfaceMesh(MeshView mesh) {
    SurfaceMesh out;
    std::vector<SurfaceMesh::Vertex_index> vertices(mesh.positionCount);
    for (std::size_t v = 0; v < mesh.positionCount; ++v) {
        const glm::vec3& p = mesh.positions[v];
        vertices[v] = out.add_vertex(Point(p.x, p.y, p.z));
    }
    for (std::size_t f = 0; f < mesh.triangleCount; ++f) {
        const glm::uvec3& t = mesh.triangles[f];
        if (out.add_face(vertices[t.x], vertices[t.y], vertices[t.z]) == SurfaceMesh::null_face())
            throw std::runtime_error("CGAL: Surface_mesh rejected triangle " + std::to_string(f) +
                                     " (non-manifold or inconsistently oriented)");
    }
    return out;
}

class CgalSide final : public Classifier {
public:
    explicit CgalSide(MeshView mesh) : mesh_(toSurfaceMesh(mesh)), side_(mesh_) {
        side_(Point(0.0, 0.0, 0.0)); // builds the AABB tree now, not in the first timed query
    }

    Method method() const override { return Method::Custom; }
    std::uint8_t rules() const override { return 1u << unsigned(Rule::Parity); }
    std::string summary() const override { return cgalVersion() + " Side_of_triangle_mesh on 1 thread"; }
    std::size_t memoryBytes() const override { return 0; } // CGAL does not say

protected:
    // One thread, as users get it: `options.threads` is not used.
    void classifyFloats(const float* xyz, std::size_t count, std::size_t strideBytes, std::uint8_t* labels,
                        const ClassifyOptions&) const override {
        for (std::size_t k = 0; k < count; ++k) {
            const float* p = reinterpret_cast<const float*>(reinterpret_cast<const char*>(xyz) + k * strideBytes);
            labels[k] = side_(Point(p[0], p[1], p[2])) != CGAL::ON_UNBOUNDED_SIDE ? 1 : 0;
        }
    }

private:
    SurfaceMesh mesh_; // before side_, which keeps a pointer to it
    Side side_;
};

} // namespace

std::unique_ptr<Classifier> makeCgalSide(MeshView mesh) { return std::make_unique<CgalSide>(mesh); }

std::string cgalVersion() { return "CGAL " CGAL_VERSION_STR; }

} // namespace vds::peers
