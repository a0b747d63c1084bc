// Occupancy grids: the exact sweep against the exact classifier on every
// cell, the sprite sweep against Sprite::contains on every cell.
#include <vds/occupancy.h>

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <vds/bake.h>
#include <vds/error.h>
#include <vds/exact.h>

#include "solids.h"

namespace vds {
namespace {

// Every cell of `grid`, classified one by one by `answer`.
template <class Answer> std::vector<std::uint8_t> cellByCell(const Grid& grid, const Answer& answer) {
    std::vector<std::uint8_t> labels(grid.cellCount());
    for (std::uint32_t i = 0; i < grid.dims.x; ++i)
        for (std::uint32_t j = 0; j < grid.dims.y; ++j)
            for (std::uint32_t k = 0; k < grid.dims.z; ++k)
                labels[grid.index(i, j, k)] = answer(grid.cellCentre(i, j, k)) ? 1 : 0;
    return labels;
}

std::size_t differing(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b) {
    std::size_t n = 0;
    for (std::size_t k = 0; k < a.size(); ++k) n += a[k] != b[k];
    return n;
}

TEST(Occupancy, ExactSweepEqualsTheExactClassifierOnEveryCell) {
    const auto torus = solids::torus({0.1f, 0.2f, 0.3f}, 1.0f, 0.35f, 48);
    const auto shell = solids::shell({0, 0, 0}, 1.0f, 0.6f, 32);
    const auto two = solids::overlappingBoxes({-1, -1, -1}, {0.5f, 0.5f, 0.5f}, {-0.5f, -0.3f, -0.2f}, {1, 1, 1});
    // Faces on cell centres: the box [0, 1]^3 in a grid whose centres are
    // -1, -0.5, 0, 0.5, 1, 1.5, 2 along each axis (points on the surface).
    const auto unit = solids::box({0, 0, 0}, {1, 1, 1});
    const struct {
        const TriangleMesh* mesh;
        Grid grid;
    } cases[] = {
        {&torus.mesh, {meshBounds(torus.mesh), {37, 41, 29}}},
        {&shell.mesh, {Box{{-1.2f, -1.1f, -1.3f}, {1.3f, 1.2f, 1.1f}}, {33, 30, 35}}},
        {&two.mesh, {meshBounds(two.mesh), {24, 25, 26}}},
        {&unit.mesh, {Box{{-1.25f, -1.25f, -1.25f}, {2.25f, 2.25f, 2.25f}}, {7, 7, 7}}},
    };
    for (const auto& c : cases) {
        const ExactClassifier exact(*c.mesh, Axis::Z);
        for (Rule rule : {Rule::Parity, Rule::Winding}) {
            std::vector<std::uint8_t> swept(c.grid.cellCount(), 7);
            occupancy(*c.mesh, c.grid, swept.data(), {rule, 2});
            const auto expected = cellByCell(c.grid, [&](const glm::vec3& p) { return exact.contains(p, rule); });
            EXPECT_EQ(differing(swept, expected), 0u) << c.mesh->name << " " << toString(rule);
            std::size_t inside = 0;
            for (std::uint8_t l : swept) inside += l;
            EXPECT_GT(inside, 0u);
            EXPECT_LT(inside, swept.size());
        }
    }
}

TEST(Occupancy, SpriteSweepEqualsContainsOnEveryCell) {
    const auto torus = solids::torus({0.1f, 0.2f, 0.3f}, 1.0f, 0.35f, 48);
    const Grid grid{meshBounds(torus.mesh), {31, 27, 23}};
    for (Axis axis : {Axis::X, Axis::Y, Axis::Z}) {
        BakeOptions o;
        o.resolution = 40;
        o.axis = axis;
        o.method = BakeMethod::Cpu;
        Sprite sprite = bakeCpu(torus.mesh, o);
        // Turned exactly a quarter about its axis (s and t swap world axes:
        // still swept by columns) and mirrored along it (depth falls along
        // the axis: cells one by one), entries exactly 0 and 1.
        const glm::ivec3 p = axisPermutation(axis);
        glm::mat4 quarter(0.0f), mirror(1.0f);
        quarter[p.x][p.y] = 1.0f;
        quarter[p.y][p.x] = -1.0f;
        quarter[p.z][p.z] = quarter[3][3] = 1.0f;
        mirror[p.z][p.z] = -1.0f;
        for (int moved = 0; moved < 5; ++moved) {
            if (moved == 1) sprite.transform(glm::translate(glm::mat4(1.0f), {0.05f, -0.1f, 0.02f})); // still aligned
            if (moved == 2) sprite.transform(quarter);
            if (moved == 3) sprite.transform(mirror);
            if (moved == 4) sprite.transform(glm::rotate(glm::mat4(1.0f), 0.3f, {0.2f, 1.0f, 0.4f}));  // rotated
            for (Rule rule : {Rule::Parity, Rule::Winding}) {
                std::vector<std::uint8_t> swept(grid.cellCount(), 7);
                occupancy(sprite, grid, swept.data(), {rule, 2});
                const auto expected = cellByCell(grid, [&](const glm::vec3& at) { return sprite.contains(at, rule); });
                EXPECT_EQ(differing(swept, expected), 0u) << toString(axis) << " moved " << moved;
            }
        }
    }
}

TEST(Occupancy, CubicGridsAndPackedLabels) {
    const Grid g = cubicGrid(Box{{0, 0, 0}, {4, 2, 1}}, 8);
    EXPECT_EQ(g.dims, glm::uvec3(8, 4, 2));
    EXPECT_FLOAT_EQ(g.cellCentre(0, 0, 0).x, 0.25f);
    EXPECT_FLOAT_EQ(g.cellCentre(7, 3, 1).z, 0.75f);
    const std::uint8_t cells[11] = {1, 0, 0, 0, 0, 0, 0, 1, 1, 1, 0};
    std::uint8_t bits[2] = {0xff, 0xff};
    packLabels(cells, 11, bits);
    EXPECT_EQ(bits[0], 0x81);
    EXPECT_EQ(bits[1], 0xc0);
}

TEST(Occupancy, BadGridsAreRefused) {
    const auto box = solids::box({0, 0, 0}, {1, 1, 1});
    std::vector<std::uint8_t> cells(8);
    EXPECT_THROW(occupancy(box.mesh, {Box{{0, 0, 0}, {1, 1, 1}}, {0, 2, 2}}, cells.data()), InvalidArgument);
    EXPECT_THROW(occupancy(box.mesh, {Box{{0, 0, 0}, {1, 1, 1}}, {1u << 20, 1u << 20, 1u << 20}}, cells.data()),
                 InvalidArgument);
    EXPECT_THROW(occupancy(box.mesh, {Box{{0, 0, 0}, {0, 1, 1}}, {2, 2, 2}}, cells.data()), InvalidArgument);
    const float nan = std::nanf("");
    EXPECT_THROW(occupancy(box.mesh, {Box{{nan, 0, 0}, {1, 1, 1}}, {2, 2, 2}}, cells.data()), InvalidArgument);
    TriangleMesh empty;
    EXPECT_THROW(occupancy(empty, {Box{{0, 0, 0}, {1, 1, 1}}, {2, 2, 2}}, cells.data()), InvalidMesh);
}

} // namespace
} // namespace vds

namespace vds {
namespace {

// A grid labelled a slab of x layers at a time (Grid::slabX) gives the whole
// grid's labels: the exact sweep (parity, and the GWN of an open mesh), a
// sprite along z and along x.
TEST(Occupancy, SlabsGiveTheWholeGridsLabels) {
    const TriangleMesh torus = solids::torus({0.1f, 0.0f, -0.1f}, 1.0f, 0.4f, 24).mesh;
    const TriangleMesh cup = solids::sphereCup();
    const Grid grid{{glm::vec3(-1.6f, -1.5f, -1.3f), glm::vec3(1.7f, 1.4f, 1.2f)}, {23, 17, 13}};
    const auto slabs = [&](const auto& label) {
        std::vector<std::uint8_t> whole(grid.cellCount()), pieces(grid.cellCount());
        label(grid, whole.data());
        for (std::uint32_t i0 = 0; i0 < grid.dims.x; i0 += 5) {
            const std::uint32_t i1 = std::min(grid.dims.x, i0 + 5);
            label(grid.slabX(i0, i1), pieces.data() + grid.index(i0, 0, 0));
        }
        EXPECT_EQ(whole, pieces);
        return std::count(whole.begin(), whole.end(), 1);
    };
    EXPECT_GT(slabs([&](const Grid& g, std::uint8_t* out) { occupancy(torus, g, out); }), 100);
    ClassifyOptions gwn;
    gwn.rule = Rule::GeneralizedWinding;
    EXPECT_GT(slabs([&](const Grid& g, std::uint8_t* out) { occupancy(cup, g, out, gwn); }), 100);
    for (Axis axis : {Axis::Z, Axis::X}) {
        BakeOptions o;
        o.resolution = 40;
        o.axis = axis;
        const Sprite sprite = bakeCpu(torus, o);
        EXPECT_GT(slabs([&](const Grid& g, std::uint8_t* out) { occupancy(sprite, g, out); }), 100);
    }
    Grid past = grid.slabX(20, 23);
    past.dims.x = 4;
    EXPECT_THROW(checkGrid(past), InvalidArgument);
}

} // namespace
} // namespace vds
