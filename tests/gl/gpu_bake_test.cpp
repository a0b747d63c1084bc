// vds::bakeToGpu: the sprite baked straight into GL equals, texel for texel
// and offset for offset, the host bake uploaded with GpuSprite.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>
#include <cstring>
#include <vector>

#include <GL/gl.h>
#include <GL/glext.h>
#include <gtest/gtest.h>

#include <vds/all.h>
#include <vds/bake.h>
#include <vds/error.h>
#include <vds/gl/bake.h>
#include <vds/gl/sprite.h>
#include "solids.h"

#include "../support/gl_fixture.h"

namespace vds {
namespace {

std::vector<float> textureTexels(const GpuSprite& s) {
    const glm::uvec3 n = s.size();
    std::vector<float> texels(std::size_t(n.x) * n.y * n.z);
    glGetTextureImage(s.texture().id(), 0, GL_RED, GL_FLOAT, GLsizei(texels.size() * 4), texels.data());
    return texels;
}

template <class T> std::vector<T> bufferContents(const Buffer& b, std::size_t count) {
    std::vector<T> v(count);
    if (count) glGetNamedBufferSubData(b.id(), 0, GLsizeiptr(count * sizeof(T)), v.data());
    return v;
}

class GpuBakeTest : public test::GlTest {
protected:
    // bakeToGpu against GpuSprite(bake()) for the same options, bit for bit.
    void expectSameAsHostBake(const TriangleMesh& mesh, const BakeOptions& given, const GlBakeOptions& glOptions = {}) {
        // The same baker on both sides: bakeToGpu's Auto is the fragment lists.
        BakeOptions options = given;
        if (options.method == BakeMethod::Auto) options.method = BakeMethod::Lists;
        const Sprite host = bakeOnGl(gl(), mesh, options, glOptions);
        const GpuSprite uploaded(host);
        const GpuBake baked = bakeToGpu(gl(), mesh, options, GpuSpriteParts::Both, glOptions);
        ASSERT_TRUE(bool(baked.sprite.texture()));
        ASSERT_TRUE(bool(baked.sprite.offsets()));
        EXPECT_EQ(baked.depthComplexity, host.depthComplexity);
        EXPECT_EQ(baked.crossings, host.crossings.size());
        EXPECT_EQ(baked.status, host.status);
        EXPECT_EQ(baked.validation, host.validation);
        EXPECT_EQ(baked.grid.width, host.grid.width);
        EXPECT_EQ(baked.grid.height, host.grid.height);
        EXPECT_EQ(baked.grid.matrix, host.grid.matrix);
        EXPECT_EQ(baked.grid.position, host.grid.position);
        EXPECT_EQ(baked.sprite.matrix(), uploaded.matrix());
        EXPECT_EQ(baked.sprite.position(), uploaded.position());
        ASSERT_EQ(baked.sprite.size(), uploaded.size());
        const std::vector<float> a = textureTexels(baked.sprite), b = textureTexels(uploaded);
        ASSERT_EQ(a.size(), b.size());
        EXPECT_EQ(0, std::memcmp(a.data(), b.data(), a.size() * 4)) << "texels differ";
        EXPECT_EQ(bufferContents<std::uint32_t>(baked.sprite.offsets(), host.offsets.size()), host.offsets);
        const auto crossings = bufferContents<float>(baked.sprite.crossings(), host.crossings.size());
        EXPECT_EQ(0, std::memcmp(crossings.data(), host.crossings.data(), crossings.size() * 4)) << "crossings differ";
        EXPECT_EQ(baked.sprite.crossingCount(), host.crossings.size());
    }
};

TEST_F(GpuBakeTest, EqualsTheHostBakeUploadedTexelForTexel) {
    const auto torus = solids::torus({0.1f, 0.2f, 0.3f}, 1.0f, 0.35f, 96);
    const auto shell = solids::shell({0, 0, 0}, 1.0f, 0.6f, 64);
    const auto two = solids::overlappingBoxes({-1, -1, -1}, {0.5f, 0.5f, 0.5f}, {-0.5f, -0.3f, -0.2f}, {1, 1, 1});
    for (const TriangleMesh* mesh : {&torus.mesh, &shell.mesh, &two.mesh})
        for (Axis axis : {Axis::X, Axis::Z}) {
            BakeOptions o;
            o.resolution = 80;
            o.axis = axis;
            SCOPED_TRACE(mesh->name + " along " + toString(axis));
            expectSameAsHostBake(*mesh, o);
        }
}

TEST_F(GpuBakeTest, RowBandsAreJoinedIntoOneSprite) {
    const auto shell = solids::shell({0, 0, 0}, 1.0f, 0.6f, 48);
    BakeTimings timings;
    BakeOptions o;
    o.method = BakeMethod::Lists;
    o.axis = Axis::Z;
    o.resolution = 80;
    o.timings = &timings;
    GlBakeOptions glOptions;
    glOptions.maxListNodes = 700;
    expectSameAsHostBake(shell.mesh, o, glOptions);
    EXPECT_GT(timings.bands, 1u);
}

TEST_F(GpuBakeTest, OtherMethodsBakeOnTheHostAndUpload) {
    const auto torus = solids::torus({0, 0, 0}, 1.0f, 0.4f, 64);
    for (BakeMethod m : {BakeMethod::Peel, BakeMethod::Cpu}) {
        BakeOptions o;
        o.resolution = 48;
        o.method = m;
        SCOPED_TRACE(toString(m));
        expectSameAsHostBake(torus.mesh, o);
    }
}

TEST_F(GpuBakeTest, KeepsOnlyThePartsAskedFor) {
    const auto sphere = solids::sphere({0, 0, 0}, 1.0f, 48);
    BakeOptions o;
    o.resolution = 32;
    const GpuBake columns = bakeToGpu(gl(), sphere.mesh, o, GpuSpriteParts::ColumnsOnly);
    EXPECT_FALSE(bool(columns.sprite.texture()));
    EXPECT_TRUE(bool(columns.sprite.offsets()));
    EXPECT_EQ(columns.sprite.size(), glm::uvec3(32, 32, 2));
    const GpuBake texture = bakeToGpu(gl(), sphere.mesh, o, GpuSpriteParts::TextureOnly);
    EXPECT_TRUE(bool(texture.sprite.texture()));
    EXPECT_FALSE(bool(texture.sprite.offsets()));
    EXPECT_EQ(texture.depthComplexity, 2u);
}

TEST_F(GpuBakeTest, TimesTheTextureFillAndNoReadBack) {
    const auto torus = solids::torus({0, 0, 0}, 1.0f, 0.4f, 64);
    BakeTimings t;
    BakeOptions o;
    o.resolution = 64;
    o.timings = &t;
    const GpuBake baked = bakeToGpu(gl(), torus.mesh, o);
    EXPECT_EQ(t[BakePhase::TextureFill].runs, 1u);
    EXPECT_EQ(t[BakePhase::ReadBack].runs, 0u);
    EXPECT_EQ(t[BakePhase::Assembly].runs, 1u); // the GpuSprite made (its boundary, if open), nothing read back
    EXPECT_EQ(t[BakePhase::Raster].runs, 1u);
    EXPECT_EQ(t.crossings, baked.crossings);
    EXPECT_GT(t.wallSeconds, 0.0);
}

TEST_F(GpuBakeTest, InvalidMeshesThrowAsBakeDoes) {
    TriangleMesh empty;
    EXPECT_THROW(bakeToGpu(gl(), empty, {}), InvalidMesh);
}

// The auto axis counted in the GL bakers' own raster (chooseViewAxisOnGl,
// what bakeOnGl counts on a GPU): its layers and crossings per axis are
// those of the fragment-list sprites, and the axis the fewest layers'.
TEST_F(GpuBakeTest, AxisCountedInTheRasterEqualsTheListsBakes) {
    const std::vector<TriangleMesh> meshes = {
        solids::torusKnot({0, 0, 0}, 1.0f, 2, 3, 0.25f, 96, 12).mesh,
        solids::merge(solids::sphere({0, 0, 0}, 1.0f, 24).mesh, solids::box({1.5f, -0.2f, -2.0f}, {1.6f, 0.2f, 2.0f}).mesh)};
    for (const TriangleMesh& mesh : meshes)
        for (std::uint32_t resolution : {31u, 96u}) {
            const AxisChoice choice = chooseViewAxisOnGl(gl(), mesh, resolution);
            EXPECT_EQ(choice.resolution, resolution);
            std::uint32_t fewest = ~0u;
            for (Axis axis : {Axis::X, Axis::Y, Axis::Z}) {
                BakeOptions o;
                o.resolution = resolution;
                o.axis = axis;
                o.method = BakeMethod::Lists;
                const Sprite sprite = bakeOnGl(gl(), mesh, o);
                EXPECT_EQ(choice.layers[std::size_t(axis)], sprite.depthComplexity) << toString(axis) << " " << resolution;
                EXPECT_EQ(choice.crossings[std::size_t(axis)], sprite.crossings.size()) << toString(axis);
                fewest = std::min(fewest, sprite.depthComplexity);
            }
            EXPECT_EQ(choice.layers[std::size_t(choice.axis)], fewest);
        }
}

// VDS_AXIS_COUNT=gpu for a scope: the GL bakes count the axis on llvmpipe's
// GPU path as on a GPU.
class AxisCountOnGpu {
public:
    AxisCountOnGpu() { setenv("VDS_AXIS_COUNT", "gpu", 1); }
    ~AxisCountOnGpu() { unsetenv("VDS_AXIS_COUNT"); }
    AxisCountOnGpu(const AxisCountOnGpu&) = delete;
    AxisCountOnGpu& operator=(const AxisCountOnGpu&) = delete;
};

// Where the GPU counts the axis, bakeToGpu and bake() on GL issue the count
// before validating and validate while the GPU draws: the axis and the
// sprite are the sequential bake's (count after validation), also where an
// unused vertex lies outside the used box (counted again in validation's
// bounds), and a mesh that cannot be drawn (an index out of range, a
// coordinate not finite) is refused by validation with the same message.
TEST_F(GpuBakeTest, AxisCountedBesideValidationIsTheSequentialBakes) {
    const AxisCountOnGpu onGpu;
    // A 1 x 2 x 3 box: two layers along each axis, the fewest crossings
    // along y (its 3 x 1 side fills the least of its square view). An unused
    // vertex at y = 10 would make z's the fewest in the box it stretches.
    TriangleMesh outlier = solids::box({0, 0, 0}, {1, 2, 3}).mesh;
    outlier.positions.push_back({0.0f, 10.0f, 0.0f});
    ASSERT_EQ(chooseViewAxisOnGl(gl(), outlier, 80).axis, Axis::Y);
    const std::vector<TriangleMesh> meshes = {
        solids::torusKnot({0, 0, 0}, 1.0f, 2, 3, 0.25f, 96, 12).mesh,
        solids::merge(solids::sphere({0, 0, 0}, 1.0f, 24).mesh, solids::box({1.5f, -0.2f, -2.0f}, {1.6f, 0.2f, 2.0f}).mesh),
        outlier};
    for (const TriangleMesh& mesh : meshes) {
        BakeTimings t;
        BakeOptions o;
        o.resolution = 80;
        o.method = BakeMethod::Lists;
        expectSameAsHostBake(mesh, o);
        // bake() on GL validates beside the count too: its sprite is the one
        // along the axis the sequential count chooses.
        BakeOptions fixed = o;
        fixed.axis = chooseViewAxisOnGl(gl(), mesh, o.resolution).axis;
        const Sprite sequential = bake(gl(), mesh, fixed), overlapped = bake(gl(), mesh, o);
        EXPECT_EQ(overlapped.grid.axis, *fixed.axis);
        EXPECT_EQ(overlapped.offsets, sequential.offsets);
        EXPECT_EQ(overlapped.crossings, sequential.crossings);
        o.timings = &t;
        const GpuBake baked = bakeToGpu(gl(), mesh, o);
        EXPECT_EQ(baked.grid.axis, *fixed.axis);
        EXPECT_EQ(t[BakePhase::Axis].runs, 2u); // issued, then read back (or counted again)
        EXPECT_EQ(t[BakePhase::Validation].runs, 1u);
    }
    TriangleMesh badIndex = meshes[0], notFinite = meshes[0];
    badIndex.triangles[5].y = std::uint32_t(badIndex.positions.size());
    notFinite.positions[3].x = std::nanf("");
    for (const TriangleMesh& mesh : {badIndex, notFinite}) {
        std::string onGpuMessage, onCpuMessage;
        try {
            bakeToGpu(gl(), mesh, {});
        } catch (const InvalidMesh& e) {
            onGpuMessage = e.what();
        }
        setenv("VDS_AXIS_COUNT", "cpu", 1);
        try {
            bakeToGpu(gl(), mesh, {});
        } catch (const InvalidMesh& e) {
            onCpuMessage = e.what();
        }
        setenv("VDS_AXIS_COUNT", "gpu", 1);
        EXPECT_FALSE(onGpuMessage.empty());
        EXPECT_EQ(onGpuMessage, onCpuMessage);
    }
}

// Past 256 MiB for the three axes' counts at once (4,800 texels a side of
// a cubic box: 3 x 88 MiB), the GL count takes one buffer, axis after axis;
// its layers and choice are the CPU's there as at 1,200 texels (three
// buffers at once).
TEST_F(GpuBakeTest, AxisCountsOfLargeImagesShareOneBuffer) {
    const TriangleMesh mesh =
        solids::merge(solids::box({0, 0, 0}, {1, 2, 3}).mesh, solids::box({2.5f, 2.5f, 2.5f}, {3, 3, 3}).mesh);
    for (std::uint32_t resolution : {1200u, 4800u}) {
        const AxisChoice choice = chooseViewAxisOnGl(gl(), mesh, resolution);
        const AxisChoice cpu = chooseViewAxis(mesh, resolution);
        EXPECT_EQ(choice.layers, cpu.layers) << resolution;
        EXPECT_EQ(choice.axis, cpu.axis) << resolution;
    }
}

} // namespace
} // namespace vds
