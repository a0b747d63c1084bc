// Geometry-shader slicing voxelization (Chang et al. 2014): each voxel gets
// one fragment per triangle whose plane crosses its slab at its column
// centre, with the triangles' normals.
#include <cmath>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include <vds/error.h>
#include "solids.h"
#include <vds/voxel/slicing.h>

#include "../support/gl_fixture.h"
#include "voxel_test_util.h"

namespace vds::voxel {
namespace {

class SlicingTest : public vds::test::GlTest {};

struct Expected {
    std::vector<std::uint32_t> count;
    std::vector<glm::dvec3> normal;
};

// Per voxel: the triangles (snapped as the voxelizer sees them) covering the
// column centre under the fill rule of shaders/voxel/solid_common.glsl
// (another driver's rule may pick the other triangle at a shared edge, never
// both or none), counted in the slice holding their depth there.
Expected expectedFragments(const TriangleMesh& mesh, const VoxelGrid& grid) {
    Expected e;
    e.count.assign(grid.cellCount(), 0);
    e.normal.assign(grid.cellCount(), glm::dvec3(0.0));
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        glm::vec3 v[3];
        test::snappedTriangle(mesh, grid, t, v);
        glm::dvec3 a(v[0]), b(v[1]), c(v[2]);
        const glm::dvec3 n = glm::cross(b - a, c - a);
        if (n.z == 0.0) continue;
        if (n.z < 0.0) std::swap(b, c); // counter-clockwise in xy
        for (std::uint32_t y = 0; y < grid.dims.y; ++y)
            for (std::uint32_t x = 0; x < grid.dims.x; ++x) {
                const glm::dvec2 q(x + 0.5, y + 0.5);
                const auto edge = [&](const glm::dvec3& p, const glm::dvec3& r) {
                    return (r.x - p.x) * (q.y - p.y) - (r.y - p.y) * (q.x - p.x);
                };
                const auto claims = [&](const glm::dvec3& p, const glm::dvec3& r) {
                    const double w = edge(p, r);
                    return w > 0.0 || (w == 0.0 && (r.y < p.y || (r.y == p.y && r.x > p.x)));
                };
                if (!claims(a, b) || !claims(b, c) || !claims(c, a)) continue;
                const double wa = edge(b, c), wb = edge(c, a), wc = edge(a, b);
                const double z = (wa * a.z + wb * b.z + wc * c.z) / (wa + wb + wc);
                const int k = int(std::floor(z));
                if (k < 0 || k >= int(grid.dims.z)) continue;
                const std::size_t i = (std::size_t(k) * grid.dims.y + y) * grid.dims.x + x;
                ++e.count[i];
                e.normal[i] += glm::normalize(n);
            }
    }
    return e;
}

TEST_F(SlicingTest, BoxFacesAcrossZFillOneSliceEachAndSidesAlongZNone) {
    const auto box = solids::box({0.25f, 0.25f, 0.3f}, {0.75f, 0.75f, 0.7f});
    const VoxelGrid grid = makeVoxelGrid({{0, 0, 0}, {1, 1, 1}}, 16);
    SlicingOptions options;
    options.absorptionPerFragment = 0.5f;
    const SlicedVoxels v = voxelizeSlices(gl(), box.mesh, grid, options);
    EXPECT_EQ(v.instances, 1u);
    std::size_t wrong = 0;
    for (std::uint32_t z = 0; z < 16; ++z)
        for (std::uint32_t y = 0; y < 16; ++y)
            for (std::uint32_t x = 0; x < 16; ++x) {
                const bool column = x >= 4 && x < 12 && y >= 4 && y < 12;
                const bool bottom = column && z == 4, top = column && z == 11; // 0.3 * 16 = 4.8, 0.7 * 16 = 11.2
                wrong += v.fragments(x, y, z) != ((bottom || top) ? 1u : 0u);
                if (bottom) {
                    EXPECT_EQ(v.normal(x, y, z), glm::vec3(0, 0, -1));
                }
                if (top) {
                    EXPECT_EQ(v.normal(x, y, z), glm::vec3(0, 0, 1));
                    EXPECT_EQ(v.absorption(x, y, z), 0.5f);
                }
            }
    EXPECT_EQ(wrong, 0u);
    EXPECT_EQ(v.occupancy().count(), 128u);
    EXPECT_EQ(v.memoryBytes(), 16u * 16u * 16u * 16u);
}

TEST_F(SlicingTest, EveryVoxelCountsTheTrianglesCrossingItsColumnCentreInItsSlab) {
    const auto torus = solids::torus({0.1f, 0.2f, 0.3f}, 1.0f, 0.4f, 40);
    const auto sphere = solids::sphere({0, 0, 0}, 1.0f, 40);
    for (const auto* solid : {&torus, &sphere})
        for (std::uint32_t resolution : {32u, 48u}) {
            const VoxelGrid grid = makeVoxelGrid(meshBounds(solid->mesh), resolution);
            const SlicedVoxels v = voxelizeSlices(gl(), solid->mesh, grid);
            const Expected e = expectedFragments(solid->mesh, grid);
            std::size_t fragments = 0, differing = 0;
            for (std::uint32_t z = 0; z < grid.dims.z; ++z)
                for (std::uint32_t y = 0; y < grid.dims.y; ++y)
                    for (std::uint32_t x = 0; x < grid.dims.x; ++x) {
                        const std::size_t i = v.index(x, y, z);
                        fragments += e.count[i];
                        if (v.fragments(x, y, z) != e.count[i]) {
                            // A crossing within rounding of a slab boundary, or a
                            // column centre within snapping of a projected edge.
                            ++differing;
                            EXPECT_TRUE(test::nearInDepth(solid->mesh, grid, x, y, z) ||
                                        test::nearInDepth(solid->mesh, grid, x, y, z + 1) ||
                                        test::nearProjectedEdge(solid->mesh, grid, x, y, 1.0 / 256.0))
                                << "voxel " << x << "," << y << "," << z << ": " << v.fragments(x, y, z)
                                << " fragments, expected " << e.count[i];
                            continue;
                        }
                        if (e.count[i] == 0 || test::nearProjectedEdge(solid->mesh, grid, x, y, 1.0 / 256.0)) continue;
                        const glm::vec3 expected(glm::normalize(e.normal[i]));
                        EXPECT_LT(glm::length(v.normal(x, y, z) - expected), 1e-4f) << x << "," << y << "," << z;
                    }
            EXPECT_GT(fragments, 1000u);
            EXPECT_LT(differing, fragments / 100 + 1);
        }
}

TEST_F(SlicingTest, ManySlicesTakeSeveralInstancesOfOneDraw) {
    const auto sphere = solids::sphere({0, 0, 0}, 1.0f, 24);
    const VoxelGrid grid = makeVoxelGrid(meshBounds(sphere.mesh), 100);
    const SlicedVoxels v = voxelizeSlices(gl(), sphere.mesh, grid);
    EXPECT_GT(v.instances, 1u);
    // The poles are in the first and last slice, along the z axis.
    EXPECT_GT(v.fragments(49, 49, 0) + v.fragments(50, 50, 0) + v.fragments(49, 50, 0) + v.fragments(50, 49, 0), 0u);
    EXPECT_GT(v.fragments(49, 49, 99) + v.fragments(50, 50, 99) + v.fragments(49, 50, 99) + v.fragments(50, 49, 99),
              0u);
}

TEST_F(SlicingTest, BadArgumentsAreRejected) {
    const auto sphere = solids::sphere({0, 0, 0}, 1.0f, 16);
    SlicingOptions options;
    options.slabPadding = 1.5f;
    EXPECT_THROW(voxelizeSlices(gl(), sphere.mesh, makeVoxelGrid(meshBounds(sphere.mesh), 8), options),
                 InvalidArgument);
    EXPECT_THROW(voxelizeSlices(gl(), sphere.mesh, makeVoxelGrid(meshBounds(sphere.mesh), 4096)),
                 InvalidArgument);
    EXPECT_THROW(voxelizeSlices(gl(), TriangleMesh{}, makeVoxelGrid(meshBounds(sphere.mesh), 8)), InvalidMesh);
}

} // namespace
} // namespace vds::voxel
