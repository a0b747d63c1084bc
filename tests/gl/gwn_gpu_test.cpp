// The generalized winding number of open meshes on the GPU (vpt.glsl's
// boundary term, GpuClassifier with Rule::GeneralizedWinding) against the
// CPU: `Sprite::classify` with the exact per-edge sum, and a double-precision
// reference (tests/support/gwn_reference.h: column count + solid angles at the texel's
// centre point).
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <GL/gl.h>
#include <GL/glext.h>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <vds/all.h>
#include <vds/bake.h>
#include <vds/error.h>
#include <vds/exact.h>
#include <vds/gl/bake.h>
#include <vds/gl/sprite.h>
#include <vds/gl/shader.h>
#include "solids.h"

#include "../support/gl_fixture.h"
#include "../support/gwn_reference.h"
#include "points.h"

namespace vds {
namespace {

using test::referenceGwn;

struct OpenCase {
    const char* name;
    TriangleMesh mesh;
};

std::vector<OpenCase> openCases() {
    return {{"cup", solids::sphereCup()},
            {"sphere with holes", solids::sphereWithHoles()},
            {"overlapping shells", solids::overlappingShells()}};
}

class GwnGpuTest : public test::GlTest {
protected:
    Sprite bakeAt(const TriangleMesh& mesh, Axis axis, std::uint32_t resolution) {
        BakeOptions o;
        o.resolution = resolution;
        o.axis = axis;
        return bake(gl(), mesh, o);
    }
};

TEST_F(GwnGpuTest, ClassifierMatchesTheCpuOnOpenMeshes) {
    GpuClassifier classifier(gl());
    for (const OpenCase& c : openCases())
        for (Axis axis : {Axis::Z, Axis::X}) {
            Sprite sprite = bakeAt(c.mesh, axis, 64);
            ASSERT_FALSE(sprite.boundaryEdges.empty()) << c.name;
            auto points = test::randomPoints(sprite.grid.box, 20000, 0.1f, 7);
            for (int placed = 0; placed < 2; ++placed) {
                if (placed) { // move the sprite without re-baking; the points move along
                    const glm::mat4 model = glm::scale(
                        glm::rotate(glm::translate(glm::mat4(1.0f), {0.3f, -2.0f, 0.7f}), 0.7f, glm::normalize(glm::vec3(1, 2, 3))),
                        glm::vec3(1.5f, 0.5f, 2.0f));
                    sprite.transform(model);
                    for (auto& q : points) q = glm::vec3(model * glm::vec4(q, 1.0f));
                }
                ClassifyOptions options;
                options.rule = Rule::GeneralizedWinding;
                        std::vector<std::uint8_t> cpu(points.size());
                classify(sprite, {points.data(), points.size()}, cpu.data(), options, {QueryLayout::Auto, BoundaryEvaluation::Exact});
                for (GpuSpriteParts parts : {GpuSpriteParts::ColumnsOnly, GpuSpriteParts::TextureOnly}) {
                    const GpuSprite gpu(sprite, parts);
                    EXPECT_EQ(gpu.boundary().edgeCount(), sprite.boundaryEdges.size() / 2);
                    // The holes' loops get a tree: far nodes are taken by
                    // their chords and fans' expansion in the shader.
                    if (std::string(c.name) == "sphere with holes") {
                        EXPECT_GT(gpu.boundary().nodeCount(), 3u);
                    }
                    std::vector<std::uint8_t> labels(points.size(), 7);
                    classifier.classify(gpu, {points.data(), points.size()}, labels.data(), {Rule::GeneralizedWinding});
                    std::size_t nearHalf = 0, elsewhere = 0, inside = 0;
                    for (std::size_t k = 0; k < points.size(); ++k) {
                        inside += cpu[k];
                        const double w = referenceGwn(sprite, points[k]);
                        if (cpu[k] == labels[k]) continue;
                        if (std::fabs(w - 0.5) <= 1e-4) ++nearHalf;
                        else ++elsewhere;
                    }
                    const std::string what = std::string(c.name) + ", axis " + toString(axis) +
                                             (placed ? ", placed" : "") +
                                             (parts == GpuSpriteParts::TextureOnly ? ", texture" : ", columns");
                    EXPECT_EQ(elsewhere, 0u) << what;
                    EXPECT_LE(nearHalf, 3u) << what;
                    EXPECT_GT(inside, points.size() / 20) << what; // not vacuous
                }
            }
        }
}

TEST_F(GwnGpuTest, AnswersOutsideTheBoxBeyondAnOpening) {
    // Just above a bowl's rim, with a disk hung inside, the GWN exceeds 1/2
    // though the points lie outside the sprite's box: behind it along y,
    // beside it along z (and beside it along both, past the rim: outside).
    // The classifier's columns and texture paths answer there as the exact
    // classifier does.
    const TriangleMesh mesh = solids::bowlWithDisk();
    std::mt19937 rng(9);
    std::uniform_real_distribution<float> u(-0.4f, 0.4f), above(0.02f, 0.1f), far(1.2f, 2.0f);
    std::vector<glm::vec3> points;
    for (int k = 0; k < 500; ++k) points.push_back({u(rng), above(rng), u(rng)});
    for (int k = 0; k < 100; ++k) points.push_back({far(rng), u(rng), u(rng)});
    const ExactClassifier exact(mesh, Axis::Z);
    std::size_t inside = 0;
    for (const glm::vec3& p : points) inside += exact.contains(p, Rule::GeneralizedWinding);
    EXPECT_GT(inside, 250u);
    GpuClassifier classifier(gl());
    for (Axis axis : {Axis::Y, Axis::Z}) {
        const Sprite sprite = bakeAt(mesh, axis, 64);
        ASSERT_GT(sprite.grid.toTexture(points[0])[axis == Axis::Y ? 2 : 1], 1.0f) << toString(axis);
        for (GpuSpriteParts parts : {GpuSpriteParts::ColumnsOnly, GpuSpriteParts::TextureOnly}) {
            const GpuSprite gpu(sprite, parts);
            std::vector<std::uint8_t> labels(points.size(), 7);
            classifier.classify(gpu, {points.data(), points.size()}, labels.data(), {Rule::GeneralizedWinding});
            std::size_t wrong = 0;
            for (std::size_t k = 0; k < points.size(); ++k)
                wrong += (labels[k] != 0) != exact.contains(points[k], Rule::GeneralizedWinding);
            EXPECT_EQ(wrong, 0u) << toString(axis) << (parts == GpuSpriteParts::TextureOnly ? ", texture" : ", columns");
        }
    }
}

// Points in each of the 26 regions around the box (beside it along s or t,
// in front of it, behind it, and at its corners), on its faces' planes, and
// not finite: every program (rule x form) labels them as the CPU does, the
// generalized winding rule up to its float error near 1/2.
std::vector<glm::vec3> aroundTheBox(const Box& box, std::size_t perRegion) {
    std::mt19937 rng(17);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const glm::vec3 size = box.hi - box.lo;
    std::vector<glm::vec3> points;
    for (int region = 0; region < 27; ++region) {
        const int where[3] = {region % 3, region / 3 % 3, region / 9}; // 0 below, 1 within, 2 above
        for (std::size_t n = 0; n < perRegion; ++n) {
            glm::vec3 p;
            for (int c = 0; c < 3; ++c) {
                const float f = where[c] == 1 ? u(rng) : where[c] == 0 ? -0.6f * u(rng) : 1.0f + 0.6f * u(rng);
                p[c] = box.lo[c] + f * size[c];
            }
            points.push_back(p);
            const int c = int(n % 3); // the same point moved onto a face's plane
            p[c] = n % 2 ? box.lo[c] : box.hi[c];
            points.push_back(p);
        }
    }
    const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
    points.push_back({inf, 0.0f, 0.0f});
    points.push_back({0.0f, -inf, 0.0f});
    points.push_back({0.0f, 0.0f, nan});
    return points;
}

// The boundary term alone at q itself (solid angles along the view axis
// over 4 pi, in double).
double termAt(const Sprite& sprite, const glm::dvec3& q) {
    glm::dvec3 axis(0.0);
    axis[axisPermutation(sprite.grid.axis).z] = 1.0;
    double sum = 0.0;
    for (std::size_t k = 0; k + 1 < sprite.boundaryEdges.size(); k += 2) {
        const glm::dvec3 u = glm::dvec3(sprite.boundaryEdges[k]) - q, v = glm::dvec3(sprite.boundaryEdges[k + 1]) - q;
        const double lu = glm::length(u), lv = glm::length(v);
        sum += 2.0 * std::atan2(glm::dot(axis, glm::cross(u, v)),
                                lu * lv + glm::dot(axis, u) * lv + glm::dot(axis, v) * lu + glm::dot(u, v));
    }
    return sum / (4.0 * 3.14159265358979323846);
}

// Whether the term jumps by about 1 within 1e-5 of the box's size of p:
// p lies, within float error, on the sweep of a boundary edge along the view
// axis (here: on the bowl's rim plane, a face of its box, which holds the
// rim's sweeps), where float and double may take either side (vpt.glsl).
bool onASweep(const Sprite& sprite, const glm::vec3& p) {
    for (int c = 0; c < 3; ++c) {
        glm::dvec3 lo(p), hi(p);
        const double d = 1e-5 * (double(sprite.grid.box.hi[c]) - double(sprite.grid.box.lo[c]));
        lo[c] -= d;
        hi[c] += d;
        if (std::fabs(termAt(sprite, hi) - termAt(sprite, lo)) > 0.25) return true;
    }
    return false;
}

TEST_F(GwnGpuTest, EveryProgramMatchesTheCpuBesideInFrontAndBehindTheBox) {
    const auto torus = solids::torus({0.2f, -0.1f, 0.0f}, 1.0f, 0.4f, 48);
    GpuClassifier classifier(gl());
    for (const OpenCase& c : {OpenCase{"torus", torus.mesh}, OpenCase{"bowl with disk", solids::bowlWithDisk()},
                              OpenCase{"sphere with holes", solids::sphereWithHoles()}})
        for (Axis axis : {Axis::Z, Axis::X}) {
            const Sprite sprite = bakeAt(c.mesh, axis, 48);
            const auto points = aroundTheBox(sprite.grid.box, 150);
            for (Rule rule : {Rule::Parity, Rule::Winding, Rule::GeneralizedWinding}) {
                ClassifyOptions options;
                options.rule = rule;
                std::vector<std::uint8_t> cpu(points.size());
                classify(sprite, {points.data(), points.size()}, cpu.data(), options,
                         {QueryLayout::Auto, BoundaryEvaluation::Exact});
                for (GpuSpriteParts parts : {GpuSpriteParts::ColumnsOnly, GpuSpriteParts::TextureOnly}) {
                    const GpuSprite gpu(sprite, parts);
                    std::vector<std::uint8_t> labels(points.size(), 7);
                    classifier.classify(gpu, {points.data(), points.size()}, labels.data(), {rule});
                    std::size_t wrong = 0, inside = 0;
                    for (std::size_t k = 0; k < points.size(); ++k) {
                        inside += labels[k];
                        if (labels[k] == cpu[k]) continue;
                        // float against double: only where the value is within its error of 1/2,
                        // or on the sweep of a boundary edge (where the term jumps by 1)
                        const bool tie = rule == Rule::GeneralizedWinding &&
                                         (std::fabs(referenceGwn(sprite, points[k]) - 0.5) <= 1e-4 ||
                                          onASweep(sprite, points[k]));
                        wrong += !tie;
                    }
                    const std::string what = std::string(c.name) + ", axis " + toString(axis) + ", " +
                                             toString(rule) + (parts == GpuSpriteParts::TextureOnly ? ", texture" : ", columns");
                    EXPECT_EQ(wrong, 0u) << what;
                    if (rule == Rule::GeneralizedWinding && c.name != std::string("torus")) {
                        EXPECT_GT(inside, 0u) << what; // open meshes: inside somewhere outside the box's columns
                    }
                }
            }
        }
}

TEST_F(GwnGpuTest, ReferenceMatchesTheCpuLabels) {
    // The test's own reference agrees with the library's CPU labels: so the
    // GPU is compared with an independent value, not the library with itself.
    const Sprite sprite = bakeAt(solids::sphereWithHoles(), Axis::Y, 48);
    const auto points = test::randomPoints(sprite.grid.box, 5000, 0.1f, 9);
    ClassifyOptions options;
    options.rule = Rule::GeneralizedWinding;
    std::vector<std::uint8_t> cpu(points.size());
    classify(sprite, {points.data(), points.size()}, cpu.data(), options, {QueryLayout::Auto, BoundaryEvaluation::Exact});
    std::size_t differ = 0, open = 0;
    for (std::size_t k = 0; k < points.size(); ++k) {
        const double w = referenceGwn(sprite, points[k]);
        const bool inside = std::isfinite(w) && w > 0.5;
        differ += inside != bool(cpu[k]) && std::fabs(w - 0.5) > 1e-9;
        open += std::isfinite(w) && std::fabs(w - std::round(w)) > 0.05; // the boundary term matters here
    }
    EXPECT_EQ(differ, 0u);
    EXPECT_GT(open, points.size() / 10);
}

TEST_F(GwnGpuTest, ClosedMeshReadsAsWinding) {
    const auto two = solids::overlappingBoxes({-1, -1, -1}, {0.3f, 0.3f, 0.3f}, {-0.3f, -0.3f, -0.3f}, {1, 1, 1});
    const Sprite sprite = bakeAt(two.mesh, Axis::Z, 48);
    ASSERT_TRUE(sprite.boundaryEdges.empty());
    const auto points = test::randomPoints(sprite.grid.box, 20000, 0.1f, 3);
    GpuClassifier classifier(gl());
    const GpuSprite gpu(sprite);
    EXPECT_EQ(gpu.boundary().edgeCount(), 0u);
    std::vector<std::uint8_t> winding(points.size()), gwn(points.size(), 7);
    classifier.classify(gpu, {points.data(), points.size()}, winding.data(), {Rule::Winding});
    classifier.classify(gpu, {points.data(), points.size()}, gwn.data(), {Rule::GeneralizedWinding});
    EXPECT_EQ(winding, gwn);
}

TEST_F(GwnGpuTest, UnknownBoundaryIsRefused) {
    Sprite sprite = bakeAt(solids::sphereCup(), Axis::Z, 32);
    sprite.boundaryEdges.clear();
    sprite.boundaryKnown = false; // as read from a version-1 file
    GpuClassifier classifier(gl());
    const GpuSprite gpu(sprite);
    const std::vector<glm::vec3> points{{0.0f, 0.0f, 0.0f}};
    std::vector<std::uint8_t> labels(1);
    EXPECT_THROW(classifier.classify(gpu, {points.data(), 1}, labels.data(), {Rule::GeneralizedWinding}), InvalidArgument);
    EXPECT_NO_THROW(classifier.classify(gpu, {points.data(), 1}, labels.data(), {Rule::Winding}));
}

TEST_F(GwnGpuTest, BakeToGpuCarriesTheBoundary) {
    const TriangleMesh cup = solids::sphereCup();
    BakeOptions o;
    o.resolution = 64;
    const Sprite host = bake(gl(), cup, o);
    const GpuBake baked = bakeToGpu(gl(), cup, o, GpuSpriteParts::ColumnsOnly);
    ASSERT_EQ(baked.sprite.boundary().edgeCount(), host.boundaryEdges.size() / 2);
    ASSERT_GT(baked.sprite.boundary().edgeCount(), 0u);
    const auto points = test::randomPoints(host.grid.box, 20000, 0.1f, 5);
    GpuClassifier classifier(gl());
    std::vector<std::uint8_t> fromBake(points.size()), fromHost(points.size(), 7);
    classifier.classify(baked.sprite, {points.data(), points.size()}, fromBake.data(), {Rule::GeneralizedWinding});
    classifier.classify(GpuSprite(host), {points.data(), points.size()}, fromHost.data(), {Rule::GeneralizedWinding});
    EXPECT_EQ(fromBake, fromHost); // the same columns, edges and float arithmetic
}

// The include in a vertex shader: vdsGeneralizedWinding's value and
// vdsContainsGeneralized's label (1 or 0) per point.
std::vector<glm::vec2> includeValues(const GpuSprite& gpu, const std::vector<glm::vec3>& points) {
    const std::string vs = R"(#define VDS_BOUNDARY_BINDING 1
#include "vds/vpt.glsl"
uniform sampler3D u_ldi;
uniform VdsPlacement u_placement;
uniform VdsBoundary u_boundary;
layout(location = 0) in vec3 a_point;
layout(std430, binding = 0) writeonly buffer Values { vec2 values[]; };
void main() {
    values[gl_VertexID] = vec2(vdsGeneralizedWinding(u_ldi, u_placement, u_boundary, a_point),
                               vdsContainsGeneralized(u_ldi, u_placement, u_boundary, a_point) ? 1.0 : 0.0);
    gl_Position = vec4(0.0);
}
)";
    const std::string fs = "out vec4 c; void main() { c = vec4(1.0); }\n";
    const Program program = buildProgram({{GL_VERTEX_SHADER, "gwn.vert", vs}, {GL_FRAGMENT_SHADER, "gwn.frag", fs}});
    Buffer pointBuffer = Buffer::create(), valueBuffer = Buffer::create();
    glNamedBufferStorage(pointBuffer.id(), GLsizeiptr(points.size() * 12), points.data(), 0);
    glNamedBufferStorage(valueBuffer.id(), GLsizeiptr(points.size() * 8), nullptr, 0);
    VertexArray vao = VertexArray::create();
    glVertexArrayVertexBuffer(vao.id(), 0, pointBuffer.id(), 0, 12);
    glVertexArrayAttribFormat(vao.id(), 0, 3, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(vao.id(), 0, 0);
    glEnableVertexArrayAttrib(vao.id(), 0);
    Framebuffer empty = Framebuffer::create();
    glNamedFramebufferParameteri(empty.id(), GL_FRAMEBUFFER_DEFAULT_WIDTH, 1);
    glNamedFramebufferParameteri(empty.id(), GL_FRAMEBUFFER_DEFAULT_HEIGHT, 1);
    glBindFramebuffer(GL_FRAMEBUFFER, empty.id());
    glUseProgram(program.id());
    gpu.setUniforms(program.id(), "u_ldi", "u_placement", 0);
    gpu.boundary().setUniforms(program.id(), "u_boundary", 1);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, valueBuffer.id());
    glEnable(GL_RASTERIZER_DISCARD);
    glBindVertexArray(vao.id());
    glDrawArrays(GL_POINTS, 0, GLsizei(points.size()));
    glDisable(GL_RASTERIZER_DISCARD);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<glm::vec2> values(points.size());
    glGetNamedBufferSubData(valueBuffer.id(), 0, GLsizeiptr(values.size() * 8), values.data());
    glBindVertexArray(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, 0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, 0);
    glUseProgram(0);
    return values;
}

// The include in a vertex shader: vdsGeneralizedWinding's value per point
// against the double reference.
TEST_F(GwnGpuTest, VertexStageValueMatchesTheReference) {
    const Sprite sprite = bakeAt(solids::sphereWithHoles(), Axis::Z, 64);
    const GpuSprite gpu(sprite, GpuSpriteParts::TextureOnly);
    const auto points = test::randomPoints(sprite.grid.box, 20000, 0.1f, 13);
    const std::vector<glm::vec2> values = includeValues(gpu, points);
    std::vector<double> errors;
    std::size_t labelsDiffer = 0, fractional = 0;
    for (std::size_t k = 0; k < points.size(); ++k) {
        double w = referenceGwn(sprite, points[k]);
        if (!std::isfinite(w)) w = 0.0;
        errors.push_back(std::fabs(double(values[k].x) - w));
        labelsDiffer += (values[k].y != 0.0f) != (w > 0.5) && std::fabs(w - 0.5) > 1e-4;
        fractional += std::fabs(w - std::round(w)) > 0.05;
    }
    // Float: about 1e-7 over the distance to the boundary curve (measured
    // here on llvmpipe: median 1.0e-6, 99.9th percentile 1.8e-5, worst
    // 1.6e-4, the same with the tree's expansions as with every edge
    // summed).
    std::sort(errors.begin(), errors.end());
    EXPECT_LT(errors[errors.size() / 2], 2e-6);
    EXPECT_LT(errors[errors.size() * 999 / 1000], 5e-5);
    EXPECT_LT(errors.back(), 1e-3);
    EXPECT_EQ(labelsDiffer, 0u);
    EXPECT_GT(fractional, points.size() / 10);
}

// boundary_tiles.glsl's vdsBoundaryTerms in a compute shader, one point an
// invocation, workgroups of 64: the term at each point.
std::vector<float> tiledTerms(const GpuSprite& gpu, const std::vector<glm::vec3>& points) {
    const std::string cs = R"(#define VDS_LOCAL_SIZE 64
layout(local_size_x = VDS_LOCAL_SIZE) in;
#define VDS_BOUNDARY_BINDING 1
#include "vds/vpt.glsl"
#define VDS_TERM_POINTS 1
#include "vds/boundary_tiles.glsl"
layout(std430, binding = 0) readonly buffer Points { float points[]; };
layout(std430, binding = 2) writeonly buffer Values { float values[]; };
uniform VdsPlacement u_placement;
uniform VdsBoundary u_boundary;
uniform ivec2 u_size;
uniform uint u_count;
void main() {
    uint i = gl_WorkGroupID.x * gl_WorkGroupSize.x + gl_LocalInvocationID.x;
    bool live[1] = bool[1](i < u_count);
    vec3 p = live[0] ? vec3(points[3u * i], points[3u * i + 1u], points[3u * i + 2u]) : vec3(0.0);
    vec3 q[1] = vec3[1](vdsBesidePoint(u_boundary, u_size, vdsToTexture(u_placement, p)));
    float term[1];
    vdsBoundaryTerms(u_boundary, q, live, term);
    if (live[0]) values[i] = term[0];
}
)";
    const Program program = buildProgram({{GL_COMPUTE_SHADER, "tiles.comp", cs}});
    Buffer pointBuffer = Buffer::create(), valueBuffer = Buffer::create();
    glNamedBufferStorage(pointBuffer.id(), GLsizeiptr(points.size() * 12), points.data(), 0);
    glNamedBufferStorage(valueBuffer.id(), GLsizeiptr(points.size() * 4), nullptr, 0);
    const GLuint id = program.id();
    glUseProgram(id);
    glUniformMatrix3fv(glGetUniformLocation(id, "u_placement.matrix"), 1, GL_FALSE, &gpu.matrix()[0][0]);
    glUniform3fv(glGetUniformLocation(id, "u_placement.position"), 1, &gpu.position()[0]);
    glUniform2i(glGetUniformLocation(id, "u_size"), GLint(gpu.size().x), GLint(gpu.size().y));
    glUniform1ui(glGetUniformLocation(id, "u_count"), GLuint(points.size()));
    gpu.boundary().setUniforms(id, "u_boundary", 1);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, pointBuffer.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, valueBuffer.id());
    glDispatchCompute(GLuint((points.size() + 63) / 64), 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<float> values(points.size());
    glGetNamedBufferSubData(valueBuffer.id(), 0, GLsizeiptr(values.size() * 4), values.data());
    for (GLuint b = 0; b <= 2; ++b) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, b, 0);
    glUseProgram(0);
    return values;
}

// The workgroup's walk of the chain tree: clusters of 64 points beside the
// box (no crossing in their column: the winding number is the term), some
// close to the openings, most far from some of them, so that the workgroup
// takes far chains and loops whole by their expansions and sums the rest;
// the terms against the double reference.
TEST_F(GwnGpuTest, WorkgroupTreeWalkMatchesTheReferenceForClusteredPoints) {
    const Sprite sprite = bakeAt(solids::sphereWithHoles(), Axis::Z, 64);
    const GpuSprite gpu(sprite, GpuSpriteParts::ColumnsOnly);
    // The texture's extent in x and y (its s and t: whole texels, so up to one past the box).
    const glm::vec3 lo = sprite.grid.box.lo, size = sprite.grid.box.hi - lo;
    const glm::vec3 hi = lo + glm::vec3(float(sprite.width()), float(sprite.height()), 0.0f) * sprite.grid.texelSize +
                         glm::vec3(0.0f, 0.0f, size.z);
    std::mt19937 rng(21);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::vector<glm::vec3> points;
    for (int cluster = 0; cluster < 200; ++cluster) {
        // Beside the texture in x or y (the sprite's s or t), 0.02 to 6 sizes away.
        const int side = cluster % 4;
        const float away = 0.02f + 6.0f * u(rng) * u(rng);
        glm::vec3 c = lo + glm::vec3(u(rng), u(rng), u(rng)) * size;
        if (side < 2) c.x = side == 0 ? lo.x - away * size.x : hi.x + away * size.x;
        else c.y = side == 2 ? lo.y - away * size.y : hi.y + away * size.y;
        const float spread = 0.01f + 0.1f * u(rng);
        for (int k = 0; k < 64; ++k) {
            glm::vec3 p = c + (glm::vec3(u(rng), u(rng), u(rng)) - 0.5f) * spread * size;
            if (side < 2) p.x = side == 0 ? std::min(p.x, lo.x - 1e-3f * size.x) : std::max(p.x, hi.x + 1e-3f * size.x);
            else p.y = side == 2 ? std::min(p.y, lo.y - 1e-3f * size.y) : std::max(p.y, hi.y + 1e-3f * size.y);
            points.push_back(p);
        }
    }
    const std::vector<float> terms = tiledTerms(gpu, points);
    std::vector<double> errors;
    for (std::size_t k = 0; k < points.size(); ++k) errors.push_back(std::fabs(double(terms[k]) - referenceGwn(sprite, points[k])));
    std::sort(errors.begin(), errors.end());
    // Float, and at most 1e-5 a node taken (VDS_NODE_TOLERANCE).
    EXPECT_LT(errors[errors.size() / 2], 5e-6);
    EXPECT_LT(errors.back(), 2e-4);
}

// One large opening: a UV sphere (256 segments) without its cap above
// z = 0.5, its rim one loop of 256 edges in a plane z = c. Points near that
// plane inside the rim have w near 1/2 (on the disk the rim bounds,
// exactly 1/2), so the classifier and the include's value there rest on
// the chains near the point and the chords and expansions of the rest of
// the rim, which must give the per-edge sum's labels and values within
// float error.
TEST_F(GwnGpuTest, OneLargeOpeningMatchesTheCpuNearItsPlane) {
    const TriangleMesh cup =
        solids::without(solids::sphere({0, 0, 0}, 1.0f, 256).mesh, [](const glm::vec3& c) { return c.z > 0.5f; });
    const float rim = float(std::cos(43.0 * 3.14159265358979323846 / 128.0)); // ring 43 of 128, the first below 0.5
    std::mt19937 rng(21);
    std::uniform_real_distribution<float> across(-1.2f, 1.2f), opening(-1.0f, 1.0f), height(-0.05f, 0.05f),
        anywhere(-1.1f, 1.1f);
    std::vector<glm::vec3> points;
    for (int k = 0; k < 8000; ++k) points.push_back({opening(rng), opening(rng), rim + height(rng)});
    for (int k = 0; k < 2000; ++k) points.push_back({across(rng), across(rng), anywhere(rng)});
    GpuClassifier classifier(gl());
    for (Axis axis : {Axis::Y, Axis::Z}) {
        const Sprite sprite = bakeAt(cup, axis, 64);
        ASSERT_GE(sprite.boundaryEdges.size(), 2u * 256u); // the rim (and the pole's zero-length edges)
        ClassifyOptions options;
        options.rule = Rule::GeneralizedWinding;
        std::vector<std::uint8_t> cpu(points.size());
        classify(sprite, {points.data(), points.size()}, cpu.data(), options, {QueryLayout::Auto, BoundaryEvaluation::Exact});
        const GpuSprite gpu(sprite, GpuSpriteParts::TextureOnly);
        // one loop, halved into chains closed by their chords
        EXPECT_GE(gpu.boundary().nodeCount(), 256u / 4u) << toString(axis);
        std::vector<std::uint8_t> labels(points.size(), 7);
        classifier.classify(gpu, {points.data(), points.size()}, labels.data(), {Rule::GeneralizedWinding});
        const std::vector<glm::vec2> values = includeValues(gpu, points);
        std::size_t wrong = 0, valueWrong = 0, inside = 0, doubtful = 0;
        std::vector<double> errors;
        for (std::size_t k = 0; k < points.size(); ++k) {
            double w = referenceGwn(sprite, points[k]);
            if (!std::isfinite(w)) w = 0.0;
            errors.push_back(std::fabs(double(values[k].x) - w));
            inside += cpu[k];
            doubtful += std::fabs(w - 0.5) < 0.05;
            if (std::fabs(w - 0.5) <= 1e-4) continue; // within float error of 1/2
            wrong += labels[k] != cpu[k];
            valueWrong += (values[k].y != 0.0f) != bool(cpu[k]);
        }
        std::sort(errors.begin(), errors.end());
        EXPECT_EQ(wrong, 0u) << toString(axis);
        EXPECT_EQ(valueWrong, 0u) << toString(axis);
        EXPECT_GT(doubtful, points.size() / 5) << toString(axis); // the points do test near 1/2
        EXPECT_GT(inside, points.size() / 10) << toString(axis);
        // Float error, as large with every edge summed (median 2.2e-6 and
        // 5.0e-6 there, 4.4e-6 at most here): most of these points lie near
        // the rim's plane, many near the rim.
        EXPECT_LT(errors[errors.size() / 2], 1e-5) << toString(axis);
        EXPECT_LT(errors[errors.size() * 99 / 100], 1e-3) << toString(axis);
    }
}

} // namespace
} // namespace vds
