// The generalized winding number of the exact classifier against a
// brute-force double-precision solid-angle sum over every triangle, on open,
// holed, overlapping, self-intersecting, soup and non-manifold meshes built
// in code; and equal to the winding rule on closed meshes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <vds/bake.h>
#include <vds/error.h>
#include <vds/exact.h>
#include <vds/vds_file.h>
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

using solids::flatRimBowl;
using solids::without;

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

// ---- sprites ---------------------------------------------------------------

using solids::overlappingShells;
using solids::sphereCup;
using solids::sphereWithHoles;
// A closed cube with a fin of two extra triangles on one of its edges (four
// triangles on that edge, unbalanced by two) and a flap hanging off it.
TriangleMesh nonManifoldFan() {
    TriangleMesh m = solids::box({-0.6f, -0.6f, -0.6f}, {0.6f, 0.6f, 0.6f}).mesh;
    const auto base = std::uint32_t(m.positions.size());
    m.positions.push_back({0.6f, 0.6f, -0.6f});
    m.positions.push_back({0.6f, 0.6f, 0.6f});
    m.positions.push_back({1.2f, 1.2f, 0.0f});
    m.positions.push_back({0.0f, 1.3f, 0.1f});
    m.triangles.push_back({base, base + 1, base + 2});
    m.triangles.push_back({base, base + 1, base + 3});
    return m;
}

glm::vec3 closestOnTriangle(const glm::vec3& p, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
    // Ericson, Real-Time Collision Detection, 5.1.5.
    const glm::vec3 ab = b - a, ac = c - a, ap = p - a;
    const float d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
    if (d1 <= 0 && d2 <= 0) return a;
    const glm::vec3 bp = p - b;
    const float d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
    if (d3 >= 0 && d4 <= d3) return b;
    const float vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + ab * (d1 / (d1 - d3));
    const glm::vec3 cp = p - c;
    const float d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
    if (d6 >= 0 && d5 <= d6) return c;
    const float vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + ac * (d2 / (d2 - d6));
    const float va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    const float denom = 1.0f / (va + vb + vc);
    return a + ab * (vb * denom) + ac * (vc * denom);
}

float distanceToSurface(const TriangleMesh& mesh, const glm::vec3& p) {
    float best = HUGE_VALF;
    for (const glm::uvec3& t : mesh.triangles)
        best = std::min(best, glm::length(p - closestOnTriangle(p, mesh.positions[t[0]], mesh.positions[t[1]],
                                                                mesh.positions[t[2]])));
    return best;
}

Sprite bakeAt(const TriangleMesh& mesh, Axis axis, std::uint32_t resolution) {
    BakeOptions o;
    o.resolution = resolution;
    o.axis = axis;
    return bakeCpu(mesh, o);
}

struct OpenCase {
    const char* name;
    TriangleMesh mesh;
};

std::vector<OpenCase> openCases() {
    return {{"cup", sphereCup()},
            {"sphere with holes", sphereWithHoles()},
            {"overlapping shells", overlappingShells()},
            {"non-manifold fan", nonManifoldFan()}};
}

TEST(SpriteGeneralizedWinding, AgreesWithTheExactGwnAwayFromTheSurface) {
    std::mt19937 rng(21);
    for (const OpenCase& c : openCases())
        for (Axis axis : {Axis::Z, Axis::X}) {
            const Sprite sprite = bakeAt(c.mesh, axis, 96);
            ASSERT_EQ(sprite.status, SolidStatus::Open) << c.name;
            const ExactClassifier exact(c.mesh, axis);
            ASSERT_EQ(sprite.boundaryEdges.size(), 2 * exact.boundaryEdgeCount()) << c.name;
            const Box box = meshBounds(c.mesh);
            const glm::vec3 pad = 0.1f * (box.hi - box.lo);
            std::uniform_real_distribution<float> ux(box.lo.x - pad.x, box.hi.x + pad.x),
                uy(box.lo.y - pad.y, box.hi.y + pad.y), uz(box.lo.z - pad.z, box.hi.z + pad.z);
            const float texel = sprite.grid.texelSize;
            std::vector<glm::vec3> points;
            for (int k = 0; k < 3000; ++k) points.push_back({ux(rng), uy(rng), uz(rng)});
            // And points near the boundary curve, where the caps' tree is
            // summed finely and labels most often need the per-edge sum.
            std::mt19937 nearRng(5);
            std::normal_distribution<float> near(0.0f, 0.03f);
            for (std::size_t e = 0; e + 1 < sprite.boundaryEdges.size(); e += 2)
                for (int k = 0; k < 4; ++k)
                    points.push_back(0.5f * (sprite.boundaryEdges[e] + sprite.boundaryEdges[e + 1]) +
                                     glm::vec3(near(nearRng), near(nearRng), near(nearRng)));
            std::vector<std::uint8_t> exactLabels(points.size()), capLabels(points.size());
            classify(sprite, {points.data(), points.size()}, exactLabels.data(),
                     {Rule::GeneralizedWinding, 0}, {QueryLayout::Auto, BoundaryEvaluation::Exact});
            classify(sprite, {points.data(), points.size()}, capLabels.data(),
                     {Rule::GeneralizedWinding, 0}, {QueryLayout::Auto, BoundaryEvaluation::Caps});
            std::size_t compared = 0, wrong = 0, farWrong = 0;
            for (std::size_t k = 0; k < points.size(); ++k) {
                const glm::vec3& p = points[k];
                const bool label = sprite.contains(p, Rule::GeneralizedWinding);
                // The capped loops' labels are the per-edge sum's (they fall
                // back to it wherever their bound could change the answer).
                ASSERT_EQ(capLabels[k], exactLabels[k]) << c.name << " point " << k;
                ASSERT_EQ(exactLabels[k], label ? 1 : 0) << c.name;
                const float distance = distanceToSurface(c.mesh, p);
                const double mine = sprite.generalizedWinding(p);
                const glm::vec3 t = sprite.grid.toTexture(p);
                if (distance > 1.5f * texel && t.x > 0.0f && t.x < 1.0f && t.y > 0.0f && t.y < 1.0f &&
                    t.z > 0.0f && t.z < 1.0f) {
                    // The value is the GWN at the texel-centre point within
                    // the caps' value tolerance (1e-3). (The brute-force sum,
                    // not the exact classifier: texel centres on the plane x =
                    // y lie in the fin's plane, where the per-edge sum's tie
                    // rule takes the side of a ray that crosses the fin.)
                    const glm::vec3 q = sprite.grid.texelCentre(
                        std::min(sprite.grid.width - 1, std::uint32_t(t.x * float(sprite.grid.width))),
                        std::min(sprite.grid.height - 1, std::uint32_t(t.y * float(sprite.grid.height))), t.z);
                    ASSERT_NEAR(mine, bruteForceGwn(c.mesh, q), 1.001e-3) << c.name << " point " << k;
                }
                if (k >= 3000) continue; // the uniform points only, below
                const double w = exact.generalizedWinding(p);
                if (std::fabs(w - 0.5) <= 0.02) continue;
                ++compared;
                if (label == (w > 0.5)) continue;
                ++wrong;
                if ((w < 0.25 || w > 0.75) && distance > 1.5f * texel) {
                    ++farWrong;
                    ADD_FAILURE() << c.name << ": (" << p.x << ", " << p.y << ", " << p.z << ") GWN " << w << ", sprite "
                                  << mine << ", " << distance / texel << " texels from the surface";
                }
            }
            EXPECT_EQ(farWrong, 0u) << c.name << " along " << toString(axis);
            EXPECT_LE(double(wrong), 0.005 * double(compared)) << c.name << " along " << toString(axis);
            EXPECT_GT(compared, 2500u) << c.name;
        }
}

TEST(SpriteGeneralizedWinding, CapsLabelsEqualTheExactTermsNearOneHalf) {
    // Points where the GWN at the texel centre is within ~1e-6 of 1/2, found
    // by bisection in depth along columns (the value is continuous there
    // unless a crossing lies between): the caps' refinement must reach the
    // per-edge sum's label wherever its bound could not decide.
    std::mt19937 rng(33);
    std::size_t nearHalf = 0, tested = 0;
    for (const OpenCase& c : openCases())
        for (Axis axis : {Axis::Z, Axis::Y}) {
            const Sprite sprite = bakeAt(c.mesh, axis, 64);
            const SpriteGrid& g = sprite.grid;
            std::uniform_int_distribution<std::uint32_t> ui(0, g.width - 1), uj(0, g.height - 1);
            std::vector<glm::vec3> points;
            for (int column = 0; column < 200; ++column) {
                const std::uint32_t i = ui(rng), j = uj(rng);
                const auto value = [&](float r) { return sprite.generalizedWinding(g.texelCentre(i, j, r)) - 0.5; };
                constexpr int kSteps = 64;
                for (int k = 0; k < kSteps; ++k) {
                    float lo = (float(k) + 0.5f) / kSteps, hi = (float(k) + 1.5f) / kSteps;
                    double vlo = value(lo);
                    const double vhi = value(hi);
                    if ((vlo > 0.0) == (vhi > 0.0)) continue; // no crossing of 1/2 (or a jump: kept too)
                    for (int step = 0; step < 40 && hi - lo > 0.0f; ++step) {
                        const float mid = 0.5f * (lo + hi);
                        if (mid <= lo || mid >= hi) break;
                        const double vmid = value(mid);
                        if ((vmid > 0.0) == (vlo > 0.0)) {
                            lo = mid;
                            vlo = vmid;
                        } else {
                            hi = mid;
                        }
                    }
                    points.push_back(g.texelCentre(i, j, lo));
                    points.push_back(g.texelCentre(i, j, hi));
                }
            }
            std::vector<std::uint8_t> exactLabels(points.size()), capLabels(points.size());
            classify(sprite, {points.data(), points.size()}, exactLabels.data(),
                     {Rule::GeneralizedWinding, 0}, {QueryLayout::Auto, BoundaryEvaluation::Exact});
            classify(sprite, {points.data(), points.size()}, capLabels.data(),
                     {Rule::GeneralizedWinding, 0}, {QueryLayout::Auto, BoundaryEvaluation::Caps});
            tested += points.size();
            for (std::size_t k = 0; k < points.size(); ++k) {
                ASSERT_EQ(capLabels[k], exactLabels[k]) << c.name << " point " << k;
                nearHalf += std::fabs(sprite.generalizedWinding(points[k]) - 0.5) < 1e-3;
            }
        }
    EXPECT_GT(nearHalf, tested / 10); // many are near 1/2, not at jumps
    EXPECT_GT(nearHalf, 100u);
}

TEST(SpriteGeneralizedWinding, IsTheWindingRuleOnClosedMeshes) {
    const auto shell = solids::shell({0, 0, 0}, 1.0f, 0.6f, 24);
    const Sprite sprite = bakeAt(shell.mesh, Axis::Z, 64);
    EXPECT_EQ(sprite.status, SolidStatus::Closed);
    EXPECT_TRUE(sprite.boundaryEdges.empty());
    std::mt19937 rng(4);
    std::uniform_real_distribution<float> u(-1.2f, 1.2f);
    std::vector<glm::vec3> points;
    for (int k = 0; k < 5000; ++k) points.push_back({u(rng), u(rng), u(rng)});
    std::vector<std::uint8_t> gwn(points.size()), winding(points.size());
    classify(sprite, {points.data(), points.size()}, gwn.data(), {Rule::GeneralizedWinding});
    classify(sprite, {points.data(), points.size()}, winding.data(), {Rule::Winding});
    EXPECT_EQ(gwn, winding);
    for (std::size_t k = 0; k < 200; ++k)
        ASSERT_EQ(sprite.generalizedWinding(points[k]), sprite.contains(points[k], Rule::Winding) ? 1.0 : 0.0);
}

TEST(SpriteGeneralizedWinding, FollowsTheSpritesPlacement) {
    const TriangleMesh cup = sphereCup();
    Sprite sprite = bakeAt(cup, Axis::Z, 96);
    const ExactClassifier exact(cup, Axis::Z);
    const glm::mat4 model = glm::translate(glm::mat4(1.0f), glm::vec3(3.0f, -1.0f, 0.5f)) *
                            glm::rotate(glm::mat4(1.0f), 0.7f, glm::normalize(glm::vec3(1.0f, 2.0f, 0.5f))) *
                            glm::scale(glm::mat4(1.0f), glm::vec3(2.0f));
    Sprite moved = sprite;
    moved.transform(model);
    std::mt19937 rng(8);
    std::uniform_real_distribution<float> u(-1.2f, 1.2f);
    std::size_t compared = 0, wrong = 0, differ = 0;
    for (int k = 0; k < 3000; ++k) {
        const glm::vec3 p(u(rng), u(rng), u(rng));
        const glm::vec3 world = glm::vec3(model * glm::vec4(p, 1.0f));
        const bool label = moved.contains(world, Rule::GeneralizedWinding);
        differ += label != sprite.contains(p, Rule::GeneralizedWinding);
        const double w = exact.generalizedWinding(p);
        if (std::fabs(w - 0.5) <= 0.02) continue;
        ++compared;
        wrong += label != (w > 0.5);
    }
    // Rounding in the placement may move a point across a texel border.
    EXPECT_LE(differ, 6u);
    EXPECT_LE(double(wrong), 0.005 * double(compared));
}

// The capped loops are derived data a SpriteClassifier keeps: a classifier
// of a copy builds its own from its own edges (so a copy whose edges are
// then changed answers for the changed edges); a moved classifier takes
// them along. Answers against the per-edge sum on the same sprite.
TEST(SpriteGeneralizedWinding, CapsFollowCopiesAndMoves) {
    const TriangleMesh mesh = sphereWithHoles();
    Sprite sprite = bakeAt(mesh, Axis::Z, 64);
    std::mt19937 rng(9);
    std::uniform_real_distribution<float> u(-1.2f, 1.2f);
    std::vector<glm::vec3> points(2000);
    for (glm::vec3& p : points) p = {u(rng), u(rng), u(rng)};
    const auto labels = [&](const Classifier& c) {
        std::vector<std::uint8_t> out(points.size());
        c.classify({points.data(), points.size()}, out.data(), {Rule::GeneralizedWinding, 1});
        return out;
    };
    const SpriteQueryOptions perEdge{QueryLayout::Auto, BoundaryEvaluation::Exact};
    SpriteClassifier byCaps(sprite);
    const std::vector<std::uint8_t> before = labels(byCaps); // builds the caps
    EXPECT_EQ(before, labels(SpriteClassifier(sprite, perEdge)));
    Sprite copy = sprite;
    for (glm::vec3& e : copy.boundaryEdges) e *= 1.5f; // a larger hole rim: a different boundary term
    const std::vector<std::uint8_t> scaled = labels(SpriteClassifier(copy));
    EXPECT_EQ(scaled, labels(SpriteClassifier(copy, perEdge)));
    EXPECT_NE(scaled, before);
    const SpriteClassifier moved = std::move(byCaps);
    EXPECT_EQ(labels(moved), before);
    EXPECT_EQ(labels(moved), before); // from the caps it keeps
}

TEST(SpriteGeneralizedWinding, BoundaryEdgesSurviveTheFile) {
    const TriangleMesh mesh = overlappingShells();
    const Sprite sprite = bakeAt(mesh, Axis::Y, 48);
    ASSERT_FALSE(sprite.boundaryEdges.empty());
    const std::vector<char> bytes = encodeSprite(sprite);
    const Sprite back = decodeSprite(bytes.data(), bytes.size());
    ASSERT_EQ(back.boundaryEdges.size(), sprite.boundaryEdges.size());
    EXPECT_EQ(0, std::memcmp(back.boundaryEdges.data(), sprite.boundaryEdges.data(),
                             sprite.boundaryEdges.size() * sizeof(glm::vec3)));
    EXPECT_TRUE(back.boundaryKnown);
    EXPECT_EQ(back.crossings.size(), sprite.crossings.size());
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(-1.2f, 1.6f);
    for (int k = 0; k < 500; ++k) {
        const glm::vec3 p(u(rng), u(rng), u(rng));
        ASSERT_EQ(back.generalizedWinding(p), sprite.generalizedWinding(p));
    }
    // A changed edge is caught by the checksum.
    Sprite edited = sprite;
    std::vector<char> good = encodeSprite(edited);
    edited.boundaryEdges[0].x += 0.25f;
    std::vector<char> other = encodeSprite(edited);
    EXPECT_NE(good, other);
}

#ifdef VDS_TEST_DATA
TEST(SpriteGeneralizedWinding, VersionOneFilesStillRead) {
    // Written by the library at format version 1 (before boundary edges):
    // a 16-segment sphere of radius 1 at (0.1, 0.2, 0.3), and the same
    // sphere without the triangles whose centroid has z >= 0.8, both baked
    // on the CPU at resolution 12 along z.
    const auto sphere = solids::sphere({0.1f, 0.2f, 0.3f}, 1.0f, 16);
    const Sprite closed = readSprite(std::string(VDS_TEST_DATA) + "/sphere-v1.vds");
    const Sprite rebaked = bakeAt(sphere.mesh, Axis::Z, 12);
    EXPECT_EQ(closed.crossings, rebaked.crossings);
    EXPECT_EQ(closed.offsets, rebaked.offsets);
    EXPECT_TRUE(closed.boundaryKnown);
    EXPECT_TRUE(closed.boundaryEdges.empty());
    EXPECT_EQ(closed.contains({0.1f, 0.2f, 0.3f}, Rule::GeneralizedWinding), true);
    EXPECT_EQ(closed.contains({0.1f, 0.2f, 1.5f}, Rule::GeneralizedWinding), false);

    const Sprite open = readSprite(std::string(VDS_TEST_DATA) + "/cup-v1.vds");
    EXPECT_EQ(open.status, SolidStatus::Open);
    EXPECT_FALSE(open.boundaryKnown);
    EXPECT_TRUE(open.boundaryEdges.empty());
    EXPECT_TRUE(open.contains({0.1f, 0.2f, 0.3f}, Rule::Parity));
    EXPECT_THROW(open.contains({0.1f, 0.2f, 0.3f}, Rule::GeneralizedWinding), InvalidArgument);
    EXPECT_THROW(encodeSprite(open), FormatError);
    // Re-baked at version 2 it answers.
    TriangleMesh cup = sphere.mesh;
    cup.triangles.clear();
    for (const glm::uvec3& t : sphere.mesh.triangles)
        if ((sphere.mesh.positions[t[0]] + sphere.mesh.positions[t[1]] + sphere.mesh.positions[t[2]]).z / 3.0f < 0.8f)
            cup.triangles.push_back(t);
    const Sprite again = bakeAt(cup, Axis::Z, 12);
    EXPECT_EQ(again.crossings, open.crossings);
    EXPECT_TRUE(again.contains({0.1f, 0.2f, 0.3f}, Rule::GeneralizedWinding));
}
#endif

// ---- ties and degenerate rays ------------------------------------------------

// Points exactly in the plane of a flat boundary loop, with the view axis in
// that plane: every boundary edge's spherical triangle is degenerate there,
// and the rays pass over the loop (through its vertices, too). The value is
// continuous off the surface: it must equal the brute-force solid-angle sum.
TEST(GeneralizedWinding, InThePlaneOfAFlatBoundaryLoop) {
    const TriangleMesh bowl = flatRimBowl(12, 48);
    // A tilted open square above, so that the value is not a multiple of 1/2.
    TriangleMesh mesh = bowl;
    const std::uint32_t base = std::uint32_t(mesh.positions.size());
    for (const glm::vec3& v : {glm::vec3(-0.4f, 0.5f, -0.3f), glm::vec3(0.5f, 0.7f, -0.4f), glm::vec3(0.45f, 0.6f, 0.5f),
                               glm::vec3(-0.5f, 0.4f, 0.35f)})
        mesh.positions.push_back(v);
    mesh.triangles.push_back({base, base + 1, base + 2});
    mesh.triangles.push_back({base, base + 2, base + 3});
    std::vector<glm::vec3> points;
    for (int k = -6; k <= 6; ++k)
        for (int l = -6; l <= 6; ++l) points.emplace_back(0.17f * float(k), 0.0f, 0.17f * float(l));
    // Straight over rim vertices along +z and +x: their rays pass through them.
    for (int j : {0, 5, 13, 30}) {
        const glm::vec3 v = mesh.positions[std::size_t(j)];
        points.emplace_back(v.x, 0.0f, v.z + 0.25f);
        points.emplace_back(v.x + 0.25f, 0.0f, v.z);
    }
    for (Axis axis : {Axis::X, Axis::Y, Axis::Z}) {
        const ExactClassifier exact(mesh, axis);
        for (const glm::vec3& p : points) {
            if (std::fabs(glm::length(glm::vec2(p.x, p.z)) - 1.0f) < 1e-3f) continue; // on the rim
            const double expected = bruteForceGwn(mesh, p);
            EXPECT_NEAR(exact.generalizedWinding(p), expected, 1e-9) << toString(axis) << " " << p.x << " " << p.z;
            EXPECT_EQ(exact.contains(p, Rule::GeneralizedWinding), expected > 0.5 + 1e-9) << toString(axis);
        }
    }
}

// A flat sheet: its generalized winding number is below 1/2 off the sheet,
// and exactly 1/2 at its points (the tie rule's side): on the surface, not
// inside, whichever way the sheet lies to the view axis.
TEST(GeneralizedWinding, FlatSheetIsOnTheSurfaceNotInside) {
    for (int normal = 0; normal < 3; ++normal) {
        TriangleMesh sheet; // 8 x 8 squares over [0, 1]^2 in the plane across `normal`, at 0.5
        const int n = 8;
        for (int i = 0; i <= n; ++i)
            for (int j = 0; j <= n; ++j) {
                glm::vec3 v(0.5f);
                v[(normal + 1) % 3] = float(i) / n;
                v[(normal + 2) % 3] = float(j) / n;
                sheet.positions.push_back(v);
            }
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < n; ++j) {
                const auto id = [&](int a, int b) { return std::uint32_t(a * (n + 1) + b); };
                sheet.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
                sheet.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
            }
        std::mt19937 rng(3);
        std::uniform_real_distribution<float> u(0.0f, 1.0f);
        std::vector<glm::vec3> points;
        for (int k = 0; k < 400; ++k) {
            glm::vec3 p(0.5f);
            p[(normal + 1) % 3] = u(rng);
            p[(normal + 2) % 3] = u(rng);
            points.push_back(p); // in the sheet
            p[normal] = u(rng);
            points.push_back(p); // anywhere
        }
        for (Axis axis : {Axis::X, Axis::Y, Axis::Z}) {
            const ExactClassifier exact(sheet, axis);
            std::vector<std::uint8_t> labels(points.size());
            exact.classify(points, labels.data(), {Rule::GeneralizedWinding, 1});
            EXPECT_EQ(std::count(labels.begin(), labels.end(), std::uint8_t(1)), 0) << normal << " " << toString(axis);
            for (std::size_t k = 0; k < points.size(); k += 2)
                EXPECT_NEAR(std::fabs(exact.generalizedWinding(points[k])), 0.5, 1e-9);
        }
        const Grid grid{{glm::vec3(0.0f), glm::vec3(1.0f)}, glm::uvec3(16)}; // centres in the sheet's plane
        std::vector<std::uint8_t> cells(grid.cellCount());
        occupancy(sheet, grid, cells.data(), {Rule::GeneralizedWinding, 1});
        EXPECT_EQ(std::count(cells.begin(), cells.end(), std::uint8_t(1)), 0) << normal;
    }
}

// Cells exactly on a lone triangle: the voxelizer's sweep and the exact
// classifier agree, and every cell is outside (a flat triangle's value is
// below 1/2 off it and 1/2, a tie, on it).
TEST(VoxelizeGeneralizedWinding, CellsOnATriangleAreOutsideAsInClassify) {
    const Grid grid{{glm::vec3(0.0f), glm::vec3(1.0f)}, glm::uvec3(16)};
    const float on = grid.cellCentre(0, 0, 8).z; // 0.53125
    std::vector<TriangleMesh> meshes;
    for (int normal = 0; normal < 3; ++normal) {
        TriangleMesh t;
        glm::vec3 a(on), b(on), c(on);
        const int s = (normal + 1) % 3, r = (normal + 2) % 3;
        a[s] = 0.05f, a[r] = 0.1f;
        b[s] = 0.95f, b[r] = 0.2f;
        c[s] = 0.3f, c[r] = 0.97f;
        t.positions = {a, b, c};
        t.triangles = {{0, 1, 2}};
        meshes.push_back(t);
    }
    for (const TriangleMesh& mesh : meshes) {
        std::vector<std::uint8_t> cells(grid.cellCount()), labels(grid.cellCount());
        occupancy(mesh, grid, cells.data(), {Rule::GeneralizedWinding, 1});
        std::vector<glm::vec3> centres(grid.cellCount());
        for (std::uint32_t i = 0; i < 16; ++i)
            for (std::uint32_t j = 0; j < 16; ++j)
                for (std::uint32_t k = 0; k < 16; ++k) centres[grid.index(i, j, k)] = grid.cellCentre(i, j, k);
        const ExactClassifier exact(mesh, Axis::Z);
        exact.classify(centres, labels.data(), {Rule::GeneralizedWinding, 1});
        EXPECT_EQ(cells, labels);
        EXPECT_EQ(std::count(cells.begin(), cells.end(), std::uint8_t(1)), 0);
    }
}

// Beyond a large opening the generalized winding number can exceed 1/2
// outside the mesh's box: a bowl (rim at y = 0, the box's top) with a disk
// inside it seen from just above the rim plane. A sprite answers there as
// the exact classifier does, beside its box (view axis z) and in front of
// or behind it (view axis y).
TEST(SpriteGeneralizedWinding, AnswersOutsideTheBoxBeyondAnOpening) {
    const TriangleMesh mesh = solids::bowlWithDisk();
    std::mt19937 rng(9);
    std::uniform_real_distribution<float> u(-0.4f, 0.4f), above(0.02f, 0.1f);
    std::vector<glm::vec3> points(500);
    for (glm::vec3& p : points) p = {u(rng), above(rng), u(rng)};
    const ExactClassifier exact(mesh, Axis::Z);
    std::size_t inside = 0;
    for (const glm::vec3& p : points) inside += exact.contains(p, Rule::GeneralizedWinding);
    EXPECT_GT(inside, points.size() / 2);
    for (Axis axis : {Axis::Z, Axis::Y}) {
        const Sprite sprite = bakeAt(mesh, axis, 64);
        ASSERT_GT(sprite.grid.toTexture(points[0])[axis == Axis::Z ? 1 : 2], 1.0f); // outside the box
        std::vector<std::uint8_t> labels(points.size());
        classify(sprite, points, labels.data(), {Rule::GeneralizedWinding, 1});
        for (std::size_t k = 0; k < points.size(); ++k) {
            const bool expected = exact.contains(points[k], Rule::GeneralizedWinding);
            EXPECT_EQ(labels[k] != 0, expected) << toString(axis) << " " << k;
            EXPECT_EQ(sprite.contains(points[k], Rule::GeneralizedWinding), expected) << toString(axis) << " " << k;
            EXPECT_NEAR(sprite.generalizedWinding(points[k]), exact.generalizedWinding(points[k]), 0.02);
        }
    }
}

// ---- voxelizers -------------------------------------------------------------

TEST(VoxelizeGeneralizedWinding, EqualsTheExactClassifierAtCellCentres) {
    for (const OpenCase& c : openCases()) {
        const ExactClassifier exact(c.mesh, Axis::Z);
        for (std::uint32_t n : {24u, 64u}) { // cell by cell, and by the column brackets
            const Grid grid = cubicGrid(meshBounds(c.mesh), n);
            const std::size_t count = std::size_t(grid.dims.x) * grid.dims.y * grid.dims.z;
            std::vector<std::uint8_t> cells(count);
            occupancy(c.mesh, grid, cells.data(), {Rule::GeneralizedWinding, 0});
            std::size_t differ = 0, inside = 0;
            for (std::uint32_t i = 0; i < grid.dims.x; ++i)
                for (std::uint32_t j = 0; j < grid.dims.y; ++j)
                    for (std::uint32_t k = 0; k < grid.dims.z; ++k) {
                        const glm::vec3 p = grid.cellCentre(i, j, k);
                        const std::uint8_t got = cells[grid.index(i, j, k)];
                        inside += got;
                        differ += got != (exact.contains(p, Rule::GeneralizedWinding) ? 1 : 0);
                    }
            EXPECT_GT(inside, count / 20) << c.name;
            EXPECT_EQ(differ, 0u) << c.name << " " << n;
        }
    }
}

TEST(GeneralizedWinding, ExactMemoryCountsTheBoundarysCaps) {
    // The generalized winding number's queries read the boundary's caps and
    // the plans their grid fills as queries arrive: memoryBytes() counts
    // them, so it grows as the plans are filled (a closed mesh has none).
    for (const OpenCase& c : openCases()) {
        const ExactClassifier exact(c.mesh, Axis::Z);
        const std::size_t before = exact.memoryBytes();
        const Box box = meshBounds(c.mesh);
        std::mt19937 rng(41);
        std::uniform_real_distribution<float> u(0.0f, 1.0f);
        std::vector<glm::vec3> points(20000);
        for (glm::vec3& p : points) p = box.lo + glm::vec3(u(rng), u(rng), u(rng)) * (box.hi - box.lo);
        std::vector<std::uint8_t> labels(points.size());
        exact.classify({points.data(), points.size()}, labels.data(), {Rule::GeneralizedWinding, 1});
        EXPECT_GT(exact.memoryBytes(), before) << c.name;
    }
    const TriangleMesh closed = solids::sphere(glm::vec3(0.0f), 1.0f, 32).mesh;
    const ExactClassifier exact(closed, Axis::Z);
    const std::size_t before = exact.memoryBytes();
    const glm::vec3 p(0.1f, 0.2f, 0.3f);
    std::uint8_t label = 0;
    exact.classify({&p, 1}, &label, {Rule::GeneralizedWinding, 1});
    EXPECT_EQ(label, 1);
    EXPECT_EQ(exact.memoryBytes(), before);
}

TEST(OccupancyGeneralizedWinding, EqualsTheSpritesClassify) {
    const TriangleMesh cup = sphereCup();
    const Sprite sprite = bakeAt(cup, Axis::Z, 64);
    const Grid grid = cubicGrid(meshBounds(cup), 20);
    const std::size_t count = std::size_t(grid.dims.x) * grid.dims.y * grid.dims.z;
    std::vector<std::uint8_t> cells(count), labels(count);
    occupancy(sprite, grid, cells.data(), {Rule::GeneralizedWinding, 1});
    std::vector<glm::vec3> centres(count);
    for (std::uint32_t i = 0; i < grid.dims.x; ++i)
        for (std::uint32_t j = 0; j < grid.dims.y; ++j)
            for (std::uint32_t k = 0; k < grid.dims.z; ++k) centres[grid.index(i, j, k)] = grid.cellCentre(i, j, k);
    classify(sprite, centres, labels.data(), {Rule::GeneralizedWinding});
    EXPECT_EQ(cells, labels);
    EXPECT_GT(std::count(cells.begin(), cells.end(), std::uint8_t(1)), std::ptrdiff_t(count / 20));
    EXPECT_EQ(parseRule("generalized-winding"), Rule::GeneralizedWinding);
}

} // namespace
} // namespace vds
