// Method::CertifiedGpu equals the exact classifier on every point: uniform
// points and the hard cases (vertices, edge midpoints, face centroids, the
// box's boundary, texel borders, points off the surface by a hair, non-finite
// points), for every rule, from host arrays and from GL buffers, in batches;
// meshes the bands cannot certify go exact whole. And certified.glsl's
// vdsContainsCertain, computed into an image over a slice, is never wrong
// where it answers and unsure only near the surface.
#include <vds/gl/certified.h>

#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <vds/error.h>
#include <vds/exact.h>
#include <vds/gl/objects.h>
#include <vds/gl/shader.h>

#include "../support/gl_fixture.h"
#include "points.h"
#include "solids.h"

namespace vds {
namespace {

using test::GlTest;

constexpr Rule kRules[] = {Rule::Parity, Rule::Winding, Rule::GeneralizedWinding};

// Uniform points in the box grown by 10%, then the hard cases.
std::vector<glm::vec3> hardPoints(const TriangleMesh& mesh, const SpriteGrid& grid, std::uint32_t seed) {
    std::vector<glm::vec3> points = test::randomPoints(meshBounds(mesh), 3000, 0.1f, seed);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f), hair(-1e-5f, 1e-5f);
    for (const glm::vec3& v : mesh.positions) points.push_back(v);
    for (const glm::uvec3& t : mesh.triangles) {
        const glm::vec3 a = mesh.positions[t[0]], b = mesh.positions[t[1]], c = mesh.positions[t[2]];
        points.push_back(0.5f * (a + b));           // on an edge
        points.push_back((a + b + c) / 3.0f);       // on the face
        const glm::vec3 n = glm::cross(b - a, c - a);
        if (glm::length(n) > 0.0f) points.push_back((a + b + c) / 3.0f + hair(rng) * glm::normalize(n));
    }
    const Box box = meshBounds(mesh);
    const glm::ivec3 p = axisPermutation(grid.axis);
    for (int k = 0; k < 600; ++k) {
        glm::vec3 q = box.lo + glm::vec3(unit(rng), unit(rng), unit(rng)) * (box.hi - box.lo);
        q[k % 3] = (k / 3) % 2 ? box.hi[k % 3] : box.lo[k % 3]; // on the box's boundary
        points.push_back(q);
        // Grazing a texel's border in s, in t, or both (a texel corner).
        glm::vec3 g = box.lo + glm::vec3(unit(rng), unit(rng), unit(rng)) * (box.hi - box.lo);
        if (k % 3 != 1) g[p.x] = grid.box.lo[p.x] + float(rng() % (grid.width + 1)) * grid.texelSize;
        if (k % 3 != 0) g[p.y] = grid.box.lo[p.y] + float(rng() % (grid.height + 1)) * grid.texelSize;
        points.push_back(g);
    }
    const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
    const glm::vec3 c = 0.5f * (box.lo + box.hi);
    for (const glm::vec3 q : {glm::vec3(nan, c.y, c.z), glm::vec3(c.x, nan, c.z), glm::vec3(c.x, c.y, nan),
                              glm::vec3(inf, c.y, c.z), glm::vec3(c.x, -inf, c.z), glm::vec3(1e30f, -1e30f, 0)})
        points.push_back(q);
    return points;
}

std::vector<std::uint8_t> exactLabels(const ExactClassifier& exact, const std::vector<glm::vec3>& points, Rule rule) {
    std::vector<std::uint8_t> labels(points.size());
    exact.classify(points, labels.data(), {rule, 2});
    return labels;
}

std::size_t differences(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b) {
    std::size_t n = 0;
    for (std::size_t k = 0; k < a.size(); ++k) n += a[k] != b[k];
    return n;
}

// A closed mesh like the benchmarks' scanned ones: a knotted tube, and a
// box and a torus beside it in one mesh.
TriangleMesh benchLike() {
    const auto knot = solids::torusKnot({0, 0, 0}, 1.0f, 2, 3, 0.25f, 90, 12);
    return solids::merge(solids::merge(knot.mesh, solids::box({1.8f, -0.4f, -0.4f}, {2.4f, 0.4f, 0.9f}).mesh),
                         solids::torus({-1.9f, 0.3f, 0.2f}, 0.5f, 0.2f, 24).mesh);
}

// The labels of `points` from and to host arrays.
std::vector<std::uint8_t> classifyOnHost(const GpuCertifiedClassifier& c, const std::vector<glm::vec3>& points,
                                         const ClassifyOptions& options) {
    std::vector<std::uint8_t> labels(points.size(), 7);
    c.classify(points, labels.data(), options);
    return labels;
}

// The labels of `points` in GL buffers (4-byte words, the tail's padding kept).
std::vector<std::uint8_t> classifyOnGl(const GpuCertifiedClassifier& c, const std::vector<glm::vec3>& points,
                                       const ClassifyOptions& options) {
    Buffer pointBuffer = Buffer::create(), labelBuffer = Buffer::create();
    const std::size_t bytes = (points.size() + 3) / 4 * 4;
    glNamedBufferStorage(pointBuffer.id(), GLsizeiptr(points.size() * 12), points.data(), 0);
    const std::vector<std::uint8_t> junk(bytes, 0x5a);
    glNamedBufferStorage(labelBuffer.id(), GLsizeiptr(bytes), junk.data(), 0);
    c.classify(pointBuffer.id(), points.size(), labelBuffer.id(), options);
    std::vector<std::uint8_t> labels(bytes);
    glGetNamedBufferSubData(labelBuffer.id(), 0, GLsizeiptr(bytes), labels.data());
    for (std::size_t k = points.size(); k < bytes; ++k) EXPECT_EQ(labels[k], 0) << "the tail word's padding";
    labels.resize(points.size());
    return labels;
}

class CertifiedGpu : public GlTest {};

TEST_F(CertifiedGpu, EqualsTheExactClassifierOnEveryPointFromHostArraysAndGlBuffers) {
    const auto torus = solids::torus({0.1f, 0.2f, 0.3f}, 1.0f, 0.35f, 32);
    const auto box = solids::box({-1.0f, -0.5f, 0.25f}, {1.5f, 0.75f, 1.0f});
    const auto sphere = solids::sphere({0.5f, -0.25f, 2.0f}, 1.5f, 32);
    const auto two = solids::overlappingBoxes({-1, -1, -1}, {0.5f, 0.5f, 0.5f}, {-0.5f, -0.3f, -0.2f}, {1, 1, 1});
    const TriangleMesh bench = benchLike();
    std::uint32_t seed = 1;
    for (const TriangleMesh* mesh : {&torus.mesh, &box.mesh, &sphere.mesh, &two.mesh, &bench})
        for (Axis axis : {Axis::Z, Axis::X}) {
            CertifiedOptions o;
            o.axis = axis;
            o.resolution = 40;
            // Batches of 1024 points: the hard cases span several.
            const GpuCertifiedClassifier c(gl(), *mesh, o, 1024);
            ASSERT_TRUE(c.certified().certifies());
            const std::vector<glm::vec3> points = hardPoints(*mesh, c.certified().grid(), seed++);
            for (Rule rule : kRules) {
                SCOPED_TRACE(mesh->name + " " + toString(axis) + " " + enumName(rule));
                const std::vector<std::uint8_t> truth = exactLabels(c.certified().exact(), points, rule);
                ClassifyStats stats;
                ClassifyOptions options{rule, 2};
                options.stats = &stats;
                EXPECT_EQ(differences(classifyOnHost(c, points, options), truth), 0u);
                EXPECT_EQ(stats.certain + stats.exact, points.size());
                EXPECT_GT(stats.certain, 1500u) << "the bands answer most of the 3000 uniform points";
                EXPECT_GT(stats.exact, 0u) << "the hard cases need the exact path";
                ClassifyStats glStats;
                options.stats = &glStats;
                EXPECT_EQ(differences(classifyOnGl(c, points, options), truth), 0u);
                EXPECT_EQ(glStats.certain, stats.certain);
                EXPECT_EQ(glStats.exact, stats.exact);
            }
        }
}

TEST_F(CertifiedGpu, MoreUnsurePointsThanTheReadBackHoldsAreReadWhole) {
    // A batch of 65536 points reads back its first 1024 unsure records from
    // the mapped buffer and the rest from the list: points on the surface
    // (vertices, edge midpoints, centroids), nearly all unsure, fill one
    // batch with many more than that.
    const auto sphere = solids::sphere({0.1f, 0.0f, -0.2f}, 1.0f, 64);
    CertifiedOptions o;
    o.resolution = 48;
    const GpuCertifiedClassifier c(gl(), sphere.mesh, o, 65536);
    std::vector<glm::vec3> points = sphere.mesh.positions;
    for (const glm::uvec3& t : sphere.mesh.triangles) {
        const glm::vec3 a = sphere.mesh.positions[t[0]], b = sphere.mesh.positions[t[1]], d = sphere.mesh.positions[t[2]];
        points.push_back(0.5f * (a + b));
        points.push_back((a + b + d) / 3.0f);
    }
    ASSERT_LT(points.size(), 65536u) << "one batch";
    const std::vector<std::uint8_t> truth = exactLabels(c.certified().exact(), points, Rule::Parity);
    ClassifyStats stats;
    ClassifyOptions options{Rule::Parity, 2};
    options.stats = &stats;
    EXPECT_EQ(differences(classifyOnHost(c, points, options), truth), 0u);
    EXPECT_GT(stats.exact, 4096u) << "more unsure points than the read-back holds";
    EXPECT_EQ(differences(classifyOnGl(c, points, options), truth), 0u);
}

TEST_F(CertifiedGpu, UncertifiedMeshesAndRulesGoExactWhole) {
    // An open cup: the generalized winding number is answered, every point exact.
    const TriangleMesh cup = solids::sphereCup();
    CertifiedOptions o;
    o.resolution = 24;
    const GpuCertifiedClassifier c(gl(), cup, o, 1024);
    EXPECT_FALSE(c.certified().certifies());
    EXPECT_EQ(c.bands().certifiedRules(), 0);
    const std::vector<glm::vec3> points = hardPoints(cup, c.certified().grid(), 9);
    for (Rule rule : kRules) {
        SCOPED_TRACE(enumName(rule));
        const std::vector<std::uint8_t> truth = exactLabels(c.certified().exact(), points, rule);
        ClassifyStats stats;
        ClassifyOptions options{rule, 2};
        options.stats = &stats;
        EXPECT_EQ(differences(classifyOnHost(c, points, options), truth), 0u);
        EXPECT_EQ(stats.exact, points.size());
        EXPECT_EQ(differences(classifyOnGl(c, points, options), truth), 0u);
    }
    // The centre of the cup is inside by the generalized winding number.
    EXPECT_TRUE(c.contains({0.0f, 0.0f, 0.0f}, Rule::GeneralizedWinding));
}

TEST_F(CertifiedGpu, EmptyBatchesAndStridedPoints) {
    const auto torus = solids::torus({0, 0, 0}, 1.0f, 0.4f, 24);
    CertifiedOptions o;
    o.resolution = 64;
    const GpuCertifiedClassifier c(gl(), torus.mesh, o);
    ClassifyStats stats{5, 5};
    ClassifyOptions options;
    options.stats = &stats;
    c.classify(std::vector<glm::vec3>{}, nullptr, options);
    EXPECT_EQ(stats.certain + stats.exact, 0u);
    // Points inside 16-byte records.
    const std::vector<glm::vec3> points = test::randomPoints(meshBounds(torus.mesh), 999, 0.1f, 3);
    std::vector<glm::vec4> records(points.size());
    for (std::size_t k = 0; k < points.size(); ++k) records[k] = glm::vec4(points[k], -1.0f);
    std::vector<std::uint8_t> labels(points.size());
    c.classify(PointsView::floats(&records[0].x, records.size(), sizeof(glm::vec4)), labels.data());
    EXPECT_EQ(differences(labels, exactLabels(c.certified().exact(), points, Rule::Parity)), 0u);
}

// vdsContainsCertain into an r32i image: pixel (x, y) answers the point
// the host put at points[y * size + x], a slice z = const through the torus.
std::vector<int> certainImage(const GpuCertifiedBands& bands, const std::vector<glm::vec3>& points, int size) {
    const std::string source = R"(
layout(local_size_x = 8, local_size_y = 8) in;
#define VDS_CERTIFIED_OFFSETS_BINDING 1
#define VDS_CERTIFIED_BANDS_BINDING 2
#include "vds/certified.glsl"
layout(std430, binding = 0) readonly buffer Slice { float xyz[]; };
layout(r32i, binding = 0) uniform writeonly iimage2D u_image;
uniform VdsCertified u_certified;
void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(u_image);
    if (pixel.x >= size.x || pixel.y >= size.y) return;
    uint k = 3u * uint(pixel.y * size.x + pixel.x);
    vec3 p = vec3(xyz[k], xyz[k + 1u], xyz[k + 2u]);
    imageStore(u_image, pixel, ivec4(vdsContainsCertain(u_certified, p, VDS_RULE_PARITY)));
}
)";
    const Program program = buildProgram({{GL_COMPUTE_SHADER, "slice.comp", source}});
    Texture image = Texture::create(GL_TEXTURE_2D);
    glTextureStorage2D(image.id(), 1, GL_R32I, size, size);
    Buffer slice = Buffer::create();
    glNamedBufferStorage(slice.id(), GLsizeiptr(points.size() * 12), points.data(), 0);
    glUseProgram(program.id());
    bands.setUniforms(program.id(), "u_certified", 1, 2);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, slice.id());
    glBindImageTexture(0, image.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32I);
    glDispatchCompute(GLuint(size + 7) / 8, GLuint(size + 7) / 8, 1);
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
    std::vector<int> pixels(std::size_t(size) * size);
    glGetTextureImage(image.id(), 0, GL_RED_INTEGER, GL_INT, GLsizei(pixels.size() * sizeof(int)), pixels.data());
    for (GLuint b = 0; b < 3; ++b) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, b, 0);
    glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32I);
    glUseProgram(0);
    return pixels;
}

TEST_F(CertifiedGpu, ContainsCertainInAnImageIsExactWhereItAnswersAndUnsureOnlyNearTheSurface) {
    const auto torus = solids::torus({0.1f, 0.2f, 0.3f}, 1.0f, 0.35f, 48);
    CertifiedOptions o;
    o.resolution = 48; // coarse: a texel is 0.056, the image's pixels 0.021
    const CertifiedClassifier certified(torus.mesh, o);
    const GpuCertifiedBands bands(certified);
    constexpr int kImage = 128;
    const Box box = meshBounds(torus.mesh);
    std::vector<glm::vec3> points;
    for (int y = 0; y < kImage; ++y)
        for (int x = 0; x < kImage; ++x) // the slice z = 0.4 across the box, by pixel centres
            points.push_back({box.lo.x + (float(x) + 0.5f) / kImage * (box.hi.x - box.lo.x),
                              box.lo.y + (float(y) + 0.5f) / kImage * (box.hi.y - box.lo.y), 0.4f});
    const std::vector<int> pixels = certainImage(bands, points, kImage);
    const float texel = certified.grid().texelSize;
    std::size_t unsure = 0, wrong = 0, unsureFar = 0, inside = 0;
    for (std::size_t k = 0; k < points.size(); ++k) {
        const bool truth = certified.exact().contains(points[k], Rule::Parity);
        inside += truth;
        if (pixels[k] == -1) {
            ++unsure;
            // A band holds the planes of the triangles over a footprint: it reaches
            // about a texel's diagonal past the mesh (1.12 texels measured here).
            unsureFar += std::abs(torus.distance(points[k])) > 2.0f * texel + torus.tessellationError;
            continue;
        }
        ASSERT_TRUE(pixels[k] == 0 || pixels[k] == 1) << pixels[k];
        wrong += (pixels[k] == 1) != truth;
    }
    EXPECT_EQ(wrong, 0u);
    EXPECT_EQ(unsureFar, 0u);
    EXPECT_GT(inside, points.size() / 10) << "the slice passes through the solid";
    EXPECT_GT(unsure, 0u);
    EXPECT_LT(unsure, points.size() / 4) << "unsure pixels are a minority";
}

TEST_F(CertifiedGpu, BandsRefuseAnotherContext) {
    const auto box = solids::box({0, 0, 0}, {1, 1, 1});
    CertifiedOptions o;
    o.resolution = 8;
    const CertifiedClassifier certified(box.mesh, o);
    const GpuCertifiedBands bands(certified);
    EXPECT_EQ(bands.certifiedRules(), 7); // closed and oriented: every rule
    {
        const GlContext other; // made current
        EXPECT_THROW(bands.setUniforms(0, "u_certified", 1, 2), GlError);
    }
    gl().makeCurrent();
}

} // namespace
} // namespace vds
