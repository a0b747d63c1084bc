// The boundary term's capped loops (<vds/detail/boundary_caps.h>) against the
// per-edge sum (antipodal.h), the independent exact form: the expansion's
// error bound, the drift bound along a move (what the occupancy sweep's runs
// rest on), the margin of decide() and its cost beside a large loop, how
// the boundary splits into loops where a non-manifold ring of edges meets
// fins, the grid of ranges inside() answers from first, and the exact grid
// sweep's two ways, forced, cell by cell; and a sprite's cells over which
// its columns count one integer.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <vds/bake.h>
#include <vds/grid.h>
#include <vds/mesh.h>
#include <vds/sprite.h>

#include <vds/detail/antipodal.h>
#include <vds/detail/boundary_caps.h>
#include <vds/detail/chain_labels.h>
#include <vds/detail/projected_mesh.h>
#include "solids.h"

namespace vds::detail {
namespace {

constexpr double kPi = 3.14159265358979323846;

// An open-bottomed sphere with a fin on every edge of its equator, pointing
// inward: those edges have three faces, and the boundary passes each ring
// vertex twice.
TriangleMesh finnedShell(int rings, int segments) {
    TriangleMesh m = solids::openSphere(rings, segments, [](const glm::vec3& c) { return c.z > -0.7f; });
    const int i = rings / 2;
    for (int j = 0; j < segments; ++j) {
        const std::uint32_t a = std::uint32_t(i * segments + j), b = std::uint32_t(i * segments + (j + 1) % segments);
        m.positions.push_back(0.3f * (m.positions[a] + m.positions[b]) + glm::vec3(0.0f, 0.0f, 0.3f));
        m.triangles.push_back({a, b, std::uint32_t(m.positions.size() - 1)});
    }
    return m;
}

struct Case {
    std::string name;
    TriangleMesh mesh;
};

std::vector<Case> cases() {
    std::vector<Case> out;
    out.push_back({"cup, one large opening", solids::openSphere(24, 48, [](const glm::vec3& c) { return c.z < 0.5f; })});
    out.push_back({"sphere, 12 punched holes", solids::openSphere(32, 64, [](const glm::vec3& c) {
                       for (int h = 0; h < 12; ++h) {
                           const double z = -1.0 + (2.0 * h + 1.0) / 12.0, r = std::sqrt(1.0 - z * z), phi = 2.4 * h;
                           const glm::vec3 centre(float(r * std::cos(phi)), float(r * std::sin(phi)), float(z));
                           if (glm::dot(c, centre) > 0.985f) return false;
                       }
                       return true;
                   })});
    out.push_back({"finned shell", finnedShell(16, 32)});
    return out;
}

std::vector<glm::vec3> points(std::size_t count, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-1.3f, 1.3f);
    std::vector<glm::vec3> out(count);
    for (glm::vec3& p : out) p = {u(rng), u(rng), u(rng)};
    return out;
}

double exactTerm(const std::vector<glm::vec3>& edges, const glm::vec3& q) {
    return boundaryTermExact(edges.data(), edges.size() / 2, 2, glm::dvec3(q));
}

// The cases and a soup of loose triangles.
std::vector<Case> casesAndSoup() {
    std::vector<Case> all = cases();
    all.push_back({"soup", solids::looseTriangles(80, 0.2f, 23)});
    return all;
}

// A mesh's caps given its surface, as the exact classifier builds them,
// over the domain [-1, 1]^3.
struct CapsWithSurface {
    explicit CapsWithSurface(const TriangleMesh& mesh)
        : edges(boundaryEdges(MeshView(mesh))), projected(MeshView(mesh), Axis::Z), surface(projected),
          caps(edges.data(), edges.size() / 2, Axis::Z, &domain, &surface) {}
    Box domain{glm::vec3(-1.0f), glm::vec3(1.0f)};
    std::vector<glm::vec3> edges;
    ProjectedMesh projected;
    ProjectedSurface surface;
    BoundaryCaps caps;
};

// The per-edge sum as the library takes it (EdgeAngles: products of each
// edge's den + i det, a block of edges at a time, the turns counted, one
// atan2) against each edge's own atan2 (edgeSolidAngle) summed: on a helix
// winding six times around q's line (the products turn many times, both
// ways, as the helix's edges run up and then back down), on random edges
// in every count from 1 to 40 (short and partial blocks), on edges with
// det = 0 (q on an edge's sweep, an end on q's ray, an edge along it),
// and taken in pieces as the tree's leaves take them.
TEST(PerEdgeSum, ProductsSumTheEdgesOwnAngles) {
    const auto byAtan2 = [](const std::vector<glm::vec3>& edges, const glm::dvec3& q) {
        double sum = 0.0;
        for (std::size_t k = 0; k < edges.size(); k += 2)
            sum += edgeSolidAngle(2, glm::dvec3(edges[k]), glm::dvec3(edges[k + 1]), q);
        return sum;
    };
    const auto byProducts = [](const std::vector<glm::vec3>& edges, const glm::dvec3& q, std::size_t piece) {
        EdgeAngles sum;
        for (std::size_t first = 0; first < edges.size() / 2; first += piece)
            sum.add(&edges[2 * first], std::min(piece, edges.size() / 2 - first), 2, q);
        return sum.angle();
    };
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    for (const double turn : {1.0, -1.0}) { // six turns up, counterclockwise and clockwise
        std::vector<glm::vec3> helix;
        const auto at = [turn](int j) {
            const double phi = turn * 2.0 * kPi * j / 50.0;
            return glm::vec3(float(std::cos(phi)), float(std::sin(phi)), float(-1.0 + j / 150.0));
        };
        for (int k = 0; k < 300; ++k) {
            helix.push_back(at(k));
            helix.push_back(at(k + 1));
        }
        double largest = 0.0;
        for (int trial = 0; trial < 100; ++trial) {
            const glm::dvec3 q(0.2 * u(rng), 0.2 * u(rng), 0.5 * u(rng));
            const double expected = byAtan2(helix, q);
            largest = std::max(largest, std::fabs(expected));
            for (const std::size_t piece : {std::size_t(300), std::size_t(16), std::size_t(7), std::size_t(1)})
                ASSERT_NEAR(byProducts(helix, q, piece), expected, 1e-11) << "helix, pieces of " << piece;
        }
        EXPECT_GT(largest, 4.0 * kPi) << turn; // the edges really do sum past two turns
    }
    for (std::size_t count = 1; count <= 40; ++count)
        for (int trial = 0; trial < 20; ++trial) {
            std::vector<glm::vec3> edges;
            for (std::size_t k = 0; k < 2 * count; ++k) edges.push_back({u(rng), u(rng), u(rng)});
            const glm::dvec3 q(u(rng), u(rng), u(rng));
            ASSERT_NEAR(byProducts(edges, q, count), byAtan2(edges, q), 1e-12) << count << " edges";
            ASSERT_NEAR(byProducts(edges, q, 3), byAtan2(edges, q), 1e-12) << count << " edges, pieces of 3";
        }
    // det = 0: q under an edge (on its sweep), q's ray through an end, an
    // edge along q's line; among ordinary edges, in one block and apart.
    const glm::dvec3 q(0.25, 0.25, 0.0);
    std::vector<glm::vec3> edges = {{0.0f, 0.0f, -1.0f}, {0.5f, 0.5f, -0.5f}, {0.25f, 0.25f, -2.0f},
                                    {1.0f, 0.0f, 0.5f},  {0.25f, 0.25f, 1.0f}, {0.25f, 0.25f, -1.0f}};
    for (int k = 0; k < 13; ++k) {
        edges.push_back({u(rng), u(rng), u(rng)});
        edges.push_back({u(rng), u(rng), u(rng)});
    }
    for (const std::size_t piece : {std::size_t(16), std::size_t(2), std::size_t(1)}) {
        const double expected = byAtan2(edges, q);
        ASSERT_TRUE(std::isfinite(expected));
        ASSERT_NEAR(byProducts(edges, q, piece), expected, 1e-12) << "det = 0, pieces of " << piece;
    }
}

TEST(CapsTree, ExpansionErrsByNoMoreThanItsBound) {
    for (const Case& c : cases()) {
        const std::vector<glm::vec3> edges = boundaryEdges(MeshView(c.mesh));
        const BoundaryCaps caps(edges.data(), edges.size() / 2, Axis::Z);
        ASSERT_TRUE(caps.closed()) << c.name;
        std::size_t checked = 0, loose = 0;
        for (const glm::vec3& q : points(1500, 3))
            for (const double tolerance : {0.1, 1e-2, 1e-4}) {
                const BoundaryCaps::Estimate e = caps.estimate(q, tolerance);
                if (!std::isfinite(e.bound)) continue; // on a cap
                const double error = std::fabs(e.term - exactTerm(edges, q));
                ASSERT_LE(error, e.bound) << c.name << " tolerance " << tolerance;
                ++checked;
                loose += e.bound > 1e-6; // nodes really were taken by expansion
            }
        EXPECT_GT(checked, 4000u) << c.name;
        EXPECT_GT(loose, checked / 4) << c.name;
    }
}

TEST(CapsTree, ATreeOfManyCapTrianglesBuiltOnThreadsErrsByNoMoreThanItsBound) {
    // A rim of 512 edges and more, about 40 times their length in radius: each fan
    // triangle is cut into 64, 32,768 cap triangles and more, enough for the value
    // tree's subtrees to be built on threads and put together.
    const TriangleMesh cup = solids::openSphere(12, 512, [](const glm::vec3& c) { return c.z < 0.2f; });
    const std::vector<glm::vec3> edges = boundaryEdges(MeshView(cup));
    ASSERT_GE(edges.size() / 2, 512u);
    const BoundaryCaps caps(edges.data(), edges.size() / 2, Axis::Z);
    ASSERT_TRUE(caps.closed());
    std::size_t checked = 0, loose = 0;
    for (const glm::vec3& q : points(400, 5))
        for (const double tolerance : {0.1, 1e-3}) {
            const BoundaryCaps::Estimate e = caps.estimate(q, tolerance);
            if (!std::isfinite(e.bound)) continue; // on a cap
            ASSERT_LE(std::fabs(e.term - exactTerm(edges, q)), e.bound) << "tolerance " << tolerance;
            ++checked;
            loose += e.bound > 1e-6;
        }
    EXPECT_GT(checked, 700u);
    EXPECT_GT(loose, checked / 4);
}

TEST(CapsTree, BoundaryTermDriftsNoMoreThanItsReach) {
    std::mt19937 rng(9);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    for (const Case& c : cases()) {
        const std::vector<glm::vec3> edges = boundaryEdges(MeshView(c.mesh));
        const BoundaryCaps caps(edges.data(), edges.size() / 2, Axis::Z);
        std::size_t moves = 0;
        double tightest = 0.0; // largest observed drift over its bound
        for (const glm::vec3& q : points(800, 5)) {
            const BoundaryCaps::Reach reach = caps.reach(q);
            ASSERT_GE(reach.gap, 0.0);
            if (!(reach.gap > 0.0) || !std::isfinite(reach.gap)) continue;
            const double b0 = exactTerm(edges, q);
            // Along the axis, up or down (across it B steps where the ray
            // starts or stops passing under the boundary curve).
            const glm::dvec3 direction(0.0, 0.0, unit(rng) < 0.0 ? -1.0 : 1.0);
            for (const double fraction : {0.05, 0.3, 0.7, 0.95}) {
                const double length = fraction * reach.gap;
                const glm::vec3 moved = glm::vec3(glm::dvec3(q) + length * direction);
                const double actual = glm::length(glm::dvec3(moved) - glm::dvec3(q)); // after rounding to float
                if (!(actual < reach.gap)) continue;
                const double drift = std::fabs(exactTerm(edges, moved) - b0);
                const double bound = reach.drift(actual);
                ASSERT_LE(drift, bound + 1e-12) << c.name << " moved " << fraction << " of the gap";
                tightest = std::max(tightest, drift / bound);
                ++moves;
            }
        }
        EXPECT_GT(moves, 2000u) << c.name;
        EXPECT_GT(tightest, 0.05) << c.name; // a bound, not a wall
    }
}

TEST(CapsTree, WindingNumberDriftsNoMoreThanDriftWithinAnyBallClearOfTheSurface) {
    // driftWithin bounds the change over a move in any direction, each part
    // of the boundary taken at the nearest a move reaches: checked on the
    // whole winding number (crossing count plus per-edge sum), smooth in a
    // ball that no triangle meets, across the boundary's sweep too.
    std::vector<Case> all = cases();
    all.push_back({"soup", solids::looseTriangles(40, 0.2f, 31)});
    std::mt19937 rng(37);
    std::normal_distribution<double> gauss(0.0, 1.0);
    for (const Case& c : all) {
        const std::vector<glm::vec3> edges = boundaryEdges(MeshView(c.mesh));
        const ProjectedMesh projected(MeshView(c.mesh), Axis::Z);
        const BoundaryCaps caps(edges.data(), edges.size() / 2, Axis::Z);
        const auto gwn = [&](const glm::vec3& p) { return double(projected.winding(p)) + exactTerm(edges, p); };
        std::size_t moves = 0;
        double tightest = 0.0;
        for (const glm::vec3& q : points(500, 41)) {
            // The distance to the nearest triangle's bounding ball: no
            // triangle meets a ball about q of a smaller radius.
            double clear = std::numeric_limits<double>::infinity();
            for (const auto& t : c.mesh.triangles) {
                const glm::dvec3 a(c.mesh.positions[t[0]]), b(c.mesh.positions[t[1]]), d(c.mesh.positions[t[2]]);
                const glm::dvec3 g = (a + b + d) / 3.0;
                const double r = std::max({glm::length(a - g), glm::length(b - g), glm::length(d - g)});
                clear = std::min(clear, glm::length(glm::dvec3(q) - g) - r);
            }
            for (const double length : {0.02, 0.08, 0.25}) {
                if (!(length < 0.9 * clear)) continue;
                const double bound = caps.driftWithin(q, length, std::numeric_limits<double>::infinity());
                ASSERT_GE(bound, 0.0);
                if (!std::isfinite(bound)) continue;
                const double w0 = gwn(q);
                for (int k = 0; k < 4; ++k) {
                    const glm::dvec3 direction = glm::normalize(glm::dvec3(gauss(rng), gauss(rng), gauss(rng)));
                    const glm::vec3 moved = glm::vec3(glm::dvec3(q) + length * direction);
                    if (!(glm::length(glm::dvec3(moved) - glm::dvec3(q)) <= length)) continue; // float rounding
                    const double drift = std::fabs(gwn(moved) - w0);
                    ASSERT_LE(drift, bound + 1e-12) << c.name << " moved " << length;
                    tightest = std::max(tightest, drift / bound);
                    ++moves;
                }
            }
        }
        EXPECT_GT(moves, 1000u) << c.name;
        EXPECT_GT(tightest, 0.05) << c.name; // a bound, not a wall
    }
}

TEST(CapsTree, DecideLeavesItsMarginOrGivesTheExactValue) {
    for (const Case& c : cases()) {
        const std::vector<glm::vec3> edges = boundaryEdges(MeshView(c.mesh));
        const BoundaryCaps caps(edges.data(), edges.size() / 2, Axis::Z);
        const double threshold = 0.5 + kGeneralizedWindingTie;
        for (const glm::vec3& q : points(1500, 7))
            for (const int winding : {0, 1}) {
                const double exact = double(winding) + exactTerm(edges, q);
                const BoundaryCaps::Estimate e = caps.decide(winding, q, 2.0);
                ASSERT_LE(std::fabs(e.term - exact), std::max(e.bound, 1e-12)) << c.name;
                if (e.bound > 1e-6) {
                    ASSERT_GT(std::fabs(e.term - threshold), 2.0 * e.bound) << c.name;
                }
                ASSERT_EQ(e.term > threshold, generalizedWindingInside(exact)) << c.name;
                ASSERT_EQ(caps.inside(winding, q), generalizedWindingInside(exact)) << c.name;
            }
    }
}

TEST(CapsTree, FinsOnANonManifoldRingAreLoopsOfTheirOwn) {
    // 32 fins of three edges each, and the opening's ring of 32 edges: the
    // ring vertices are passed twice, and a walk that kept going straight
    // would run around the equator instead (a cap across the whole shell).
    const TriangleMesh shell = finnedShell(16, 32);
    const std::vector<glm::vec3> edges = boundaryEdges(MeshView(shell));
    ASSERT_EQ(edges.size() / 2, 32u * 3u + 32u);
    const BoundaryCaps caps(edges.data(), edges.size() / 2, Axis::Z);
    ASSERT_TRUE(caps.closed());
    ASSERT_EQ(caps.loops().size(), 33u);
    std::size_t triangles = 0;
    for (const CapLoop& loop : caps.loops()) triangles += loop.count == 3;
    EXPECT_EQ(triangles, 32u);
}

// The unit circle in z = 0 as `count` edges, counter-clockwise seen from +z.
std::vector<glm::vec3> unitCircle(int count) {
    std::vector<glm::vec3> edges;
    const auto at = [count](int k) {
        const double phi = 2.0 * kPi * (k % count) / count;
        return glm::vec3(float(std::cos(phi)), float(std::sin(phi)), 0.0f);
    };
    for (int k = 0; k < count; ++k) {
        edges.push_back(at(k));
        edges.push_back(at(k + 1));
    }
    return edges;
}

TEST(CapsTree, PointsBesideALargeLoopCostItsChainsNearThemNotItsEdges) {
    // A circle of 4,096 edges in z = 0, alone: just above and below its
    // disk the boundary term lies within 0.05 of -1/2 or 1/2, so with
    // winding 1 or 0 the value lies near 1/2, where labels need the term to
    // some 1e-2, and there every cap's fan triangle is close by. The chain
    // tree takes the far arcs by their chords and needs a few chains near
    // the point: far less work than the per-edge sum's 4,096 angles.
    constexpr int kEdges = 4096;
    const std::vector<glm::vec3> edges = unitCircle(kEdges);
    const BoundaryCaps caps(edges.data(), edges.size() / 2, Axis::Z);
    ASSERT_TRUE(caps.closed());
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> radius(0.0f, 0.9f), angle(0.0f, 6.2831853f), height(-0.05f, 0.05f);
    double work = 0.0, nearest = 1.0;
    std::size_t count = 0;
    for (int k = 0; k < 400; ++k) {
        const float r = radius(rng), phi = angle(rng);
        const glm::vec3 q(r * std::cos(phi), r * std::sin(phi), height(rng));
        for (const int winding : {0, 1}) {
            const double exact = double(winding) + exactTerm(edges, q);
            if (std::fabs(exact - 0.5) > 0.1) continue;
            nearest = std::min(nearest, std::fabs(exact - 0.5));
            const BoundaryCaps::Estimate e = caps.decide(winding, q, 1.0);
            ASSERT_EQ(e.term > 0.5 + kGeneralizedWindingTie, generalizedWindingInside(exact)) << q.x << " " << q.y << " " << q.z;
            ASSERT_LE(std::fabs(e.term - exact), std::max(e.bound, 1e-12));
            work += e.work;
            ++count;
        }
    }
    ASSERT_GT(count, 300u);
    EXPECT_LT(nearest, 1e-3); // some points really are close to 1/2
    EXPECT_LT(work / double(count), kEdges / 16.0);
}

TEST(CapsTree, RefiningFromACellsFrontierTakesWhatRefiningFromTheRootTakes) {
    // A planned cell's queries refine from the chain nodes none of them can
    // take a level above (ChainLabels::frontier). Beside a circle of 4,096
    // edges, for points within a small ball, that must take the same nodes
    // and sum the same edges as refining from the root: the same value (to
    // the order of summing), bound and work, and the per-edge sum's label.
    constexpr int kEdges = 4096;
    const std::vector<glm::vec3> edges = unitCircle(kEdges);
    const CapLoops loops(edges.data(), edges.size() / 2, Axis::Z);
    const ChainLabels labels(loops);
    std::mt19937 rng(13);
    std::uniform_real_distribution<float> radius(0.0f, 1.2f), angle(0.0f, 6.2831853f), height(-0.1f, 0.1f), unit(-1.0f, 1.0f);
    const std::uint32_t root = 0;
    std::vector<std::uint32_t> starts;
    std::size_t descended = 0, compared = 0;
    for (int cell = 0; cell < 60; ++cell) {
        const float r = radius(rng), phi = angle(rng);
        const glm::dvec3 c(r * std::cos(phi), r * std::sin(phi), height(rng));
        const double half = 0.02;
        labels.frontier(&root, 1, c, half, starts);
        ASSERT_FALSE(starts.empty());
        descended += starts.size() > 1;
        for (int k = 0; k < 20; ++k) {
            glm::dvec3 d(unit(rng), unit(rng), unit(rng));
            if (glm::length(d) > 1.0 || glm::length(d) == 0.0) continue;
            const glm::vec3 q(c + 0.99 * half * d);
            for (const int winding : {0, 1}) {
                CapsEstimate fromRoot, fromStarts;
                const bool a = labels.refine(winding, q, 1.0, &root, 1, 0.0, 0.0, fromRoot);
                const bool b = labels.refine(winding, q, 1.0, starts.data(), starts.size(), 0.0, 0.0, fromStarts);
                ASSERT_EQ(a, b);
                ASSERT_EQ(fromRoot.work, fromStarts.work);
                if (!a) continue;
                ASSERT_NEAR(fromRoot.term, fromStarts.term, 1e-12);
                ASSERT_NEAR(fromRoot.bound, fromStarts.bound, 1e-12);
                const double exact = double(winding) + exactTerm(edges, q);
                ASSERT_EQ(fromStarts.term > 0.5 + kGeneralizedWindingTie, generalizedWindingInside(exact));
                ++compared;
            }
        }
    }
    EXPECT_GT(descended, 40u); // the frontier lies below the root for most cells
    EXPECT_GT(compared, 800u);
}

TEST(CapsTree, RangesOfTheBoundaryTermLabelAsThePerEdgeSum) {
    // With a domain, inside() answers first from each grid cell's range of
    // B (an estimate at the cell's centre, widened by the reach over the
    // cell) where the curve and its sweep along +axis keep out of the
    // cell: the same labels as the per-edge sum, points near the boundary
    // curve and its sweep included.
    for (const Case& c : cases()) {
        const std::vector<glm::vec3> edges = boundaryEdges(MeshView(c.mesh));
        const Box domain{glm::vec3(-1.0f), glm::vec3(1.0f)};
        const BoundaryCaps caps(edges.data(), edges.size() / 2, Axis::Z, &domain);
        std::vector<glm::vec3> at = points(3000, 17);
        std::mt19937 rng(19);
        std::normal_distribution<float> near(0.0f, 0.02f);
        for (std::size_t e = 0; e + 1 < edges.size(); e += 2) // beside the curve, and above it (its sweep)
            for (const float up : {0.0f, 0.4f, 0.9f})
                at.push_back(0.5f * (edges[e] + edges[e + 1]) + glm::vec3(near(rng), near(rng), up + near(rng)));
        // Every label checked; how many cells answered from their ranges
        // or plans is a matter of speed, which vds_gwn_bench reports.
        for (const glm::vec3& q : at)
            for (const int winding : {-1, 0, 1, 2}) {
                const double exact = double(winding) + exactTerm(edges, q);
                ASSERT_EQ(caps.inside(winding, q), generalizedWindingInside(exact))
                    << c.name << " at " << q.x << " " << q.y << " " << q.z << " winding " << winding;
            }
    }
}

TEST(CapsTree, RangesOfTheWholeWindingNumberLabelAsThePerEdgeSum) {
    // Given its surface, a cell the triangles keep out of gets the range of
    // the whole winding number (the crossing count at its centre plus B
    // there, widened by the reach: the winding number is smooth there,
    // across the boundary's sweep too), and inside(q) answers from it
    // without the crossing count. The same labels as the crossing count
    // plus the per-edge sum: uniform points, points just off the triangles
    // on both sides, and beside and above the boundary curve.
    std::mt19937 rng(23);
    for (const Case& c : casesAndSoup()) {
        const CapsWithSurface built(c.mesh);
        const std::vector<glm::vec3>& edges = built.edges;
        const ProjectedMesh& projected = built.projected;
        const BoundaryCaps& caps = built.caps;
        std::vector<glm::vec3> at = points(4000, 29);
        std::normal_distribution<float> near(0.0f, 0.01f);
        for (const auto& t : c.mesh.triangles) {
            const glm::vec3 a = c.mesh.positions[t[0]], b = c.mesh.positions[t[1]], d = c.mesh.positions[t[2]];
            const glm::vec3 n = glm::normalize(glm::cross(b - a, d - a));
            for (const float side : {-1e-3f, 1e-3f}) at.push_back((a + b + d) / 3.0f + side * n);
        }
        for (std::size_t e = 0; e + 1 < edges.size(); e += 2)
            for (const float up : {0.0f, 0.3f, 0.8f})
                at.push_back(0.5f * (edges[e] + edges[e + 1]) + glm::vec3(near(rng), near(rng), up + near(rng)));
        std::size_t inside = 0;
        for (const glm::vec3& q : at) {
            const bool expected = generalizedWindingInside(double(projected.winding(q)) + exactTerm(edges, q));
            ASSERT_EQ(caps.inside(q), expected) << c.name << " at " << q.x << " " << q.y << " " << q.z;
            inside += expected;
        }
        EXPECT_GT(inside, 20u) << c.name; // labels of both kinds
    }
}

TEST(CapsTree, BusyCellsAnswerFromTheirFineCellsAsThePerEdgeSum) {
    // A coarse cell without a range that many queries land in hands them
    // to the fine grid's cells (their own ranges and plans, filled on
    // their first visits): the same labels as the crossing count plus the
    // per-edge sum. Many queries in a few cells: points packed in small
    // cubes beside the boundary curve, each cube's asked several times.
    std::mt19937 rng(31);
    std::uniform_real_distribution<float> within(-0.01f, 0.01f);
    std::size_t inside = 0, asked = 0;
    for (const Case& c : casesAndSoup()) {
        const CapsWithSurface built(c.mesh);
        const std::vector<glm::vec3>& edges = built.edges;
        const ProjectedMesh& projected = built.projected;
        const BoundaryCaps& caps = built.caps;
        std::vector<glm::vec3> at;
        std::vector<bool> expected;
        const std::size_t edgeCount = edges.size() / 2, spots = 6;
        for (std::size_t k = 0; k < spots; ++k) {
            const std::size_t e = 2 * (k * edgeCount / spots);
            const glm::vec3 spot = 0.5f * (edges[e] + edges[e + 1]) + glm::vec3(0.0f, 0.0f, 0.03f * float(k % 3));
            for (int i = 0; i < 1000; ++i) {
                const glm::vec3 q = spot + glm::vec3(within(rng), within(rng), within(rng));
                at.push_back(q);
                expected.push_back(generalizedWindingInside(double(projected.winding(q)) + exactTerm(edges, q)));
            }
        }
        for (int round = 0; round < 6; ++round)
            for (std::size_t i = 0; i < at.size(); ++i) {
                ASSERT_EQ(caps.inside(at[i]), expected[i])
                    << c.name << " round " << round << " at " << at[i].x << " " << at[i].y << " " << at[i].z;
                inside += expected[i];
                ++asked;
            }
    }
    EXPECT_GT(inside, asked / 20); // labels of both kinds
    EXPECT_LT(inside, asked - asked / 20);
}

TEST(CapsTree, ColumnSweepsLabelEveryCellAsThePerEdgeSum) {
    // Both ways of the exact grid sweep, forced: cell by cell (decide and
    // reach) and by brackets over each column's cut of the chain tree
    // (chords and far fans, edges near the column). The reference: each
    // cell's crossing count plus the per-edge sum at its centre. A soup of
    // loose triangles joins the cases (many small loops close together).
    std::vector<Case> all = cases();
    all.push_back({"soup", solids::looseTriangles(60, 0.3f, 13)});
    for (const Case& c : all) {
        const std::vector<glm::vec3> edges = boundaryEdges(MeshView(c.mesh));
        const ProjectedMesh projected(MeshView(c.mesh), Axis::Z);
        Box box{glm::vec3(-1.3f), glm::vec3(1.3f)};
        const Grid grid = cubicGrid(box, 40);
        const std::size_t count = std::size_t(grid.dims.x) * grid.dims.y * grid.dims.z;
        std::vector<std::uint8_t> expected(count);
        std::size_t inside = 0;
        for (std::uint32_t i = 0; i < grid.dims.x; ++i)
            for (std::uint32_t j = 0; j < grid.dims.y; ++j)
                for (std::uint32_t k = 0; k < grid.dims.z; ++k) {
                    const glm::vec3 p = grid.cellCentre(i, j, k);
                    const double value = double(projected.winding(p)) + exactTerm(edges, p);
                    inside += expected[grid.index(i, j, k)] = generalizedWindingInside(value) ? 1 : 0;
                }
        EXPECT_GT(inside, 50u) << c.name; // labels of both kinds
        for (const SweepWay way : {SweepWay::CellByCell, SweepWay::Brackets, SweepWay::Timed}) {
            std::vector<std::uint8_t> cells(count, 7);
            sweepExact(projected, edges, grid, cells.data(), {Rule::GeneralizedWinding, 2}, way);
            std::size_t differ = 0;
            for (std::size_t k = 0; k < count; ++k) differ += cells[k] != expected[k];
            EXPECT_EQ(differ, 0u) << c.name << " way " << int(way);
        }
    }
}

// An open cylinder along z (radius 0.5, z in [-0.5, 0.5]): side walls, a
// bottom disk, no lid. Baked along z its walls run along the columns: the
// columns inside the wall cross the bottom and those outside cross nothing,
// so above the bottom they count differently with no crossing anywhere near.
TriangleMesh openCylinder(int segments) {
    TriangleMesh m;
    m.positions.push_back({0.0f, 0.0f, -0.5f});
    for (int k = 0; k < segments; ++k) {
        const double phi = 2.0 * kPi * k / segments;
        const float x = float(0.5 * std::cos(phi)), y = float(0.5 * std::sin(phi));
        m.positions.push_back({x, y, -0.5f});
        m.positions.push_back({x, y, 0.5f});
    }
    const auto bottom = [&](int k) { return std::uint32_t(1 + 2 * (k % segments)); };
    const auto top = [&](int k) { return std::uint32_t(2 + 2 * (k % segments)); };
    for (int k = 0; k < segments; ++k) {
        m.triangles.push_back({0u, bottom(k + 1), bottom(k)});
        m.triangles.push_back({bottom(k), bottom(k + 1), top(k + 1)});
        m.triangles.push_back({bottom(k), top(k + 1), top(k)});
    }
    return m;
}

// The sprite cases of the next test: each seen along its axis.
struct SpriteCase {
    std::string name;
    TriangleMesh mesh;
    Axis axis;
};

std::vector<SpriteCase> spriteCases() {
    // A box without its floor, seen along z: its walls lie on the texture's
    // edges, so the cells along them reach past the texture, and its rim's
    // sweep runs up them. A point just beyond a wall counts 0 and has B at
    // itself, where the columns inside (the floor's cap in front: 1) would
    // put it inside: its cell's closed count does not answer for it.
    const TriangleMesh openBox =
        solids::without(solids::box({-0.5f, -0.5f, -0.5f}, {0.5f, 0.5f, 0.5f}).mesh,
                        [](const glm::vec3& centroid) { return centroid.z < -0.49f; });
    return {
        {"box open below, walls on the texture's edges", openBox, Axis::Z},
        {"open cylinder along its walls", openCylinder(48), Axis::Z},
        {"open cylinder across", openCylinder(48), Axis::X},
        {"cup, one large opening", cases()[0].mesh, Axis::Z},
        {"finned shell", finnedShell(16, 32), Axis::Y},
    };
}

// Points in, beside, in front of and behind a sprite's box, close to the
// walls of a cylinder or box (where columns either side count
// differently) and to the boundary curve.
std::vector<glm::vec3> spritePoints(const Sprite& baked, std::mt19937& rng) {
    std::uniform_real_distribution<float> u(-1.0f, 1.0f), angle(0.0f, 6.2831853f), height(-0.7f, 0.7f);
    std::normal_distribution<float> near(0.0f, 0.01f);
    const Box box = baked.grid.box;
    const glm::vec3 mid = 0.5f * (box.lo + box.hi), half = 0.5f * (box.hi - box.lo);
    std::vector<glm::vec3> at;
    for (int k = 0; k < 6000; ++k) // the box and 80% more each way: past the grid's margin
        at.push_back(mid + 1.8f * half * glm::vec3(u(rng), u(rng), u(rng)));
    for (int k = 0; k < 3000; ++k) { // beside a cylinder's wall
        const float phi = angle(rng), r = 0.5f + near(rng);
        at.push_back({r * std::cos(phi), r * std::sin(phi), height(rng)});
    }
    for (int k = 0; k < 3000; ++k) { // just beyond a box's wall (and just inside it)
        const float across = 0.5f + 3.0f * near(rng), along = 0.9f * u(rng) * 0.5f;
        const int wall = k % 4;
        const float x = wall < 2 ? (wall == 0 ? across : -across) : along;
        const float y = wall < 2 ? along : (wall == 2 ? across : -across);
        at.push_back({x, y, height(rng)});
    }
    for (std::size_t e = 0; e + 1 < baked.boundaryEdges.size(); e += 2)
        for (int k = 0; k < 4; ++k)
            at.push_back(0.5f * (baked.boundaryEdges[e] + baked.boundaryEdges[e + 1]) +
                         glm::vec3(near(rng), near(rng), near(rng)) * 3.0f);
    return at;
}

TEST(CapsTree, SpriteCellsWhereEveryColumnCountsAlikeLabelAsThePerEdgeSum) {
    // A sprite's caps know its columns, not its triangles: a cell clear of
    // the boundary's sweep, none of whose columns has a crossing within its
    // depths and all of which count alike (0 where the cell reaches beside
    // the texture), gets the range of the whole winding number, that count
    // plus B's range, and answers without reading a column; in the sweep,
    // where the caps keep out of a cell and every column's count plus the
    // caps' crossings in it are alike, that sum less w_caps's range. Labels by the
    // caps equal those by the per-edge sum (BoundaryEvaluation::Exact) on
    // spritePoints(), the cells found on one thread and on all; and on the
    // sprite placed in the world by a rotation, scale and translation.
    std::mt19937 rng(41);
    for (const SpriteCase& c : spriteCases())
        for (const std::uint32_t resolution : {40u, 96u}) {
            BakeOptions o;
            o.resolution = resolution;
            o.axis = c.axis;
            const Sprite baked = bakeCpu(c.mesh, o);
            ASSERT_EQ(baked.status, SolidStatus::Open) << c.name;
            const std::vector<glm::vec3> at = spritePoints(baked, rng);
            std::vector<std::uint8_t> expected(at.size()), labels(at.size());
            classify(baked, {at.data(), at.size()}, expected.data(),
                     {Rule::GeneralizedWinding, 1}, {QueryLayout::Auto, BoundaryEvaluation::Exact});
            std::size_t inside = 0;
            for (const std::uint8_t l : expected) inside += l;
            EXPECT_GT(inside, at.size() / 50) << c.name; // labels of both kinds
            EXPECT_LT(inside, at.size() - at.size() / 50) << c.name;
            for (const unsigned threads : {1u, 0u}) {
                // Every label checked; which cells answered alone (by their
                // range, or the closed surface's count in the boundary's
                // sweep) is a matter of speed, reported by vds_gwn_bench.
                classify(baked, {at.data(), at.size()}, labels.data(), // its caps built for the call
                         {Rule::GeneralizedWinding, threads}, {QueryLayout::Auto, BoundaryEvaluation::Caps});
                for (std::size_t k = 0; k < at.size(); ++k)
                    ASSERT_EQ(labels[k], expected[k]) << c.name << " at " << resolution << ", " << threads
                                                      << " threads: " << at[k].x << " " << at[k].y << " " << at[k].z;
            }
            // Placed in the world: the points come through the placement,
            // the cells stay in the bake's coordinates.
            Sprite placed = baked;
            const glm::mat4 model = glm::translate(glm::mat4(1.0f), glm::vec3(3.0f, -1.0f, 0.5f)) *
                                    glm::rotate(glm::mat4(1.0f), 0.7f, glm::normalize(glm::vec3(1.0f, 2.0f, 0.5f))) *
                                    glm::scale(glm::mat4(1.0f), glm::vec3(2.0f));
            placed.transform(model);
            std::vector<glm::vec3> world(at.size());
            for (std::size_t k = 0; k < at.size(); ++k) world[k] = glm::vec3(model * glm::vec4(at[k], 1.0f));
            classify(placed, {world.data(), world.size()}, expected.data(),
                     {Rule::GeneralizedWinding, 1}, {QueryLayout::Auto, BoundaryEvaluation::Exact});
            classify(placed, {world.data(), world.size()}, labels.data(),
                     {Rule::GeneralizedWinding, 0}, {QueryLayout::Auto, BoundaryEvaluation::Caps});
            for (std::size_t k = 0; k < at.size(); ++k)
                ASSERT_EQ(labels[k], expected[k]) << c.name << " placed, at " << resolution << ": " << at[k].x << " "
                                                  << at[k].y << " " << at[k].z;
        }
}

} // namespace
} // namespace vds::detail
