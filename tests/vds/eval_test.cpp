// The accuracy evaluation on generated solids whose answer is known.
#include <cmath>

#include <gtest/gtest.h>

#include <vds/error.h>
#include <vds/eval.h>
#include <vds/solids.h>

#include "../support/gl_fixture.h"

namespace vds {
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
}

TEST(PointTriangleDistance, MatchesHandComputedCases) {
    const glm::vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
    EXPECT_FLOAT_EQ(pointTriangleDistance({0.25f, 0.25f, 2.0f}, a, b, c), 2.0f);  // above the face
    EXPECT_FLOAT_EQ(pointTriangleDistance({-3.0f, 0.0f, 4.0f}, a, b, c), 5.0f);  // nearest a vertex
    EXPECT_FLOAT_EQ(pointTriangleDistance({0.5f, -1.0f, 0.0f}, a, b, c), 1.0f);  // nearest an edge
    EXPECT_NEAR(pointTriangleDistance({1.0f, 1.0f, 0.0f}, a, b, c), std::sqrt(0.5f), 1e-6f); // hypotenuse
}

TEST(Eval, RefusesUnusableMeshes) {
    EvalOptions o;
    o.method = BakeMethod::Cpu;
    EXPECT_THROW(evaluate(TriangleMesh{}, o), InvalidMesh);
}

} // namespace
} // namespace vds
