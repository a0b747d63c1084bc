// GLSL answers equal C++ answers: the compute classifier, and the include used
// with eight sprites at once in the vertex and fragment stages.
#include <cmath>

#include <GL/gl.h>
#include <GL/glext.h>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <vds/all.h>
#include <vds/bake.h>
#include <vds/gl/bake.h>
#include <vds/gl/sprite.h>
#include <vds/gl/shader.h>
#include "solids.h"

#include "../support/gl_fixture.h"
#include "points.h"

namespace vds {
namespace {

class GpuClassifyTest : public test::GlTest {
protected:
    Sprite bakeSolid(const TriangleMesh& mesh, std::uint32_t resolution, Axis axis = Axis::Z) {
        BakeOptions o;
        o.resolution = resolution;
        o.axis = axis;
        return bake(gl(), mesh, o);
    }
};

// Points that stress the texel and depth boundaries: random, plus texel
// centres and texel corners at stored crossing depths.
std::vector<glm::vec3> hardPoints(const Sprite& s, std::size_t n) {
    auto points = test::randomPoints(s.grid.box, n, 0.15f, 3);
    const glm::ivec3 p = axisPermutation(s.grid.axis);
    for (std::uint32_t j = 0; j < s.height(); j += 3)
        for (std::uint32_t i = 0; i < s.width(); i += 3) {
            const std::size_t c = std::size_t(j) * s.width() + i;
            for (std::uint32_t k = s.offsets[c]; k < s.offsets[c + 1]; ++k) {
                glm::vec3 q = s.grid.texelCentre(i, j, crossingDepth(s.crossings[k]));
                points.push_back(q);
                q[p.x] = s.grid.box.lo[p.x] + float(i) * s.grid.texelSize; // on the texel's edge
                points.push_back(q);
            }
        }
    return points;
}

TEST_F(GpuClassifyTest, ComputeShaderMatchesCppOnEveryPoint) {
    const auto torus = solids::torus({0.2f, -0.1f, 0.0f}, 1.0f, 0.4f, 96);
    const auto two = solids::overlappingBoxes({-1, -1, -1}, {0.3f, 0.3f, 0.3f}, {-0.3f, -0.3f, -0.3f}, {1, 1, 1});
    GpuClassifier classifier(gl());
    for (const TriangleMesh* mesh : {&torus.mesh, &two.mesh})
        for (Axis axis : {Axis::Z, Axis::X}) {
            Sprite sprite = bakeSolid(*mesh, 96, axis);
            auto points = hardPoints(sprite, 50000);
            for (int placed = 0; placed < 2; ++placed) {
                if (placed) { // move, rotate and scale without re-baking; the points move along
                    const glm::mat4 model =
                        glm::scale(glm::rotate(glm::translate(glm::mat4(1.0f), {0.3f, -2.0f, 0.7f}), 0.7f,
                                               glm::normalize(glm::vec3(1, 2, 3))),
                                   glm::vec3(1.5f, 0.5f, 2.0f));
                    sprite.transform(model);
                    for (auto& q : points) q = glm::vec3(model * glm::vec4(q, 1.0f));
                }
                const GpuSprite gpu(sprite);
                for (Rule rule : {Rule::Parity, Rule::Winding}) {
                    std::vector<std::uint8_t> cpu(points.size()), gpuLabels(points.size(), 7);
                    ClassifyOptions options;
                    options.rule = rule;
                    classify(sprite, {points.data(), points.size()}, cpu.data(), options);
                    classifier.classify(gpu, {points.data(), points.size()}, gpuLabels.data(), {rule});
                    std::size_t differ = 0, inside = 0;
                    for (std::size_t k = 0; k < points.size(); ++k) {
                        differ += cpu[k] != gpuLabels[k];
                        inside += cpu[k];
                    }
                    EXPECT_EQ(differ, 0u) << "axis " << toString(axis) << ", rule " << toString(rule);
                    EXPECT_GT(inside, points.size() / 20); // the test is not vacuous
                }
            }
        }
}

// Points and labels that stay in GL buffers: one byte a point, four to a
// word; a count that is not a multiple of four leaves the tail bytes 0.
TEST_F(GpuClassifyTest, ResidentBuffersMatchCppOnEveryPoint) {
    const auto torus = solids::torus({0.2f, -0.1f, 0.0f}, 1.0f, 0.4f, 96);
    const auto two = solids::overlappingBoxes({-1, -1, -1}, {0.3f, 0.3f, 0.3f}, {-0.3f, -0.3f, -0.3f}, {1, 1, 1});
    GpuClassifier classifier(gl());
    for (const TriangleMesh* mesh : {&torus.mesh, &two.mesh}) {
        Sprite sprite = bakeSolid(*mesh, 96, Axis::Y);
        sprite.transform(glm::rotate(glm::mat4(1.0f), 0.4f, glm::vec3(0, 0, 1)));
        auto points = hardPoints(sprite, 60000);
        points.resize(points.size() / 4 * 4 + 3);
        for (auto& q : points) q = glm::vec3(glm::rotate(glm::mat4(1.0f), 0.4f, glm::vec3(0, 0, 1)) * glm::vec4(q, 1.0f));
        const std::size_t n = points.size(), words = (n + 3) / 4;
        Buffer pointBuffer = Buffer::create(), labelBuffer = Buffer::create();
        glNamedBufferStorage(pointBuffer.id(), GLsizeiptr(n * 12), points.data(), 0);
        glNamedBufferStorage(labelBuffer.id(), GLsizeiptr(words * 4 + 4), nullptr, GL_DYNAMIC_STORAGE_BIT);
        for (GpuSpriteParts parts : {GpuSpriteParts::Both, GpuSpriteParts::TextureOnly, GpuSpriteParts::ColumnsOnly}) {
            const GpuSprite gpu(sprite, parts);
            for (Rule rule : {Rule::Parity, Rule::Winding}) {
                const std::uint32_t poison = 0x07070707u;
                std::vector<std::uint32_t> fill(words + 1, poison);
                glNamedBufferSubData(labelBuffer.id(), 0, GLsizeiptr(fill.size() * 4), fill.data());
                classifier.classify(gpu, pointBuffer.id(), n, labelBuffer.id(), {rule});
                std::vector<std::uint8_t> labels((words + 1) * 4);
                glGetNamedBufferSubData(labelBuffer.id(), 0, GLsizeiptr(labels.size()), labels.data());
                std::vector<std::uint8_t> cpu(n);
                ClassifyOptions options;
                options.rule = rule;
                classify(sprite, PointsView(points.data(), n), cpu.data(), options);
                std::size_t differ = 0, inside = 0;
                for (std::size_t k = 0; k < n; ++k) {
                    differ += cpu[k] != labels[k];
                    inside += cpu[k];
                }
                EXPECT_EQ(differ, 0u) << mesh->name << ", parts " << int(parts) << ", rule " << toString(rule);
                EXPECT_GT(inside, n / 20);
                EXPECT_EQ(labels[n], 0u) << "the tail word's unused byte";
                EXPECT_EQ(labels[words * 4], 7u) << "written past the last word";
            }
        }
    }
}

// The renderer's path: bake into GL, classify points already in GL.
TEST_F(GpuClassifyTest, SpriteBakedOnTheGpuClassifiesLikeTheHostSprite) {
    const auto shell = solids::shell({0, 0, 0}, 1.0f, 0.55f, 64);
    BakeOptions o;
    o.resolution = 128;
    const Sprite host = bake(gl(), shell.mesh, o);
    const GpuBake baked = bakeToGpu(gl(), shell.mesh, o);
    const auto points = test::randomPoints(host.grid.box, 100001, 0.1f, 5);
    Buffer pointBuffer = Buffer::create(), labelBuffer = Buffer::create();
    glNamedBufferStorage(pointBuffer.id(), GLsizeiptr(points.size() * 12), points.data(), 0);
    glNamedBufferStorage(labelBuffer.id(), GLsizeiptr((points.size() + 3) / 4 * 4), nullptr, 0);
    GpuClassifier classifier(gl());
    classifier.classify(baked.sprite, pointBuffer.id(), points.size(), labelBuffer.id());
    std::vector<std::uint8_t> labels((points.size() + 3) / 4 * 4), cpu(points.size());
    glGetNamedBufferSubData(labelBuffer.id(), 0, GLsizeiptr(labels.size()), labels.data());
    classify(host, points, cpu.data());
    std::size_t differ = 0, inside = 0;
    for (std::size_t k = 0; k < points.size(); ++k) {
        differ += cpu[k] != labels[k];
        inside += cpu[k];
    }
    EXPECT_EQ(differ, 0u);
    EXPECT_GT(inside, points.size() / 10);
}

// The host-array call in batches of every size, its staging buffers kept and
// grown between calls; every point equal to the CPU's answer.
TEST_F(GpuClassifyTest, HostArraysInManyBatchesMatchCpp) {
    const auto torus = solids::torus({0, 0, 0}, 1.0f, 0.45f, 64);
    const Sprite sprite = bakeSolid(torus.mesh, 64, Axis::X);
    const GpuSprite gpu(sprite);
    for (HostTransfer transfer : {HostTransfer::Mapped, HostTransfer::Copied})
        for (std::size_t batch : {std::size_t(1024), std::size_t(4096), std::size_t(1) << 22}) {
            GpuClassifier classifier(gl(), batch, transfer);
            for (std::size_t n : {std::size_t(1), std::size_t(1023), std::size_t(5000), std::size_t(70001)}) {
                const auto points = test::randomPoints(sprite.grid.box, n, 0.1f, std::uint32_t(n + batch));
                std::vector<std::uint8_t> cpu(n), labels(n, 9);
                classify(sprite, PointsView(points.data(), n), cpu.data());
                classifier.classify(gpu, {points.data(), n}, labels.data(), {Rule::Parity});
                EXPECT_EQ(cpu, labels) << n << " points in batches of " << batch << ", copied "
                                       << (transfer == HostTransfer::Copied);
            }
        }
}

// Blocks of MiBs (points and labels) are copied on the library's pool
// threads, kept from one batch and one call to the next.
TEST_F(GpuClassifyTest, LargeHostArraysMatchCppCallAfterCall) {
    const auto torus = solids::torus({0, 0, 0}, 1.0f, 0.45f, 64);
    const Sprite sprite = bakeSolid(torus.mesh, 64, Axis::Y);
    const GpuSprite gpu(sprite);
    const std::size_t n = 3000007; // 36 MB of points, 3 MB of labels: several batches of 1M points
    const auto points = test::randomPoints(sprite.grid.box, n, 0.1f, 11);
    std::vector<std::uint8_t> cpu(n);
    classify(sprite, PointsView(points.data(), n), cpu.data());
    for (HostTransfer transfer : {HostTransfer::Mapped, HostTransfer::Copied}) {
        GpuClassifier classifier(gl(), std::size_t(1) << 20, transfer);
        for (int call = 0; call < 2; ++call) {
            std::vector<std::uint8_t> labels(n, 9);
            classifier.classify(gpu, {points.data(), n}, labels.data(), {Rule::Parity});
            EXPECT_EQ(cpu, labels) << "call " << call << ", copied " << (transfer == HostTransfer::Copied);
        }
    }
}

TEST_F(GpuClassifyTest, TransformedSpriteAnswersForTheTransformedSolid) {
    const auto sphere = solids::sphere({0, 0, 0}, 1.0f, 96);
    Sprite s = bakeSolid(sphere.mesh, 128);
    const glm::mat4 model = glm::scale(glm::translate(glm::mat4(1.0f), {5, 0, 0}), glm::vec3(2.0f));
    s.transform(model);
    EXPECT_TRUE(s.contains({5, 0, 0}));
    EXPECT_TRUE(s.contains({6.8f, 0, 0}));
    EXPECT_FALSE(s.contains({7.2f, 0, 0}));
    EXPECT_FALSE(s.contains({0, 0, 0}));
}

// Eight sprites (boxes and spheres at different places) in one draw: the
// vertex stage writes one bit per sprite for each point; the fragment stage
// does the same for each pixel of a plane through the sprites.
class EightSpritesTest : public GpuClassifyTest {
protected:
    void SetUp() override {
        GpuClassifyTest::SetUp();
        if (IsSkipped() || HasFailure()) return;
        for (int i = 0; i < 8; ++i) {
            const glm::vec3 c(float(i % 4) * 0.5f - 0.75f, float(i / 4) * 0.8f - 0.4f, 0.1f * float(i));
            const TriangleMesh mesh = i % 2 ? solids::sphere(c, 0.3f, 48).mesh
                                            : solids::box(c - glm::vec3(0.22f), c + glm::vec3(0.22f, 0.3f, 0.25f)).mesh;
            sprites.push_back(bakeSolid(mesh, 64, Axis(i % 3)));
            gpu.emplace_back(sprites.back());
        }
    }
    std::uint32_t cpuMask(const glm::vec3& p) const {
        std::uint32_t m = 0;
        for (std::size_t i = 0; i < sprites.size(); ++i) m |= sprites[i].contains(p) ? 1u << i : 0u;
        return m;
    }
    void bindAll(GLuint program) {
        for (int i = 0; i < 8; ++i)
            gpu[std::size_t(i)].setUniforms(program, "u_ldi[" + std::to_string(i) + "]",
                                            "u_placement[" + std::to_string(i) + "]", GLuint(i));
    }
    std::vector<Sprite> sprites;
    std::vector<GpuSprite> gpu;
};

const char* kMaskFunction = R"(#include "vds/vpt.glsl"
uniform sampler3D u_ldi[8];
uniform VdsPlacement u_placement[8];
uint vdsMask(vec3 p) {
    uint m = 0u;
    for (int i = 0; i < 8; ++i)
        if (vdsContains(u_ldi[i], u_placement[i], p, VDS_RULE_PARITY)) m |= 1u << uint(i);
    return m;
}
)";

TEST_F(EightSpritesTest, VertexStageMatchesCpu) {
    const std::string vs = std::string(kMaskFunction) + R"(
layout(location = 0) in vec3 a_point;
layout(std430, binding = 0) writeonly buffer Masks { uint masks[]; };
void main() { masks[gl_VertexID] = vdsMask(a_point); gl_Position = vec4(0.0); }
)";
    const std::string fs = "out vec4 c; void main() { c = vec4(1.0); }\n";
    const Program program = buildProgram({{GL_VERTEX_SHADER, "mask.vert", vs}, {GL_FRAGMENT_SHADER, "mask.frag", fs}});
    const auto points = test::randomPoints(Box{{-1.2f, -0.9f, -0.4f}, {1.2f, 0.9f, 1.2f}}, 40000, 0.0f, 11);
    Buffer pointBuffer = Buffer::create(), maskBuffer = Buffer::create();
    glNamedBufferStorage(pointBuffer.id(), GLsizeiptr(points.size() * 12), points.data(), 0);
    glNamedBufferStorage(maskBuffer.id(), GLsizeiptr(points.size() * 4), nullptr, 0);
    VertexArray vao = VertexArray::create();
    glVertexArrayVertexBuffer(vao.id(), 0, pointBuffer.id(), 0, 12);
    glVertexArrayAttribFormat(vao.id(), 0, 3, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(vao.id(), 0, 0);
    glEnableVertexArrayAttrib(vao.id(), 0);
    Framebuffer empty = Framebuffer::create(); // a draw needs a complete framebuffer, even with nothing to write
    glNamedFramebufferParameteri(empty.id(), GL_FRAMEBUFFER_DEFAULT_WIDTH, 1);
    glNamedFramebufferParameteri(empty.id(), GL_FRAMEBUFFER_DEFAULT_HEIGHT, 1);
    glBindFramebuffer(GL_FRAMEBUFFER, empty.id());
    glUseProgram(program.id());
    bindAll(program.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, maskBuffer.id());
    glEnable(GL_RASTERIZER_DISCARD);
    glBindVertexArray(vao.id());
    glDrawArrays(GL_POINTS, 0, GLsizei(points.size()));
    glDisable(GL_RASTERIZER_DISCARD);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<std::uint32_t> masks(points.size());
    glGetNamedBufferSubData(maskBuffer.id(), 0, GLsizeiptr(masks.size() * 4), masks.data());
    glBindVertexArray(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glUseProgram(0);
    std::size_t differ = 0, bitsSet = 0;
    for (std::size_t k = 0; k < points.size(); ++k) {
        differ += masks[k] != cpuMask(points[k]);
        bitsSet += std::size_t(__builtin_popcount(masks[k]));
    }
    EXPECT_EQ(differ, 0u);
    EXPECT_GT(bitsSet, points.size() / 10);
}

TEST_F(EightSpritesTest, FragmentStageMatchesCpuPerPixel) {
    // A full-screen triangle; each pixel's world point lies on the plane z = 0.3.
    const std::string vs = R"(
out vec2 v_uv;
void main() {
    vec2 p = vec2(gl_VertexID == 1 ? 3.0 : -1.0, gl_VertexID == 2 ? 3.0 : -1.0);
    v_uv = 0.5 * p + 0.5;
    gl_Position = vec4(p, 0.0, 1.0);
}
)";
    const std::string fs = std::string(kMaskFunction) + R"(
uniform ivec2 u_size;
layout(location = 0) out uint o_mask;
vec3 pixelPoint(ivec2 p) {
    return vec3(-1.2 + 2.4 * (float(p.x) + 0.5) / float(u_size.x), -0.9 + 1.8 * (float(p.y) + 0.5) / float(u_size.y), 0.3);
}
void main() { o_mask = vdsMask(pixelPoint(ivec2(gl_FragCoord.xy))); }
)";
    const Program program = buildProgram({{GL_VERTEX_SHADER, "quad.vert", vs}, {GL_FRAGMENT_SHADER, "mask.frag", fs}});
    const int w = 240, h = 180;
    Texture target = Texture::create(GL_TEXTURE_2D);
    glTextureStorage2D(target.id(), 1, GL_R32UI, w, h);
    Framebuffer fbo = Framebuffer::create();
    glNamedFramebufferTexture(fbo.id(), GL_COLOR_ATTACHMENT0, target.id(), 0);
    ASSERT_EQ(glCheckNamedFramebufferStatus(fbo.id(), GL_FRAMEBUFFER), GLenum(GL_FRAMEBUFFER_COMPLETE));
    VertexArray vao = VertexArray::create();
    glBindFramebuffer(GL_FRAMEBUFFER, fbo.id());
    glViewport(0, 0, w, h);
    glUseProgram(program.id());
    bindAll(program.id());
    glUniform2i(glGetUniformLocation(program.id(), "u_size"), w, h);
    glBindVertexArray(vao.id());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    std::vector<std::uint32_t> masks(std::size_t(w) * h);
    glGetTextureImage(target.id(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, GLsizei(masks.size() * 4), masks.data());
    glBindVertexArray(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glUseProgram(0);
    std::size_t differ = 0, bitsSet = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            // The same float arithmetic as pixelPoint() in the shader.
            const glm::vec3 p(-1.2f + 2.4f * (float(x) + 0.5f) / float(w), -0.9f + 1.8f * (float(y) + 0.5f) / float(h), 0.3f);
            const std::uint32_t m = masks[std::size_t(y) * w + x];
            differ += m != cpuMask(p);
            bitsSet += std::size_t(__builtin_popcount(m));
        }
    // Division in GLSL may round differently from C++, which can move a
    // pixel's point across a texel boundary; allow a handful such pixels.
    EXPECT_LE(differ, std::size_t(w * h) / 1000);
    EXPECT_GT(bitsSet, std::size_t(w * h) / 10);
}

} // namespace
} // namespace vds
