// The GPU column sweep against the CPU one (vds::occupancy), cell by cell,
// on llvmpipe or a real GPU: sprites along each axis, both rules, a sprite
// moved and scaled after the bake, grids whose box reaches past the sprite's
// and whose sizes are not multiples of four (label words shared by columns);
// and Rule::GeneralizedWinding on open meshes against the CPU's labels and a
// double-precision value (tests/support/gwn_reference.h).
#include <cmath>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <vds/all.h>
#include <vds/bake.h>
#include <vds/error.h>
#include <vds/gl/occupancy.h>
#include <vds/gl/sprite.h>
#include <vds/occupancy.h>
#include "solids.h"

#include "../support/gl_fixture.h"
#include "../support/gwn_reference.h"

namespace vds {
namespace {

class GpuOccupancyTest : public test::GlTest {};

using test::referenceGwn;

TEST_F(GpuOccupancyTest, GpuSweepEqualsCpuSweepOnEveryCell) {
    const auto torus = solids::torus({0.2f, -0.1f, 0.0f}, 1.0f, 0.4f, 64);
    const auto two = solids::overlappingBoxes({-1, -1, -1}, {0.3f, 0.3f, 0.3f}, {-0.3f, -0.3f, -0.3f}, {1, 1, 1});
    GpuOccupancy sweep(gl());
    for (const TriangleMesh* mesh : {&torus.mesh, &two.mesh})
        for (Axis axis : {Axis::Z, Axis::X, Axis::Y})
            for (bool moved : {false, true}) {
                BakeOptions o;
                o.resolution = 80;
                o.axis = axis;
                o.method = BakeMethod::Cpu;
                Sprite sprite = bake(*mesh, o);
                Box box = meshBounds(*mesh);
                if (moved) { // translated and stretched, not rotated: the grid follows the solid
                    const glm::mat4 model =
                        glm::scale(glm::translate(glm::mat4(1.0f), {0.5f, -1.0f, 2.0f}), glm::vec3(1.5f, 0.75f, 2.0f));
                    sprite.transform(model);
                    box = {glm::vec3(model * glm::vec4(box.lo, 1.0f)), glm::vec3(model * glm::vec4(box.hi, 1.0f))};
                }
                const glm::vec3 pad = 0.1f * (box.hi - box.lo);
                const Grid grid{{box.lo - pad, box.hi + pad}, {37, 29, 23}};
                const GpuSprite gpu(sprite, GpuSpriteParts::ColumnsOnly);
                for (Rule rule : {Rule::Parity, Rule::Winding}) {
                    std::vector<std::uint8_t> cpu(grid.cellCount(), 9), gpuCells(grid.cellCount(), 7);
                    occupancy(sprite, grid, cpu.data(), {rule, 1});
                    sweep.occupancy(gpu, grid, gpuCells.data(), {rule});
                    std::size_t differ = 0, inside = 0;
                    for (std::size_t k = 0; k < cpu.size(); ++k) {
                        differ += cpu[k] != gpuCells[k];
                        inside += cpu[k];
                    }
                    EXPECT_EQ(differ, 0u) << "axis " << toString(axis) << " moved " << moved << " " << toString(rule);
                    EXPECT_GT(inside, cpu.size() / 20); // not vacuous
                    EXPECT_LT(inside, cpu.size() / 2);
                }
            }
}

TEST_F(GpuOccupancyTest, GeneralizedWindingOfOpenMeshesEqualsTheCpu) {
    GpuOccupancy sweep(gl());
    const struct {
        const char* name;
        TriangleMesh mesh;
    } meshes[] = {{"cup", solids::sphereCup()}, {"sphere with holes", solids::sphereWithHoles()}};
    for (const auto& m : meshes)
        for (Axis axis : {Axis::Z, Axis::X}) {
            BakeOptions o;
            o.resolution = 48;
            o.axis = axis;
            o.method = BakeMethod::Cpu;
            const Sprite sprite = bake(m.mesh, o);
            ASSERT_FALSE(sprite.boundaryEdges.empty()) << m.name;
            const Box box = meshBounds(m.mesh);
            const glm::vec3 pad = 0.08f * (box.hi - box.lo);
            const Grid grid{{box.lo - pad, box.hi + pad}, {33, 27, 30}};
            const GpuSprite gpu(sprite, GpuSpriteParts::ColumnsOnly);
            ASSERT_EQ(gpu.boundary().edgeCount(), sprite.boundaryEdges.size() / 2);
            std::vector<std::uint8_t> cpu(grid.cellCount(), 9), gpuCells(grid.cellCount(), 7);
            occupancy(sprite, grid, cpu.data(), {Rule::GeneralizedWinding, 1});
            sweep.occupancy(gpu, grid, gpuCells.data(), {Rule::GeneralizedWinding});
            // The CPU's exact per-edge sum at the same cell centres.
            std::vector<glm::vec3> centres;
            centres.reserve(grid.cellCount());
            for (std::uint32_t i = 0; i < grid.dims.x; ++i)
                for (std::uint32_t j = 0; j < grid.dims.y; ++j)
                    for (std::uint32_t k = 0; k < grid.dims.z; ++k) centres.push_back(grid.cellCentre(i, j, k));
            ClassifyOptions exact;
            exact.rule = Rule::GeneralizedWinding;
            exact.threads = 1;
            std::vector<std::uint8_t> exactCells(grid.cellCount(), 5);
            classify(sprite, {centres.data(), centres.size()}, exactCells.data(), exact,
                     {QueryLayout::Auto, BoundaryEvaluation::Exact});
            std::size_t nearHalf = 0, elsewhere = 0, cpuDiffer = 0, inside = 0, open = 0, referenceDiffer = 0;
            for (std::uint32_t i = 0; i < grid.dims.x; ++i)
                for (std::uint32_t j = 0; j < grid.dims.y; ++j)
                    for (std::uint32_t k = 0; k < grid.dims.z; ++k) {
                        const std::size_t c = grid.index(i, j, k);
                        const double w = referenceGwn(sprite, grid.cellCentre(i, j, k));
                        const bool tie = std::isfinite(w) && std::fabs(w - 0.5) <= 1e-4;
                        inside += cpu[c];
                        open += std::isfinite(w) && std::fabs(w - std::round(w)) > 0.05;
                        cpuDiffer += cpu[c] != exactCells[c] && !tie;
                        referenceDiffer += (std::isfinite(w) && w > 0.5) != bool(cpu[c]) && !tie;
                        if (gpuCells[c] == cpu[c]) continue;
                        if (tie) ++nearHalf;
                        else ++elsewhere;
                    }
            const std::string what = std::string(m.name) + ", axis " + toString(axis);
            EXPECT_EQ(elsewhere, 0u) << what;
            EXPECT_LE(nearHalf, 3u) << what;
            EXPECT_EQ(cpuDiffer, 0u) << what;       // occupancy's caps = the exact sum
            EXPECT_EQ(referenceDiffer, 0u) << what; // and both = this test's own value
            EXPECT_GT(inside, cpu.size() / 20) << what; // not vacuous
            EXPECT_GT(open, cpu.size() / 20) << what;   // the boundary term matters on many cells
        }
}

// Cells beside, in front of and behind the sprite's box: just above a
// bowl's rim, with a disk hung inside, the generalized winding number exceeds
// 1/2 outside the box. The GPU sweep labels every cell as the CPU's does, by
// every rule.
TEST_F(GpuOccupancyTest, CellsAroundTheBoxEqualTheCpu) {
    GpuOccupancy sweep(gl());
    const TriangleMesh mesh = solids::bowlWithDisk();
    for (Axis axis : {Axis::Y, Axis::Z}) {
        BakeOptions o;
        o.resolution = 40;
        o.axis = axis;
        o.method = BakeMethod::Cpu;
        const Sprite sprite = bake(mesh, o);
        const Box box = meshBounds(mesh);
        const glm::vec3 pad = 0.4f * (box.hi - box.lo);
        const Grid grid{{box.lo - pad, box.hi + pad}, {29, 31, 27}};
        const GpuSprite gpu(sprite, GpuSpriteParts::ColumnsOnly);
        for (Rule rule : {Rule::Parity, Rule::Winding, Rule::GeneralizedWinding}) {
            std::vector<std::uint8_t> cpu(grid.cellCount(), 9), gpuCells(grid.cellCount(), 7);
            occupancy(sprite, grid, cpu.data(), {rule, 1});
            sweep.occupancy(gpu, grid, gpuCells.data(), {rule});
            std::size_t differ = 0, inside = 0, outsideTheBox = 0;
            for (std::uint32_t i = 0; i < grid.dims.x; ++i)
                for (std::uint32_t j = 0; j < grid.dims.y; ++j)
                    for (std::uint32_t k = 0; k < grid.dims.z; ++k) {
                        const std::size_t c = grid.index(i, j, k);
                        const glm::vec3 t = sprite.grid.toTexture(grid.cellCentre(i, j, k));
                        const bool out = t.x < 0 || t.x > 1 || t.y < 0 || t.y > 1 || t.z < 0 || t.z > 1;
                        inside += cpu[c];
                        outsideTheBox += out && cpu[c];
                        if (gpuCells[c] == cpu[c]) continue;
                        ++differ; // float against double near 1/2: the tests above bound those
                    }
            const std::string what = std::string(toString(axis)) + ", " + toString(rule);
            EXPECT_LE(differ, rule == Rule::GeneralizedWinding ? 3u : 0u) << what;
            EXPECT_GT(inside, 0u) << what;
            if (rule == Rule::GeneralizedWinding) {
                EXPECT_GT(outsideTheBox, 0u) << what; // the rim's cells outside the box count
            }
        }
    }
}

TEST_F(GpuOccupancyTest, GeneralizedWindingOfAClosedSpriteIsWinding) {
    const auto two = solids::overlappingBoxes({-1, -1, -1}, {0.3f, 0.3f, 0.3f}, {-0.3f, -0.3f, -0.3f}, {1, 1, 1});
    BakeOptions o;
    o.resolution = 40;
    o.method = BakeMethod::Cpu;
    const Sprite sprite = bake(two.mesh, o);
    const GpuSprite gpu(sprite, GpuSpriteParts::ColumnsOnly);
    ASSERT_EQ(gpu.boundary().edgeCount(), 0u);
    const Box box = meshBounds(two.mesh);
    const Grid grid{{box.lo - 0.1f, box.hi + 0.1f}, {21, 22, 23}};
    std::vector<std::uint8_t> gwn(grid.cellCount(), 7), winding(grid.cellCount(), 9), cpu(grid.cellCount(), 5);
    GpuOccupancy sweep(gl());
    sweep.occupancy(gpu, grid, gwn.data(), {Rule::GeneralizedWinding});
    sweep.occupancy(gpu, grid, winding.data(), {Rule::Winding});
    occupancy(sprite, grid, cpu.data(), {Rule::GeneralizedWinding, 1});
    EXPECT_EQ(gwn, winding);
    EXPECT_EQ(gwn, cpu);
}

TEST_F(GpuOccupancyTest, GeneralizedWindingNeedsAKnownBoundary) {
    BakeOptions o;
    o.resolution = 24;
    o.method = BakeMethod::Cpu;
    Sprite sprite = bake(solids::sphereCup(), o);
    sprite.boundaryKnown = false; // as read from a version 1 file
    const GpuSprite gpu(sprite, GpuSpriteParts::ColumnsOnly);
    ASSERT_FALSE(gpu.boundary().known());
    const Grid grid{sprite.grid.box, {8, 8, 8}};
    std::vector<std::uint8_t> cells(grid.cellCount());
    GpuOccupancy sweep(gl());
    EXPECT_THROW(sweep.occupancy(gpu, grid, cells.data(), {Rule::GeneralizedWinding}), InvalidArgument);
    EXPECT_NO_THROW(sweep.occupancy(gpu, grid, cells.data(), {Rule::Winding}));
}

// A sprite turned exactly 90 degrees about its axis, or mirrored along it,
// still has each texture axis on one world axis: sprite-gpu's occupancy
// answers as the CPU sprite does (it once refused them).
TEST_F(GpuOccupancyTest, QuarterTurnedAndMirroredSpritesAnswerLikeTheCpu) {
    const auto torus = solids::torus({0.2f, -0.1f, 0.05f}, 1.0f, 0.4f, 48);
    for (Axis axis : {Axis::Z, Axis::X}) {
        const glm::ivec3 p = axisPermutation(axis);
        // s -> t and t -> -s about the view axis, entries exactly 0 and 1.
        glm::mat4 quarter(0.0f);
        quarter[p.x][p.y] = 1.0f;
        quarter[p.y][p.x] = -1.0f;
        quarter[p.z][p.z] = 1.0f;
        quarter[3][3] = 1.0f;
        glm::mat4 mirror(1.0f);
        mirror[p.z][p.z] = -1.0f;
        for (const glm::mat4* model : {&quarter, &mirror}) {
            BakeOptions o;
            o.resolution = 48;
            o.axis = axis;
            o.method = BakeMethod::Cpu;
            Sprite sprite = bake(torus.mesh, o);
            sprite.transform(*model);
            const Box box = meshBounds(torus.mesh);
            const glm::vec3 lo(*model * glm::vec4(box.lo, 1.0f)), hi(*model * glm::vec4(box.hi, 1.0f));
            const Grid grid{{glm::min(lo, hi) - 0.1f, glm::max(lo, hi) + 0.1f}, {27, 21, 19}};
            const std::string what = std::string(model == &quarter ? "quarter turn" : "mirror") + " about " +
                                     toString(axis);
            const auto gpu = makeClassifier(gl(), sprite, Method::SpriteGpu);
            const auto cpu = makeClassifier(sprite, Method::Sprite);
            for (Rule rule : {Rule::Parity, Rule::Winding}) {
                std::vector<std::uint8_t> fromCpu(grid.cellCount(), 9), fromGpu(grid.cellCount(), 7);
                cpu->occupancy(grid, fromCpu.data(), {rule, 1});
                ASSERT_NO_THROW(gpu->occupancy(grid, fromGpu.data(), {rule})) << what;
                EXPECT_EQ(fromGpu, fromCpu) << what << " " << toString(rule);
                std::size_t inside = 0;
                for (std::uint8_t l : fromCpu) inside += l;
                EXPECT_GT(inside, fromCpu.size() / 20) << what;
                // Both are the torus moved: the ideal solid's labels at the
                // cells moved back, away from its surface (texels of 0.06).
                const glm::mat4 back = glm::inverse(*model);
                std::size_t differ = 0;
                for (std::uint32_t i = 0; i < grid.dims.x; ++i)
                    for (std::uint32_t j = 0; j < grid.dims.y; ++j)
                        for (std::uint32_t k = 0; k < grid.dims.z; ++k) {
                            const float d = torus.distance(glm::vec3(back * glm::vec4(grid.cellCentre(i, j, k), 1.0f)));
                            if (std::fabs(d) > 0.1f) differ += fromCpu[grid.index(i, j, k)] != (d < 0.0f ? 1 : 0);
                        }
                EXPECT_EQ(differ, 0u) << what;
            }
        }
    }
}

TEST_F(GpuOccupancyTest, RotatedSpritesAndMissingColumnsAreRefused) {
    const auto torus = solids::torus({0, 0, 0}, 1.0f, 0.4f, 32);
    BakeOptions o;
    o.resolution = 32;
    o.method = BakeMethod::Cpu;
    Sprite sprite = bake(torus.mesh, o);
    const Grid grid{meshBounds(torus.mesh), {8, 8, 8}};
    std::vector<std::uint8_t> cells(grid.cellCount());
    GpuOccupancy sweep(gl());
    EXPECT_THROW(sweep.occupancy(GpuSprite(sprite, GpuSpriteParts::TextureOnly), grid, cells.data()), InvalidArgument);
    EXPECT_THROW(sweep.occupancy(GpuSprite(sprite), Grid{grid.box, {0, 8, 8}}, cells.data()), InvalidArgument);
    sprite.transform(glm::rotate(glm::mat4(1.0f), 0.3f, glm::vec3(0, 0, 1)));
    EXPECT_THROW(sweep.occupancy(GpuSprite(sprite), grid, cells.data()), InvalidArgument);
}

} // namespace
} // namespace vds
