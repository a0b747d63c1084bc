// Sparse narrow bands (<vds/sparse_band.h>) against the dense band of the
// same mesh and grid (`SignedDistance::grid`, itself held to a brute force
// in distance_test.cpp): the same value in every cell, the same band cells,
// tiles whose label is every cell's; and bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <vds/distance.h>
#include <vds/error.h>
#include <vds/sparse_band.h>

#include "solids.h"

namespace vds {
namespace {

struct BandCase {
    std::string name;
    TriangleMesh mesh;
    Rule rule;
    glm::uvec3 dims;
    double halfWidth; ///< in cells
};

std::vector<BandCase> bandCases() {
    return {
        {"torus", solids::torus(glm::vec3(0.1f, -0.2f, 0.3f), 1.0f, 0.35f, 48).mesh, Rule::Parity, glm::uvec3(64), 3.0},
        {"sphere", solids::sphere(glm::vec3(0.0f), 1.0f, 40).mesh, Rule::GeneralizedWinding, glm::uvec3(61, 64, 58),
         2.0},
        {"shell", solids::shell(glm::vec3(0.0f), 1.0f, 0.6f, 32).mesh, Rule::Winding, glm::uvec3(72), 1.5},
    };
}

Grid gridAround(const TriangleMesh& mesh, const glm::uvec3& dims) {
    Grid grid;
    grid.box = meshBounds(mesh);
    grid.box.lo -= glm::vec3(0.17f);
    grid.box.hi += glm::vec3(0.23f);
    grid.dims = dims;
    return grid;
}

double cellSize(const Grid& grid) { return double(grid.box.hi.x - grid.box.lo.x) / grid.dims.x; }

TEST(SparseBand, EveryCellEqualsTheDenseBand) {
    for (const BandCase& c : bandCases()) {
        SCOPED_TRACE(c.name);
        const SignedDistance distance(c.mesh, c.rule);
        const Grid grid = gridAround(c.mesh, c.dims);
        const double width = c.halfWidth * cellSize(grid);
        std::vector<float> dense(grid.cellCount());
        distance.grid(grid, dense.data(), DistanceGridOptions{2, width});
        const SparseBand band = sparseBand(distance, c.mesh, grid, SparseBandOptions{2, width});
        EXPECT_EQ(band.blockDims, (grid.dims + 7u) / 8u);
        std::size_t denseBand = 0, inside = 0;
        for (std::uint32_t i = 0; i < grid.dims.x; ++i)
            for (std::uint32_t j = 0; j < grid.dims.y; ++j)
                for (std::uint32_t k = 0; k < grid.dims.z; ++k) {
                    const float expected = dense[grid.index(i, j, k)];
                    const float got = band.value(i, j, k);
                    // Bitwise: the same float and the same sign, -0 included.
                    ASSERT_EQ(std::signbit(got), std::signbit(expected)) << i << " " << j << " " << k;
                    ASSERT_EQ(got, expected) << i << " " << j << " " << k;
                    denseBand += std::abs(expected) < float(width);
                    inside += std::signbit(expected);
                }
        // The band cells are the dense band's, one value each.
        EXPECT_EQ(band.values.size(), denseBand);
        EXPECT_GT(denseBand, 1000u);
        EXPECT_GT(inside, 0u);
        std::size_t bits = 0;
        for (const BandBlock& b : band.blocks)
            for (std::uint64_t w : b.band) bits += std::size_t(__builtin_popcountll(w));
        EXPECT_EQ(bits, denseBand);
        // Some blocks are tiles (ABandPastTheDenseLimit... shows how few a fine grid keeps).
        const std::uint64_t blocks = std::uint64_t(band.blockDims.x) * band.blockDims.y * band.blockDims.z;
        EXPECT_LT(band.blocks.size(), blocks);
    }
}

TEST(SparseBand, TilesHoldTheLabelOfEveryCellInThem) {
    const BandCase c = bandCases()[1]; // a sphere: whole blocks inside
    const SignedDistance distance(c.mesh, c.rule);
    const Grid grid = gridAround(c.mesh, c.dims);
    const double width = c.halfWidth * cellSize(grid);
    std::vector<std::uint8_t> labels(grid.cellCount());
    ClassifyOptions classify;
    classify.rule = c.rule;
    distance.classifier().occupancy(grid, labels.data(), classify);
    const SparseBand band = sparseBand(distance, c.mesh, grid, SparseBandOptions{2, width});
    std::size_t insideTiles = 0, outsideTiles = 0;
    for (std::uint32_t bx = 0; bx < band.blockDims.x; ++bx)
        for (std::uint32_t by = 0; by < band.blockDims.y; ++by)
            for (std::uint32_t bz = 0; bz < band.blockDims.z; ++bz) {
                const glm::uvec3 block(bx, by, bz), origin = block * 8u;
                if (band.blockOf(origin.x, origin.y, origin.z)) continue;
                const bool tile = band.tileInside(block);
                (tile ? insideTiles : outsideTiles)++;
                const glm::uvec3 end = glm::min(origin + 8u, grid.dims);
                for (std::uint32_t i = origin.x; i < end.x; ++i)
                    for (std::uint32_t j = origin.y; j < end.y; ++j)
                        for (std::uint32_t k = origin.z; k < end.z; ++k)
                            ASSERT_EQ(labels[grid.index(i, j, k)], tile ? 1 : 0) << i << " " << j << " " << k;
            }
    EXPECT_GT(insideTiles, 0u);
    EXPECT_GT(outsideTiles, 0u);
}

TEST(SparseBand, ABandPastTheDenseLimitHoldsOnlyItsCells) {
    // 4096 x 4096 x 1040 cells (just past the dense limit, 2^34) around a
    // small box: only the blocks near its faces are made.
    const TriangleMesh mesh = solids::box(glm::vec3(0.2f), glm::vec3(0.22f)).mesh;
    const SignedDistance distance(mesh, Rule::Parity);
    Grid grid;
    grid.box = {glm::vec3(0.0f), glm::vec3(1.0f, 1.0f, 1040.0f / 4096.0f)};
    grid.dims = glm::uvec3(4096, 4096, 1040);
    ASSERT_GT(grid.cellCount(), kMaxGridCells);
    const double cell = 1.0 / 4096;
    const SparseBand band = sparseBand(distance, mesh, grid, SparseBandOptions{2, 1.5 * cell});
    // Each face is 82 cells wide, its band three layers of cells.
    EXPECT_GT(band.values.size(), 6u * 3u * 78u * 78u);
    EXPECT_LT(band.values.size(), 6u * 3u * 90u * 90u);
    EXPECT_LT(band.memoryBytes(), std::size_t(32) << 20);
    EXPECT_EQ(band.value(860, 860, 860), -float(1.5 * cell)); // deep inside the box
    EXPECT_EQ(band.value(10, 10, 10), float(1.5 * cell));
    EXPECT_EQ(band.value(860, 860, 1039), float(1.5 * cell));
}

TEST(SparseBand, RefusesBadInput) {
    const TriangleMesh mesh = solids::sphere(glm::vec3(0.0f), 1.0f, 12).mesh;
    const SignedDistance distance(mesh, Rule::Parity);
    const Grid grid = gridAround(mesh, glm::uvec3(16));
    for (double w : {0.0, -1.0, std::nan(""), std::numeric_limits<double>::infinity()})
        EXPECT_THROW(sparseBand(distance, mesh, grid, SparseBandOptions{1, w}), InvalidArgument) << w;
    Grid huge = grid;
    huge.dims = glm::uvec3(1u << 14, 1u << 14, 1u << 13); // 2^41 cells
    EXPECT_THROW(sparseBand(distance, mesh, huge, SparseBandOptions{1, 0.1}), InvalidArgument);
    Grid empty = grid;
    empty.dims.y = 0;
    EXPECT_THROW(sparseBand(distance, mesh, empty, SparseBandOptions{1, 0.1}), InvalidArgument);
    EXPECT_THROW(sparseBand(distance, mesh, grid.slabX(2, 5), SparseBandOptions{1, 0.1}), InvalidArgument);
    EXPECT_THROW(voxelSizeGrid(grid.box, 0.0), InvalidArgument);
    EXPECT_THROW(voxelSizeGrid(grid.box, 1e-9), InvalidArgument);
    const Grid sized = voxelSizeGrid(grid.box, 0.1);
    EXPECT_EQ(sized.dims, glm::uvec3(std::uint32_t(std::ceil((double(grid.box.hi.x) - double(grid.box.lo.x)) / 0.1))));
}

} // namespace
} // namespace vds
