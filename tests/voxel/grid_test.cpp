// The voxel grid and the bit layout, on the CPU.
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include <vds/error.h>
#include "solids.h"
#include <vds/sprite.h>
#include <vds/voxel/grid.h>

namespace vds::voxel {
namespace {

TEST(VoxelGridTest, CubicCellsWithTheResolutionAlongTheLongestSide) {
    const VoxelGrid g = makeVoxelGrid({{1, 2, 3}, {5, 3, 4}}, 16);
    EXPECT_EQ(g.size, glm::uvec3(16, 4, 4));
    EXPECT_FLOAT_EQ(g.cellSize, 0.25f);
    EXPECT_EQ(g.scale, glm::vec3(4.0f));
    EXPECT_EQ(g.origin, glm::vec3(1, 2, 3));
    EXPECT_EQ(g.zWords(), 1u);
    const VoxelGrid h = makeVoxelGrid({{0, 0, 0}, {1, 1, 3}}, 40);
    EXPECT_EQ(h.size, glm::uvec3(14, 14, 40)); // ceil(1 / 0.075) = 14
    EXPECT_EQ(h.zWords(), 2u);
}

TEST(VoxelGridTest, SizedAsEveryCubicGridWithItsOwnCellCentres) {
    // The cells of a few boxes as before the sizing was shared: the counts
    // of `vds::cubicGrid`, the centres origin + (i + 0.5) * cellSize in float
    // (an ulp from the Grid's for boxes not in powers of two).
    struct Case {
        Box box;
        std::uint32_t n;
        glm::uvec3 size;
        glm::vec3 first, last;
    };
    const Case cases[] = {
        {{{0, 0, 0}, {1, 1, 3}}, 40, {14, 14, 40}, glm::vec3(0.03750000149011612f),
         {1.0125000476837158f, 1.0125000476837158f, 2.9625000953674316f}},
        {{{-0.3f, 0.7f, 0.1f}, {0.9f, 1.1f, 2.5f}}, 10, {5, 2, 10},
         {-0.18000000715255737f, 0.8199999928474426f, 0.2199999988079071f},
         {0.7800000309944153f, 1.059999942779541f, 2.380000114440918f}},
        {{{-1, -2, -0.5f}, {3, 1, 1.5f}}, 7, {7, 6, 4},
         {-0.7142857313156128f, -1.7142857313156128f, -0.2142857015132904f},
         {2.7142858505249023f, 1.142857313156128f, 1.5f}},
    };
    for (const Case& c : cases) {
        const VoxelGrid g = makeVoxelGrid(c.box, c.n);
        EXPECT_EQ(g.size, c.size) << c.n;
        EXPECT_EQ(g.size, cubicGrid(c.box, c.n).dims) << c.n;
        EXPECT_EQ(g.cellCentre(0, 0, 0), c.first) << c.n;
        EXPECT_EQ(g.cellCentre(c.size.x - 1, c.size.y - 1, c.size.z - 1), c.last) << c.n;
    }
}

TEST(VoxelGridTest, PointsMapToTheCellHoldingThem) {
    const VoxelGrid g = makeVoxelGrid({{0, 0, 0}, {2, 2, 2}}, 8);
    glm::uvec3 c;
    ASSERT_TRUE(g.cellOf({0.3f, 1.99f, 0.0f}, c));
    EXPECT_EQ(c, glm::uvec3(1, 7, 0));
    EXPECT_FALSE(g.cellOf({-0.01f, 1, 1}, c));
    EXPECT_FALSE(g.cellOf({1, 2.0f, 1}, c));
    EXPECT_FALSE(g.cellOf({1, 1, std::numeric_limits<float>::quiet_NaN()}, c));
    for (std::uint32_t k = 0; k < 8; ++k) {
        ASSERT_TRUE(g.cellOf(g.cellCentre(3, 5, k), c));
        EXPECT_EQ(c, glm::uvec3(3, 5, k));
    }
}

TEST(VoxelGridTest, BitLayoutPacksZThenXThenY) {
    const VoxelGrid g = makeVoxelGrid({{0, 0, 0}, {3, 2, 70}}, 70);
    ASSERT_EQ(g.size, glm::uvec3(3, 2, 70));
    ASSERT_EQ(g.zWords(), 3u);
    EXPECT_EQ(BitGrid::wordIndex(g, 0, 0, 0), 0u);
    EXPECT_EQ(BitGrid::wordIndex(g, 0, 0, 31), 0u);
    EXPECT_EQ(BitGrid::wordIndex(g, 0, 0, 32), 1u);
    EXPECT_EQ(BitGrid::wordIndex(g, 1, 0, 0), 3u);
    EXPECT_EQ(BitGrid::wordIndex(g, 0, 1, 65), 3u * 3u + 2u);
    BitGrid b = makeBitGrid(g);
    b.set(2, 1, 69, true);
    EXPECT_EQ(b.words[BitGrid::wordIndex(g, 2, 1, 69)], 1u << 5);
    EXPECT_TRUE(b.contains(g.cellCentre(2, 1, 69)));
    EXPECT_FALSE(b.contains(g.cellCentre(2, 1, 68)));
    EXPECT_EQ(b.count(), 1u);
    EXPECT_EQ(b.memoryBytes(), 3u * 2u * 3u * 4u);
}

TEST(VoxelGridTest, SnappingRoundsToTheSubpixelGrid) {
    EXPECT_EQ(snapToSubcells(1.0f), 1.0f);
    EXPECT_EQ(snapToSubcells(0.3f), 77.0f / 256.0f);
    EXPECT_EQ(snapToSubcells(1.0f / 512.0f), 1.0f / 256.0f); // ties upwards
    EXPECT_EQ(snapToSubcells(-1.0f / 512.0f), 0.0f);
    EXPECT_EQ(snapToSubcells(16383.997f), 16383.99609375f);
}

TEST(VoxelGridTest, BadGridsAreRejected) {
    const Box box{{0, 0, 0}, {1, 1, 1}};
    EXPECT_THROW(makeVoxelGrid(box, 0), InvalidArgument);
    EXPECT_THROW(makeVoxelGrid(box, kMaxResolution + 1), InvalidArgument);
    EXPECT_THROW(makeVoxelGrid(box, kMaxResolution), InvalidArgument); // 2^42 cells
    EXPECT_THROW(makeVoxelGrid({{0, 0, 0}, {1, 1, 0}}, 8), InvalidArgument);
    EXPECT_THROW(makeVoxelGrid({{0, 0, 0}, {1, 1, std::numeric_limits<float>::infinity()}}, 8), InvalidArgument);
}

TEST(VoxelGridTest, OpenMeshesDoNotBoundASolid) {
    auto box = solids::box({0, 0, 0}, {1, 1, 1}).mesh;
    EXPECT_NO_THROW(requireClosed(box, "box"));
    EXPECT_NO_THROW(requireClosed(solids::boxesSharingAnEdge({0, 0, 0}, 1.0f).mesh, "touching boxes"));
    auto flipped = box;
    std::swap(flipped.triangles[0].y, flipped.triangles[0].z); // parity ignores orientation
    EXPECT_NO_THROW(requireClosed(flipped, "flipped box"));
    box.triangles.pop_back();
    try {
        requireClosed(box, "box");
        FAIL() << "open mesh accepted";
    } catch (const InvalidMesh& e) {
        EXPECT_NE(std::string(e.what()).find("box is open (3 boundary edges)"), std::string::npos) << e.what();
    }
    TriangleMesh empty;
    EXPECT_THROW(requireClosed(empty, "empty"), InvalidMesh);
}

} // namespace
} // namespace vds::voxel
