// vds_peers_bench: CGAL's Side_of_triangle_mesh, the robust inside test of
// CGAL's Polygon Mesh Processing, as a user gets it: a Surface_mesh over the
// Epick kernel (exact predicates, inexact constructions), queried on one
// thread.
#pragma once

#include <memory>
#include <string>

#include <vds/classify.h>
#include <vds/mesh.h>


namespace vds::peers {

/// A `Classifier` of Method::Custom, parity only. Copies the mesh into a CGAL::Surface_mesh and builds the AABB tree of
/// Side_of_triangle_mesh (CGAL builds it at the first query; the factory
/// makes that query, so the tree is part of the build). A point on the
/// surface (CGAL::ON_BOUNDARY) counts as inside. Throws `std::runtime_error`
/// if CGAL rejects a face (non-manifold input).
std::unique_ptr<Classifier> makeCgalSide(MeshView mesh);

/// "CGAL 5.5.1", the version compiled against.
std::string cgalVersion();

} // namespace vds::peers
