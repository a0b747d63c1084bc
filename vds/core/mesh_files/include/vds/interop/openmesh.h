// vds: meshes from OpenMesh (its TriMesh or PolyMesh over the array kernel).
// Header-only; a program that includes it links OpenMesh itself
// (libopenmesh-dev; find_package(OpenMesh), target OpenMeshCore).
//
//   MyMesh om;  OpenMesh::IO::read_mesh(om, path);    // the application's own
//   const vds::AdaptedMesh mesh = vds::fromOpenMesh(om);
//
// Positions are viewed in place when the mesh's points are three floats
// (OpenMesh::Vec3f, the default traits); faces are always copied (OpenMesh
// keeps them as halfedge cycles): triangles as they are, polygons fanned from
// their first vertex. Faces marked deleted (before garbage collection) are
// left out; deleted vertices stay as unused positions.
#pragma once

#include <cstdint>
#include <type_traits>

#include <OpenMesh/Core/Mesh/Attributes.hh>

#include <vds/interop/adapted_mesh.h>

namespace vds {

template <class OpenMeshMesh> AdaptedMesh fromOpenMesh(const OpenMeshMesh& om) {
    using Point = typename OpenMeshMesh::Point;
    AdaptedMesh mesh;
    const std::size_t nv = om.n_vertices();
    if constexpr (std::is_same<typename Point::value_type, float>::value && sizeof(Point) == 3 * sizeof(float)) {
        mesh.viewPositions(nv ? reinterpret_cast<const glm::vec3*>(om.points()) : nullptr, nv);
    } else {
        std::vector<glm::vec3>& p = mesh.copyPositions(nv);
        for (std::size_t i = 0; i < nv; ++i) {
            const Point& q = om.point(typename OpenMeshMesh::VertexHandle(int(i)));
            p[i] = glm::vec3(float(q[0]), float(q[1]), float(q[2]));
        }
    }
    std::size_t count = 0;
    const bool deleted = om.has_face_status();
    for (auto f : om.faces()) {
        if (deleted && om.status(f).deleted()) continue;
        const std::size_t valence = om.valence(f);
        if (valence >= 3) count += valence - 2;
    }
    std::vector<glm::uvec3>& t = mesh.copyTriangles(count);
    std::size_t at = 0;
    std::vector<std::uint32_t> cycle;
    for (auto f : om.faces()) {
        if (deleted && om.status(f).deleted()) continue;
        cycle.clear();
        for (auto v : om.fv_range(f)) cycle.push_back(std::uint32_t(v.idx()));
        for (std::size_t k = 1; k + 1 < cycle.size(); ++k) t[at++] = glm::uvec3(cycle[0], cycle[k], cycle[k + 1]);
    }
    return mesh;
}

} // namespace vds
