// vdsDistance (shaders/vds/vpt.glsl) against the exact distance: a slice of
// a distance texture rendered into a float image, every pixel's value held
// to the exact signed distance of its point within the include's stated
// bound (half a cell's diagonal, plus the filter's weight rounding).
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <vds/distance.h>
#include <vds/gl/distance.h>
#include <vds/gl/objects.h>
#include <vds/gl/shader.h>
#include <vds/sprite.h>
#include <vds/bake.h>
#include <vds/error.h>
#include <vds/gl/sprite.h>

#include "../support/gl_fixture.h"
#include "solids.h"

namespace vds {
namespace {

using DistanceGlTest = test::GlTest;

constexpr int kImage = 96;

/// The image's pixel (x, y): a point of the plane z = `z` across the grid's
/// cell-centre box, computed as the shader computes it (float).
glm::vec3 pixelPoint(const glm::vec3& lo, const glm::vec3& hi, float z, int x, int y) {
    const glm::vec2 t = (glm::vec2(float(x), float(y)) + 0.5f) / float(kImage);
    return glm::vec3(lo.x + t.x * (hi.x - lo.x), lo.y + t.y * (hi.y - lo.y), z);
}

/// The slice at z through `vdsDistance`: its values, or with `band` > 0 the
/// band |d| <= band as 1 and the rest as 0 (the clip sample's test).
std::vector<float> renderSlice(const Texture& field, const Grid& grid, const glm::vec3& lo, const glm::vec3& hi,
                               float z, float band = 0.0f) {
    const std::string vs = "void main() { vec2 c = vec2(gl_VertexID & 1, gl_VertexID >> 1) * 4.0 - 1.0;"
                           " gl_Position = vec4(c, 0.0, 1.0); }\n";
    const std::string fs = R"(#include "vds/vpt.glsl"
uniform sampler3D u_field;
uniform vec3 u_boxLo, u_boxHi, u_lo, u_hi;
uniform float u_z, u_size, u_band;
layout(location = 0) out float distance;
void main() {
    vec2 t = gl_FragCoord.xy / u_size;
    vec3 p = vec3(u_lo.x + t.x * (u_hi.x - u_lo.x), u_lo.y + t.y * (u_hi.y - u_lo.y), u_z);
    float d = vdsDistance(u_field, u_boxLo, u_boxHi, p);
    distance = u_band > 0.0 ? (abs(d) <= u_band ? 1.0 : 0.0) : d;
}
)";
    const Program program = buildProgram({{GL_VERTEX_SHADER, "slice.vert", vs}, {GL_FRAGMENT_SHADER, "slice.frag", fs}});
    Texture target = Texture::create(GL_TEXTURE_2D);
    glTextureStorage2D(target.id(), 1, GL_R32F, kImage, kImage);
    Framebuffer framebuffer = Framebuffer::create();
    glNamedFramebufferTexture(framebuffer.id(), GL_COLOR_ATTACHMENT0, target.id(), 0);
    VertexArray vao = VertexArray::create();
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer.id());
    glViewport(0, 0, kImage, kImage);
    glUseProgram(program.id());
    glBindTextureUnit(0, field.id());
    const GLuint id = program.id();
    glUniform1i(glGetUniformLocation(id, "u_field"), 0);
    glUniform3fv(glGetUniformLocation(id, "u_boxLo"), 1, &grid.box.lo.x);
    glUniform3fv(glGetUniformLocation(id, "u_boxHi"), 1, &grid.box.hi.x);
    glUniform3fv(glGetUniformLocation(id, "u_lo"), 1, &lo.x);
    glUniform3fv(glGetUniformLocation(id, "u_hi"), 1, &hi.x);
    glUniform1f(glGetUniformLocation(id, "u_z"), z);
    glUniform1f(glGetUniformLocation(id, "u_size"), float(kImage));
    glUniform1f(glGetUniformLocation(id, "u_band"), band);
    glBindVertexArray(vao.id());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    std::vector<float> image(std::size_t(kImage) * kImage);
    glGetTextureImage(target.id(), 0, GL_RED, GL_FLOAT, GLsizei(image.size() * sizeof(float)), image.data());
    glBindVertexArray(0);
    glUseProgram(0);
    glBindTextureUnit(0, 0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
    return image;
}

TEST_F(DistanceGlTest, TheLookupIsWithinHalfACellDiagonalOfTheExactDistance) {
    const TriangleMesh mesh = solids::torus(glm::vec3(0.0f), 1.0f, 0.4f, 48).mesh;
    const SignedDistance exact(mesh, Rule::Winding);
    Grid grid;
    grid.box = {glm::vec3(-1.6f, -1.6f, -0.7f), glm::vec3(1.6f, 1.6f, 0.7f)};
    grid.dims = glm::uvec3(40, 40, 18);
    std::vector<float> cells(grid.cellCount());
    exact.grid(grid, cells.data());
    const Texture field = uploadDistanceTexture(grid, cells.data());
    // The slice spans the cell-centre box, where the bound holds.
    const glm::vec3 cell = (grid.box.hi - grid.box.lo) / glm::vec3(grid.dims);
    const glm::vec3 lo = grid.box.lo + 0.5f * cell, hi = grid.box.hi - 0.5f * cell;
    const double bound = 0.5 * glm::length(glm::dvec3(cell)) + std::sqrt(3.0) * glm::length(glm::dvec3(cell)) / 256.0;
    for (float z : {0.0f, 0.13f, -0.31f}) {
        const std::vector<float> image = renderSlice(field, grid, lo, hi, z);
        double worst = 0.0;
        std::size_t inside = 0;
        for (int y = 0; y < kImage; ++y)
            for (int x = 0; x < kImage; ++x) {
                const double d = exact.distance(pixelPoint(lo, hi, z, x, y));
                const double lookup = image[std::size_t(y) * kImage + x];
                worst = std::max(worst, std::abs(lookup - d));
                inside += d < 0.0;
            }
        EXPECT_LE(worst, bound) << "z " << z;
        EXPECT_GT(worst, 0.0); // a real interpolation, not the exact values
        EXPECT_GT(inside, 0u);
        std::printf("slice z = %.2f: worst |vdsDistance - exact| %.4f, %.2f of the bound (cell diagonal / 2 = %.4f)\n",
                    double(z), worst, worst / bound, 0.5 * glm::length(glm::dvec3(cell)));
    }
}

// The band of the clip sample (|d| <= width, shaders/samples/scene.frag) as
// the GPU draws it through vdsDistance, against the same band from the exact
// distances of the same pixels' points: a pixel may differ only where the
// exact distance lies within the lookup's bound (under one cell) of the
// band's edge.
TEST_F(DistanceGlTest, TheBandDiffersFromTheExactBandOnlyWithinACellOfItsEdge) {
    const TriangleMesh mesh = solids::torus(glm::vec3(0.0f), 1.0f, 0.4f, 48).mesh;
    const SignedDistance exact(mesh, Rule::Winding);
    const SpriteDistance field = bakeDistance(mesh, meshBounds(mesh), 32, Rule::Winding, 0);
    const Grid& grid = field.grid;
    const Texture texture = uploadDistanceTexture(grid, field.cells.data());
    const glm::vec3 cell = (grid.box.hi - grid.box.lo) / glm::vec3(grid.dims);
    const glm::vec3 lo = grid.box.lo + 0.5f * cell, hi = grid.box.hi - 0.5f * cell;
    const double bound = 0.5 * glm::length(glm::dvec3(cell)) + std::sqrt(3.0) * glm::length(glm::dvec3(cell)) / 256.0;
    ASSERT_LT(bound, double(cell.x)); // within one cell
    const float width = 0.1f;
    for (float z : {0.0f, 0.21f}) {
        const std::vector<float> image = renderSlice(texture, grid, lo, hi, z, width);
        std::size_t band = 0, differing = 0, far = 0;
        double farthest = 0.0; // of a differing pixel's exact distance from the band's edge
        for (int y = 0; y < kImage; ++y)
            for (int x = 0; x < kImage; ++x) {
                const double d = exact.distance(pixelPoint(lo, hi, z, x, y));
                const bool gpu = image[std::size_t(y) * kImage + x] == 1.0f, cpu = std::abs(d) <= double(width);
                band += cpu;
                if (gpu == cpu) continue;
                ++differing;
                far += std::abs(std::abs(d) - double(width)) > bound;
                farthest = std::max(farthest, std::abs(std::abs(d) - double(width)));
            }
        EXPECT_EQ(far, 0u) << "z " << z << ": pixels differing farther than the bound from the band's edge";
        EXPECT_GT(band, std::size_t(kImage)) << "z " << z; // a band of many pixels, both edges
        EXPECT_LT(differing, band / 4) << "z " << z;
        std::printf("band z = %.2f: %zu band pixels, %zu differ from the exact band, at most %.4f from its edge "
                    "(%.2f cell; the bound %.4f)\n",
                    double(z), band, differing, farthest, farthest / double(cell.x), bound);
    }
}

// A sprite's distance grid travels with it to the GPU, texel for cell.
TEST_F(DistanceGlTest, AGpuSpriteCarriesItsDistanceGrid) {
    const TriangleMesh mesh = solids::sphere(glm::vec3(0.0f), 1.0f, 24).mesh;
    BakeOptions options;
    options.resolution = 32;
    Sprite sprite = bakeCpu(mesh, options);
    const GpuSprite plain(sprite);
    EXPECT_FALSE(bool(plain.distanceGrid()));
    EXPECT_THROW(plain.distanceGrid().setUniforms(0, "u_distance", "u_lo", "u_hi", 1), InvalidArgument);
    sprite.distance = bakeDistance(mesh, sprite.grid.box, 16, Rule::Winding, 0);
    const GpuSprite carried(sprite, GpuSpriteParts::ColumnsOnly);
    ASSERT_TRUE(bool(carried.distanceGrid()));
    const Grid& g = sprite.distance.grid;
    EXPECT_EQ(carried.distanceGrid().box().lo, g.box.lo);
    EXPECT_EQ(carried.distanceGrid().box().hi, g.box.hi);
    std::vector<float> texels(g.cellCount());
    glGetTextureImage(carried.distanceGrid().texture().id(), 0, GL_RED, GL_FLOAT, GLsizei(texels.size() * sizeof(float)),
                      texels.data());
    std::size_t same = 0;
    for (std::uint32_t i = 0; i < g.dims.x; ++i)
        for (std::uint32_t j = 0; j < g.dims.y; ++j)
            for (std::uint32_t k = 0; k < g.dims.z; ++k)
                same += texels[i + std::size_t(g.dims.x) * (j + std::size_t(g.dims.y) * k)] ==
                        sprite.distance.cells[g.index(i, j, k)];
    EXPECT_EQ(same, g.cellCount());
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
}

} // namespace
} // namespace vds
