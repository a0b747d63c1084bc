// Slicemaps (Eisemann & Décoret 2006): the inner-voxel rule, the bit layout,
// local slicing's per-column ranges, and the classification they give.
#include <cmath>
#include <cstring>

#include <gtest/gtest.h>

#include <vds/all.h>
#include <vds/bake.h>
#include <vds/error.h>
#include <vds/exact.h>
#include "solids.h"
#include <vds/voxel/slicemap.h>

#include "../support/gl_fixture.h"
#include "points.h"
#include "voxel_test_util.h"

namespace vds::voxel {
namespace {

// A column of 64 slices from a string, slice 0 first: 'f' front, 'b' back,
// 'x' both, '.' (and every slice past the string) empty. `inside()` shows
// the rule's answer for the slices the string covers: 'I' inside.
struct Column {
    std::uint32_t front[2] = {0, 0}, back[2] = {0, 0};
    std::uint32_t length = 0;
    explicit Column(const char* pattern) {
        for (std::uint32_t s = 0; pattern[s]; ++s, ++length) {
            if (pattern[s] == 'f' || pattern[s] == 'x') front[s / 32] |= 1u << (s % 32);
            if (pattern[s] == 'b' || pattern[s] == 'x') back[s / 32] |= 1u << (s % 32);
        }
    }
    std::string inside() const {
        std::string out;
        for (std::uint32_t s = 0; s < length; ++s) out += slicemapInside(front, back, 2, s) ? 'I' : '.';
        return out;
    }
};

TEST(SlicemapRuleTest, VoxelsBetweenAFrontAndTheNextBackAreInside) {
    EXPECT_EQ(Column("..f....b..f.b....").inside(), "..IIIIII..III....");
    // Across a word boundary.
    EXPECT_EQ(Column("..............................f.....b.........................").inside(),
              "..............................IIIIIII.........................");
}

TEST(SlicemapRuleTest, AmbiguousVoxelsAreInsideAndTheNextBoundaryResolvesTheGap) {
    // Ambiguous then back: the gap was inside; ambiguous then front: outside.
    EXPECT_EQ(Column("..x...b...x...f..b...").inside(), "..IIIII...I...IIII...");
    // Two ambiguous voxels in a row leave the gap unresolved: outside.
    EXPECT_EQ(Column("..x....x....").inside(), "..I....I....");
    // Nothing in front: outside, even before a back voxel (an open column).
    EXPECT_EQ(Column(".....b....").inside(), ".....I....");
    // An ambiguous voxel in the second word resolved by a back voxel in it.
    EXPECT_EQ(Column("f.b..........................x.......b...").inside(),
              "III..........................IIIIIIIII...");
}

class SlicemapTest : public vds::test::GlTest {};

// Two boxes stacked in z with a gap, the lower one wider: columns over the
// narrow one cross faces at depths 0 (front), 1/4 (back), 1/2 (front), 1 (back).
TriangleMesh stackedBoxes() {
    return solids::merge(solids::box({0, 0, 0}, {1, 1, 0.25f}).mesh, solids::box({0, 0, 0.5f}, {0.5f, 1, 1}).mesh);
}

TEST_F(SlicemapTest, SliceSIsBitSMod32OfWordSDiv32FrontAndBackApart) {
    const TriangleMesh mesh = stackedBoxes();
    SlicemapOptions options;
    options.slices = 256;
    const Slicemap map = buildSlicemap(gl(), mesh, meshBounds(mesh), 32, options);
    EXPECT_EQ(map.slices(), 256u);
    EXPECT_EQ(map.words, 8u);
    EXPECT_EQ(map.renderTargets, 2u); // 128 slices per RGBA32UI target
    EXPECT_EQ(map.passes, 1u);        // 2 x 2 targets fit in one pass
    EXPECT_EQ(map.grid.dims.x, 32u);
    for (std::uint32_t y = 0; y < map.grid.dims.y; ++y)
        for (std::uint32_t x = 0; x < map.grid.dims.x; ++x) {
            const std::size_t c = (std::size_t(y) * map.grid.dims.x + x) * map.words;
            std::uint32_t front[8] = {}, back[8] = {};
            front[0] = 1u;                         // slice 0: the bottom face at depth 0
            back[64 / 32] = 1u;                    // slice 64: the top of the lower box at 1/4
            if (x < 16) front[128 / 32] = 1u;      // slice 128: the bottom of the upper box at 1/2
            if (x < 16) back[255 / 32] = 1u << 31; // slice 255: the top at depth 1 (the last slice)
            ASSERT_EQ(0, std::memcmp(&map.front[c], front, sizeof front)) << "column " << x << "," << y;
            ASSERT_EQ(0, std::memcmp(&map.back[c], back, sizeof back)) << "column " << x << "," << y;
        }
    EXPECT_TRUE(map.frontBit(3, 3, 128));
    EXPECT_FALSE(map.frontBit(20, 3, 128));
    EXPECT_TRUE(map.backBit(20, 3, 64));
    // Inside: the lower box, and the upper box over its columns; the gap is outside.
    EXPECT_TRUE(map.contains({0.75f, 0.5f, 0.1f}));
    EXPECT_FALSE(map.contains({0.75f, 0.5f, 0.4f}));
    EXPECT_FALSE(map.contains({0.75f, 0.5f, 0.75f}));
    EXPECT_TRUE(map.contains({0.25f, 0.5f, 0.75f}));
    EXPECT_FALSE(map.contains({0.25f, 0.5f, 0.4f}));
    EXPECT_FALSE(map.contains({0.25f, 0.5f, 1.01f}));
}

TEST_F(SlicemapTest, ManySlicesTakeEightTargetsAndOnePassPerFacing) {
    const TriangleMesh mesh = stackedBoxes();
    SlicemapOptions options;
    options.slices = 1024;
    const Slicemap map = buildSlicemap(gl(), mesh, meshBounds(mesh), 16, options);
    EXPECT_EQ(map.renderTargets, 8u);
    EXPECT_EQ(map.passes, 2u);
    EXPECT_TRUE(map.frontBit(3, 3, 0));
    EXPECT_TRUE(map.backBit(3, 3, 256));
    EXPECT_TRUE(map.frontBit(3, 3, 512));
    EXPECT_TRUE(map.backBit(3, 3, 1023));
    EXPECT_FALSE(map.frontBit(12, 3, 512));
    EXPECT_TRUE(map.contains({0.25f, 0.5f, 0.75f}));
    EXPECT_FALSE(map.contains({0.25f, 0.5f, 0.4f}));
}

TEST_F(SlicemapTest, LocalSlicingRangesAreEachColumnsNearestAndFarthestCrossing) {
    const auto torus = solids::torus({0.1f, 0.2f, 0.3f}, 1.0f, 0.35f, 48);
    const Box box = meshBounds(torus.mesh);
    SlicemapOptions options;
    options.slicing = Slicing::Local;
    const Slicemap map = buildSlicemap(gl(), torus.mesh, box, 48, options);
    EXPECT_EQ(map.passes, 2u); // ranges, then both facings at once
    BakeOptions bake;
    bake.method = BakeMethod::Cpu;
    bake.resolution = 48;
    const Sprite sprite = vds::bake(torus.mesh, bake); // the same columns, exact crossings
    ASSERT_EQ(sprite.width(), map.grid.dims.x);
    ASSERT_EQ(sprite.height(), map.grid.dims.y);
    std::size_t covered = 0, coverageDiffers = 0;
    for (std::uint32_t y = 0; y < map.grid.dims.y; ++y)
        for (std::uint32_t x = 0; x < map.grid.dims.x; ++x) {
            const std::size_t c = std::size_t(y) * map.grid.dims.x + x;
            const std::uint32_t begin = sprite.offsets[c], end = sprite.offsets[c + 1];
            const bool empty = map.nearDepth[c] > map.farDepth[c];
            if ((begin == end) != empty) {
                ++coverageDiffers; // snapping moved the silhouette across the column centre
                EXPECT_TRUE(test::nearProjectedEdge(torus.mesh, map.grid, x, y, 1.0 / 256.0)) << x << "," << y;
                continue;
            }
            if (empty) continue;
            ++covered;
            const float slices = float(map.slices());
            EXPECT_NEAR(map.nearDepth[c] / slices, crossingDepth(sprite.crossings[begin]), 1e-3) << x << "," << y;
            EXPECT_NEAR(map.farDepth[c] / slices, crossingDepth(sprite.crossings[end - 1]), 1e-3) << x << "," << y;
            EXPECT_FLOAT_EQ(map.slicesPerDepth[c], slices / (map.farDepth[c] - map.nearDepth[c]));
            // The nearest crossing is in slice 0, the farthest in the last.
            EXPECT_TRUE(map.frontBit(x, y, 0)) << x << "," << y;
            EXPECT_TRUE(map.backBit(x, y, map.slices() - 1)) << x << "," << y;
        }
    EXPECT_GT(covered, map.grid.dims.x * map.grid.dims.y / 3);
    EXPECT_LT(coverageDiffers, 5u);
}

// Points farther from the surface than a slice and half a column diagonal
// (plus the tessellation error) are classified as the analytic solid.
void expectFarPointsRight(const Slicemap& map, const solids::Solid& solid, float sliceThickness) {
    const float margin = sliceThickness + 0.75f * map.grid.cellSize() + solid.tessellationError;
    const auto points = vds::test::randomPoints(map.grid.box, 20000, 0.1f, 3);
    std::size_t checked = 0, wrong = 0;
    for (const auto& p : points) {
        const float d = solid.distance(p);
        if (std::fabs(d) <= margin) continue;
        ++checked;
        wrong += map.contains(p) != (d < 0.0f);
    }
    EXPECT_GT(checked, 10000u);
    EXPECT_EQ(wrong, 0u) << "of " << checked << " points far from the surface";
}

TEST_F(SlicemapTest, UniformAndLocalSlicemapsClassifyPointsAwayFromTheSurface) {
    const auto shell = solids::shell({0, 0, 0}, 1.0f, 0.6f, 48);
    const auto torus = solids::torus({0, 0, 0}, 1.0f, 0.4f, 48);
    const auto touching = solids::boxesSharingAnEdge({-1.0f, -1.0f, -0.5f}, 1.0f); // non-manifold, still a solid
    for (const auto* solid : {&shell, &torus, &touching})
        for (Slicing slicing : {Slicing::Uniform, Slicing::Local}) {
            SlicemapOptions options;
            options.slicing = slicing;
            const Box box = meshBounds(solid->mesh);
            const Slicemap map = buildSlicemap(gl(), solid->mesh, box, 64, options);
            // Uniform slices divide the box depth; local ones at most that.
            expectFarPointsRight(map, *solid, (box.hi.z - box.lo.z) / float(map.slices()));
        }
}

TEST_F(SlicemapTest, AThinPlateBecomesAmbiguousVoxelsThatCountAsInside) {
    // A plate thinner than a slice: its two faces share slices, the voxels
    // holding them count as inside on both sides of the plate.
    const auto plate = solids::box({0, 0, 0.5f}, {1, 1, 0.505f});
    const auto frame = solids::box({0, 0, 0}, {0.1f, 0.1f, 1});
    const TriangleMesh mesh = solids::merge(plate.mesh, frame.mesh);
    SlicemapOptions options;
    options.slices = 32;
    const Slicemap map = buildSlicemap(gl(), mesh, meshBounds(mesh), 32, options);
    EXPECT_TRUE(map.frontBit(20, 20, 16));
    EXPECT_TRUE(map.backBit(20, 20, 16));
    EXPECT_TRUE(map.contains({0.6f, 0.6f, 0.502f})); // in the plate
    EXPECT_TRUE(map.contains({0.6f, 0.6f, 0.52f}));  // above it, same slice: wrongly inside
    EXPECT_FALSE(map.contains({0.6f, 0.6f, 0.6f}));  // the next slice: outside again
    EXPECT_FALSE(map.contains({0.6f, 0.6f, 0.45f})); // the slice before
}

TEST_F(SlicemapTest, BadArgumentsAreRejected) {
    const auto sphere = solids::sphere({0, 0, 0}, 1.0f, 16);
    const Box box = meshBounds(sphere.mesh);
    SlicemapOptions options;
    options.slices = 48;
    EXPECT_THROW(buildSlicemap(gl(), sphere.mesh, box, 16, options), InvalidArgument);
    options.slices = 2048;
    EXPECT_THROW(buildSlicemap(gl(), sphere.mesh, box, 16, options), InvalidArgument);
    EXPECT_THROW(buildSlicemap(gl(), sphere.mesh, box, 0), InvalidArgument);
    auto open = sphere.mesh;
    open.triangles.resize(open.triangles.size() / 2);
    EXPECT_THROW(buildSlicemap(gl(), open, box, 16), InvalidMesh);
    EXPECT_THROW(parseSlicing("adaptive"), InvalidArgument);
    EXPECT_EQ(defaultSlices(box, 16), 32u);
    EXPECT_EQ(defaultSlices(box, 100), 128u);
    EXPECT_EQ(defaultSlices(box, 5000), kMaxSlices);
}

} // namespace
} // namespace vds::voxel
