// Certified classification equals the exact classifier on every point: on
// uniform points, points within 0.01 texel of the surface, vertices, edge
// midpoints and points on texel boundaries, for both rules; and it answers
// most uniform points from its bands.
#include <vds/certified.h>

#include <gtest/gtest.h>

#include <random>

#include <glm/geometric.hpp>

#include <vds/error.h>

#include "solids.h"

namespace vds {
namespace {

std::vector<glm::vec3> testPoints(const TriangleMesh& mesh, const SpriteGrid& grid, std::uint32_t seed) {
    std::mt19937 rng(seed);
    const Box b = meshBounds(mesh);
    const glm::vec3 size = b.hi - b.lo;
    std::uniform_real_distribution<float> u(-0.1f, 1.1f), unit(0.0f, 1.0f), offset(-0.01f, 0.01f);
    std::vector<glm::vec3> points;
    for (int k = 0; k < 20000; ++k) points.push_back(b.lo + glm::vec3(u(rng), u(rng), u(rng)) * size);
    // Near the surface: within 0.01 texel along the face normal.
    for (int k = 0; k < 20000; ++k) {
        const glm::uvec3 t = mesh.triangles[rng() % mesh.triangles.size()];
        float x = unit(rng), y = unit(rng);
        if (x + y > 1.0f) x = 1.0f - x, y = 1.0f - y;
        const glm::vec3 a = mesh.positions[t[0]], e1 = mesh.positions[t[1]] - a, e2 = mesh.positions[t[2]] - a;
        const glm::vec3 n = glm::normalize(glm::cross(e1, e2));
        points.push_back(a + x * e1 + y * e2 + offset(rng) * grid.texelSize * n);
    }
    for (const glm::vec3& v : mesh.positions) points.push_back(v);
    for (const glm::uvec3& t : mesh.triangles)
        for (int e = 0; e < 3; ++e) points.push_back(0.5f * (mesh.positions[t[e]] + mesh.positions[t[(e + 1) % 3]]));
    // On texel boundaries: corners of texels at random depths.
    const glm::ivec3 p = axisPermutation(grid.axis);
    for (int k = 0; k < 5000; ++k) {
        glm::vec3 q;
        q[p.x] = grid.box.lo[p.x] + float(rng() % (grid.width + 1)) * grid.texelSize;
        q[p.y] = grid.box.lo[p.y] + float(rng() % (grid.height + 1)) * grid.texelSize;
        q[p.z] = b.lo[p.z] + unit(rng) * size[p.z];
        points.push_back(q);
    }
    return points;
}

TEST(Certified, EqualsTheExactClassifierOnEveryPoint) {
    const auto torus = solids::torus({0.1f, 0.2f, 0.3f}, 1.0f, 0.35f, 48);
    const auto shell = solids::shell({0, 0, 0}, 1.0f, 0.6f, 32);
    const auto two = solids::overlappingBoxes({-1, -1, -1}, {0.5f, 0.5f, 0.5f}, {-0.5f, -0.3f, -0.2f}, {1, 1, 1});
    const auto sphere = solids::sphere({0.5f, -0.25f, 2.0f}, 1.5f, 64);
    for (const TriangleMesh* mesh : {&torus.mesh, &shell.mesh, &two.mesh, &sphere.mesh})
        for (Axis axis : {Axis::X, Axis::Z})
            for (std::uint32_t resolution : {48u, 200u}) {
                CertifiedOptions o;
                o.axis = axis;
                o.resolution = resolution;
                const CertifiedClassifier certified(*mesh, o);
                ASSERT_TRUE(certified.certifies());
                const std::vector<glm::vec3> points = testPoints(*mesh, certified.grid(), resolution);
                for (Rule rule : {Rule::Parity, Rule::Winding}) {
                    std::vector<std::uint8_t> labels(points.size(), 7);
                    vds::ClassifyStats stats;
                    ClassifyOptions options{rule, 2};
                    options.stats = &stats;
                    certified.classify(points, labels.data(), options);
                    std::size_t wrong = 0;
                    for (std::size_t k = 0; k < points.size(); ++k)
                        wrong += labels[k] != (certified.exact().contains(points[k], rule) ? 1 : 0);
                    EXPECT_EQ(wrong, 0u) << mesh->name << " " << toString(axis) << " @" << resolution;
                    EXPECT_EQ(stats.certain + stats.exact, points.size());
                    // The 20000 uniform points come first: most are answered by the bands.
                    std::vector<std::uint8_t> uniform(20000);
                    vds::ClassifyStats u;
                    ClassifyOptions first{rule, 1};
                    first.stats = &u;
                    certified.classify(vds::PointsView(points.data(), 20000), uniform.data(), first);
                    EXPECT_GT(u.certain, resolution == 200u ? 19000u : 17000u) << mesh->name << " @" << resolution;
                }
            }
}

TEST(Certified, OpenMeshesTakeTheExactPath) {
    auto box = solids::box({0, 0, 0}, {1, 1, 1});
    box.mesh.triangles.pop_back(); // a hole
    const CertifiedClassifier certified(box.mesh, {32, Axis::Z, 1});
    EXPECT_FALSE(certified.certifies());
    const std::vector<glm::vec3> points = testPoints(box.mesh, certified.grid(), 3);
    std::vector<std::uint8_t> labels(points.size());
    vds::ClassifyStats stats;
    ClassifyOptions options;
    options.stats = &stats;
    certified.classify(points, labels.data(), options);
    EXPECT_EQ(stats.exact, points.size());
    for (std::size_t k = 0; k < points.size(); ++k) ASSERT_EQ(labels[k], certified.exact().contains(points[k]) ? 1 : 0);
}

TEST(Certified, BadInputIsRefused) {
    TriangleMesh empty;
    EXPECT_THROW(CertifiedClassifier(empty, {}), InvalidMesh);
    const auto box = solids::box({0, 0, 0}, {1, 1, 1});
    EXPECT_THROW(CertifiedClassifier(box.mesh, {0, Axis::Z, 1}), InvalidArgument);
    EXPECT_THROW(CertifiedClassifier(box.mesh, {kMaxResolution + 1, Axis::Z, 1}), InvalidArgument);
}

} // namespace
} // namespace vds
