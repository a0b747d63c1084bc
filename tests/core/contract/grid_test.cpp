// The one grid and the one sizing of cubic grids: the cells of a few boxes,
// computed independently (float boxes, the sizes and centres worked out in
// double and rounded once), unchanged by the sizing being shared.
#include <vds/grid.h>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include <vds/error.h>
#include <vds/sprite.h>

namespace vds {
namespace {

struct CubicCase {
    Box box;
    std::uint32_t n;
    glm::uvec3 dims;
    glm::vec3 firstCentre, lastCentre; // of cells (0, 0, 0) and dims - 1
};

const CubicCase kCases[] = {
    {{{1, 2, 3}, {5, 3, 4}}, 16, {16, 4, 4}, {1.125f, 2.125f, 3.125f}, {4.875f, 2.875f, 3.875f}},
    {{{0, 0, 0}, {1, 1, 3}}, 40, {14, 14, 40}, // ceil(1 / 0.075) = 14
     {0.03749999776482582f, 0.03749999776482582f, 0.03750000149011612f},
     {1.0124999284744263f, 1.0124999284744263f, 2.9625000953674316f}},
    {{{-0.3f, 0.7f, 0.1f}, {0.9f, 1.1f, 2.5f}}, 10, {5, 2, 10},
     {-0.18000000715255737f, 0.8199999928474426f, 0.2199999988079071f},
     {0.7800000309944153f, 1.0600000619888306f, 2.380000114440918f}},
    {{{-1, -2, -0.5f}, {3, 1, 1.5f}}, 7, {7, 6, 4}, // cells of 4/7: ceil(3 * 7 / 4) = 6, ceil(2 * 7 / 4) = 4
     {-0.7142857313156128f, -1.7142857313156128f, -0.2142857164144516f},
     {2.7142856121063232f, 1.1428571939468384f, 1.5f}},
};

TEST(CubicGrid, CellsAndCentresOfAFewBoxes) {
    for (const CubicCase& c : kCases) {
        const Grid g = cubicGrid(c.box, c.n);
        EXPECT_EQ(g.dims, c.dims) << c.n;
        EXPECT_EQ(cubicCells(c.box.hi - c.box.lo, c.n), c.dims) << c.n;
        EXPECT_EQ(g.box.lo, c.box.lo);
        EXPECT_EQ(g.cellCentre(0, 0, 0), c.firstCentre) << c.n;
        EXPECT_EQ(g.cellCentre(c.dims.x - 1, c.dims.y - 1, c.dims.z - 1), c.lastCentre) << c.n;
        EXPECT_NO_THROW(checkGrid(g));
    }
}

TEST(CubicGrid, CellsOfFlatAndDegenerateExtents) {
    EXPECT_EQ(cubicCells({4, 2, 0}, 8), glm::uvec3(8, 4, 1)); // a sprite's sides across the view
    EXPECT_EQ(cubicCells({1, 1, 1}, 3), glm::uvec3(3, 3, 3));
    EXPECT_EQ(cubicCells({1, 1e-6f, 1}, 3), glm::uvec3(3, 1, 3));
    EXPECT_EQ(cubicCells({0, 0, 0}, 5), glm::uvec3(1, 1, 1));
    EXPECT_EQ(cubicCells({std::numeric_limits<float>::quiet_NaN(), 1, 1}, 5).x, 1u);
}

TEST(CubicGrid, ASpritesTexelsHaveTheSameSizing) {
    for (const CubicCase& c : kCases) {
        const SpriteGrid z = makeGrid(c.box, Axis::Z, c.n);
        const glm::vec3 e = c.box.hi - c.box.lo;
        const glm::uvec3 across = cubicCells({e.x, e.y, 0.0f}, c.n);
        EXPECT_EQ(z.width, across.x) << c.n;
        EXPECT_EQ(z.height, across.y) << c.n;
    }
    // The texels of the boxes above, worked out by hand: the longest side
    // across the view gets n, the other ceil(e / texel).
    EXPECT_EQ(makeGrid(kCases[0].box, Axis::Z, 16).height, 4u);
    EXPECT_EQ(makeGrid(kCases[1].box, Axis::X, 40).width, 14u); // s = y, t = z: 1 x 3 -> 14 x 40
    EXPECT_EQ(makeGrid(kCases[1].box, Axis::X, 40).height, 40u);
    EXPECT_EQ(makeGrid(kCases[1].box, Axis::Z, 40).width, 40u); // 1 x 1 across
    EXPECT_EQ(makeGrid(kCases[3].box, Axis::Y, 7).width, 4u); // s = z, t = x: 2 x 4 -> 4 x 7
    EXPECT_EQ(makeGrid(kCases[3].box, Axis::Y, 7).height, 7u);
}

TEST(CubicGrid, OneCellLimit) {
    Grid g;
    g.box = {{0, 0, 0}, {1, 1, 1}};
    g.dims = {1u << 12, 1u << 11, 1u << 11}; // 2^34 cells: at the limit
    EXPECT_EQ(g.cellCount(), kMaxGridCells);
    EXPECT_NO_THROW(checkGrid(g));
    g.dims.z += 1;
    EXPECT_THROW(checkGrid(g), InvalidArgument);
}

} // namespace
} // namespace vds
