// The distance hierarchy at every width this CPU can search (4, 8 and 16
// lanes: SSE, AVX2 and AVX-512 on a machine with all three), each against
// brute force: the nearest triangle's squared distance, computed by the same
// exact kernel over every triangle, is equal bit for bit, on closed, open
// and degenerate meshes, for points far, near, on the surface and at its
// corners; and the grid's leaf lists find the same as the whole search.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include <vds/detail/bvh.h>
#include <vds/detail/triangle_distance.h>
#include <vds/mesh.h>

#include "points.h"
#include "solids.h"

namespace {

using vds::detail::Bvh;
using vds::detail::NearestState;

double bruteForce2(const vds::TriangleMesh& mesh, const glm::vec3& p) {
    double best = std::numeric_limits<double>::infinity();
    const glm::dvec3 q(p);
    for (const glm::uvec3& t : mesh.triangles) {
        const glm::dvec3 c = vds::detail::closestOnTriangle(q, glm::dvec3(mesh.positions[t.x]), glm::dvec3(mesh.positions[t.y]),
                                                            glm::dvec3(mesh.positions[t.z]))
                                 .point;
        const glm::dvec3 d = q - c;
        best = std::min(best, d.x * d.x + d.y * d.y + d.z * d.z);
    }
    return best;
}

/// A unit sphere with slivers, needles, zero-area and repeated triangles
/// added, some of them far from the origin (their planes are zero: always
/// tested exactly).
vds::TriangleMesh degenerateMesh() {
    vds::TriangleMesh mesh = vds::solids::sphere(glm::vec3(0.0f), 1.0f, 24).mesh;
    const auto add = [&mesh](const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
        const std::uint32_t first = std::uint32_t(mesh.positions.size());
        mesh.positions.insert(mesh.positions.end(), {a, b, c});
        mesh.triangles.push_back({first, first + 1, first + 2});
    };
    add({0.2f, 0.1f, 0.0f}, {0.2f, 0.1f, 0.0f}, {0.2f, 0.1f, 0.0f});       // a point
    add({-0.5f, 0.0f, 0.3f}, {0.5f, 0.0f, 0.3f}, {0.1f, 0.0f, 0.3f});      // collinear
    add({0.0f, 0.0f, -0.4f}, {0.6f, 0.0f, -0.4f}, {0.3f, 1e-7f, -0.4f});   // a sliver
    add({1.5f, 1.5f, 1.5f}, {1.5f, 1.5f, 1.5f}, {1.6f, 1.5f, 1.5f});       // a segment, outside
    add({0.0f, -2.0f, 0.0f}, {0.0f, -2.0f, 1e-6f}, {1.0f, -2.0f, 0.0f});  // a needle
    const glm::uvec3 again = mesh.triangles[7];
    mesh.triangles.push_back(again); // a repeat
    return mesh;
}

std::vector<glm::vec3> probePoints(const vds::TriangleMesh& mesh) {
    vds::Box box = vds::meshBounds(mesh);
    std::vector<glm::vec3> points = vds::test::randomPoints(box, 400, 0.3f, 44);
    const std::vector<glm::vec3> far = vds::test::randomPoints(box, 40, 6.0f, 45);
    points.insert(points.end(), far.begin(), far.end());
    std::mt19937 rng(46);
    std::uniform_real_distribution<float> u(0.0f, 1.0f), off(-1e-3f, 1e-3f);
    const std::size_t step = std::max<std::size_t>(3, mesh.triangles.size() / 200);
    for (std::size_t k = 0; k < mesh.triangles.size(); k += step) { // on and just off triangles, and corners
        const glm::uvec3 t = mesh.triangles[k];
        const glm::vec3 a = mesh.positions[t.x], b = mesh.positions[t.y], c = mesh.positions[t.z];
        float r = u(rng), s = u(rng);
        if (r + s > 1.0f) r = 1.0f - r, s = 1.0f - s;
        const glm::vec3 on = a + (b - a) * r + (c - a) * s;
        points.push_back(on);
        points.push_back(on + glm::vec3(off(rng), off(rng), off(rng)));
        points.push_back(a);
    }
    return points;
}

std::vector<int> availableWidths() {
    std::vector<int> widths;
    for (const int w : {4, 8, 16})
        if (vds::detail::bvhWidthAvailable(w)) widths.push_back(w);
    return widths;
}

void expectEveryWidthExact(const vds::TriangleMesh& mesh, const std::string& name) {
    const std::vector<glm::vec3> points = probePoints(mesh);
    std::vector<double> brute(points.size());
    for (std::size_t k = 0; k < points.size(); ++k) brute[k] = bruteForce2(mesh, points[k]);
    for (const int width : availableWidths()) {
        const Bvh bvh(vds::MeshView(mesh), width, 2);
        ASSERT_EQ(bvh.width(), width);
        std::size_t differ = 0;
        for (std::size_t k = 0; k < points.size(); ++k) {
            NearestState state{std::numeric_limits<double>::infinity()};
            bvh.nearest(points[k], state);
            ASSERT_NE(state.slot, vds::kNoTriangle);
            differ += state.distance2 != brute[k] || bvh.distance2(points[k], state.slot) != brute[k];
        }
        EXPECT_EQ(differ, 0u) << name << " at width " << width << ": of " << points.size() << " points";
    }
}

TEST(BvhWidth, FourLanesAreAlwaysAvailableAndTheDefaultIsAvailable) {
    EXPECT_TRUE(vds::detail::bvhWidthAvailable(4));
    EXPECT_FALSE(vds::detail::bvhWidthAvailable(5));
    EXPECT_TRUE(vds::detail::bvhWidthAvailable(vds::detail::defaultBvhWidth()));
    EXPECT_EQ(Bvh(vds::MeshView(vds::solids::box(glm::vec3(0.0f), glm::vec3(1.0f)).mesh)).width(),
              vds::detail::defaultBvhWidth());
}

TEST(BvhWidth, EveryWidthEqualsBruteForceOnAClosedMesh) {
    expectEveryWidthExact(vds::solids::torusKnot(glm::vec3(0.0f), 1.0f, 2, 3, 0.25f, 120, 12).mesh, "trefoil");
}

TEST(BvhWidth, EveryWidthEqualsBruteForceOnAnOpenMesh) {
    expectEveryWidthExact(vds::solids::sphereWithHoles(), "sphere with holes");
    expectEveryWidthExact(vds::solids::looseTriangles(600, 0.1f, 3), "loose triangles");
}

TEST(BvhWidth, EveryWidthEqualsBruteForceWithDegenerateTriangles) {
    expectEveryWidthExact(degenerateMesh(), "degenerate");
}

TEST(BvhWidth, EveryWidthEqualsBruteForceOnTinyMeshes) {
    vds::TriangleMesh one;
    one.positions = {{0.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}};
    one.triangles = {{0, 1, 2}};
    expectEveryWidthExact(one, "one triangle");
    expectEveryWidthExact(vds::solids::box(glm::vec3(-1.0f), glm::vec3(2.0f)).mesh, "box");
}

/// A mesh large enough that its subtrees are built on threads of their own
/// (past 4096 triangles), against brute force, with the tree of one thread.
TEST(BvhWidth, TreesBuiltOnThreadsEqualBruteForce) {
    const vds::TriangleMesh mesh = vds::solids::sphere(glm::vec3(0.0f), 1.0f, 96).mesh;
    ASSERT_GT(mesh.triangles.size(), 2u * 4096u);
    const std::vector<glm::vec3> points = vds::test::randomPoints(vds::meshBounds(mesh), 150, 0.2f, 48);
    for (const int width : availableWidths()) {
        const Bvh serial(vds::MeshView(mesh), width, 1), threaded(vds::MeshView(mesh), width, 4);
        for (const glm::vec3& p : points) {
            NearestState a{std::numeric_limits<double>::infinity()}, b = a;
            serial.nearest(p, a);
            threaded.nearest(p, b);
            EXPECT_EQ(b.distance2, bruteForce2(mesh, p)) << "width " << width;
            EXPECT_EQ(a.distance2, b.distance2) << "width " << width;
        }
    }
}

TEST(BvhWidth, LeafListsOfABoxFindWhatTheWholeSearchFinds) {
    const vds::TriangleMesh mesh = vds::solids::torusKnot(glm::vec3(0.0f), 1.0f, 2, 3, 0.25f, 120, 12).mesh;
    const glm::vec3 lo(0.1f, 0.2f, -0.2f), hi(0.4f, 0.5f, 0.1f);
    const std::vector<glm::vec3> points = vds::test::randomPoints({lo, hi}, 200, 0.0f, 47);
    for (const int width : availableWidths()) {
        const Bvh bvh(vds::MeshView(mesh), width, 1);
        double reach2 = 0.0; // the farthest point's nearest distance, squared
        for (const glm::vec3& p : points) {
            NearestState state{std::numeric_limits<double>::infinity()};
            bvh.nearest(p, state);
            reach2 = std::max(reach2, state.distance2);
        }
        std::vector<vds::detail::BvhNode> leaves;
        ASSERT_TRUE(bvh.leavesNear(lo, hi, reach2 * 1.01, leaves, 1u << 20));
        for (const glm::vec3& p : points) {
            NearestState among{std::numeric_limits<double>::infinity()};
            bvh.nearestAmong(p, leaves, among);
            EXPECT_EQ(among.distance2, bruteForce2(mesh, p)) << "width " << width;
        }
    }
}

} // namespace
