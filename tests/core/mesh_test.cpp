// Mesh validation, on meshes built in code.
#include <cmath>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <vds/error.h>
#include <vds/exact.h>
#include <vds/mesh.h>
#include <vds/sprite.h>
#include "solids.h"

#include "../support/points.h"

namespace vds {
namespace {

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
    EXPECT_EQ(r.oddNonManifoldEdges, 1u);
    EXPECT_EQ(r.boundaryEdges, 2u);

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

TEST(ValidateMesh, SolidsTouchingAlongAnEdgeAreClosedButNotManifold) {
    const auto boxes = solids::boxesSharingAnEdge({0, 0, 0}, 1.0f);
    const MeshReport r = validateMesh(boxes.mesh);
    EXPECT_EQ(r.nonManifoldEdges, 1u);
    EXPECT_EQ(r.oddNonManifoldEdges, 0u);
    EXPECT_EQ(r.boundaryEdges, 0u);
    EXPECT_EQ(r.inconsistentEdges, 0u);
    EXPECT_TRUE(r.closed());
    EXPECT_TRUE(r.oriented());
    EXPECT_FALSE(r.manifold());
    EXPECT_EQ(r.summary(), "closed, 1 non-manifold edge, 24 triangles, 16 vertices");
    EXPECT_NO_THROW(requireInsideDefined(r, "boxes.obj", Rule::Parity));
    EXPECT_NO_THROW(requireInsideDefined(r, "boxes.obj", Rule::Winding));
    EXPECT_EQ(insideWarning(r, Rule::Parity),
              "1 non-manifold edge (more than two triangles on an edge); inside is still defined by the parity rule");
    EXPECT_EQ(insideWarning(validateMesh(solids::box({0, 0, 0}, {1, 1, 1}).mesh), Rule::Winding), "");
}

TEST(ValidateMesh, AnEdgeOfThreeTrianglesLeavesInsideUndefined) {
    // Two boxes sharing a wall that is there once: its four edges carry three
    // triangles each, so a ray's parity changes across them as across a hole.
    const auto a = solids::box({0, 0, 0}, {1, 1, 1}).mesh, b = solids::box({1, 0, 0}, {2, 1, 1}).mesh;
    TriangleMesh theta = a; // a whole, the shared wall (a's x = 1 side, triangles 10 and 11) included
    auto withoutLowXSide = b;
    withoutLowXSide.triangles.erase(withoutLowXSide.triangles.begin() + 8, withoutLowXSide.triangles.begin() + 10);
    theta = solids::merge(theta, withoutLowXSide);
    theta.triangles.erase(theta.triangles.begin() + 10, theta.triangles.begin() + 12);
    theta.triangles.push_back(a.triangles[10]);
    theta.triangles.push_back(a.triangles[11]);
    const MeshReport r = validateMesh(theta);
    EXPECT_EQ(r.boundaryEdges, 0u);
    EXPECT_EQ(r.nonManifoldEdges, 4u);
    EXPECT_EQ(r.oddNonManifoldEdges, 4u);
    EXPECT_FALSE(r.closed());
    EXPECT_NE(r.summary().find("open (4 edges shared by an odd number of triangles)"), std::string::npos)
        << r.summary();
    EXPECT_THROW(requireInsideDefined(r, "theta.obj", Rule::Parity), InvalidMesh);
}

TEST(ValidateMesh, CountsDuplicateTrianglesIsolatedVerticesAndOrientationConflicts) {
    auto m = solids::box({0, 0, 0}, {1, 1, 1}).mesh;
    m.triangles.push_back(m.triangles[0]);                                                // same orientation
    m.triangles.push_back({m.triangles[1].x, m.triangles[1].z, m.triangles[1].y});       // reversed
    m.positions.push_back({5, 5, 5});                                                     // used by nothing
    m.positions.push_back(m.positions[0]);                                                // unused, but its twin is used
    const MeshReport r = validateMesh(m);
    EXPECT_EQ(r.duplicateTriangles, 2u);
    EXPECT_EQ(r.isolatedVertices, 1u);
    EXPECT_EQ(r.vertexCount, 10u);
    EXPECT_NE(r.summary().find("2 duplicate triangles, 1 isolated vertex"), std::string::npos) << r.summary();

    auto flipped = solids::box({0, 0, 0}, {1, 1, 1}).mesh;
    std::swap(flipped.triangles[0].y, flipped.triangles[0].z);
    const MeshReport f = validateMesh(flipped);
    EXPECT_EQ(f.inconsistentEdges, 3u);
    EXPECT_TRUE(f.closed());
    EXPECT_FALSE(f.oriented());
    EXPECT_EQ(f.summary(), "closed, 3 inconsistently oriented edges, 12 triangles, 8 vertices");
    EXPECT_NO_THROW(requireInsideDefined(f, "flipped.obj", Rule::Parity));
    EXPECT_EQ(insideWarning(f, Rule::Parity),
              "3 inconsistently oriented edges; inside is still defined by the parity rule");
    try {
        requireInsideDefined(f, "flipped.obj", Rule::Winding);
        FAIL() << "winding accepted with orientation conflicts";
    } catch (const InvalidMesh& e) {
        EXPECT_STREQ(e.what(), "flipped.obj has 3 inconsistently oriented edges: inside is not defined by the "
                               "winding rule; the parity rule defines it");
    }
}

TEST(ValidateMesh, OpenMeshesHaveNoInsideAndTheMessageSaysWhatAnswers) {
    auto open = solids::box({0, 0, 0}, {1, 1, 1}).mesh;
    open.triangles.pop_back();
    EXPECT_NO_THROW(requireInsideDefined(validateMesh(open), "open.obj", Rule::GeneralizedWinding));
    for (Rule rule : {Rule::Parity, Rule::Winding}) {
        try {
            requireInsideDefined(validateMesh(open), "open.obj", rule);
            FAIL() << "open mesh accepted";
        } catch (const InvalidMesh& e) {
            EXPECT_EQ(std::string(e.what()), std::string("open.obj is open (3 boundary edges): inside is not defined "
                                                         "by the ") +
                                                 toString(rule) +
                                                 " rule; the generalized-winding rule answers for it (exactly), and "
                                                 "a sprite baked from it still answers by crossing count");
        }
    }
    EXPECT_THROW(requireInsideDefined(validateMesh(TriangleMesh{}), "empty.obj", Rule::Parity), InvalidMesh);
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

} // namespace
} // namespace vds
