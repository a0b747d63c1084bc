// The voxel grid and the bit layout, on the CPU.
#include <algorithm>
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
    EXPECT_EQ(g.dims, glm::uvec3(16, 4, 4));
    EXPECT_FLOAT_EQ(g.cellSize(), 0.25f);
    EXPECT_EQ(g.scale, glm::vec3(4.0f));
    EXPECT_EQ(g.box.lo, glm::vec3(1, 2, 3));
    EXPECT_EQ(g.zWords(), 1u);
    const VoxelGrid h = makeVoxelGrid({{0, 0, 0}, {1, 1, 3}}, 40);
    EXPECT_EQ(h.dims, glm::uvec3(14, 14, 40)); // ceil(1 / 0.075) = 14
    EXPECT_EQ(h.zWords(), 2u);
}

// Boxes whose sides are not powers of two, one far from the origin.
const Box kOddBoxes[] = {{{0, 0, 0}, {1, 1, 3}},
                         {{-0.3f, 0.7f, 0.1f}, {0.9f, 1.1f, 2.5f}},
                         {{-1, -2, -0.5f}, {3, 1, 1.5f}},
                         {{1000.3f, -250.1f, 17.7f}, {1001.2f, -249.9f, 18.0f}}};

TEST(VoxelGridTest, IsTheCubicGridWithItsLattice) {
    struct Case {
        Box box;
        std::uint32_t n;
        glm::uvec3 dims;
    };
    const Case cases[] = {
        {kOddBoxes[0], 40, {14, 14, 40}}, {kOddBoxes[1], 10, {5, 2, 10}}, {kOddBoxes[2], 7, {7, 6, 4}}};
    for (const Case& c : cases) {
        const VoxelGrid g = makeVoxelGrid(c.box, c.n);
        const Grid cubic = cubicGrid(c.box, c.n);
        EXPECT_EQ(g.dims, c.dims) << c.n;
        EXPECT_EQ(g.box.lo, c.box.lo) << c.n;
        EXPECT_EQ(g.box.hi, cubic.box.hi) << c.n; // grown to whole cells
        const glm::vec3 ext = c.box.hi - c.box.lo;
        EXPECT_EQ(g.scale, glm::vec3(float(c.n / double(std::max({ext.x, ext.y, ext.z}))))) << c.n;
        EXPECT_EQ(g.cellCentre(c.dims.x - 1, 0, 1), cubic.cellCentre(c.dims.x - 1, 0, 1)) << c.n;
    }
}

// The one centre formula (Grid's, in double) and the float lattice agree:
// every centre lands in its own cell (x layers 0, step, 2 step, ... and the last).
void expectCentresInTheirCells(const VoxelGrid& g, std::uint32_t step) {
    std::size_t wrong = 0;
    for (std::uint32_t i = 0; i < g.dims.x; i = i + 1 == g.dims.x ? g.dims.x : std::min(i + step, g.dims.x - 1))
        for (std::uint32_t j = 0; j < g.dims.y; ++j)
            for (std::uint32_t k = 0; k < g.dims.z; ++k) {
                glm::uvec3 c;
                wrong += !(g.cellOf(g.cellCentre(i, j, k), c) && c == glm::uvec3(i, j, k));
            }
    EXPECT_EQ(wrong, 0u) << g.dims.x << "x" << g.dims.y << "x" << g.dims.z;
}

TEST(VoxelGridTest, EveryCellCentreLandsInItsCell) {
    for (const Box& box : kOddBoxes)
        for (std::uint32_t n : {1u, 7u, 40u, 97u}) expectCentresInTheirCells(makeVoxelGrid(box, n), 1);
    // The most cells along an axis, every 97th layer and the last.
    expectCentresInTheirCells(makeVoxelGrid({{-3.1f, 0.2f, 5.0f}, {4.7f, 0.21f, 5.02f}}, kMaxResolution), 97);
    expectCentresInTheirCells(makeSlicemapGrid(kOddBoxes[3], 64, 96), 1);
}

TEST(VoxelGridTest, ASlicemapGridKeepsTheColumnsAndSlicesTheBoxDepth) {
    const Box box{{0, 0, 0}, {1, 2, 3}};
    const VoxelGrid g = makeSlicemapGrid(box, 8, 64); // cells of 3/8
    EXPECT_EQ(g.dims, glm::uvec3(3, 6, 64));
    EXPECT_EQ(g.box.hi, glm::vec3(1.125f, 2.25f, 3.0f));
    EXPECT_EQ(g.scale, glm::vec3(float(8.0 / 3.0), float(8.0 / 3.0), float(64.0 / 3.0)));
    EXPECT_EQ(g.cellCentre(0, 5, 0), glm::vec3(0.1875f, 2.0625f, 3.0f / 128.0f));
    EXPECT_FLOAT_EQ(g.cellSize(), 0.375f);
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
    ASSERT_EQ(g.dims, glm::uvec3(3, 2, 70));
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
    // A grid of 2^42 cells can be made (sizes are worked out on it) but not filled.
    EXPECT_EQ(makeVoxelGrid(box, kMaxResolution).cellCount(), std::size_t(1) << 42);
    EXPECT_THROW(makeBitGrid(makeVoxelGrid(box, kMaxResolution)), InvalidArgument);
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
