// Tests of the exact classifier and the CPU baker (<vds/exact.h>).
#include <vds/exact.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <vds/bake.h>


#include <vds/error.h>
#include "solids.h"

namespace {

using vds::Axis;
using vds::ExactClassifier;
using vds::Rule;
using vds::TriangleMesh;

const Axis kAxes[] = {Axis::X, Axis::Y, Axis::Z};

int axisIndex(Axis a) { return vds::axisPermutation(a).z; }

/// Uniform points in the mesh's box grown by a fifth on every side.
std::vector<glm::vec3> randomPoints(const TriangleMesh& m, std::size_t count, unsigned seed) {
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (const auto& p : m.positions) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    const glm::vec3 margin = 0.2f * (hi - lo);
    std::mt19937 rng(seed);
    std::vector<glm::vec3> points(count);
    for (auto& p : points)
        for (int a = 0; a < 3; ++a)
            p[a] = std::uniform_real_distribution<float>(lo[a] - margin[a], hi[a] + margin[a])(rng);
    return points;
}

/// Points on the mesh and on rays through its vertices and edges: vertices,
/// edge midpoints and centroids (rounded to float), and copies of vertices and
/// midpoints moved along each axis (same projection, other depths).
std::vector<glm::vec3> degeneratePoints(const TriangleMesh& m) {
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (const auto& p : m.positions) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    std::vector<glm::vec3> on(m.positions.begin(), m.positions.end());
    for (const auto& t : m.triangles) {
        const glm::vec3 a = m.positions[t.x], b = m.positions[t.y], c = m.positions[t.z];
        on.push_back(0.5f * (a + b));
        on.push_back(0.5f * (b + c));
        on.push_back(0.5f * (c + a));
    }
    std::vector<glm::vec3> points = on;
    for (const auto& t : m.triangles)
        points.push_back((m.positions[t.x] + m.positions[t.y] + m.positions[t.z]) / 3.0f);
    for (const auto& p : on)
        for (int a = 0; a < 3; ++a)
            for (float depth : {lo[a] - 1.0f, 0.25f * lo[a] + 0.75f * hi[a], hi[a] + 1.0f}) {
                glm::vec3 q = p;
                q[a] = depth;
                points.push_back(q);
            }
    return points;
}

/// Accelerated and brute-force answers agree on every point, for both rules
/// and along every axis; the batch form agrees with the single one.
void expectAgreement(const TriangleMesh& mesh, const std::vector<glm::vec3>& points) {
    for (Axis axis : kAxes) {
        const ExactClassifier exact(mesh, axis);
        for (Rule rule : {Rule::Parity, Rule::Winding}) {
            std::size_t mismatches = 0, inside = 0;
            for (const auto& p : points) {
                const bool fast = exact.contains(p, rule);
                inside += fast;
                if (fast != exact.containsByEveryTriangle(p, rule)) {
                    if (++mismatches <= 5)
                        ADD_FAILURE() << mesh.name << " axis " << vds::toString(axis) << " rule " << vds::toString(rule)
                                      << ": disagree at (" << p.x << ", " << p.y << ", " << p.z << ")";
                }
            }
            EXPECT_EQ(mismatches, 0u) << mesh.name << " axis " << vds::toString(axis);
            EXPECT_GT(inside, 0u);
            EXPECT_LT(inside, points.size());

            std::vector<std::uint8_t> labels(points.size(), 7);
            vds::ClassifyOptions options;
            options.rule = rule;
            options.threads = 2;
            exact.classify({points.data(), points.size()}, labels.data(), options);
            for (std::size_t k = 0; k < points.size(); ++k)
                ASSERT_EQ(labels[k], exact.contains(points[k], rule) ? 1 : 0) << "point " << k;
        }
    }
}

/// Points further from the ideal surface than the tessellation are classified
/// as the analytic solid says.
void expectAnalytic(const vds::solids::Solid& solid, Rule rule, std::size_t count) {
    const float margin = solid.tessellationError + 1e-4f * glm::length(solid.size);
    const auto points = randomPoints(solid.mesh, count, 7);
    for (Axis axis : kAxes) {
        const ExactClassifier exact(solid.mesh, axis);
        std::size_t checked = 0, wrong = 0;
        for (const auto& p : points) {
            const float d = solid.distance(p);
            if (std::fabs(d) <= margin) continue;
            ++checked;
            if (exact.contains(p, rule) != (d < 0.0f) && ++wrong <= 5)
                ADD_FAILURE() << solid.mesh.name << " axis " << vds::toString(axis) << ": (" << p.x << ", " << p.y
                              << ", " << p.z << ") at distance " << d;
        }
        EXPECT_EQ(wrong, 0u);
        EXPECT_GT(checked, count / 2);
    }
}

TEST(ExactClassifier, BruteForceAgreesOnRandomAndDegeneratePoints) {
    using namespace vds::solids;
    const Solid solids[] = {
        box({-1.0f, -0.5f, 0.25f}, {2.0f, 1.5f, 1.0f}),
        sphere({0.3f, -0.2f, 0.1f}, 1.5f, 24),
        torus({0.0f, 0.5f, -0.25f}, 2.0f, 0.6f, 20),
        shell({0.0f, 0.0f, 0.0f}, 2.0f, 1.0f, 16),
        overlappingBoxes({0.0f, 0.0f, 0.0f}, {2.0f, 2.0f, 2.0f}, {1.0f, 1.0f, 1.0f}, {3.0f, 3.0f, 3.0f}),
    };
    for (const auto& s : solids) {
        auto points = randomPoints(s.mesh, 3000, 11);
        const auto degenerate = degeneratePoints(s.mesh);
        points.insert(points.end(), degenerate.begin(), degenerate.end());
        expectAgreement(s.mesh, points);
    }
}

/// The grid lists each cell's triangles by their nearest vertex depth and
/// stops at the first wholly behind the point, and counts a claimed triangle
/// wholly in front without orient3d: points whose depth equals a vertex depth
/// of the triangles over them (on the vertices' and edges' rays, at the
/// centroids) sit exactly on those shortcuts' boundaries.
TEST(ExactClassifier, BruteForceAgreesAtTheTrianglesOwnVertexDepths) {
    using namespace vds::solids;
    const Solid solids[] = {
        sphere({0.3f, -0.2f, 0.1f}, 1.5f, 40),
        torus({0.0f, 0.5f, -0.25f}, 2.0f, 0.6f, 24),
        overlappingBoxes({0.0f, 0.0f, 0.0f}, {2.0f, 2.0f, 2.0f}, {1.0f, 1.0f, 1.0f}, {3.0f, 3.0f, 3.0f}),
    };
    for (const auto& s : solids) {
        const TriangleMesh& m = s.mesh;
        std::vector<glm::vec3> points;
        for (const auto& t : m.triangles) {
            const glm::vec3 v[3] = {m.positions[t.x], m.positions[t.y], m.positions[t.z]};
            const glm::vec3 onRays[] = {v[0], v[1], v[2], 0.5f * (v[0] + v[1]), 0.5f * (v[1] + v[2]),
                                        (v[0] + v[1] + v[2]) / 3.0f};
            for (const glm::vec3& p : onRays)
                for (int a = 0; a < 3; ++a)
                    for (const glm::vec3& depth : v) {
                        glm::vec3 q = p;
                        q[a] = depth[a];
                        points.push_back(q);
                    }
        }
        expectAgreement(m, points);
    }
}

TEST(ExactClassifier, CoplanarTouchingBoxes) {
    // Two boxes sharing the face x = 1, with opposite facings there.
    const TriangleMesh mesh = vds::solids::merge(vds::solids::box({0, 0, 0}, {1, 1, 1}).mesh,
                                                 vds::solids::box({1, 0, 0}, {2, 1, 1}).mesh);
    auto points = randomPoints(mesh, 3000, 5);
    for (float y : {0.0f, 0.25f, 0.5f, 1.0f})
        for (float z : {0.0f, 0.25f, 0.5f, 0.75f, 1.0f}) points.push_back({1.0f, y, z});
    const auto degenerate = degeneratePoints(mesh);
    points.insert(points.end(), degenerate.begin(), degenerate.end());
    expectAgreement(mesh, points);

    for (Axis axis : kAxes) {
        const ExactClassifier exact(mesh, axis);
        // Inside either box, and on the shared face, the union is inside.
        const glm::vec3 inA(0.5f, 0.5f, 0.5f), inB(1.5f, 0.3f, 0.6f), onShared(1.0f, 0.5f, 0.5f);
        for (const glm::vec3& p : {inA, inB, onShared}) {
            EXPECT_TRUE(exact.contains(p, Rule::Parity)) << vds::toString(axis);
            EXPECT_EQ(exact.winding(p), 1) << vds::toString(axis);
        }
        EXPECT_EQ(exact.winding({2.5f, 0.5f, 0.5f}), 0);
    }
}

TEST(ExactClassifier, AnalyticSolids) {
    using namespace vds::solids;
    expectAnalytic(box({-1.0f, -2.0f, -0.5f}, {1.0f, 0.5f, 3.0f}), Rule::Parity, 4000);
    expectAnalytic(sphere({0.5f, 0.25f, -1.0f}, 2.0f, 64), Rule::Parity, 4000);
    expectAnalytic(torus({0.0f, 0.0f, 0.0f}, 2.0f, 0.75f, 64), Rule::Parity, 4000);
    expectAnalytic(shell({1.0f, 0.0f, 0.0f}, 2.0f, 1.0f, 64), Rule::Parity, 4000);
    expectAnalytic(shell({1.0f, 0.0f, 0.0f}, 2.0f, 1.0f, 64), Rule::Winding, 4000);
}

TEST(ExactClassifier, OverlapIsOutsideByParityInsideByWinding) {
    const auto s = vds::solids::overlappingBoxes({0, 0, 0}, {2, 2, 2}, {1, 1, 1}, {3, 3, 3});
    for (Axis axis : kAxes) {
        const ExactClassifier exact(s.mesh, axis);
        const glm::vec3 overlap(1.5f, 1.25f, 1.75f), onlyA(0.5f, 0.5f, 0.5f), onlyB(2.5f, 2.5f, 2.25f);
        EXPECT_EQ(exact.winding(overlap), 2);
        EXPECT_FALSE(exact.contains(overlap, Rule::Parity));
        EXPECT_TRUE(exact.contains(overlap, Rule::Winding));
        for (const glm::vec3& p : {onlyA, onlyB}) {
            EXPECT_TRUE(exact.contains(p, Rule::Parity));
            EXPECT_TRUE(exact.contains(p, Rule::Winding));
        }
        EXPECT_FALSE(exact.contains({2.5f, 0.5f, 0.5f}, Rule::Winding));
    }
}

TEST(ExactClassifier, ShellCavityIsOutside) {
    const auto s = vds::solids::shell({0, 0, 0}, 2.0f, 1.0f, 32);
    for (Axis axis : kAxes) {
        const ExactClassifier exact(s.mesh, axis);
        for (const glm::vec3 p : {glm::vec3(0.0f), glm::vec3(0.3f, -0.2f, 0.4f)}) {
            EXPECT_EQ(exact.winding(p), 0);
            EXPECT_FALSE(exact.contains(p, Rule::Parity));
            EXPECT_FALSE(exact.contains(p, Rule::Winding));
        }
        EXPECT_TRUE(exact.contains({1.5f, 0.0f, 0.0f}, Rule::Parity));
        EXPECT_TRUE(exact.contains({0.0f, -1.5f, 0.1f}, Rule::Winding));
    }
}

TEST(ExactClassifier, RaysThroughSharedEdgesCountOneCrossingPerSheet) {
    // The box [-1,1]^3 splits each face along the diagonal from its low to its
    // high corner: seen along any axis, points with equal s and t lie exactly
    // on the projections of two shared edges (front and back face).
    const auto box = vds::solids::box({-1, -1, -1}, {1, 1, 1});
    for (Axis axis : kAxes) {
        const ExactClassifier exact(box.mesh, axis);
        const glm::ivec3 p = vds::axisPermutation(axis);
        for (float u : {-0.75f, -1.0f / 3.0f, 0.0f, 0.125f, 0.6f}) {
            for (float depth : {-2.0f, -0.5f, 0.0f, 0.9f, 2.0f}) {
                glm::vec3 q;
                q[p.x] = u;
                q[p.y] = u;
                q[p.z] = depth;
                const int expected = std::fabs(depth) < 1.0f ? 1 : 0;
                EXPECT_EQ(exact.winding(q), expected) << vds::toString(axis) << " u " << u << " depth " << depth;
                EXPECT_EQ(exact.containsByEveryTriangle(q, Rule::Winding), expected == 1);
            }
        }
    }
}

TEST(ExactClassifier, RaysThroughVerticesCountOneCrossingPerSheet) {
    // A sphere seen along z: the poles are vertices of closed fans, and the
    // meridian at angle 0 lies exactly on the line y = centre.y in projection.
    const glm::vec3 c(0.25f, -0.5f, 0.75f);
    const float r = 1.5f;
    const auto s = vds::solids::sphere(c, r, 48);
    const ExactClassifier exact(s.mesh, Axis::Z);
    EXPECT_EQ(exact.winding({c.x, c.y, c.z}), 1);
    EXPECT_EQ(exact.winding({c.x, c.y, c.z + 0.9f * r}), 1);
    EXPECT_EQ(exact.winding({c.x, c.y, c.z + 2.0f * r}), 0);
    EXPECT_EQ(exact.winding({c.x, c.y, c.z - 2.0f * r}), 0);
    for (float u : {0.1f, 0.3f, 0.5f, 0.7f}) {
        EXPECT_EQ(exact.winding({c.x + u * r, c.y, c.z}), 1) << u;
        EXPECT_EQ(exact.winding({c.x - u * r, c.y, c.z + 4.0f}), 0) << u;
    }
    // Every vertex away from the silhouette (the equator), along z: the ray
    // through it counts one crossing per sheet.
    std::size_t tested = 0;
    for (const auto& v : s.mesh.positions) {
        if (std::fabs(v.z - c.z) < 0.3f * r) continue;
        ++tested;
        EXPECT_EQ(exact.winding({v.x, v.y, c.z}), 1) << v.x << " " << v.y << " " << v.z;
        EXPECT_EQ(exact.winding({v.x, v.y, c.z + 2.0f * r}), 0) << v.x << " " << v.y << " " << v.z;
    }
    EXPECT_GT(tested, 500u);
}

TEST(ExactClassifier, ProjectionBoundaryFollowsTopLeftRule) {
    // On the box's projected outline the rule claims a point iff the point
    // moved by (+eps, -eps^2) in (s,t) lies inside: s in [lo, hi), t in (lo, hi].
    const auto box = vds::solids::box({0, 0, 0}, {1, 1, 1});
    for (Axis axis : kAxes) {
        const ExactClassifier exact(box.mesh, axis);
        const glm::ivec3 p = vds::axisPermutation(axis);
        const float values[] = {-0.5f, 0.0f, 0.5f, 1.0f, 1.5f};
        for (float s : values)
            for (float t : values) {
                glm::vec3 q;
                q[p.x] = s;
                q[p.y] = t;
                q[p.z] = 0.5f;
                const int expected = (s >= 0.0f && s < 1.0f && t > 0.0f && t <= 1.0f) ? 1 : 0;
                EXPECT_EQ(exact.winding(q), expected) << vds::toString(axis) << " s " << s << " t " << t;
                q[p.z] = 3.0f; // behind: both faces in front
                EXPECT_EQ(exact.winding(q), 0);
            }
    }
}

TEST(ExactClassifier, PointsOnTheSurfaceDoNotCountTheirOwnCrossing) {
    const auto box = vds::solids::box({0, 0, 0}, {1, 1, 1});
    const ExactClassifier exact(box.mesh, Axis::Z);
    EXPECT_EQ(exact.winding({0.5f, 0.25f, 0.0f}), 0); // on the entering face
    EXPECT_EQ(exact.winding({0.5f, 0.25f, 1.0f}), 1); // on the leaving face
    EXPECT_EQ(exact.winding({0.5f, 0.5f, 1.0f}), 1);  // on its diagonal
}

TEST(ExactClassifier, FarAndNonFinitePointsAreOutside) {
    const auto s = vds::solids::sphere({0, 0, 0}, 1.0f, 16);
    const ExactClassifier exact(s.mesh);
    EXPECT_EQ(exact.axis(), Axis::Z);
    const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
    for (const glm::vec3 p : {glm::vec3(5, 0, 0), glm::vec3(0, 0, -5), glm::vec3(0, 0, inf), glm::vec3(nan, 0, 0),
                              glm::vec3(0, nan, 0), glm::vec3(0, 0, nan), glm::vec3(1e30f, -1e30f, 0)}) {
        EXPECT_EQ(exact.winding(p), 0);
        EXPECT_FALSE(exact.containsByEveryTriangle(p, Rule::Winding));
    }
}

TEST(ExactClassifier, TrianglesParallelToTheAxisAreNeverCrossed) {
    // Two triangles in the plane x = 0: seen along y or z they have no
    // projected area; seen along x they do.
    TriangleMesh wall;
    wall.positions = {{0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {0, 0, 1}};
    wall.triangles = {{0, 1, 2}, {0, 2, 3}};
    for (Axis axis : {Axis::Y, Axis::Z}) {
        const ExactClassifier exact(wall, axis);
        for (const glm::vec3 p : {glm::vec3(0, 0.5f, 0.5f), glm::vec3(0, 0.25f, 2), glm::vec3(0, 2, 0.25f)}) {
            EXPECT_EQ(exact.winding(p), 0);
            EXPECT_FALSE(exact.containsByEveryTriangle(p, Rule::Winding));
        }
    }
    const ExactClassifier alongX(wall, Axis::X);
    EXPECT_EQ(alongX.winding({1.0f, 0.25f, 0.5f}), -1); // normal +x: leaving
    EXPECT_TRUE(alongX.contains({1.0f, 0.25f, 0.5f}, Rule::Parity));
    EXPECT_EQ(alongX.winding({-1.0f, 0.25f, 0.5f}), 0);
}

TEST(ExactClassifier, ClassifyMatchesContainsOnAnyThreadCount) {
    const auto s = vds::solids::torus({0, 0, 0}, 2.0f, 0.5f, 32);
    const ExactClassifier exact(s.mesh, Axis::Y);
    const auto points = randomPoints(s.mesh, 20000, 3);
    std::vector<std::uint8_t> expected(points.size());
    for (std::size_t k = 0; k < points.size(); ++k) expected[k] = exact.contains(points[k], Rule::Winding);
    for (unsigned threads : {0u, 1u, 2u, 3u, 8u}) {
        std::vector<std::uint8_t> labels(points.size(), 9);
        vds::ClassifyOptions options;
        options.rule = Rule::Winding;
        options.threads = threads;
        exact.classify({points.data(), points.size()}, labels.data(), options);
        EXPECT_EQ(labels, expected) << threads << " threads";
    }
    exact.classify(vds::PointsView(), nullptr);
}

// The batched classify (cells located and prefetched sixteen points at a
// time) against one point at a time and brute force, on a batch whose size
// is no multiple of the batch, with points outside the grid and not finite.
TEST(ExactClassifier, BatchedClassifyMatchesBruteForce) {
    const auto s = vds::solids::overlappingBoxes({-1, -1, -1}, {0.3f, 0.3f, 0.3f}, {-0.3f, -0.3f, -0.3f}, {1, 1, 1});
    const ExactClassifier exact(s.mesh, Axis::Z);
    auto points = randomPoints(s.mesh, 4999, 5);
    const float inf = std::numeric_limits<float>::infinity();
    points.insert(points.begin() + 7, {{inf, 0, 0}, {0, std::nanf(""), 0}, {0, 0, -inf}, {50, 50, 50}});
    for (Rule rule : {Rule::Parity, Rule::Winding}) {
        std::vector<std::uint8_t> labels(points.size(), 9);
        exact.classify({points.data(), points.size()}, labels.data(), {rule, 2});
        std::size_t inside = 0;
        for (std::size_t k = 0; k < points.size(); ++k) {
            ASSERT_EQ(labels[k], exact.containsByEveryTriangle(points[k], rule) ? 1 : 0) << k << " " << toString(rule);
            inside += labels[k];
        }
        EXPECT_GT(inside, points.size() / 10);
    }
}

TEST(ExactClassifier, MovesKeepTheIndex) {
    const auto s = vds::solids::box({0, 0, 0}, {1, 1, 1});
    ExactClassifier a(s.mesh, Axis::X);
    ExactClassifier b(std::move(a));
    EXPECT_EQ(b.axis(), Axis::X);
    EXPECT_TRUE(b.contains({0.5f, 0.5f, 0.5f}));
    ExactClassifier c(vds::solids::sphere({0, 0, 0}, 1.0f, 8).mesh);
    c = std::move(b);
    EXPECT_EQ(c.axis(), Axis::X);
    EXPECT_FALSE(c.contains({1.5f, 0.5f, 0.5f}));
}

TEST(ExactClassifier, RejectsUnusableMeshes) {
    TriangleMesh empty;
    EXPECT_THROW(ExactClassifier{empty}, vds::InvalidMesh);
    auto nan = vds::solids::box({0, 0, 0}, {1, 1, 1}).mesh;
    nan.positions[3].y = std::numeric_limits<float>::quiet_NaN();
    EXPECT_THROW(ExactClassifier{nan}, vds::InvalidMesh);
    auto badIndex = vds::solids::box({0, 0, 0}, {1, 1, 1}).mesh;
    badIndex.triangles[5].z = 8;
    EXPECT_THROW(ExactClassifier{badIndex}, vds::InvalidMesh);
}

// ---- bakeCpu --------------------------------------------------------------

struct Slab {
    glm::vec3 lo, hi;
};

TEST(BakeCpu, BoxesGiveTwoCrossingsInsideTheirProjectionAndNoneElsewhere) {
    // Two disjoint boxes at different depths in one mesh; texel centres never
    // fall on their outlines at this resolution.
    const Slab slabs[] = {{{0, 0, 0}, {1, 1, 1}}, {{2, 2, 0.5f}, {4, 4, 1}}};
    const TriangleMesh mesh = vds::solids::merge(vds::solids::box(slabs[0].lo, slabs[0].hi).mesh,
                                                 vds::solids::box(slabs[1].lo, slabs[1].hi).mesh);
    const glm::vec3 meshLo(0, 0, 0), meshHi(4, 4, 1);
    for (Axis axis : kAxes) {
        vds::BakeOptions options;
        options.method = vds::BakeMethod::Cpu;
        options.axis = axis;
        options.resolution = 16;
        options.sourceName = "two boxes";
        std::vector<std::string> messages;
        options.progress = [&](const std::string& m) { messages.push_back(m); };
        const vds::Sprite sprite = vds::bakeCpu(mesh, options);
        EXPECT_FALSE(messages.empty());
        EXPECT_EQ(sprite.depthComplexity, 2u);
        EXPECT_EQ(sprite.status, vds::SolidStatus::Closed);
        EXPECT_EQ(sprite.sourceName, "two boxes");
        EXPECT_EQ(sprite.sourceTriangles, 24u);
        const glm::ivec3 p = vds::axisPermutation(axis);
        const int a = axisIndex(axis);
        std::size_t filled = 0;
        for (std::uint32_t j = 0; j < sprite.height(); ++j)
            for (std::uint32_t i = 0; i < sprite.width(); ++i) {
                const glm::vec3 c = sprite.grid.texelCentre(i, j, 0.5f);
                std::vector<float> expected;
                for (const Slab& s : slabs)
                    if (c[p.x] > s.lo[p.x] && c[p.x] < s.hi[p.x] && c[p.y] > s.lo[p.y] && c[p.y] < s.hi[p.y]) {
                        expected.push_back((s.lo[a] - meshLo[a]) / (meshHi[a] - meshLo[a]));
                        expected.push_back(-(s.hi[a] - meshLo[a]) / (meshHi[a] - meshLo[a]));
                    }
                const std::size_t column = std::size_t(j) * sprite.width() + i;
                const std::uint32_t begin = sprite.offsets[column], end = sprite.offsets[column + 1];
                ASSERT_EQ(end - begin, expected.size()) << vds::toString(axis) << " texel " << i << "," << j;
                filled += expected.empty() ? 0 : 1;
                for (std::size_t k = 0; k < expected.size(); ++k) {
                    const float got = sprite.crossings[begin + k];
                    EXPECT_EQ(std::signbit(got), std::signbit(expected[k])) << "crossing " << k;
                    EXPECT_NEAR(got, expected[k], 1e-6f) << "crossing " << k;
                }
            }
        EXPECT_GT(filled, 0u);
        EXPECT_LT(filled, std::size_t(sprite.width()) * sprite.height());
    }
}

TEST(BakeCpu, CoplanarFacesAreOrderedByTriangleIndex) {
    // Box A [0,1]^3 (triangles 0-11) leaves at x = 1 where box B (12-23) enters.
    const TriangleMesh mesh = vds::solids::merge(vds::solids::box({0, 0, 0}, {1, 1, 1}).mesh,
                                                 vds::solids::box({1, 0, 0}, {2, 1, 1}).mesh);
    vds::BakeOptions options;
    options.method = vds::BakeMethod::Cpu;
    options.axis = Axis::X;
    options.resolution = 8;
    const vds::Sprite sprite = vds::bakeCpu(mesh, options);
    ASSERT_EQ(sprite.depthComplexity, 4u);
    for (std::size_t c = 0; c + 1 < sprite.offsets.size(); ++c) {
        ASSERT_EQ(sprite.offsets[c + 1] - sprite.offsets[c], 4u);
        const float* x = &sprite.crossings[sprite.offsets[c]];
        EXPECT_EQ(x[0], 0.0f);
        EXPECT_EQ(x[1], -0.5f);
        EXPECT_EQ(x[2], 0.5f);
        EXPECT_EQ(x[3], -1.0f);
    }
}

TEST(BakeCpu, ColumnsAgreeWithTheClassifier) {
    // The stored crossings of every column sum to the winding of a point
    // behind the mesh on the texel centre's ray, and their depths are sorted.
    using namespace vds::solids;
    const Solid solids[] = {sphere({0.1f, 0.2f, 0.3f}, 1.0f, 40), torus({0, 0, 0}, 1.5f, 0.5f, 32),
                            shell({0, 0, 0}, 2.0f, 1.25f, 32)};
    for (const auto& s : solids)
        for (Axis axis : kAxes) {
            vds::BakeOptions options;
            options.method = vds::BakeMethod::Cpu;
            options.axis = axis;
            options.resolution = 48;
            const vds::Sprite sprite = vds::bakeCpu(s.mesh, options);
            const ExactClassifier exact(s.mesh, axis);
            std::size_t mismatches = 0;
            for (std::uint32_t j = 0; j < sprite.height(); ++j)
                for (std::uint32_t i = 0; i < sprite.width(); ++i) {
                    const std::size_t column = std::size_t(j) * sprite.width() + i;
                    int winding = 0;
                    float previous = 0.0f;
                    for (std::uint32_t k = sprite.offsets[column]; k < sprite.offsets[column + 1]; ++k) {
                        const float e = sprite.crossings[k];
                        winding += vds::crossingEnters(e) ? 1 : -1;
                        EXPECT_GE(vds::crossingDepth(e), previous);
                        previous = vds::crossingDepth(e);
                        // Along a ray, a closed surface alternates entering and leaving.
                        EXPECT_EQ(vds::crossingEnters(e), (k - sprite.offsets[column]) % 2 == 0);
                    }
                    mismatches += winding != exact.winding(sprite.grid.texelCentre(i, j, 2.0f));
                }
            EXPECT_EQ(mismatches, 0u) << s.mesh.name << " axis " << vds::toString(axis);
        }
}

TEST(BakeCpu, DepthComplexityOfSphereAndShell) {
    vds::BakeOptions options;
    options.method = vds::BakeMethod::Cpu;
    options.resolution = 64;
    EXPECT_EQ(vds::bakeCpu(vds::solids::sphere({0, 0, 0}, 1.0f, 32).mesh, options).depthComplexity, 2u);
    EXPECT_EQ(vds::bakeCpu(vds::solids::shell({0, 0, 0}, 2.0f, 1.0f, 32).mesh, options).depthComplexity, 4u);
}

TEST(BakeCpu, FillsTheTimingsOfItsPhases) {
    const auto torus = vds::solids::torus({0, 0, 0}, 1.0f, 0.4f, 48);
    vds::BakeTimings timings;
    timings.bands = 7; // reset by the bake
    vds::BakeOptions options;
    options.method = vds::BakeMethod::Cpu;
    options.resolution = 48;
    options.timings = &timings;
    const vds::Sprite s = vds::bakeCpu(torus.mesh, options);
    using vds::BakePhase;
    for (BakePhase p : {BakePhase::Validation, BakePhase::Upload, BakePhase::Raster, BakePhase::Scan, BakePhase::Assembly}) {
        EXPECT_EQ(timings[p].runs, 1u) << vds::toString(p);
        EXPECT_GE(timings[p].wallSeconds, 0.0);
        EXPECT_LT(timings[p].gpuSeconds, 0.0) << "no GPU time on the CPU";
    }
    for (BakePhase p : {BakePhase::Compile, BakePhase::Sort, BakePhase::TextureFill, BakePhase::ReadBack})
        EXPECT_EQ(timings[p].runs, 0u) << vds::toString(p);
    EXPECT_EQ(timings.bands, 0u);
    EXPECT_EQ(timings.crossings, s.crossings.size());
    EXPECT_GT(timings.wallSeconds, 0.0);
    EXPECT_EQ(timings.gpuSeconds(), 0.0);
    const std::string report = timings.report();
    EXPECT_NE(report.find("raster"), std::string::npos) << report;
    EXPECT_EQ(report.find("sort"), std::string::npos) << report;
    EXPECT_NE(report.find("total"), std::string::npos) << report;
    EXPECT_STREQ(vds::toString(BakePhase::ReadBack), "read-back");
}

TEST(BakeCpu, RejectsUnusableMeshes) {
    vds::BakeOptions options;
    options.method = vds::BakeMethod::Cpu;
    options.resolution = 16;
    TriangleMesh empty;
    EXPECT_THROW(vds::bakeCpu(empty, options), vds::InvalidMesh);
    auto nan = vds::solids::box({0, 0, 0}, {1, 1, 1}).mesh;
    nan.positions[0].x = std::numeric_limits<float>::quiet_NaN();
    EXPECT_THROW(vds::bakeCpu(nan, options), vds::InvalidMesh);
    auto badIndex = vds::solids::box({0, 0, 0}, {1, 1, 1}).mesh;
    badIndex.triangles[0].y = 100;
    EXPECT_THROW(vds::bakeCpu(badIndex, options), vds::InvalidMesh);
}

} // namespace
