// The axis choice (<vds/bake.h>'s chooseViewAxis): its layer and crossing
// counts against the CPU baker's sprites, and validation's facings against
// the exact predicate.
#include <algorithm>
#include <cmath>
#include <random>
#include <utility>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <vds/bake.h>
#include <vds/detail/edge_partners.h>
#include <vds/detail/predicates.h>
#include <vds/error.h>
#include <vds/mesh_check.h>
#include <vds/sprite.h>

#include "solids.h"

namespace vds {
namespace {

// The choice's layers and crossings along `axis` against the CPU baker's
// sprite along that axis at the choice's resolution.
void expectCountsOfTheBake(const TriangleMesh& mesh, const AxisChoice& choice, Axis axis) {
    BakeOptions o;
    o.resolution = choice.resolution;
    o.axis = axis;
    const Sprite sprite = bakeCpu(mesh, o);
    EXPECT_EQ(choice.layers[std::size_t(axis)], sprite.depthComplexity) << toString(axis) << " " << choice.resolution;
    EXPECT_EQ(choice.crossings[std::size_t(axis)], sprite.crossings.size()) << toString(axis) << " " << choice.resolution;
}

TEST(ChooseViewAxis, PicksTheAxisWithTheFewestLayers) {
    // A torus seen along its symmetry axis has two layers, from the side four.
    auto torus = solids::torus({0, 0, 0}, 1.0f, 0.3f, 48).mesh;
    EXPECT_EQ(chooseViewAxis(torus, 64).axis, Axis::Z);
    for (auto& p : torus.positions) p = glm::vec3(p.z, p.x, p.y); // symmetry axis now x
    EXPECT_EQ(chooseViewAxis(torus, 64).axis, Axis::X);
    for (auto& p : torus.positions) p = glm::vec3(p.z, p.x, p.y); // and now y
    const AxisChoice choice = chooseViewAxis(torus, 64);
    EXPECT_EQ(choice.axis, Axis::Y);
    EXPECT_EQ(choice.summary(), "axis y: 2 layers (x 4, y 2, z 4 at 64 texels)");
}

// The choice counts what the bakers make, at the resolution baked: its layers
// and crossings per axis equal those of the CPU baker's sprites, on meshes
// where a coarse probe and the real resolution disagree.
TEST(ChooseViewAxis, CountsExactlyWhatTheBakerMakesAtThatResolution) {
    std::vector<TriangleMesh> meshes = {solids::torusKnot({0, 0, 0}, 1.0f, 2, 3, 0.25f, 96, 12).mesh,
                                        solids::merge(solids::sphere({0, 0, 0}, 1.0f, 24).mesh,
                                                      solids::box({1.5f, -0.2f, -2.0f}, {1.6f, 0.2f, 2.0f}).mesh)};
    for (const TriangleMesh& mesh : meshes)
        for (std::uint32_t resolution : {7u, 64u, 300u}) {
            const AxisChoice choice = chooseViewAxis(mesh, resolution);
            EXPECT_EQ(choice.resolution, resolution);
            for (Axis axis : {Axis::X, Axis::Y, Axis::Z}) expectCountsOfTheBake(mesh, choice, axis);
            // No axis assigned: the bakers take the choice.
            BakeOptions unset;
            unset.resolution = resolution;
            EXPECT_EQ(bakeCpu(mesh, unset).grid.axis, choice.axis);
        }
}

// The count cuts each axis's rows into bands of about 2^16 texels (65 rows
// at 1000 texels) and lists each triangle in every band it spans: a long box
// spans them all, a knot's triangles a few; and any number of threads counts
// alike.
TEST(ChooseViewAxis, CountsExactlyAcrossBandsAndThreads) {
    const TriangleMesh mesh = solids::merge(solids::torusKnot({0, 0, 0}, 1.0f, 2, 3, 0.25f, 64, 8).mesh,
                                            solids::box({-1.6f, -0.1f, -1.5f}, {1.4f, 0.15f, 1.6f}).mesh);
    constexpr std::uint32_t kResolution = 1000;
    const AxisChoice choice = chooseViewAxis(mesh, kResolution, 1);
    for (Axis axis : {Axis::X, Axis::Y, Axis::Z}) expectCountsOfTheBake(mesh, choice, axis);
    for (unsigned threads : {2u, 3u}) {
        const AxisChoice again = chooseViewAxis(mesh, kResolution, threads);
        EXPECT_EQ(again.layers, choice.layers) << threads;
        EXPECT_EQ(again.crossings, choice.crossings) << threads;
    }
}

// The count computes only the steps that do not cancel against a
// neighbour's (the triangles on either side of a shared edge): boundary
// edges, non-manifold edges, edges whose triangles run them the same way,
// loose triangles and triangles that share positions but no indices keep
// theirs where the count pairs edges by index (`chooseViewAxis(mesh, report,
// ...)`), not where validation pairs them by position (`chooseViewAxis(mesh,
// resolution)`, the bakes). Each counts what the baker makes.
TEST(ChooseViewAxis, CountsExactlyOnOpenNonManifoldAndUnsharedMeshes) {
    TriangleMesh flipped = solids::sphere({0.1f, 0.0f, -0.2f}, 1.0f, 20).mesh;
    for (std::size_t k = 0; k < flipped.triangles.size(); k += 7) std::swap(flipped.triangles[k].y, flipped.triangles[k].z);
    TriangleMesh unshared; // the same sphere, every triangle with its own three vertices
    for (const glm::uvec3& t : solids::sphere({0.1f, 0.0f, -0.2f}, 1.0f, 20).mesh.triangles) {
        const auto& p = solids::sphere({0.1f, 0.0f, -0.2f}, 1.0f, 20).mesh.positions;
        const auto n = std::uint32_t(unshared.positions.size());
        unshared.positions.insert(unshared.positions.end(), {p[t.x], p[t.y], p[t.z]});
        unshared.triangles.push_back({n, n + 1, n + 2});
    }
    const std::vector<TriangleMesh> meshes = {solids::sphereWithHoles(), solids::boxesSharingAnEdge({0, 0, 0}, 1.0f).mesh,
                                              flipped, unshared, solids::looseTriangles(200, 0.3f, 7),
                                              solids::merge(flipped, solids::overlappingShells())};
    for (const TriangleMesh& mesh : meshes)
        for (std::uint32_t resolution : {64u, 301u}) {
            const AxisChoice choice = chooseViewAxis(mesh, resolution);
            const AxisChoice byIndex = chooseViewAxis(mesh, validateMesh(mesh), resolution);
            EXPECT_EQ(byIndex.layers, choice.layers);
            EXPECT_EQ(byIndex.crossings, choice.crossings);
            for (Axis axis : {Axis::X, Axis::Y, Axis::Z}) expectCountsOfTheBake(mesh, choice, axis);
        }
}

// Texel centres rounded to floats far from the origin are unevenly spaced,
// some equal: the count then searches the centres instead of trusting the
// even spacing, and still counts what the baker makes.
TEST(ChooseViewAxis, CountsExactlyWhereCentresAreUnevenlySpaced) {
    const TriangleMesh mesh = solids::torusKnot({1000.0f, -2000.0f, 500.0f}, 0.01f, 2, 3, 0.0025f, 48, 8).mesh;
    for (std::uint32_t resolution : {300u, 900u}) {
        const AxisChoice choice = chooseViewAxis(mesh, resolution);
        for (Axis axis : {Axis::X, Axis::Y, Axis::Z}) expectCountsOfTheBake(mesh, choice, axis);
    }
}

// The count's two paths (a row through a vertex or along an edge: the claim
// test at both ends; a row through the interior: the edges' slopes and a
// margin) give the baker's counts where rows run through vertices and along
// edges: every vertex of a sphere snapped onto texel centres (s and t),
// inside two corner boxes that fix the bounds, and a thin tilted slab.
TEST(ChooseViewAxis, CountsExactlyWithVerticesOnTexelCentres) {
    constexpr std::uint32_t kResolution = 40;
    const TriangleMesh anchors = solids::merge(solids::box({-2.0f, -2.0f, -2.0f}, {-1.9f, -1.9f, -1.9f}).mesh,
                                               solids::box({1.9f, 1.9f, 1.9f}, {2.0f, 2.0f, 2.0f}).mesh);
    for (Axis axis : {Axis::X, Axis::Y, Axis::Z}) {
        TriangleMesh sphere = solids::sphere({0.1f, -0.05f, 0.0f}, 1.3f, 16).mesh;
        const SpriteGrid grid = makeGrid(validateMesh(anchors).bounds, axis, kResolution);
        const glm::ivec3 perm = axisPermutation(axis);
        const glm::vec3 first = grid.texelCentre(0, 0, 0.0f), next = grid.texelCentre(1, 1, 0.0f);
        for (glm::vec3& p : sphere.positions)
            for (int c : {perm.x, perm.y}) { // the nearest centre: i or j from the even spacing
                const float k = std::round((p[c] - first[c]) / (next[c] - first[c]));
                const glm::vec3 centre = grid.texelCentre(std::uint32_t(k), std::uint32_t(k), 0.0f);
                p[c] = centre[c];
            }
        TriangleMesh slab = solids::box({-1.5f, -0.01f, -1.2f}, {1.5f, 0.01f, 1.2f}).mesh;
        for (glm::vec3& p : slab.positions) p = glm::vec3(p.x + 0.2f * p.z, p.y + 0.3f * p.x, p.z);
        for (const TriangleMesh& mesh : {solids::merge(sphere, anchors), solids::merge(slab, anchors)}) {
            ASSERT_EQ(validateMesh(mesh).bounds.lo, validateMesh(anchors).bounds.lo);
            expectCountsOfTheBake(mesh, chooseViewAxis(mesh, kResolution), axis);
        }
    }
}

// A square prism turned 45 degrees about z, each side fanned about its
// centre: seen along z, each side's triangles are three points on a line
// (the centre and two corners, two of them on one vertical edge or not),
// whose products in the orientation are not zero but cancel exactly.
TriangleMesh fannedDiamondPrism() {
    TriangleMesh mesh;
    const glm::vec2 c[4] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
    for (int k = 0; k < 4; ++k) mesh.positions.push_back({c[k], 1.0f});                            // t_k: 0-3
    for (int k = 0; k < 4; ++k) mesh.positions.push_back({c[k], -1.0f});                           // b_k: 4-7
    for (int k = 0; k < 4; ++k) mesh.positions.push_back({0.5f * (c[k] + c[(k + 1) % 4]), 0.0f}); // m_k: 8-11
    for (std::uint32_t k = 0; k < 4; ++k) {
        const std::uint32_t t0 = k, t1 = (k + 1) % 4, b0 = 4 + k, b1 = 4 + (k + 1) % 4, m = 8 + k;
        mesh.triangles.insert(mesh.triangles.end(), {{m, b0, b1}, {m, b1, t1}, {m, t1, t0}, {m, t0, b0}});
    }
    mesh.triangles.insert(mesh.triangles.end(), {{0, 1, 2}, {0, 2, 3}, {4, 6, 5}, {4, 7, 6}});
    return mesh;
}

// Validation hands the count each triangle's facing along x, y and z,
// decided in double where Shewchuk's bound allows: each facing it decides is
// the exact predicate's, it leaves undecided the ones double cannot settle
// (the prism's collinear projections), and the count, settling those
// exactly, counts what the baker makes.
TEST(ChooseViewAxis, ValidationsFacingsAreExactOrLeftToTheExactPredicate) {
    const std::vector<TriangleMesh> meshes = {fannedDiamondPrism(), solids::sphere({0.1f, 0.0f, -0.2f}, 1.0f, 20).mesh,
                                              solids::torusKnot({0, 0, 0}, 1.0f, 2, 3, 0.25f, 64, 8).mesh};
    for (const TriangleMesh& mesh : meshes) {
        detail::MeshFinds finds;
        const MeshReport report = detail::validateMesh(mesh, 2, finds);
        ASSERT_TRUE(report.closed()) << report.summary();
        ASSERT_EQ(finds.facings.size(), mesh.triangles.size());
        std::size_t undecided = 0;
        for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
            for (int a = 0; a < 3; ++a) {
                const int s = (a + 1) % 3, r = (a + 2) % 3;
                float v[3][2];
                for (int k = 0; k < 3; ++k) {
                    const glm::vec3& p = mesh.positions[mesh.triangles[t][k]];
                    v[k][0] = p[s], v[k][1] = p[r];
                }
                const int o = detail::orient2d(v[0], v[1], v[2]);
                const unsigned exact = o > 0 ? detail::kFacesPlus : o < 0 ? detail::kFacesMinus : 0;
                const unsigned found = (finds.facings[t] >> (2 * a)) & 3u;
                undecided += found == detail::kFacesUndecided;
                // Only a zero is too near zero on these meshes.
                EXPECT_EQ(found == detail::kFacesUndecided ? 0u : found, exact) << "triangle " << t << " axis " << a;
            }
        if (&mesh == &meshes[0]) {
            EXPECT_EQ(undecided, 16u); // every side's four, along z
        }
        const AxisChoice choice = chooseViewAxis(mesh, 64);
        for (Axis axis : {Axis::X, Axis::Y, Axis::Z}) expectCountsOfTheBake(mesh, choice, axis);
    }
}

} // namespace
} // namespace vds
