// The accuracy evaluation on generated solids whose answer is known.
#include <cmath>

#include <gtest/gtest.h>

#include <vds/eval/distance.h>
#include <vds/error.h>
#include <vds/eval/accuracy.h>
#include "solids.h"

#include "../support/gl_fixture.h"

namespace vds::eval {
namespace {

class EvalTest : public test::GlTest {};

TEST_F(EvalTest, ErrorsLiveWithinATexelDiagonalOfTheSurface) {
    const auto torus = solids::torus({0, 0, 0}, 1.0f, 0.4f, 64);
    EvalOptions o;
    o.resolutions = {48, 96};
    o.uniformPoints = 40000;
    o.surfacePoints = 40000;
    const EvalReport r = evaluate(torus.mesh, o, &gl());
    ASSERT_EQ(r.rows.size(), 2u);
    for (const auto& row : r.rows) {
        EXPECT_EQ(row.uniformPoints, 40000u);
        EXPECT_EQ(row.surfacePoints, 40000u);
        EXPECT_GT(row.surfaceWrong, 0u);                  // near the surface a texel grid must err...
        EXPECT_LT(row.surfaceWrong, row.surfacePoints / 5); // ...but rarely
        EXPECT_EQ(row.wrongBeyondTexelDiagonal, 0u);      // and only close to it
        EXPECT_LE(row.maxWrongDistanceTexels, std::sqrt(2.0));
        EXPECT_GT(row.fileBytes, 0u);
        EXPECT_EQ(row.denseBytes, std::size_t(row.width) * row.height * row.depthComplexity * 4);
    }
    // Finer texels, fewer wrong points among uniform ones.
    EXPECT_LE(r.rows[1].uniformWrong, r.rows[0].uniformWrong);
    const std::string json = toJson(r);
    EXPECT_NE(json.find("\"resolution\": 96"), std::string::npos);
    EXPECT_EQ(std::count(json.begin(), json.end(), '{'), std::count(json.begin(), json.end(), '}'));
    const std::string table = toTable(r);
    EXPECT_EQ(std::count(table.begin(), table.end(), '\n'), 4 + 2);
    EXPECT_EQ(table.rfind(r.mesh + ": " + std::to_string(torus.mesh.triangles.size()) + " triangles, ", 0), 0u) << table;
    const EvalRow& w = r.rows[1];
    const std::string row = "\n| 96 | " + std::to_string(w.width) + "x" + std::to_string(w.height) + "x" +
                            std::to_string(w.depthComplexity) + " | " + std::to_string(w.uniformWrong) + " / 40000 (";
    EXPECT_NE(table.find(row), std::string::npos) << row << "\nin\n" << table;
}

TEST(Distance, MatchesHandComputedCases) {
    const glm::dvec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
    EXPECT_DOUBLE_EQ(pointTriangleDistance({0.25, 0.25, 2.0}, a, b, c), 2.0); // above the face
    EXPECT_DOUBLE_EQ(pointTriangleDistance({-3.0, 0.0, 4.0}, a, b, c), 5.0);  // nearest a vertex
    EXPECT_DOUBLE_EQ(pointTriangleDistance({0.5, -1.0, 0.0}, a, b, c), 1.0);  // nearest an edge
    EXPECT_NEAR(pointTriangleDistance({1.0, 1.0, 0.0}, a, b, c), std::sqrt(0.5), 1e-12); // hypotenuse
    // Through the grid, on a box: distances to its faces, edges and corners.
    const auto box = solids::box({0, 0, 0}, {1, 2, 3});
    const SurfaceDistance d(box.mesh);
    EXPECT_NEAR(d.distance({0.5f, 1.0f, 1.5f}), 0.5, 1e-6); // centre: nearest face x = 0 or 1
    EXPECT_NEAR(d.distance({2.0f, 1.0f, 1.5f}), 1.0, 1e-6);
    EXPECT_NEAR(d.distance({-3.0f, -4.0f, 1.5f}), 5.0, 1e-6);
}

TEST(Eval, RefusesUnusableMeshes) {
    EvalOptions o;
    o.method = BakeMethod::Cpu;
    EXPECT_THROW(evaluate(TriangleMesh{}, o), InvalidMesh);
}

} // namespace
} // namespace vds::eval
