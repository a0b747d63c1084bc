// A deforming mesh re-baked with its topology validated once (<vds/gl/baker.h>):
// each re-bake equals, bit for bit, a fresh bake of the moved mesh along the
// same axis, for the CPU baker and the GL bakers, closed and open meshes.
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <vds/bake.h>
#include <vds/error.h>
#include <vds/gl/bake.h>
#include <vds/gl/baker.h>
#include "solids.h"

#include "../support/gl_fixture.h"

namespace vds {
namespace {

class BakerTest : public test::GlTest {};

// Frame `frame` of a twist about z with a breathing scale and a drift: no
// two vertices meet, no triangle collapses.
std::vector<glm::vec3> deformed(const std::vector<glm::vec3>& rest, int frame) {
    std::vector<glm::vec3> out(rest.size());
    const float phase = 0.37f * float(frame);
    for (std::size_t v = 0; v < rest.size(); ++v) {
        const glm::vec3 p = rest[v];
        const float angle = phase * p.z;
        const float c = std::cos(angle), s = std::sin(angle);
        const float scale = 1.0f + 0.2f * std::sin(phase + p.z);
        out[v] = glm::vec3(scale * (c * p.x - s * p.y), scale * (s * p.x + c * p.y), p.z * (1.0f + 0.1f * float(frame))) +
                 glm::vec3(0.05f * float(frame), -0.02f * float(frame), 0.1f);
    }
    return out;
}

void expectSame(const Sprite& a, const Sprite& b, const char* what) {
    EXPECT_EQ(a.offsets, b.offsets) << what;
    ASSERT_EQ(a.crossings.size(), b.crossings.size()) << what;
    std::size_t bitsDiffer = 0;
    for (std::size_t k = 0; k < a.crossings.size(); ++k)
        bitsDiffer += std::memcmp(&a.crossings[k], &b.crossings[k], sizeof(float)) != 0;
    EXPECT_EQ(bitsDiffer, 0u) << what;
    EXPECT_EQ(a.depthComplexity, b.depthComplexity) << what;
    EXPECT_EQ(a.grid.axis, b.grid.axis) << what;
    EXPECT_EQ(a.grid.width, b.grid.width) << what;
    EXPECT_EQ(a.grid.height, b.grid.height) << what;
    EXPECT_EQ(0, std::memcmp(&a.grid.box, &b.grid.box, sizeof(Box))) << what;
    EXPECT_EQ(a.grid.texelSize, b.grid.texelSize) << what;
    EXPECT_EQ(a.grid.matrix, b.grid.matrix) << what;
    EXPECT_EQ(a.grid.position, b.grid.position) << what;
    EXPECT_EQ(a.boundaryEdges, b.boundaryEdges) << what;
    EXPECT_EQ(a.status, b.status) << what;
    EXPECT_EQ(a.validation, b.validation) << what;
}

TEST_F(BakerTest, RebakeEqualsAFreshBakeBitForBit) {
    const TriangleMesh torus = solids::torus({0.1f, 0.0f, 0.0f}, 1.0f, 0.35f, 40).mesh;
    const TriangleMesh cup = solids::sphereCup();
    for (const TriangleMesh* rest : {&torus, &cup})
        for (BakeMethod method : {BakeMethod::Cpu, BakeMethod::Lists, BakeMethod::Peel}) {
            BakeOptions options;
            options.resolution = 48;
            options.method = method;
            Baker baker(gl(), *rest, options);
            options.axis = baker.axis();
            const Sprite still = baker.rebake();
            expectSame(still, bakeOnGl(gl(), *rest, options), toString(method));
            for (int frame = 1; frame <= 3; ++frame) {
                TriangleMesh moved = *rest;
                moved.positions = deformed(rest->positions, frame);
                baker.updateVertices(moved.positions);
                const Sprite again = baker.rebake();
                expectSame(again, bakeOnGl(gl(), moved, options), toString(method));
                EXPECT_NE(again.grid.box.hi, still.grid.box.hi); // the mesh did move
            }
        }
}

TEST_F(BakerTest, CpuBakerNeedsNoContextAndRefusesGlMethods) {
    const TriangleMesh torus = solids::torus({0, 0, 0}, 1.0f, 0.3f, 24).mesh;
    BakeOptions options;
    options.resolution = 32;
    Baker baker(torus, options); // Auto: the CPU baker
    TriangleMesh moved = torus;
    moved.positions = deformed(torus.positions, 2);
    baker.updateVertices(moved.positions);
    options.axis = baker.axis();
    options.method = BakeMethod::Cpu;
    expectSame(baker.rebake(), bakeCpu(moved, options), "cpu");
    options.method = BakeMethod::Lists;
    EXPECT_THROW(Baker(torus, options), InvalidArgument);
}

TEST_F(BakerTest, BadVerticesAreRefusedAndTheOldOnesKept) {
    const TriangleMesh torus = solids::torus({0, 0, 0}, 1.0f, 0.3f, 24).mesh;
    BakeOptions options;
    options.resolution = 32;
    options.method = BakeMethod::Cpu;
    Baker baker(gl(), torus, options);
    std::vector<glm::vec3> fewer(torus.positions.begin(), torus.positions.end() - 1);
    EXPECT_THROW(baker.updateVertices(fewer), InvalidArgument);
    std::vector<glm::vec3> bad = torus.positions;
    bad[3].y = std::numeric_limits<float>::quiet_NaN();
    EXPECT_THROW(baker.updateVertices(bad), InvalidMesh);
    std::vector<glm::vec3> flat = torus.positions;
    for (glm::vec3& p : flat) p.z = 0.0f;
    baker.updateVertices(flat);
    EXPECT_THROW(baker.rebake(), InvalidMesh); // a flat sheet bounds no volume
    baker.updateVertices(torus.positions);
    options.axis = baker.axis();
    expectSame(baker.rebake(), bakeCpu(torus, options), "restored");
}

} // namespace
} // namespace vds
