// Meshes from Eigen (libigl's V, F) and OpenMesh through the header-only
// adapters: viewed in place where the layout allows, copied otherwise, and
// the same mesh to vds either way (validation and exact labels equal those
// of the TriangleMesh the matrices were filled from).
#include <vector>

#include <gtest/gtest.h>

#include <vds/error.h>
#include <vds/exact.h>
#include <vds/mesh.h>

#if VDS_TEST_EIGEN
#include <vds/interop/eigen.h>
#endif
#if VDS_TEST_OPENMESH
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <vds/interop/openmesh.h>
#include <vds/mesh_check.h>
#endif

#include "points.h"
#include "solids.h"

namespace vds {
namespace {

// Labels of random points around `mesh` by the exact classifier, winding rule.
std::vector<std::uint8_t> labels(MeshView mesh, const std::vector<glm::vec3>& points) {
    const ExactClassifier exact(mesh);
    std::vector<std::uint8_t> out(points.size());
    ClassifyOptions o;
    o.rule = Rule::Winding;
    exact.classify(points, out.data(), o);
    return out;
}

const TriangleMesh& torus() {
    static const TriangleMesh m = solids::torus({0.2f, 0.0f, -0.1f}, 1.0f, 0.4f, 24).mesh;
    return m;
}

#if VDS_TEST_EIGEN
TEST(Eigen, RowMajorFloatAndIntAreViewedInPlace) {
    const TriangleMesh& m = torus();
    Eigen::Matrix<float, Eigen::Dynamic, 3, Eigen::RowMajor> V(m.positions.size(), 3);
    Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor> F(m.triangles.size(), 3);
    for (std::size_t i = 0; i < m.positions.size(); ++i) V.row(Eigen::Index(i)) << m.positions[i].x, m.positions[i].y, m.positions[i].z;
    for (std::size_t i = 0; i < m.triangles.size(); ++i)
        F.row(Eigen::Index(i)) << int(m.triangles[i].x), int(m.triangles[i].y), int(m.triangles[i].z);
    const AdaptedMesh mesh = fromEigen(V, F);
    EXPECT_FALSE(mesh.positionsCopied());
    EXPECT_FALSE(mesh.trianglesCopied());
    EXPECT_EQ(static_cast<const void*>(mesh.view().positions), static_cast<const void*>(V.data()));
    EXPECT_EQ(static_cast<const void*>(mesh.view().triangles), static_cast<const void*>(F.data()));
    const auto points = test::randomPoints(meshBounds(m), 4000);
    EXPECT_EQ(labels(mesh, points), labels(m, points));
}

TEST(Eigen, LibiglsColumnMajorDoublesAreCopiedAndAgree) {
    const TriangleMesh& m = torus();
    Eigen::MatrixXd V(m.positions.size(), 3);
    Eigen::MatrixXi F(m.triangles.size(), 3);
    for (std::size_t i = 0; i < m.positions.size(); ++i)
        for (int c = 0; c < 3; ++c) V(Eigen::Index(i), c) = m.positions[i][c];
    for (std::size_t i = 0; i < m.triangles.size(); ++i)
        for (int c = 0; c < 3; ++c) F(Eigen::Index(i), c) = int(m.triangles[i][c]);
    AdaptedMesh mesh = fromEigen(V, F);
    EXPECT_TRUE(mesh.positionsCopied());
    EXPECT_TRUE(mesh.trianglesCopied());
    const AdaptedMesh moved = std::move(mesh); // the view follows the copy
    EXPECT_EQ(validateMesh(moved).summary(), validateMesh(m).summary());
    const auto points = test::randomPoints(meshBounds(m), 4000);
    EXPECT_EQ(labels(moved, points), labels(m, points));
}

TEST(Eigen, BadMatricesAreRefused) {
    Eigen::MatrixXd V = Eigen::MatrixXd::Zero(4, 3);
    Eigen::MatrixXi F(1, 3);
    F << 0, 1, -2;
    EXPECT_THROW(fromEigen(V, F), InvalidMesh);
    Eigen::MatrixXi quads(1, 4);
    quads << 0, 1, 2, 3;
    EXPECT_THROW(fromEigen(V, quads), InvalidMesh);
    Eigen::MatrixXd flat(4, 2);
    F << 0, 1, 2;
    EXPECT_THROW(fromEigen(flat, F), InvalidMesh);
    // Indices past V's rows are the validator's to name.
    F << 0, 1, 9;
    const AdaptedMesh past = fromEigen(V, F);
    EXPECT_THROW(ExactClassifier{past}, InvalidMesh);
}
#endif

#if VDS_TEST_OPENMESH
template <class Mesh> Mesh toOpenMesh(const TriangleMesh& m) {
    Mesh om;
    std::vector<typename Mesh::VertexHandle> v;
    for (const glm::vec3& p : m.positions) v.push_back(om.add_vertex(typename Mesh::Point(p.x, p.y, p.z)));
    for (const glm::uvec3& t : m.triangles) om.add_face(v[t.x], v[t.y], v[t.z]);
    return om;
}

TEST(OpenMesh, TriMeshPositionsAreViewedAndFacesCopied) {
    using Mesh = OpenMesh::TriMesh_ArrayKernelT<>;
    const TriangleMesh& m = torus();
    const Mesh om = toOpenMesh<Mesh>(m);
    ASSERT_EQ(om.n_faces(), m.triangles.size());
    const AdaptedMesh mesh = fromOpenMesh(om);
    EXPECT_FALSE(mesh.positionsCopied());
    EXPECT_TRUE(mesh.trianglesCopied());
    EXPECT_EQ(mesh.view().triangleCount, m.triangles.size());
    const auto points = test::randomPoints(meshBounds(m), 4000);
    EXPECT_EQ(labels(mesh, points), labels(m, points));
}

struct DoubleTraits : OpenMesh::DefaultTraits {
    using Point = OpenMesh::Vec3d;
};

TEST(OpenMesh, PolygonsAreFannedAndDeletedFacesLeftOut) {
    using Mesh = OpenMesh::PolyMesh_ArrayKernelT<DoubleTraits>;
    // A unit cube of six quads, outward.
    Mesh om;
    std::vector<Mesh::VertexHandle> v;
    for (int k = 0; k < 8; ++k) v.push_back(om.add_vertex(Mesh::Point(k & 1, (k >> 1) & 1, (k >> 2) & 1)));
    const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& q : quads) ASSERT_TRUE(om.add_face(v[q[0]], v[q[1]], v[q[2]], v[q[3]]).is_valid());
    const AdaptedMesh cube = fromOpenMesh(om);
    EXPECT_TRUE(cube.positionsCopied());
    EXPECT_EQ(cube.view().triangleCount, 12u);
    const MeshReport report = validateMesh(cube);
    EXPECT_TRUE(report.closed()) << report.summary();
    EXPECT_TRUE(report.oriented()) << report.summary();
    const ExactClassifier exact(cube);
    EXPECT_TRUE(exact.contains({0.5f, 0.5f, 0.5f}, Rule::Winding));
    EXPECT_FALSE(exact.contains({1.5f, 0.5f, 0.5f}, Rule::Winding));

    om.request_face_status();
    om.delete_face(*om.faces_begin(), false);
    const AdaptedMesh open = fromOpenMesh(om);
    EXPECT_EQ(open.view().triangleCount, 10u);
    EXPECT_FALSE(validateMesh(open).closed());
}
#endif

} // namespace
} // namespace vds
