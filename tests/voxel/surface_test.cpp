// Conservative surface voxelization (Schwarz & Seidel 2010) against a
// brute-force separating-axis triangle/box test (Akenine-Möller 2001) in
// exact integer arithmetic on the same snapped triangles.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <random>

#include <gtest/gtest.h>
#include <glm/common.hpp>

#include <vds/error.h>
#include "solids.h"
#include <vds/voxel/surface.h>

#include "../support/gl_fixture.h"

namespace vds::voxel {
namespace {

// Coordinates are integers in 1/256 cell: for grids below 4096 cells a
// product of three coordinate differences stays far below 2^63.
using Int = std::int64_t;
using IVec = std::array<Int, 3>;

IVec fixedCells(const VoxelGrid& grid, const glm::vec3& p) {
    const glm::vec3 v = grid.toCells(p);
    IVec out;
    for (int a = 0; a < 3; ++a) out[a] = Int(std::floor(v[a] * 256.0f + 0.5f)); // 1/256 cell units, as the shader
    return out;
}

IVec sub(const IVec& a, const IVec& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
IVec cross(const IVec& a, const IVec& b) {
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
Int dot(const IVec& a, const IVec& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Int absolute(Int x) { return x < 0 ? -x : x; }

// Whether the closed triangle (v, box-relative) and the closed box of half
// size h centred at the origin overlap: no separating axis among the 13 of
// the separating axis theorem (box normals, triangle normal, edge x axis).
bool triangleBoxOverlap(const std::array<IVec, 3>& v, Int h) {
    const auto separated = [&](const IVec& axis) {
        const Int p0 = dot(axis, v[0]), p1 = dot(axis, v[1]), p2 = dot(axis, v[2]);
        const Int r = h * (absolute(axis[0]) + absolute(axis[1]) + absolute(axis[2]));
        return std::min({p0, p1, p2}) > r || std::max({p0, p1, p2}) < -r;
    };
    const IVec units[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    for (const IVec& u : units)
        if (separated(u)) return false;
    const IVec e[3] = {sub(v[1], v[0]), sub(v[2], v[1]), sub(v[0], v[2])};
    if (separated(cross(e[0], e[1]))) return false;
    for (const IVec& edge : e)
        for (const IVec& u : units)
            if (separated(cross(edge, u))) return false;
    return true;
}

// Every voxel a triangle touches, by testing every voxel near its box.
BitGrid bruteForce(const TriangleMesh& mesh, const VoxelGrid& grid) {
    BitGrid bits = makeBitGrid(grid);
    for (const auto& tri : mesh.triangles) {
        const IVec v[3] = {fixedCells(grid, mesh.positions[tri[0]]), fixedCells(grid, mesh.positions[tri[1]]),
                           fixedCells(grid, mesh.positions[tri[2]])};
        int first[3], last[3];
        for (int a = 0; a < 3; ++a) {
            const Int lo = std::min({v[0][a], v[1][a], v[2][a]}), hi = std::max({v[0][a], v[1][a], v[2][a]});
            first[a] = std::max(0, int((lo - 1) / 256) - 1); // a superset of the touched range
            last[a] = std::min(int(grid.dims[a]) - 1, int(hi / 256) + 1);
        }
        for (int z = first[2]; z <= last[2]; ++z)
            for (int y = first[1]; y <= last[1]; ++y)
                for (int x = first[0]; x <= last[0]; ++x) {
                    const IVec centre = {Int(x) * 256 + 128, Int(y) * 256 + 128, Int(z) * 256 + 128};
                    if (triangleBoxOverlap({sub(v[0], centre), sub(v[1], centre), sub(v[2], centre)}, 128))
                        bits.set(std::uint32_t(x), std::uint32_t(y), std::uint32_t(z), true);
                }
    }
    return bits;
}

void expectEqual(const BitGrid& gpu, const BitGrid& cpu, const char* what) {
    std::size_t missing = 0, extra = 0;
    for (std::uint32_t z = 0; z < gpu.grid.dims.z; ++z)
        for (std::uint32_t y = 0; y < gpu.grid.dims.y; ++y)
            for (std::uint32_t x = 0; x < gpu.grid.dims.x; ++x) {
                missing += cpu.test(x, y, z) && !gpu.test(x, y, z);
                extra += !cpu.test(x, y, z) && gpu.test(x, y, z);
            }
    EXPECT_EQ(missing, 0u) << what << ": touched voxels not set";
    EXPECT_EQ(extra, 0u) << what << ": voxels set that no triangle touches";
    EXPECT_GT(cpu.count(), 0u) << what;
}

class SurfaceTest : public vds::test::GlTest {};

TEST_F(SurfaceTest, BoxOnVoxelBoundariesSetsTheVoxelsOnBothSidesOfEachFace) {
    const auto box = solids::box({0.25f, 0.25f, 0.25f}, {0.75f, 0.75f, 0.75f});
    const VoxelGrid grid = makeVoxelGrid({{0, 0, 0}, {1, 1, 1}}, 16); // faces on cell planes 4 and 12
    const BitGrid bits = voxelizeSurface(gl(), box.mesh, grid);
    std::size_t wrong = 0;
    for (std::uint32_t z = 0; z < 16; ++z)
        for (std::uint32_t y = 0; y < 16; ++y)
            for (std::uint32_t x = 0; x < 16; ++x) {
                const auto in = [](std::uint32_t i, std::uint32_t a, std::uint32_t b) { return i >= a && i <= b; };
                const bool touches = in(x, 3, 12) && in(y, 3, 12) && in(z, 3, 12);
                const bool interior = in(x, 5, 10) && in(y, 5, 10) && in(z, 5, 10);
                wrong += bits.test(x, y, z) != (touches && !interior);
            }
    EXPECT_EQ(wrong, 0u);
    expectEqual(bits, bruteForce(box.mesh, grid), "box");
}

TEST_F(SurfaceTest, ClosedSolidsEqualTheBruteForceOverlapTest) {
    const auto sphere = solids::sphere({0.1f, -0.2f, 0.3f}, 1.0f, 32);
    const auto torus = solids::torus({0, 0, 0}, 1.0f, 0.3f, 32);
    for (const auto* solid : {&sphere, &torus})
        for (std::uint32_t resolution : {24u, 40u}) {
            const VoxelGrid grid = makeVoxelGrid(meshBounds(solid->mesh), resolution);
            expectEqual(voxelizeSurface(gl(), solid->mesh, grid), bruteForce(solid->mesh, grid), "solid");
        }
}

TEST_F(SurfaceTest, TriangleSoupWithDegenerateAndGridSizedTrianglesEqualsTheBruteForceTest) {
    TriangleMesh soup;
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::uniform_int_distribution<int> cell(0, 32);
    for (int t = 0; t < 300; ++t) {
        const auto base = std::uint32_t(soup.positions.size());
        const float size = t % 10 == 0 ? 1.0f : 0.15f;
        const glm::vec3 anchor(u(rng), u(rng), u(rng));
        for (int k = 0; k < 3; ++k) {
            glm::vec3 p = anchor + size * (glm::vec3(u(rng), u(rng), u(rng)) - 0.5f);
            if (t % 7 == 0) p = glm::vec3(cell(rng), cell(rng), cell(rng)) / 32.0f; // on cell corners
            soup.positions.push_back(glm::clamp(p, glm::vec3(0.0f), glm::vec3(1.0f)));
        }
        if (t % 13 == 0) soup.positions[base + 2] = soup.positions[base + 1]; // zero area: a segment
        if (t % 17 == 0) soup.positions[base + 2] = 0.5f * (soup.positions[base] + soup.positions[base + 1]);
        soup.triangles.emplace_back(base, base + 1, base + 2);
    }
    const VoxelGrid grid = makeVoxelGrid({{0, 0, 0}, {1, 1, 1}}, 32);
    expectEqual(voxelizeSurface(gl(), soup, grid), bruteForce(soup, grid), "soup");
}

TEST_F(SurfaceTest, UnusableMeshesAreRejected) {
    TriangleMesh empty;
    const VoxelGrid grid = makeVoxelGrid({{0, 0, 0}, {1, 1, 1}}, 8);
    EXPECT_THROW(voxelizeSurface(gl(), empty, grid), InvalidMesh);
    auto bad = solids::box({0, 0, 0}, {1, 1, 1}).mesh;
    bad.triangles[0].x = 99;
    EXPECT_THROW(voxelizeSurface(gl(), bad, grid), InvalidMesh);
}

} // namespace
} // namespace vds::voxel
