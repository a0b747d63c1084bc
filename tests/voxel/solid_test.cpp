// Solid voxelization (Schwarz 2012): rasterization and compute give the same
// bits, equal to the exact classifier at every voxel centre but where the
// rasterizer's 1/256 snapping moves an edge across a centre or a centre lies
// on the surface within rounding.
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <vds/error.h>
#include <vds/exact.h>
#include "solids.h"
#include <vds/voxel/representation.h>
#include <vds/voxel/slicemap.h>
#include <vds/voxel/solid.h>
#include <vds/voxel/surface.h>

#include "../support/gl_fixture.h"
#include "voxel_test_util.h"

namespace vds::voxel {
namespace {

class SolidTest : public vds::test::GlTest {};

// Cells where the voxel grid differs from `expected(centre)`.
template <class Expected> std::vector<glm::uvec3> differences(const BitGrid& bits, const Expected& expected) {
    std::vector<glm::uvec3> out;
    const glm::uvec3 n = bits.grid.dims;
    for (std::uint32_t z = 0; z < n.z; ++z)
        for (std::uint32_t y = 0; y < n.y; ++y)
            for (std::uint32_t x = 0; x < n.x; ++x)
                if (bits.test(x, y, z) != expected(bits.grid.cellCentre(x, y, z))) out.push_back({x, y, z});
    return out;
}

void expectIdentical(const BitGrid& a, const BitGrid& b, const std::string& what) {
    ASSERT_EQ(a.grid.dims, b.grid.dims) << what;
    std::size_t differing = 0;
    for (std::size_t w = 0; w < a.words.size(); ++w) differing += a.words[w] != b.words[w];
    EXPECT_EQ(differing, 0u) << what << ": words differ between raster and compute";
}

TEST_F(SolidTest, BoxGivesExactlyTheVoxelsWhoseCentresItHolds) {
    // Faces between voxel centres, vertices not on the snapping grid.
    const auto box = solids::box({0.3f, 0.21f, 0.13f}, {0.7f, 0.93f, 0.61f});
    const VoxelGrid grid = makeVoxelGrid({{0, 0, 0}, {1, 1, 1}}, 16);
    for (SolidMethod m : {SolidMethod::Raster, SolidMethod::Compute}) {
        const BitGrid bits = voxelizeSolid(gl(), box.mesh, grid, m);
        const auto wrong = differences(bits, [&](const glm::vec3& c) { return box.distance(c) < 0.0f; });
        EXPECT_TRUE(wrong.empty()) << toString(m) << ": " << wrong.size() << " voxels differ";
        EXPECT_EQ(bits.count(), 6u * 12u * 8u) << toString(m); // x 5..10, y 3..14, z 2..9
    }
}

TEST_F(SolidTest, MeshBeyondTheGridStillCountsWithoutDepthClipping) {
    // The grid is the middle of a box: every voxel is inside, though the
    // front and back faces lie outside the grid in depth.
    const auto box = solids::box({0, 0, 0}, {1, 1, 1});
    const VoxelGrid grid = makeVoxelGrid({{0.25f, 0.25f, 0.25f}, {0.75f, 0.75f, 0.75f}}, 8);
    for (SolidMethod m : {SolidMethod::Raster, SolidMethod::Compute})
        EXPECT_EQ(voxelizeSolid(gl(), box.mesh, grid, m).count(), 512u) << toString(m);
}

TEST_F(SolidTest, RasterAndComputeGiveIdenticalBits) {
    const auto sphere = solids::sphere({0.1f, -0.2f, 0.3f}, 1.0f, 48);
    const auto torus = solids::torus({0, 0, 0}, 1.0f, 0.4f, 40);
    const auto shell = solids::shell({0, 0, 0}, 1.0f, 0.7f, 32);
    const auto boxes = solids::overlappingBoxes({0, 0, 0}, {1, 1, 1}, {0.5f, 0.4f, 0.3f}, {1.5f, 1.3f, 1.2f});
    for (const auto* solid : {&sphere, &torus, &shell, &boxes})
        for (std::uint32_t resolution : {33u, 64u, 100u}) {
            const VoxelGrid grid = makeVoxelGrid(meshBounds(solid->mesh), resolution);
            expectIdentical(voxelizeSolid(gl(), solid->mesh, grid, SolidMethod::Raster),
                            voxelizeSolid(gl(), solid->mesh, grid, SolidMethod::Compute),
                            "resolution " + std::to_string(resolution));
        }
}

TEST_F(SolidTest, EqualsTheExactClassifierAtVoxelCentresButForNearTies) {
    const auto sphere = solids::sphere({0.1f, -0.2f, 0.3f}, 1.0f, 48);
    const auto torus = solids::torus({0, 0, 0}, 1.0f, 0.4f, 40);
    const auto shell = solids::shell({0, 0, 0}, 1.0f, 0.7f, 32);
    const auto boxes = solids::overlappingBoxes({0, 0, 0}, {1, 1, 1}, {0.5f, 0.4f, 0.3f}, {1.5f, 1.3f, 1.2f});
    const auto touching = solids::boxesSharingAnEdge({0.05f, 0.1f, 0.15f}, 0.9f); // non-manifold, still a solid
    for (const auto* solid : {&sphere, &torus, &shell, &boxes, &touching}) {
        const ExactClassifier exact(solid->mesh, Axis::Z);
        const VoxelGrid grid = makeVoxelGrid(meshBounds(solid->mesh), 64);
        const BitGrid bits = voxelizeSolid(gl(), solid->mesh, grid, SolidMethod::Compute);
        const auto wrong = differences(bits, [&](const glm::vec3& c) { return exact.contains(c); });
        EXPECT_LT(wrong.size(), grid.cellCount() / 10000 + 1);
        for (const glm::uvec3& c : wrong) {
            // Either the snapping (at most 1/512 per axis) moved an edge across
            // the column centre, or the centre lies on the surface in depth.
            EXPECT_TRUE(test::nearInDepth(solid->mesh, grid, c.x, c.y, c.z + 0.5) ||
                        test::nearProjectedEdge(solid->mesh, grid, c.x, c.y, 1.0 / 256.0))
                << "voxel " << c.x << "," << c.y << "," << c.z << " differs from the exact classifier";
        }
    }
}

TEST_F(SolidTest, ClosedMeshesOnTheSnappingGridEqualTheExactClassifierEverywhere) {
    // Vertices on multiples of 1/256 cell: snapping changes nothing, and a
    // square grid puts voxel centres exactly on the faces' diagonals, where
    // the tie rule must count one crossing.
    const auto boxes = solids::overlappingBoxes({0, 0, 0}, {1, 1, 1}, {0.25f, 0.5f, 0.25f}, {1.25f, 1.5f, 1.0f});
    const ExactClassifier exact(boxes.mesh, Axis::Z);
    const VoxelGrid grid = makeVoxelGrid(meshBounds(boxes.mesh), 24);
    for (SolidMethod m : {SolidMethod::Raster, SolidMethod::Compute}) {
        const BitGrid bits = voxelizeSolid(gl(), boxes.mesh, grid, m);
        EXPECT_TRUE(differences(bits, [&](const glm::vec3& c) { return exact.contains(c); }).empty()) << toString(m);
    }
}

TEST_F(SolidTest, BadInputIsRejectedWithAClearError) {
    auto open = solids::sphere({0, 0, 0}, 1.0f, 16).mesh;
    open.triangles.pop_back();
    const VoxelGrid grid = makeVoxelGrid(meshBounds(open), 16);
    EXPECT_THROW(voxelizeSolid(gl(), open, grid, SolidMethod::Raster), InvalidMesh);
    EXPECT_THROW(buildModel(gl(), open, Representation::Solid, {16}), InvalidMesh);
    const auto sphere = solids::sphere({0, 0, 0}, 1.0f, 16);
    EXPECT_THROW(buildModel(gl(), sphere.mesh, Representation::SolidCompute, {0}), InvalidArgument);
    EXPECT_THROW(buildModel(gl(), sphere.mesh, Representation::Solid, {100000}), InvalidArgument);
    EXPECT_THROW(buildModel(gl(), sphere.mesh, Representation::Solid, {kMaxResolution}), InvalidArgument);
    // A grid of 2^42 cells can be made, but no voxelizer fills it (kMaxGridCells).
    const VoxelGrid huge = makeVoxelGrid(meshBounds(sphere.mesh), kMaxResolution);
    EXPECT_THROW(voxelizeSolid(gl(), sphere.mesh, huge, SolidMethod::Compute), InvalidArgument);
    EXPECT_THROW(voxelizeSurface(gl(), sphere.mesh, huge), InvalidArgument);
    EXPECT_THROW(parseSolidMethod("xor"), InvalidArgument);
}

// The voxel enums read their names from one table each (<vds/enum_names.h>),
// like the core's: the parsers, the printers and the tool's choices agree.
TEST(VoxelNames, ParseAndPrintFromOneTable) {
    EXPECT_EQ(enumNames<Representation>(),
              (std::vector<std::string>{"slicemap", "slicemap-local", "solid", "solid-compute"}));
    EXPECT_EQ(enumNames<SolidMethod>(), (std::vector<std::string>{"raster", "compute"}));
    EXPECT_EQ(enumNames<Slicing>(), (std::vector<std::string>{"uniform", "local"}));
    for (const auto& name : enumNames<Representation>()) EXPECT_EQ(toString(parseRepresentation(name)), name);
    EXPECT_EQ(parseSolidMethod("compute"), SolidMethod::Compute);
    EXPECT_STREQ(toString(SolidMethod::Raster), "raster");
    EXPECT_EQ(parseSlicing("local"), Slicing::Local);
    EXPECT_STREQ(toString(Slicing::Uniform), "uniform");
    try {
        parseRepresentation("voxels");
        ADD_FAILURE() << "no exception";
    } catch (const InvalidArgument& e) {
        EXPECT_STREQ(e.what(),
                     "unknown voxel representation 'voxels' (expected slicemap, slicemap-local, solid or solid-compute)");
    }
}

TEST_F(SolidTest, ModelsAnswerPointQueriesLikeTheirGrid) {
    const auto torus = solids::torus({0, 0, 0}, 1.0f, 0.4f, 32);
    const Model model = buildModel(gl(), torus.mesh, parseRepresentation("solid-compute"), {40});
    ASSERT_NE(model.solid(), nullptr);
    EXPECT_EQ(model.slicemap(), nullptr);
    EXPECT_EQ(model.cells(), model.solid()->grid.dims);
    EXPECT_EQ(model.memoryBytes(), model.solid()->words.size() * 4);
    EXPECT_GE(model.buildSeconds(), 0.0);
    const VoxelGrid& g = model.solid()->grid;
    for (std::uint32_t x = 0; x < g.dims.x; x += 3)
        EXPECT_EQ(model.contains(g.cellCentre(x, g.dims.y / 2, g.dims.z / 2)),
                  model.solid()->test(x, g.dims.y / 2, g.dims.z / 2));
    EXPECT_FALSE(model.contains({0, 0, 0}));    // the hole
    EXPECT_TRUE(model.contains({1.0f, 0, 0}));  // in the tube
    EXPECT_FALSE(model.contains({5.0f, 0, 0})); // outside the grid
    // The contract's contains(p, rule), not hidden by the model's own.
    EXPECT_TRUE(model.contains({1.0f, 0, 0}, Rule::Parity));
    EXPECT_THROW(model.contains({1.0f, 0, 0}, Rule::Winding), InvalidArgument);
}

} // namespace
} // namespace vds::voxel
