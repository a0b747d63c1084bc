// The GPU column sweep against the CPU one (vds::occupancy), cell by cell,
// on llvmpipe or a real GPU: sprites along each axis, both rules, a sprite
// moved and scaled after the bake, grids whose box reaches past the sprite's
// and whose sizes are not multiples of four (label words shared by columns).
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <vds/bake.h>
#include <vds/error.h>
#include <vds/gpu_occupancy.h>
#include <vds/gpu_sprite.h>
#include <vds/occupancy.h>
#include "solids.h"

#include "../support/gl_fixture.h"

namespace vds {
namespace {

class GpuOccupancyTest : public test::GlTest {};

TEST_F(GpuOccupancyTest, GpuSweepEqualsCpuSweepOnEveryCell) {
    const auto torus = solids::torus({0.2f, -0.1f, 0.0f}, 1.0f, 0.4f, 64);
    const auto two = solids::overlappingBoxes({-1, -1, -1}, {0.3f, 0.3f, 0.3f}, {-0.3f, -0.3f, -0.3f}, {1, 1, 1});
    GpuOccupancy sweep(gl());
    int cases = 0;
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
                const OccupancyGrid grid{{box.lo - pad, box.hi + pad}, {37, 29, 23}};
                const GpuSprite gpu(sprite, GpuSpriteParts::ColumnsOnly);
                for (Rule rule : {Rule::Parity, Rule::Winding}) {
                    std::vector<std::uint8_t> cpu(grid.cellCount(), 9), gpuCells(grid.cellCount(), 7);
                    occupancy(sprite, grid, cpu.data(), {rule, 1});
                    sweep.run(gpu, grid, gpuCells.data(), rule);
                    std::size_t differ = 0, inside = 0;
                    for (std::size_t k = 0; k < cpu.size(); ++k) {
                        differ += cpu[k] != gpuCells[k];
                        inside += cpu[k];
                    }
                    EXPECT_EQ(differ, 0u) << "axis " << toString(axis) << " moved " << moved << " " << toString(rule);
                    EXPECT_GT(inside, cpu.size() / 20); // not vacuous
                    EXPECT_LT(inside, cpu.size() / 2);
                    ++cases;
                }
            }
    EXPECT_EQ(cases, 24);
}

TEST_F(GpuOccupancyTest, RotatedSpritesAndMissingColumnsAreRefused) {
    const auto torus = solids::torus({0, 0, 0}, 1.0f, 0.4f, 32);
    BakeOptions o;
    o.resolution = 32;
    o.method = BakeMethod::Cpu;
    Sprite sprite = bake(torus.mesh, o);
    const OccupancyGrid grid{meshBounds(torus.mesh), {8, 8, 8}};
    std::vector<std::uint8_t> cells(grid.cellCount());
    GpuOccupancy sweep(gl());
    EXPECT_THROW(sweep.run(GpuSprite(sprite, GpuSpriteParts::TextureOnly), grid, cells.data()), InvalidArgument);
    EXPECT_THROW(sweep.run(GpuSprite(sprite), OccupancyGrid{grid.box, {0, 8, 8}}, cells.data()), InvalidArgument);
    sprite.transform(glm::rotate(glm::mat4(1.0f), 0.3f, glm::vec3(0, 0, 1)));
    EXPECT_THROW(sweep.run(GpuSprite(sprite), grid, cells.data()), InvalidArgument);
}

} // namespace
} // namespace vds
