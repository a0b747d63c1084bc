// The generalized winding number of the exact classifier against a
// brute-force double-precision solid-angle sum over every triangle, on open,
// holed, overlapping, self-intersecting, soup and non-manifold meshes built
// in code; and equal to the winding rule on closed meshes.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <glm/geometric.hpp>

#include <vds/error.h>
#include <vds/exact.h>
#include <vds/occupancy.h>
#include <vds/sprite.h>

#include "solids.h"

namespace vds {
namespace {

double bruteForceGwn(const TriangleMesh& mesh, const glm::vec3& point) {
    const glm::dvec3 p(point);
    double sum = 0.0;
    for (const glm::uvec3& t : mesh.triangles) {
        const glm::dvec3 a = glm::dvec3(mesh.positions[t[0]]) - p, b = glm::dvec3(mesh.positions[t[1]]) - p,
                         c = glm::dvec3(mesh.positions[t[2]]) - p;
        const double la = glm::length(a), lb = glm::length(b), lc = glm::length(c);
        sum += 2.0 * std::atan2(glm::dot(a, glm::cross(b, c)),
                                la * lb * lc + glm::dot(a, b) * lc + glm::dot(a, c) * lb + glm::dot(b, c) * la);
    }
    return sum / (4.0 * 3.14159265358979323846);
}

TriangleMesh without(const TriangleMesh& mesh, bool (*drop)(const glm::vec3& centroid)) {
    TriangleMesh out = mesh;
    out.triangles.clear();
    for (const glm::uvec3& t : mesh.triangles)
        if (!drop((mesh.positions[t[0]] + mesh.positions[t[1]] + mesh.positions[t[2]]) / 3.0f)) out.triangles.push_back(t);
    return out;
}

TriangleMesh soup(std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f), small(-0.3f, 0.3f);
    TriangleMesh m;
    for (std::uint32_t k = 0; k < 60; ++k) {
        const glm::vec3 c(u(rng), u(rng), u(rng));
        for (int v = 0; v < 3; ++v) m.positions.push_back(c + glm::vec3(small(rng), small(rng), small(rng)));
        m.triangles.push_back({3 * k, 3 * k + 1, 3 * k + 2});
    }
    return m;
}

TEST(GeneralizedWinding, EqualsTheBruteForceSolidAngleSum) {
    const auto sphere = solids::sphere({0, 0, 0}, 1.0f, 32);
    const auto torus = solids::torus({0.1f, 0.2f, 0.3f}, 1.0f, 0.35f, 32);
    const TriangleMesh cup = without(sphere.mesh, [](const glm::vec3& c) { return c.z > 0.5f; });
    const TriangleMesh holes = without(sphere.mesh, [](const glm::vec3& c) {
        return std::fabs(c.x) > 0.8f || (c.y > 0.7f && c.z > 0.0f);
    });
    const TriangleMesh torusHoles = without(torus.mesh, [](const glm::vec3& c) { return c.x > 0.9f && c.z > 0.3f; });
    // Two overlapping spheres, one shifted: self-intersecting; a fan of three
    // triangles sharing one edge: non-manifold.
    TriangleMesh overlapping = solids::merge(sphere.mesh, solids::sphere({0.6f, 0, 0}, 0.8f, 24).mesh);
    TriangleMesh fan;
    fan.positions = {{0, 0, -1}, {0, 0, 1}, {1, 0, 0}, {-0.5f, 0.8f, 0}, {-0.5f, -0.8f, 0}};
    fan.triangles = {{0, 1, 2}, {0, 1, 3}, {1, 0, 4}};
    const TriangleMesh soupMesh = soup(5);
    const struct {
        const char* name;
        const TriangleMesh* mesh;
        bool open;
    } cases[] = {{"cup", &cup, true},          {"holes", &holes, true}, {"torus with a hole", &torusHoles, true},
                 {"overlapping", &overlapping, false}, {"fan", &fan, true},   {"soup", &soupMesh, true}};
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(-1.4f, 1.4f);
    for (const auto& c : cases)
        for (Axis axis : {Axis::X, Axis::Y, Axis::Z}) {
            const ExactClassifier exact(*c.mesh, axis);
            EXPECT_EQ(exact.boundaryEdgeCount() > 0, c.open) << c.name;
            std::size_t compared = 0, labelsWrong = 0, valuesOff = 0;
            for (int k = 0; k < 1500; ++k) {
                const glm::vec3 p(u(rng), u(rng), u(rng));
                const double expected = bruteForceGwn(*c.mesh, p);
                const double got = exact.generalizedWinding(p);
                valuesOff += std::fabs(got - expected) > 1e-9;
                if (std::fabs(expected - 0.5) <= 0.02) continue;
                ++compared;
                labelsWrong += exact.contains(p, Rule::GeneralizedWinding) != (expected > 0.5);
            }
            EXPECT_EQ(valuesOff, 0u) << c.name << " along " << toString(axis);
            EXPECT_EQ(labelsWrong, 0u) << c.name << " along " << toString(axis);
            EXPECT_GT(compared, 1400u);
        }
}

TEST(GeneralizedWinding, IsTheWindingRuleOnClosedMeshes) {
    const auto shell = solids::shell({0, 0, 0}, 1.0f, 0.6f, 24);
    const ExactClassifier exact(shell.mesh);
    EXPECT_EQ(exact.boundaryEdgeCount(), 0u);
    std::mt19937 rng(2);
    std::uniform_real_distribution<float> u(-1.2f, 1.2f);
    for (int k = 0; k < 5000; ++k) {
        const glm::vec3 p(u(rng), u(rng), u(rng));
        ASSERT_EQ(exact.contains(p, Rule::GeneralizedWinding), exact.contains(p, Rule::Winding));
        ASSERT_EQ(exact.generalizedWinding(p), double(exact.winding(p)));
    }
}

TEST(GeneralizedWinding, SpritesAndVoxelizersRefuseItOnOpenMeshesWithAClearError) {
    const auto sphere = solids::sphere({0, 0, 0}, 1.0f, 16);
    const TriangleMesh cup = without(sphere.mesh, [](const glm::vec3& c) { return c.z > 0.5f; });
    std::vector<std::uint8_t> cells(8);
    EXPECT_THROW(voxelize(cup, {meshBounds(cup), {2, 2, 2}}, cells.data(), {Rule::GeneralizedWinding, 1}),
                 InvalidArgument);
    Sprite open;
    open.status = SolidStatus::Open;
    EXPECT_THROW(open.contains({0, 0, 0}, Rule::GeneralizedWinding), InvalidArgument);
    EXPECT_EQ(parseRule("generalized-winding"), Rule::GeneralizedWinding);
}

} // namespace
} // namespace vds
