// Surface samples: on their triangles, spread by area, the same from the same
// seed as a plain re-reading of the documented recipe (a sequential SplitMix64,
// a linear search for the triangle), and refused on a mesh with no area.
#include <vds/sample.h>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <cstring>

#include <vds/error.h>

namespace vds {
namespace {

/// Two triangles in the plane z = 1, of areas 1/2 and 3/2 (ratio 1:3), sharing no vertex.
TriangleMesh twoTriangles() {
    TriangleMesh m;
    m.positions = {{0, 0, 1}, {1, 0, 1}, {0, 1, 1}, {2, 0, 1}, {5, 0, 1}, {2, 1, 1}};
    m.triangles = {{0, 1, 2}, {3, 4, 5}};
    return m;
}

/// A tilted tetrahedron with one degenerate triangle among its faces.
TriangleMesh tiltedTetrahedron() {
    TriangleMesh m;
    m.positions = {{0.1f, -0.3f, 0.2f}, {1.7f, 0.4f, -0.5f}, {0.3f, 1.9f, 0.6f}, {0.2f, 0.5f, 2.1f}};
    m.triangles = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}, {0, 0, 1}};
    return m;
}

/// The recipe of <vds/sample.h> read plainly: SplitMix64 stepped one draw at a time.
struct SequentialSplitMix {
    std::uint64_t state;
    double next() {
        std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return double((z ^ (z >> 31)) >> 11) / 9007199254740992.0;
    }
};

TEST(SampleSurface, GeneratorIsSplitMix64) {
    // SplitMix64's first output from seed 0 as published with the algorithm (Vigna's splitmix64.c).
    EXPECT_EQ(sampleUniform(0, 0), double(0xE220A8397B1DCDAFull >> 11) / 9007199254740992.0);
    SequentialSplitMix g{12345};
    for (std::uint64_t i = 0; i < 1000; ++i) ASSERT_EQ(sampleUniform(12345, i), g.next()) << i;
}

TEST(SampleSurface, EqualsThePlainRecipeBitForBit) {
    const TriangleMesh m = tiltedTetrahedron();
    const std::size_t n = 2000;
    const SurfaceSamples s = sampleSurface(m, n, 77);
    SequentialSplitMix g{77};
    std::vector<double> areas;
    double total = 0.0;
    for (const glm::uvec3& t : m.triangles) {
        const glm::dvec3 a(m.positions[t.x]), b(m.positions[t.y]), c(m.positions[t.z]);
        const glm::dvec3 e1 = b - a, e2 = c - a;
        const double x = e1.y * e2.z - e1.z * e2.y, y = e1.z * e2.x - e1.x * e2.z, z = e1.x * e2.y - e1.y * e2.x;
        areas.push_back(std::sqrt(x * x + y * y + z * z));
    }
    for (double a : areas) total += a;
    for (std::size_t k = 0; k < n; ++k) {
        const double u0 = g.next(), u1 = g.next(), u2 = g.next();
        std::size_t t = 0;
        for (double sum = areas[0]; !(sum > u0 * total); sum += areas[++t]) {}
        ASSERT_EQ(s.triangles[k], t) << k;
        const glm::uvec3 tri = m.triangles[t];
        const double r = std::sqrt(u1);
        for (int axis = 0; axis < 3; ++axis) {
            const double p = (1.0 - r) * double(m.positions[tri.x][axis]) + r * (1.0 - u2) * double(m.positions[tri.y][axis]) +
                             r * u2 * double(m.positions[tri.z][axis]);
            ASSERT_EQ(std::memcmp(&p, &s.points[3 * k + axis], sizeof p), 0) << k << " " << axis;
        }
    }
}

TEST(SampleSurface, PointsLieOnTheirTriangles) {
    const TriangleMesh m = tiltedTetrahedron();
    const SurfaceSamples s = sampleSurface(m, 5000, 3);
    for (std::size_t k = 0; k < s.triangles.size(); ++k) {
        ASSERT_NE(s.triangles[k], 4u) << "the degenerate triangle is never chosen";
        const glm::uvec3 t = m.triangles[s.triangles[k]];
        const glm::dvec3 a(m.positions[t.x]), b(m.positions[t.y]), c(m.positions[t.z]);
        const glm::dvec3 p(s.points[3 * k], s.points[3 * k + 1], s.points[3 * k + 2]);
        // Barycentric coordinates by the normal equations of p - a = v (b - a) + w (c - a).
        const glm::dvec3 e1 = b - a, e2 = c - a, d = p - a;
        const double d11 = glm::dot(e1, e1), d12 = glm::dot(e1, e2), d22 = glm::dot(e2, e2);
        const double det = d11 * d22 - d12 * d12;
        const double v = (d22 * glm::dot(d, e1) - d12 * glm::dot(d, e2)) / det;
        const double w = (d11 * glm::dot(d, e2) - d12 * glm::dot(d, e1)) / det;
        EXPECT_GE(v, -1e-12);
        EXPECT_GE(w, -1e-12);
        EXPECT_LE(v + w, 1 + 1e-12);
        EXPECT_NEAR(glm::length(a + v * e1 + w * e2 - p), 0.0, 1e-12) << "off the triangle's plane";
    }
}

TEST(SampleSurface, CountsFollowTheAreas) {
    const std::size_t n = 100000;
    const SurfaceSamples s = sampleSurface(twoTriangles(), n, 2024);
    std::size_t first = 0, below = 0;
    for (std::size_t k = 0; k < n; ++k) {
        first += s.triangles[k] == 0;
        // Uniform on a triangle: half of the big one's area lies below y = 1 - 1/sqrt(2).
        if (s.triangles[k] == 1) below += s.points[3 * k + 1] < 1.0 - std::sqrt(0.5);
    }
    // Binomial(n, 1/4): within 5 standard deviations.
    const double sigma = std::sqrt(n * 0.25 * 0.75);
    EXPECT_NEAR(double(first), 0.25 * n, 5 * sigma);
    const double second = double(n - first);
    EXPECT_NEAR(double(below), 0.5 * second, 5 * std::sqrt(second * 0.25));
}

TEST(SampleSurface, SameSeedSamePointsOtherSeedOthers) {
    const TriangleMesh m = tiltedTetrahedron();
    const SurfaceSamples a = sampleSurface(m, 100, 9), b = sampleSurface(m, 100, 9), c = sampleSurface(m, 100, 10);
    EXPECT_EQ(a.points, b.points);
    EXPECT_EQ(a.triangles, b.triangles);
    std::size_t same = 0;
    for (std::size_t k = 0; k < a.points.size(); ++k) same += a.points[k] == c.points[k];
    EXPECT_EQ(same, 0u);
    // The null triangles pointer: the same points.
    std::vector<double> points(300);
    sampleSurface(m, 100, 9, points.data(), nullptr);
    EXPECT_EQ(points, a.points);
}

// The values Python's test asserts too (python/tests/test_sample.py): one
// recipe on both sides of the binding.
TEST(SampleSurface, KnownPointsSharedWithPython) {
    const SurfaceSamples s = sampleSurface(tiltedTetrahedron(), 3, 42);
    const std::uint32_t triangles[] = {2, 1, 0};
    const double points[] = {0x1.210730563865ep+0,  0x1.b00e4a24476eap-1, 0x1.b63bcf1cdfd22p-4,
                             0x1.43ae44d21b358p-3,  -0x1.2c2732174c6f8p-3, 0x1.01e692c656970p-1,
                             0x1.68d999753556ep-1, 0x1.36576a13dfeddp+0, 0x1.c96261a93ced2p-3};
    for (int k = 0; k < 3; ++k) EXPECT_EQ(s.triangles[k], triangles[k]);
    for (int i = 0; i < 9; ++i) EXPECT_EQ(s.points[i], points[i]) << i;
}

TEST(SampleSurface, MeshWithoutAreaIsRefused) {
    TriangleMesh flat;
    flat.positions = {{0, 0, 0}, {1, 1, 1}, {2, 2, 2}};
    flat.triangles = {{0, 1, 2}, {0, 0, 1}};
    try {
        sampleSurface(flat, 10, 0);
        FAIL() << "no throw";
    } catch (const InvalidMesh& e) {
        EXPECT_STREQ(e.what(), "no area to sample: the mesh's triangles (2) all have zero area");
    }
    EXPECT_THROW(sampleSurface(TriangleMesh{}, 10, 0), InvalidMesh);
    TriangleMesh bad = twoTriangles();
    bad.triangles[1].z = 6;
    EXPECT_THROW(sampleSurface(bad, 10, 0), InvalidMesh);
    bad.triangles[1].z = 5;
    bad.positions[4].x = NAN;
    EXPECT_THROW(sampleSurface(bad, 10, 0), InvalidMesh);
}

} // namespace
} // namespace vds
