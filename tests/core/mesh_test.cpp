// Mesh validation and the OpenMesh loaders, on meshes built in code.
#include <cmath>
#include <filesystem>
#include <fstream>

#include <unistd.h>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <vds/error.h>
#include <vds/exact.h>
#include <vds/mesh.h>
#include <vds/mesh_io.h>
#include "solids.h"

#include "../support/points.h"

namespace vds {
namespace {

namespace fs = std::filesystem;

fs::path tempDir() {
    const fs::path d = fs::temp_directory_path() / ("vds_mesh_test_" + std::to_string(::getpid()));
    fs::create_directories(d);
    return d;
}

void writeText(const fs::path& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }

std::string boxObj() {
    const auto box = solids::box({0, 0, 0}, {1, 2, 3});
    std::string s;
    for (const auto& v : box.mesh.positions)
        s += "v " + std::to_string(v.x) + " " + std::to_string(v.y) + " " + std::to_string(v.z) + "\n";
    for (const auto& t : box.mesh.triangles)
        s += "f " + std::to_string(t.x + 1) + " " + std::to_string(t.y + 1) + " " + std::to_string(t.z + 1) + "\n";
    return s;
}

TEST(ValidateMesh, GeneratedSolidsAreClosed) {
    for (const auto& s : {solids::box({0, 0, 0}, {1, 1, 1}), solids::sphere({0, 0, 0}, 1, 32),
                          solids::torus({0, 0, 0}, 1, 0.3f, 32), solids::shell({0, 0, 0}, 1, 0.5f, 32),
                          solids::overlappingBoxes({0, 0, 0}, {1, 1, 1}, {0.5f, 0.5f, 0.5f}, {2, 2, 2})}) {
        const MeshReport r = validateMesh(s.mesh);
        EXPECT_TRUE(r.closed()) << s.mesh.name << ": " << r.summary();
        EXPECT_TRUE(r.usable());
        EXPECT_EQ(r.degenerateTriangles, 0u) << s.mesh.name;
    }
}

// The benchmark's trefoil: closed, facing out (positive volume, about the
// tube's cross-section times the centre line's length), inside along its
// centre line and outside away from the tube.
TEST(ValidateMesh, TorusKnotIsAClosedTubeFacingOut) {
    const auto knot = solids::torusKnot({0.5f, -0.5f, 0.25f}, 2.0f, 2, 3, 0.2f, 300, 24);
    EXPECT_EQ(knot.mesh.triangles.size(), 2u * 300u * 24u);
    const MeshReport r = validateMesh(knot.mesh);
    EXPECT_TRUE(r.closed()) << r.summary();
    EXPECT_EQ(r.degenerateTriangles, 0u);
    double volume = 0.0, length = 0.0;
    for (const auto& t : knot.mesh.triangles) {
        const glm::dvec3 a(knot.mesh.positions[t.x]), b(knot.mesh.positions[t.y]), c(knot.mesh.positions[t.z]);
        volume += glm::dot(a, glm::cross(b, c)) / 6.0;
    }
    for (std::size_t i = 0; i < knot.line.size(); ++i)
        length += glm::length(glm::dvec3(knot.line[(i + 1) % knot.line.size()] - knot.line[i]));
    const double tube = 3.14159265358979 * 0.2 * 0.2 * length;
    EXPECT_NEAR(volume, tube, 0.03 * tube);
    const ExactClassifier exact(knot.mesh);
    for (std::size_t i = 0; i < knot.line.size(); i += 7) {
        EXPECT_TRUE(exact.contains(knot.line[i])) << "centre line point " << i;
        EXPECT_LT(knot.distance(knot.line[i]), -0.19f);
    }
    const auto points = test::randomPoints(r.bounds, 3000, 0.1f, 4);
    std::size_t far = 0;
    for (const auto& p : points) {
        const float d = knot.distance(p);
        if (std::fabs(d) < 0.05f) continue;
        ++far;
        EXPECT_EQ(exact.contains(p), d < 0.0f) << "distance " << d;
    }
    EXPECT_GT(far, 2000u);
}

TEST(ValidateMesh, FindsBoundaryNonManifoldFlippedAndDegenerateFaces) {
    auto open = solids::box({0, 0, 0}, {1, 1, 1}).mesh;
    open.triangles.pop_back();
    MeshReport r = validateMesh(open);
    EXPECT_EQ(r.boundaryEdges, 3u);
    EXPECT_FALSE(r.closed());
    EXPECT_NE(r.summary().find("3 boundary edges"), std::string::npos) << r.summary();

    auto fin = solids::box({0, 0, 0}, {1, 1, 1}).mesh; // a fin: a third triangle on an existing edge
    fin.positions.push_back({0.5f, -1.0f, 0.0f});
    fin.triangles.push_back({0, 1, std::uint32_t(fin.positions.size() - 1)});
    r = validateMesh(fin);
    EXPECT_EQ(r.nonManifoldEdges, 1u);

    auto flipped = solids::box({0, 0, 0}, {1, 1, 1}).mesh;
    std::swap(flipped.triangles[0].y, flipped.triangles[0].z);
    r = validateMesh(flipped);
    EXPECT_GT(r.inconsistentEdges, 0u);

    auto degenerate = solids::box({0, 0, 0}, {1, 1, 1}).mesh;
    degenerate.triangles.push_back({0, 0, 1});
    r = validateMesh(degenerate);
    EXPECT_EQ(r.degenerateTriangles, 1u);
    EXPECT_TRUE(r.closed()); // a collapsed triangle adds no edges
}

TEST(ValidateMesh, DuplicatedVerticesAreWeldedByPosition) {
    TriangleMesh soup; // the box as a triangle soup: every triangle has its own vertices
    const auto box = solids::box({0, 0, 0}, {1, 1, 1}).mesh;
    for (const auto& t : box.triangles) {
        const auto base = std::uint32_t(soup.positions.size());
        for (int k = 0; k < 3; ++k) soup.positions.push_back(box.positions[t[k]]);
        soup.triangles.push_back({base, base + 1, base + 2});
    }
    EXPECT_TRUE(validateMesh(soup).closed());
}

TEST(ValidateMesh, UnusableMeshesAreRefused) {
    EXPECT_THROW(requireUsable(validateMesh(TriangleMesh{}), "empty.obj"), InvalidMesh);
    auto nan = solids::box({0, 0, 0}, {1, 1, 1}).mesh;
    nan.positions[0].x = std::nanf("");
    EXPECT_EQ(validateMesh(nan).nonFiniteVertices, 1u);
    EXPECT_THROW(requireUsable(validateMesh(nan), "nan.obj"), InvalidMesh);
    auto inf = solids::box({0, 0, 0}, {1, 1, 1}).mesh;
    inf.positions[1].z = INFINITY;
    EXPECT_THROW(requireUsable(validateMesh(inf), "inf.obj"), InvalidMesh);
    auto bad = solids::box({0, 0, 0}, {1, 1, 1}).mesh;
    bad.triangles[2].x = 1000;
    EXPECT_EQ(validateMesh(bad).badIndices, 1u);
    EXPECT_THROW(requireUsable(validateMesh(bad), "bad.obj"), InvalidMesh);
}

TEST(LoadMesh, ReadsObjPlyStlAndOff) {
    const fs::path d = tempDir();
    writeText(d / "box.obj", boxObj());
    const TriangleMesh obj = loadMesh((d / "box.obj").string());
    EXPECT_EQ(obj.triangles.size(), 12u);
    EXPECT_TRUE(validateMesh(obj).closed());
    EXPECT_EQ(obj.name, "box.obj");

    // OFF with quads: fan-triangulated.
    writeText(d / "cube.off", "OFF\n8 6 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n0 0 1\n1 0 1\n0 1 1\n1 1 1\n"
                              "4 0 2 3 1\n4 4 5 7 6\n4 0 1 5 4\n4 2 6 7 3\n4 0 4 6 2\n4 1 3 7 5\n");
    const TriangleMesh off = loadMesh((d / "cube.off").string());
    EXPECT_EQ(off.triangles.size(), 12u);
    EXPECT_TRUE(validateMesh(off).closed()) << validateMesh(off).summary();

    writeText(d / "tet.ply", "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                             "property float z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n"
                             "0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n");
    const TriangleMesh ply = loadMesh((d / "tet.ply").string());
    EXPECT_EQ(ply.triangles.size(), 4u);
    EXPECT_TRUE(validateMesh(ply).closed());

    std::string stl = "solid t\n";
    const glm::vec3 v[4] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    const int f[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    for (const auto& t : f) {
        stl += "facet normal 0 0 0\nouter loop\n";
        for (int k : t)
            stl += "vertex " + std::to_string(v[k].x) + " " + std::to_string(v[k].y) + " " + std::to_string(v[k].z) + "\n";
        stl += "endloop\nendfacet\n";
    }
    writeText(d / "tet.stl", stl + "endsolid t\n");
    const TriangleMesh st = loadMesh((d / "tet.stl").string());
    EXPECT_EQ(st.triangles.size(), 4u);
    EXPECT_TRUE(validateMesh(st).closed()) << validateMesh(st).summary();
    fs::remove_all(d);
}

TEST(LoadMesh, BadFilesGiveOneLineErrors) {
    const fs::path d = tempDir();
    EXPECT_THROW(loadMesh((d / "missing.obj").string()), IoError);
    EXPECT_THROW(loadMesh((d / "mesh.xyz").string()), FormatError);
    writeText(d / "empty.obj", "");
    EXPECT_THROW(loadMesh((d / "empty.obj").string()), FormatError);
    writeText(d / "garbage.ply", "this is not a ply file\n\x01\x02\x03");
    EXPECT_THROW(loadMesh((d / "garbage.ply").string()), FormatError);
    writeText(d / "truncated.off", "OFF\n8 6 0\n0 0 0\n1 0 0\n");
    try {
        const TriangleMesh m = loadMesh((d / "truncated.off").string());
        EXPECT_FALSE(validateMesh(m).usable()); // if parsed at all, it cannot be baked
    } catch (const FormatError& e) {
        EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    }
    fs::remove_all(d);
}

TEST(LoadPoints, ReadsTextAndPlyAndRejectsBadLines) {
    const fs::path d = tempDir();
    writeText(d / "p.txt", "# comment\n1 2 3\n\n  -4.5 5e-1 6\r\n");
    const auto p = loadPoints((d / "p.txt").string());
    ASSERT_EQ(p.size(), 2u);
    EXPECT_EQ(p[1], glm::vec3(-4.5f, 0.5f, 6.0f));
    writeText(d / "p.ply", "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
                           "property float z\nend_header\n1 2 3\n4 5 6\n");
    EXPECT_EQ(loadPoints((d / "p.ply").string()).size(), 2u);
    writeText(d / "nan.txt", "1 2 3\nnan 0 0\n");
    try {
        loadPoints((d / "nan.txt").string());
        FAIL() << "NaN accepted";
    } catch (const FormatError& e) {
        EXPECT_NE(std::string(e.what()).find(":2:"), std::string::npos) << e.what();
    }
    writeText(d / "two.txt", "1 2\n3 4 5\n");
    EXPECT_THROW(loadPoints((d / "two.txt").string()), FormatError);
    writeText(d / "four.txt", "1 2 3 4\n");
    EXPECT_THROW(loadPoints((d / "four.txt").string()), FormatError);
    writeText(d / "words.txt", "x y z\n");
    EXPECT_THROW(loadPoints((d / "words.txt").string()), FormatError);
    EXPECT_THROW(loadPoints((d / "none.txt").string()), IoError);
    fs::remove_all(d);
}

} // namespace
} // namespace vds
