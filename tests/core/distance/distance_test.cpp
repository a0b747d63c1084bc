// Exact signed distances (<vds/distance.h>) against a brute-force double-
// precision reference by another formula (the distance to the plane where
// the projection falls inside, else the nearest of the three segments),
// over every triangle, on closed and open meshes built in code; the sign
// against the same rule's exact classifier on every point; grids against
// the per-point distance of their cell centres; and bad input.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include <vds/distance.h>
#include <vds/error.h>

#include "points.h"
#include "solids.h"

namespace vds {
namespace {

double segmentDistance(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b) {
    const glm::dvec3 ab = b - a;
    const double len2 = glm::dot(ab, ab);
    const double t = len2 > 0.0 ? std::clamp(glm::dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
    return glm::length(p - (a + t * ab));
}

/// Distance to one triangle: the plane's where p projects inside (all three
/// edge normals' sides agree), else the nearest edge's.
double triangleDistance(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
    const glm::dvec3 n = glm::cross(b - a, c - a);
    const double n2 = glm::dot(n, n);
    const double edges = std::min({segmentDistance(p, a, b), segmentDistance(p, b, c), segmentDistance(p, c, a)});
    if (!(n2 > 0.0)) return edges;
    const bool inside = glm::dot(glm::cross(b - a, p - a), n) >= 0.0 && glm::dot(glm::cross(c - b, p - b), n) >= 0.0 &&
                        glm::dot(glm::cross(a - c, p - c), n) >= 0.0;
    return inside ? std::min(edges, std::abs(glm::dot(p - a, n)) / std::sqrt(n2)) : edges;
}

double bruteForce(const TriangleMesh& mesh, const glm::vec3& point) {
    double best = std::numeric_limits<double>::infinity();
    for (const glm::uvec3& t : mesh.triangles)
        best = std::min(best, triangleDistance(glm::dvec3(point), glm::dvec3(mesh.positions[t.x]),
                                               glm::dvec3(mesh.positions[t.y]), glm::dvec3(mesh.positions[t.z])));
    return best;
}

double diagonal(const TriangleMesh& mesh) {
    const Box b = meshBounds(mesh);
    return glm::length(glm::dvec3(b.hi) - glm::dvec3(b.lo));
}

/// Random points in and around the box, the corners, edge midpoints and
/// points just off every few triangles (both sides): far, near and on.
std::vector<glm::vec3> samplePoints(const TriangleMesh& mesh, std::size_t randomCount) {
    std::vector<glm::vec3> points = test::randomPoints(meshBounds(mesh), randomCount, 0.3f, 7);
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> offset(-0.02f, 0.02f);
    for (std::size_t t = 0; t < mesh.triangles.size(); t += 1 + mesh.triangles.size() / 400) {
        const glm::uvec3 v = mesh.triangles[t];
        const glm::vec3 a = mesh.positions[v.x], b = mesh.positions[v.y], c = mesh.positions[v.z];
        const glm::vec3 centroid = (a + b + c) / 3.0f;
        points.insert(points.end(), {a, (a + b) * 0.5f, centroid, centroid + glm::vec3(offset(rng), offset(rng), offset(rng))});
    }
    return points;
}

struct Case {
    std::string name;
    TriangleMesh mesh;
    Rule rule;
};

std::vector<Case> cases() {
    using namespace solids;
    return {
        {"sphere", sphere(glm::vec3(0.1f, -0.2f, 0.3f), 1.0f, 48).mesh, Rule::Parity},
        {"torus", torus(glm::vec3(0.0f), 1.0f, 0.3f, 40).mesh, Rule::Winding},
        {"shell", shell(glm::vec3(0.0f), 1.0f, 0.6f, 32).mesh, Rule::Parity},
        {"overlapping boxes", overlappingBoxes(glm::vec3(0.0f), glm::vec3(1.0f), glm::vec3(0.5f), glm::vec3(1.5f)).mesh,
         Rule::Winding},
        {"boxes sharing an edge", boxesSharingAnEdge(glm::vec3(0.0f), 1.0f).mesh, Rule::Parity},
        {"knot", torusKnot(glm::vec3(0.0f), 1.0f, 2, 3, 0.2f, 120, 12).mesh, Rule::GeneralizedWinding},
        {"cup", sphereCup(), Rule::GeneralizedWinding},
        {"sphere with holes", sphereWithHoles(), Rule::GeneralizedWinding},
        {"overlapping shells", overlappingShells(), Rule::GeneralizedWinding},
        {"soup", looseTriangles(300, 0.3f, 5), Rule::GeneralizedWinding},
        {"bowl with disk", bowlWithDisk(), Rule::GeneralizedWinding},
    };
}

TEST(Distance, EqualsBruteForceAndSignEqualsTheExactClassifier) {
    for (const Case& c : cases()) {
        SCOPED_TRACE(c.name);
        const SignedDistance distance(c.mesh, c.rule, c.name);
        const std::vector<glm::vec3> points = samplePoints(c.mesh, 1500);
        std::vector<double> d(points.size());
        distance.distance(points, d.data(), DistanceOptions{2});
        std::vector<std::uint8_t> inside(points.size());
        ClassifyOptions classify;
        classify.rule = c.rule;
        distance.classifier().classify(points, inside.data(), classify);
        const double tolerance = 1e-6 * diagonal(c.mesh);
        std::size_t insideCount = 0;
        for (std::size_t k = 0; k < points.size(); ++k) {
            ASSERT_NEAR(std::abs(d[k]), bruteForce(c.mesh, points[k]), tolerance) << "point " << k;
            ASSERT_EQ(std::signbit(d[k]), inside[k] != 0) << "point " << k;
            insideCount += inside[k];
        }
        EXPECT_GT(insideCount, 0u); // both signs were exercised
        EXPECT_LT(insideCount, points.size());
    }
}

TEST(Distance, IsWithinTheHeadersBoundOfTheReference) {
    // The header's bound, 2^-45 L: far tighter than the 1e-6 of the diagonal.
    const TriangleMesh mesh = solids::torusKnot(glm::vec3(3.0f), 2.0f, 2, 3, 0.4f, 100, 10).mesh;
    const SignedDistance distance(mesh, Rule::Winding);
    for (const glm::vec3& p : samplePoints(mesh, 500)) {
        const double bound = std::ldexp(1.0, -45) * 6.0;
        ASSERT_NEAR(std::abs(distance.distance(p)), bruteForce(mesh, p), bound);
    }
}

TEST(Distance, SlabBoundsHoldJustOffATiltedPatchFarFromTheOrigin) {
    // A finely cut tilted square at 1000 units, its nodes' slabs about as
    // thin as float allows, and points a few float steps off it: the float
    // product n . p is off by about their distance, so a slab bound without
    // its rounding slack and outward rounding rules out the triangle nearest
    // the point and answers a farther one. One far triangle gives the mesh a
    // volume.
    TriangleMesh mesh;
    const std::uint32_t n = 40;
    const glm::vec3 origin(1000.0f, 1100.0f, 900.0f), u(0.8f, 0.36f, -0.48f), v(-0.6f, 0.48f, -0.64f);
    for (std::uint32_t i = 0; i <= n; ++i)
        for (std::uint32_t j = 0; j <= n; ++j) mesh.positions.push_back(origin + u * (float(i) / n) + v * (float(j) / n));
    for (std::uint32_t i = 0; i < n; ++i)
        for (std::uint32_t j = 0; j < n; ++j) {
            const std::uint32_t a = i * (n + 1) + j;
            mesh.triangles.emplace_back(a, a + n + 1, a + 1);
            mesh.triangles.emplace_back(a + 1, a + n + 1, a + n + 2);
        }
    const std::uint32_t far = std::uint32_t(mesh.positions.size());
    mesh.positions.insert(mesh.positions.end(), {origin - glm::vec3(50.0f), origin - glm::vec3(50.0f, 49.0f, 50.0f),
                                                 origin - glm::vec3(50.0f, 50.0f, 49.0f)});
    mesh.triangles.emplace_back(far, far + 1, far + 2);
    const SignedDistance distance(mesh, Rule::GeneralizedWinding);
    const glm::vec3 normal = glm::normalize(glm::cross(u, v));
    std::vector<glm::vec3> points;
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> inSquare(0.02f, 0.98f), off(-4e-4f, 4e-4f);
    for (int k = 0; k < 4000; ++k) points.push_back(origin + u * inSquare(rng) + v * inSquare(rng) + normal * off(rng));
    std::vector<double> d(points.size());
    distance.unsignedDistance(points, d.data(), DistanceOptions{2});
    for (std::size_t k = 0; k < points.size(); ++k) ASSERT_NEAR(d[k], bruteForce(mesh, points[k]), 1e-9) << "point " << k;
}

TEST(Distance, TriangleBoundsHoldNearCornersAndEdgesOfNeedlesFarFromTheOrigin) {
    // A curved, sheared strip at 1000 units cut into obtuse needles (10:1),
    // and points a few float steps off its corners and edge midpoints, where
    // the nearest triangle and its neighbours are nearly equidistant. A
    // triangle's float lower bound (face and edge planes, TriangleBound)
    // without the rounding slack on its edge planes, or with an edge plane
    // turned inward, turns away the triangle nearest such a point and
    // answers a farther one.
    TriangleMesh mesh;
    const std::uint32_t n = 24;
    const glm::vec3 origin(1000.0f, -700.0f, 500.0f);
    for (std::uint32_t i = 0; i <= n; ++i)
        for (std::uint32_t j = 0; j <= n; ++j) {
            const float x = float(i) / n, y = float(j) / n;
            mesh.positions.push_back(origin + glm::vec3(x + 0.7f * y, 0.1f * y, 0.2f * (x - 0.5f) * (x - 0.5f) + 0.01f * y * y));
        }
    for (std::uint32_t i = 0; i < n; ++i)
        for (std::uint32_t j = 0; j < n; ++j) {
            const std::uint32_t a = i * (n + 1) + j;
            mesh.triangles.emplace_back(a, a + n + 1, a + 1);
            mesh.triangles.emplace_back(a + 1, a + n + 1, a + n + 2);
        }
    const std::uint32_t far = std::uint32_t(mesh.positions.size()); // gives the mesh a volume
    mesh.positions.insert(mesh.positions.end(), {origin - glm::vec3(5.0f), origin - glm::vec3(5.0f, 4.0f, 5.0f),
                                                 origin - glm::vec3(5.0f, 5.0f, 4.0f)});
    mesh.triangles.emplace_back(far, far + 1, far + 2);
    std::vector<glm::vec3> points;
    std::mt19937 rng(21);
    std::uniform_real_distribution<float> off(-3e-4f, 3e-4f);
    for (const glm::uvec3& t : mesh.triangles)
        for (const glm::vec3& at : {mesh.positions[t.x], (mesh.positions[t.x] + mesh.positions[t.y]) * 0.5f,
                                    (mesh.positions[t.y] + mesh.positions[t.z]) * 0.5f,
                                    (mesh.positions[t.z] + mesh.positions[t.x]) * 0.5f})
            points.push_back(at + glm::vec3(off(rng), off(rng), off(rng)));
    const SignedDistance distance(mesh, Rule::GeneralizedWinding);
    std::vector<double> d(points.size());
    distance.unsignedDistance(points, d.data(), DistanceOptions{2});
    for (std::size_t k = 0; k < points.size(); ++k) ASSERT_NEAR(d[k], bruteForce(mesh, points[k]), 1e-9) << "point " << k;
}

/// A batch is searched in Morton order, each point from its predecessor's
/// nearest triangle: the answers are still those of one point a call, bit
/// for bit, on any number of threads (closest points: the same triangle too).
TEST(Distance, BatchesEqualOnePointACall) {
    for (const Case& c : cases()) {
        SCOPED_TRACE(c.name);
        const SignedDistance distance(c.mesh, c.rule, c.name);
        const std::vector<glm::vec3> points = samplePoints(c.mesh, 500);
        for (const unsigned threads : {1u, 2u}) {
            std::vector<double> unsignedBatch(points.size()), signedBatch(points.size());
            std::vector<ClosestPoint> closestBatch(points.size());
            distance.unsignedDistance(points, unsignedBatch.data(), DistanceOptions{threads});
            distance.distance(points, signedBatch.data(), DistanceOptions{threads});
            distance.closestPoints(points, closestBatch.data(), DistanceOptions{threads});
            for (std::size_t k = 0; k < points.size(); ++k) {
                double one = 0.0;
                distance.unsignedDistance(PointsView(&points[k], 1), &one, DistanceOptions{1});
                ASSERT_EQ(unsignedBatch[k], one) << "point " << k;
                ASSERT_EQ(signedBatch[k], distance.distance(points[k])) << "point " << k;
                const ClosestPoint c1 = distance.closest(points[k]);
                ASSERT_EQ(closestBatch[k].triangle, c1.triangle) << "point " << k;
                ASSERT_EQ(closestBatch[k].distance, c1.distance) << "point " << k;
            }
        }
    }
}

TEST(Distance, ClosestPointsLieOnTheirTriangleAtTheDistance) {
    const TriangleMesh mesh = solids::sphereWithHoles();
    const SignedDistance distance(mesh, Rule::GeneralizedWinding);
    const std::vector<glm::vec3> points = samplePoints(mesh, 500);
    std::vector<ClosestPoint> closest(points.size());
    distance.closestPoints(points, closest.data());
    std::vector<double> unsignedD(points.size());
    distance.unsignedDistance(points, unsignedD.data());
    for (std::size_t k = 0; k < points.size(); ++k) {
        const ClosestPoint& c = closest[k];
        ASSERT_LT(c.triangle, mesh.triangles.size());
        const glm::uvec3 t = mesh.triangles[c.triangle];
        const glm::dvec3 a(mesh.positions[t.x]), b(mesh.positions[t.y]), cc(mesh.positions[t.z]);
        EXPECT_NEAR(triangleDistance(c.point, a, b, cc), 0.0, 1e-12);
        EXPECT_NEAR(glm::length(glm::dvec3(points[k]) - c.point), c.distance, 1e-12);
        EXPECT_EQ(c.distance, unsignedD[k]);
        EXPECT_NEAR(c.distance, bruteForce(mesh, points[k]), 1e-12);
        if (c.feature == Feature::Vertex) {
            EXPECT_EQ(c.point, glm::dvec3(mesh.positions[t[c.index]]));
        }
    }
}

TEST(Distance, NamesTheFeature) {
    const glm::dvec3 a(0.0), b(1.0, 0.0, 0.0), c(0.0, 1.0, 0.0);
    const ClosestPoint face = closestPointOnTriangle(glm::dvec3(0.25, 0.25, 1.0), a, b, c);
    EXPECT_EQ(face.feature, Feature::Face);
    EXPECT_EQ(face.point, glm::dvec3(0.25, 0.25, 0.0));
    EXPECT_EQ(face.distance, 1.0);
    const ClosestPoint edge = closestPointOnTriangle(glm::dvec3(1.0, 1.0, 0.0), a, b, c);
    EXPECT_EQ(edge.feature, Feature::Edge);
    EXPECT_EQ(edge.index, 1);
    EXPECT_EQ(edge.point, glm::dvec3(0.5, 0.5, 0.0));
    const ClosestPoint vertex = closestPointOnTriangle(glm::dvec3(-1.0, -2.0, 3.0), a, b, c);
    EXPECT_EQ(vertex.feature, Feature::Vertex);
    EXPECT_EQ(vertex.index, 0);
    // A degenerate triangle (a segment) answers as its edges.
    const ClosestPoint segment = closestPointOnTriangle(glm::dvec3(0.5, 1.0, 0.0), a, b, b);
    EXPECT_EQ(segment.point, glm::dvec3(0.5, 0.0, 0.0));
    EXPECT_EQ(segment.distance, 1.0);
}

TEST(Distance, DoublePointsAreRoundedToFloatLikeTheClassifier) {
    const TriangleMesh mesh = solids::sphere(glm::vec3(0.0f), 1.0f, 32).mesh;
    const SignedDistance distance(mesh, Rule::Parity);
    const std::vector<double> xyz = {0.1, 0.2, 0.3, 1.0 / 3.0, 2.0, -0.7, 0.0, 0.0, 0.999999999};
    std::vector<double> fromDoubles(3), fromFloats(3);
    distance.distance(PointsView::doubles(xyz.data(), 3), fromDoubles.data());
    std::vector<glm::vec3> rounded;
    for (int k = 0; k < 3; ++k) rounded.emplace_back(float(xyz[3 * k]), float(xyz[3 * k + 1]), float(xyz[3 * k + 2]));
    distance.distance(rounded, fromFloats.data());
    EXPECT_EQ(fromDoubles, fromFloats);
    EXPECT_LT(fromFloats[0], 0.0);
    EXPECT_GT(fromFloats[1], 0.0);
}

TEST(Distance, MaxDistanceClampsFarPoints) {
    const TriangleMesh mesh = solids::box(glm::vec3(0.0f), glm::vec3(1.0f)).mesh;
    const SignedDistance distance(mesh, Rule::Parity);
    const std::vector<glm::vec3> points = {glm::vec3(0.5f), glm::vec3(0.5f, 0.5f, 1.1f), glm::vec3(3.0f, 0.5f, 0.5f)};
    std::vector<double> d(3);
    DistanceOptions options;
    options.maxDistance = 0.25;
    distance.distance(points, d.data(), options);
    EXPECT_EQ(d[0], -0.25); // 0.5 from the faces, inside
    EXPECT_NEAR(d[1], 0.1, 1e-7);
    EXPECT_EQ(d[2], 0.25);
    std::vector<ClosestPoint> c(3);
    distance.closestPoints(points, c.data(), options);
    EXPECT_EQ(c[2].triangle, kNoTriangle);
    EXPECT_EQ(c[2].distance, 0.25);
}

/// The torus and the open cup scaled by `scale` (exact: a power of two
/// scales every float exactly, and the points with them).
TriangleMesh scaled(TriangleMesh mesh, float scale) {
    for (glm::vec3& p : mesh.positions) p *= scale;
    return mesh;
}

// Distances at any finite scale: squared in float, 1e30 overflowed and
// every distance was wrong (66 times too large); now the hierarchy holds the
// mesh scaled by a power of two and scales back exactly. Points far from a
// unit mesh (1e30 away) are answered too.
TEST(Distance, IsExactAtAnyScale) {
    for (const float scale : {0x1p-100f, 0x1p-40f, 0x1p40f, 0x1p100f, 0x1p125f}) {
        for (const Case& c : {cases()[1], cases()[6]}) {
            SCOPED_TRACE(c.name + " at " + std::to_string(scale));
            const TriangleMesh mesh = scaled(c.mesh, scale);
            const SignedDistance distance(mesh, c.rule, c.name);
            std::vector<glm::vec3> points = samplePoints(mesh, 300);
            std::vector<double> d(points.size());
            std::vector<ClosestPoint> closest(points.size());
            distance.distance(points, d.data(), DistanceOptions{2});
            distance.closestPoints(points, closest.data(), DistanceOptions{2});
            std::vector<std::uint8_t> inside(points.size());
            ClassifyOptions classify;
            classify.rule = c.rule;
            distance.classifier().classify(points, inside.data(), classify);
            for (std::size_t k = 0; k < points.size(); ++k) {
                const double reference = bruteForce(mesh, points[k]);
                ASSERT_NEAR(std::abs(d[k]), reference, 1e-12 * double(scale)) << "point " << k;
                ASSERT_NEAR(closest[k].distance, reference, 1e-12 * double(scale)) << "point " << k;
                ASSERT_EQ(std::signbit(d[k]), inside[k] != 0) << "point " << k;
            }
        }
    }
    // A grid at 2^100: its cells are its centres' distances, full and banded.
    const TriangleMesh big = scaled(cases()[1].mesh, 0x1p100f);
    const SignedDistance bigDistance(big, Rule::Winding);
    Grid grid;
    grid.box = meshBounds(big);
    grid.dims = glm::uvec3(9, 11, 7);
    std::vector<float> full(grid.cellCount()), band(grid.cellCount());
    bigDistance.grid(grid, full.data(), DistanceGridOptions{2, 0.0});
    const double width = 0.2 * 0x1p100;
    bigDistance.grid(grid, band.data(), DistanceGridOptions{2, width});
    for (std::uint32_t i = 0; i < grid.dims.x; ++i)
        for (std::uint32_t j = 0; j < grid.dims.y; ++j)
            for (std::uint32_t k = 0; k < grid.dims.z; ++k) {
                const double d = bigDistance.distance(grid.cellCentre(i, j, k));
                ASSERT_EQ(full[grid.index(i, j, k)], float(d));
                ASSERT_EQ(band[grid.index(i, j, k)], std::abs(d) >= width ? float(std::copysign(width, d)) : float(d));
            }
    // Far from a unit mesh: every triangle nearly as far, each measured in double.
    const TriangleMesh mesh = cases()[1].mesh;
    const SignedDistance distance(mesh, Rule::Winding);
    for (const glm::vec3& p : {glm::vec3(1e30f, -2e29f, 3e29f), glm::vec3(0.0f, 0.0f, -3e38f), glm::vec3(7e20f)})
        ASSERT_NEAR(distance.distance(p), bruteForce(mesh, p), 1e-12 * double(glm::length(glm::dvec3(p))));
}

TEST(Distance, GridEqualsThePointDistancesOfItsCellCentres) {
    for (const Case& c : {cases()[2], cases()[7]}) {
        SCOPED_TRACE(c.name);
        const SignedDistance distance(c.mesh, c.rule);
        Grid grid;
        grid.box = meshBounds(c.mesh);
        grid.box.lo -= glm::vec3(0.2f);
        grid.box.hi += glm::vec3(0.1f);
        grid.dims = glm::uvec3(19, 23, 29);
        std::vector<float> full(grid.cellCount()), band(grid.cellCount());
        distance.grid(grid, full.data(), DistanceGridOptions{2, 0.0});
        const double width = 0.15;
        distance.grid(grid, band.data(), DistanceGridOptions{2, width});
        std::vector<glm::vec3> centres;
        for (std::uint32_t i = 0; i < grid.dims.x; ++i)
            for (std::uint32_t j = 0; j < grid.dims.y; ++j)
                for (std::uint32_t k = 0; k < grid.dims.z; ++k) centres.push_back(grid.cellCentre(i, j, k));
        std::vector<double> d(centres.size());
        distance.distance(centres, d.data());
        std::size_t clamped = 0;
        for (std::size_t n = 0; n < d.size(); ++n) {
            ASSERT_EQ(full[n], float(d[n])) << "cell " << n;
            const bool far = std::abs(d[n]) >= width;
            ASSERT_EQ(band[n], far ? float(std::signbit(d[n]) ? -width : width) : float(d[n])) << "cell " << n;
            clamped += far;
        }
        EXPECT_GT(clamped, 0u);
        EXPECT_LT(clamped, d.size());
    }
}

TEST(Distance, GridCellsFarInsideARoundSolidSearchTheWholeHierarchy) {
    // Near the centre of a fine sphere every triangle is nearly as near as
    // the nearest: the bricks' lists grow past their cap, and those cells
    // search the hierarchy from their neighbour's triangle instead.
    const TriangleMesh mesh = solids::sphere(glm::vec3(0.0f), 1.0f, 200).mesh;
    const SignedDistance distance(mesh, Rule::Parity);
    Grid grid;
    grid.box = {glm::vec3(-0.3f), glm::vec3(0.3f)};
    grid.dims = glm::uvec3(9, 8, 7);
    std::vector<float> cells(grid.cellCount());
    distance.grid(grid, cells.data(), DistanceGridOptions{2, 0.0});
    for (std::uint32_t i = 0; i < grid.dims.x; ++i)
        for (std::uint32_t j = 0; j < grid.dims.y; ++j)
            for (std::uint32_t k = 0; k < grid.dims.z; ++k) {
                const glm::vec3 p = grid.cellCentre(i, j, k);
                ASSERT_EQ(cells[grid.index(i, j, k)], float(distance.distance(p)));
                ASSERT_NEAR(cells[grid.index(i, j, k)], -bruteForce(mesh, p), 1e-6);
            }
}

TEST(Distance, PropagatedGridIsExactNearTheSurfaceAndWithinItsBoundBeyond) {
    // FarCells::Propagated against the exact grid (itself held to the point
    // distances above) on closed and open meshes, every cell: the same sign,
    // never below the exact distance, exact within a cell diagonal of
    // the surface and within 4 diagonals beyond (the header's bound).
    for (const Case& c : {cases()[0], cases()[2], cases()[5], cases()[6], cases()[9]}) {
        SCOPED_TRACE(c.name);
        const SignedDistance distance(c.mesh, c.rule);
        Grid grid;
        grid.box = meshBounds(c.mesh);
        grid.box.lo -= glm::vec3(0.3f);
        grid.box.hi += glm::vec3(0.2f);
        grid.dims = glm::uvec3(30, 27, 33);
        std::vector<float> exact(grid.cellCount()), propagated(grid.cellCount());
        distance.grid(grid, exact.data(), DistanceGridOptions{2, 0.0});
        DistanceGridOptions options{2, 0.0};
        options.far = FarCells::Propagated;
        distance.grid(grid, propagated.data(), options);
        const double diagonal = glm::length(glm::dvec3(grid.box.hi - grid.box.lo) / glm::dvec3(grid.dims));
        std::size_t near = 0, differ = 0;
        for (std::size_t n = 0; n < exact.size(); ++n) {
            ASSERT_EQ(std::signbit(propagated[n]), std::signbit(exact[n])) << "cell " << n;
            const double d = std::abs(double(exact[n])), e = std::abs(double(propagated[n])) - d;
            if (d < diagonal) {
                ASSERT_EQ(propagated[n], exact[n]) << "cell " << n;
                ++near;
            }
            ASSERT_GE(e, -1e-6 * d) << "cell " << n;
            ASSERT_LE(e, 4.0 * diagonal + 1e-6 * d) << "cell " << n;
            differ += e != 0.0;
        }
        EXPECT_GT(near, 0u); // both sides of the band were exercised
        EXPECT_LT(near, exact.size());
        RecordProperty(c.name + " cells differing", std::to_string(differ));
    }
}

TEST(Distance, BadInputGetsOneClearError) {
    const TriangleMesh sphere = solids::sphere(glm::vec3(0.0f), 1.0f, 16).mesh;
    const SignedDistance distance(sphere, Rule::Parity);
    std::vector<glm::vec3> points = {glm::vec3(0.0f), glm::vec3(std::nanf(""), 0.0f, 0.0f)};
    std::vector<double> out = {7.0, 7.0};
    try {
        distance.distance(points, out.data());
        FAIL() << "a NaN point was answered";
    } catch (const InvalidArgument& e) {
        EXPECT_NE(std::string(e.what()).find("point 1 is not finite"), std::string::npos) << e.what();
    }
    EXPECT_EQ(out, (std::vector<double>{7.0, 7.0})); // nothing written
    EXPECT_THROW(distance.distance(points[1]), InvalidArgument);
    EXPECT_THROW(distance.unsignedDistance(PointsView(points), out.data(), DistanceOptions{0, -1.0}), InvalidArgument);

    Grid grid;
    grid.box = meshBounds(sphere);
    grid.dims = glm::uvec3(4);
    std::vector<float> cells(grid.cellCount());
    for (double band : {-1.0, std::nan(""), std::numeric_limits<double>::infinity()})
        EXPECT_THROW(distance.grid(grid, cells.data(), DistanceGridOptions{1, band}), InvalidArgument) << band;

    EXPECT_THROW(SignedDistance(TriangleMesh{}, Rule::Parity), InvalidMesh);
    TriangleMesh flat;
    flat.positions = {glm::vec3(0.0f), glm::vec3(1.0f, 0.0f, 0.0f), glm::vec3(0.0f, 1.0f, 0.0f)};
    flat.triangles = {glm::uvec3(0, 1, 2)};
    // A sheet bounds no volume: distances to it, its closest points, no sign.
    const SignedDistance sheet(flat, Rule::GeneralizedWinding);
    EXPECT_FALSE(sheet.hasSign());
    const glm::vec3 above(0.25f, 0.25f, 2.0f), beside(-3.0f, 0.0f, 4.0f);
    double d[2];
    const glm::vec3 both[2] = {above, beside};
    sheet.unsignedDistance(PointsView(both, 2), d);
    EXPECT_EQ(d[0], 2.0);
    EXPECT_EQ(d[1], 5.0); // to the corner (0, 0, 0)
    EXPECT_EQ(sheet.closest(above).point, glm::dvec3(0.25, 0.25, 0.0));
    EXPECT_THROW(sheet.distance(above), InvalidMesh);
    std::vector<float> sheetCells(8);
    EXPECT_THROW(sheet.grid(Grid{{glm::vec3(-1.0f), glm::vec3(1.0f)}, glm::uvec3(2)}, sheetCells.data()), InvalidMesh);
    EXPECT_THROW(sheet.classifier(), InvalidMesh);
    // An open mesh by parity: answered like the exact classifier (crossings as for a surface), not refused.
    const TriangleMesh cup = solids::sphereCup();
    const SignedDistance byParity(cup, Rule::Parity);
    EXPECT_EQ(std::signbit(byParity.distance(glm::vec3(0.0f))), byParity.classifier().contains(glm::vec3(0.0f)));
    TriangleMesh badIndex = sphere;
    badIndex.triangles[3].y = 100000;
    EXPECT_THROW(SignedDistance(badIndex, Rule::Parity), InvalidMesh);
}

} // namespace
} // namespace vds
