// Transmittance shadows (Eisemann & Décoret 2006, section 3.1; Chang et al.
// 2014, section 4; a VDS's exact path lengths): the GPU images against the
// CPU references on the same representation, and the representations
// against exact ray-mesh crossings.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include <vds/all.h>
#include <vds/bake.h>
#include <vds/error.h>
#include <vds/eval/image.h>
#include <vds/voxel/transmittance.h>
#include "solids.h"

#include "../support/gl_fixture.h"
#include "../support/image_compare.h"

namespace vds::voxel {
namespace {

class TransmittanceTest : public vds::test::GlTest {};

// Casters over a ground plane y = 0: a sphere (2 surfaces), a hollow shell
// (4), a box (2), lit from above at a slant.
TriangleMesh scene() {
    TriangleMesh m = solids::sphere({-0.9f, 1.2f, -0.6f}, 0.55f, 32).mesh;
    m = solids::merge(m, solids::shell({0.8f, 1.3f, 0.5f}, 0.6f, 0.35f, 32).mesh);
    m = solids::merge(m, solids::box({-0.4f, 0.8f, 0.7f}, {0.2f, 1.5f, 1.2f}).mesh);
    return m;
}

const glm::vec3 kLight(0.35f, -1.0f, 0.25f);

ReceiverPlane ground(std::uint32_t size) {
    ReceiverPlane plane;
    plane.origin = {-2.2f, 0.0f, -2.2f};
    plane.u = {4.4f, 0.0f, 0.0f};
    plane.v = {0.0f, 0.0f, 4.4f};
    plane.width = plane.height = size;
    return plane;
}

eval::Image toImage(const std::vector<float>& values, std::uint32_t w, std::uint32_t h) {
    eval::Image image(w, h);
    for (std::size_t k = 0; k < values.size(); ++k) {
        const auto g = std::uint8_t(std::lround(std::clamp(values[k], 0.0f, 1.0f) * 255.0f));
        for (int c = 0; c < 3; ++c) image.rgba[4 * k + std::size_t(c)] = g;
        image.rgba[4 * k + 3] = 255;
    }
    return image;
}

// Pixels whose quantities differ by more than `tolerance`.
std::size_t differing(const TransmittanceImage& a, const TransmittanceImage& b, float tolerance) {
    std::size_t n = 0;
    for (std::size_t k = 0; k < a.quantity.size(); ++k) n += std::fabs(a.quantity[k] - b.quantity[k]) > tolerance;
    return n;
}

TEST(LightFrameTest, RotatesTheLightOntoZ) {
    const LightFrame f = makeLightFrame(kLight);
    const glm::vec3 d = f.toLightSpace(kLight);
    EXPECT_NEAR(d.x, 0.0f, 1e-6f);
    EXPECT_NEAR(d.y, 0.0f, 1e-6f);
    EXPECT_NEAR(d.z, glm::length(kLight), 1e-6f);
    const glm::mat3 m = f.toLight * glm::transpose(f.toLight);
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) EXPECT_NEAR(m[i][j], i == j ? 1.0f : 0.0f, 1e-6f);
    EXPECT_GT(glm::determinant(f.toLight), 0.0f); // a rotation: orientation (entering faces) kept
    // Along z already: the identity.
    const LightFrame z = makeLightFrame({0, 0, 2});
    EXPECT_EQ(z.toLightSpace({1, 2, 3}), glm::vec3(1, 2, 3));
    EXPECT_THROW(makeLightFrame({0, 0, 0}), InvalidArgument);
    EXPECT_THROW(makeLightFrame({NAN, 0, 1}), InvalidArgument);
}

TEST(ExactCrossingsTest, BoxAndSphereAnalytic) {
    const TriangleMesh box = solids::box({-1, -1, -1}, {1, 1, 1}).mesh;
    ExactCrossings c = exactCrossingsInFront(box, {0.3f, 0.2f, 5.0f});
    EXPECT_EQ(c.surfaces, 2u);
    EXPECT_DOUBLE_EQ(c.thickness, 2.0);
    c = exactCrossingsInFront(box, {0.3f, 0.2f, 0.25f});
    EXPECT_EQ(c.surfaces, 1u);
    EXPECT_DOUBLE_EQ(c.thickness, 1.25);
    c = exactCrossingsInFront(box, {0.3f, 0.2f, -3.0f});
    EXPECT_EQ(c.surfaces, 0u);
    EXPECT_EQ(exactCrossingsInFront(box, {1.5f, 0.2f, 5.0f}).surfaces, 0u);

    const solids::Solid shell = solids::shell({0, 0, 0}, 1.0f, 0.5f, 64);
    const float rho = 0.2f; // a chord through both spheres: outer minus inner
    c = exactCrossingsInFront(shell.mesh, {rho, 0.0f, 4.0f}); // on meridian edges: the tie rule
    EXPECT_EQ(c.surfaces, 4u);
    const double chord = 2.0 * std::sqrt(1.0 - rho * rho) - 2.0 * std::sqrt(0.25 - rho * rho);
    EXPECT_NEAR(c.thickness, chord, 4.0 * shell.tessellationError);
}

TEST(TransmittanceOfTest, Formulas) {
    TransmittanceParameters p;
    p.sigma = 0.25f;
    p.extinction = 2.0f;
    EXPECT_FLOAT_EQ(transmittanceOf(TransmittanceSource::SlicemapSurfaces, 0, p), 1.0f);
    EXPECT_FLOAT_EQ(transmittanceOf(TransmittanceSource::SlicemapSurfaces, 3, p), 0.421875f);
    EXPECT_FLOAT_EQ(transmittanceOf(TransmittanceSource::VoxelAbsorption, 1.5, p), float(std::exp(-1.5)));
    EXPECT_FLOAT_EQ(transmittanceOf(TransmittanceSource::SpriteThickness, 0.5, p), float(std::exp(-1.0)));
}

// Limits for GPU images against the CPU reference on the same
// representation: the same arithmetic, so every pixel agrees but for
// receivers exactly on a column or slice boundary, where the GL's division
// in the pixel-to-plane mapping may round the other way.
constexpr int kSameMaxDelta = 1;       // 8-bit grey levels
constexpr double kSameMeanDelta = 0.02; // grey levels, mean over every channel

void expectSameImage(const TransmittanceImage& gpu, const TransmittanceImage& cpu, float quantityTolerance) {
    const std::size_t off = differing(gpu, cpu, quantityTolerance);
    const test::ImageDelta d =
        test::compareImages(toImage(gpu.transmittance, gpu.width, gpu.height), toImage(cpu.transmittance, cpu.width, cpu.height));
    std::printf("GPU vs CPU: %zu of %zu quantities differ by more than %g; image max %d, mean %.4f\n", off,
                gpu.quantity.size(), double(quantityTolerance), d.max, d.mean);
    EXPECT_LE(off, gpu.quantity.size() / 500);
    EXPECT_LE(d.max, kSameMaxDelta);
    EXPECT_LE(d.mean, kSameMeanDelta);
}

TEST_F(TransmittanceTest, SlicemapSurfacesMatchTheCpuAndTheExactCount) {
    const TriangleMesh world = scene();
    const LightFrame frame = makeLightFrame(kLight);
    const TriangleMesh light = toLightSpace(world, frame);
    const ReceiverPlane plane = ground(96);
    TransmittanceParameters params;
    params.sigma = 0.3f;
    const TransmittanceImage exact = transmittanceOnCpu(plane, frame, TransmittanceSource::SlicemapSurfaces, params,
                                                        [&](const glm::vec3& p) {
                                                            return double(exactCrossingsInFront(light, p).surfaces);
                                                        });
    for (Slicing slicing : {Slicing::Uniform, Slicing::Local}) {
        SCOPED_TRACE(toString(slicing));
        SlicemapOptions o;
        o.slicing = slicing;
        const Slicemap map = buildSlicemap(gl(), light, meshBounds(light), 96, o);
        const TransmittanceImage gpu =
            renderTransmittance(gl(), GpuTransmittanceCaster(map), frame, plane, params);
        const TransmittanceImage cpu = transmittanceOnCpu(
            plane, frame, TransmittanceSource::SlicemapSurfaces, params,
            [&](const glm::vec3& p) { return double(slicemapSurfacesInFront(map, p)); });
        expectSameImage(gpu, cpu, 0.0f);
        // Against the exact count: receivers far behind the casters see every
        // surface, so the count differs only where the column centre and the
        // receiver fall on different sides of a silhouette (a column wide).
        EXPECT_LE(differing(cpu, exact, 0.0f), cpu.quantity.size() / 100);
        const test::ImageDelta d = test::compareImages(toImage(cpu.transmittance, 96, 96),
                                                       toImage(exact.transmittance, 96, 96));
        std::printf("%s slicemap vs exact count: %zu of %zu pixels differ; image max %d, mean %.3f\n",
                    toString(slicing), differing(cpu, exact, 0.0f), cpu.quantity.size(), d.max, d.mean);
        EXPECT_LE(d.mean, 2.0);
        // Somewhere the shell's four surfaces are seen: (1 - 0.3)^4.
        EXPECT_NEAR(*std::min_element(cpu.transmittance.begin(), cpu.transmittance.end()), std::pow(0.7f, 4.0f),
                    1e-5f);
    }
}

TEST_F(TransmittanceTest, VoxelAbsorptionMatchesTheCpu) {
    const TriangleMesh world = scene();
    const LightFrame frame = makeLightFrame(kLight);
    const TriangleMesh light = toLightSpace(world, frame);
    const ReceiverPlane plane = ground(96);
    SlicingOptions so;
    so.absorptionPerFragment = 0.2f;
    const SlicedVoxels voxels = voxelizeSlices(gl(), light, makeVoxelGrid(meshBounds(light), 64), so);
    const TransmittanceImage gpu = renderTransmittance(gl(), GpuTransmittanceCaster(voxels), frame, plane, {});
    const TransmittanceImage cpu = transmittanceOnCpu(plane, frame, TransmittanceSource::VoxelAbsorption, {},
                                                      [&](const glm::vec3& p) { return absorptionInFront(voxels, p); });
    expectSameImage(gpu, cpu, 1e-4f);
    // Each surface crossing leaves about one fragment in its column (two
    // where it lies in two slabs' shared boundary); the shell's four give at
    // least 4 * 0.2.
    EXPECT_GE(*std::max_element(cpu.quantity.begin(), cpu.quantity.end()), 0.8f - 1e-5f);
}

TEST_F(TransmittanceTest, SpriteThicknessMatchesTheCpuAndTheExactPathLength) {
    const TriangleMesh world = scene();
    const LightFrame frame = makeLightFrame(kLight);
    const TriangleMesh light = toLightSpace(world, frame);
    const ReceiverPlane plane = ground(96);
    BakeOptions bo;
    bo.resolution = 128;
    bo.axis = Axis::Z;
    const Sprite sprite = bake(gl(), light, bo);
    TransmittanceParameters params;
    params.extinction = 1.5f;
    const TransmittanceImage gpu = renderTransmittance(gl(), GpuTransmittanceCaster(sprite), frame, plane, params);
    const TransmittanceImage cpu = transmittanceOnCpu(plane, frame, TransmittanceSource::SpriteThickness, params,
                                                      [&](const glm::vec3& p) { return spriteThicknessInFront(sprite, p); });
    expectSameImage(gpu, cpu, 1e-5f);
    const TransmittanceImage exact =
        transmittanceOnCpu(plane, frame, TransmittanceSource::SpriteThickness, params,
                           [&](const glm::vec3& p) { return exactCrossingsInFront(light, p).thickness; });
    // Exact along the light; across it the column centre stands for the
    // receiver, up to half a texel (0.012 units) away, so where the surfaces
    // are slanted to the light the length is that of a ray beside it.
    double mean = 0.0, largest = 0.0;
    for (std::size_t k = 0; k < cpu.quantity.size(); ++k) {
        const double e = std::fabs(cpu.quantity[k] - exact.quantity[k]);
        mean += e;
        largest = std::max(largest, e);
    }
    mean /= double(cpu.quantity.size());
    const test::ImageDelta d =
        test::compareImages(toImage(gpu.transmittance, 96, 96), toImage(exact.transmittance, 96, 96));
    std::printf("sprite vs exact path length: mean %.5f, max %.4f units; image max %d, mean %.3f\n", mean, largest,
                d.max, d.mean);
    EXPECT_LE(mean, 0.01);
    EXPECT_LE(d.mean, 1.0);
}

// Receivers among the casters (a plane through the shell and the box, across
// the light): the slicemap counts to a slice, the sprite is exact along the
// light.
TEST_F(TransmittanceTest, ReceiversAmongTheCasters) {
    const TriangleMesh world = scene();
    const LightFrame frame = makeLightFrame(kLight);
    const TriangleMesh light = toLightSpace(world, frame);
    ReceiverPlane plane;
    plane.origin = {-2.2f, 0.5f, 0.5f};
    plane.u = {4.4f, 0.0f, 0.0f};
    plane.v = {0.0f, 1.5f, 0.0f};
    plane.width = 96;
    plane.height = 48;
    TransmittanceParameters params;
    const auto exactSurfaces = [&](const glm::vec3& p) { return double(exactCrossingsInFront(light, p).surfaces); };
    const auto exactThickness = [&](const glm::vec3& p) { return exactCrossingsInFront(light, p).thickness; };
    const TransmittanceImage surfaces =
        transmittanceOnCpu(plane, frame, TransmittanceSource::SlicemapSurfaces, params, exactSurfaces);
    const TransmittanceImage thickness =
        transmittanceOnCpu(plane, frame, TransmittanceSource::SpriteThickness, params, exactThickness);

    SlicemapOptions o;
    o.slicing = Slicing::Local;
    const Slicemap map = buildSlicemap(gl(), light, meshBounds(light), 96, o);
    const TransmittanceImage fromMap = renderTransmittance(gl(), GpuTransmittanceCaster(map), frame, plane, params);
    BakeOptions bo;
    bo.resolution = 96;
    bo.axis = Axis::Z;
    const TransmittanceImage fromSprite =
        renderTransmittance(gl(), GpuTransmittanceCaster(bake(gl(), light, bo)), frame, plane, params);
    double countError = 0.0, lengthError = 0.0;
    for (std::size_t k = 0; k < surfaces.quantity.size(); ++k) {
        countError += std::fabs(fromMap.quantity[k] - surfaces.quantity[k]);
        lengthError += std::fabs(fromSprite.quantity[k] - thickness.quantity[k]);
    }
    countError /= double(surfaces.quantity.size());
    lengthError /= double(surfaces.quantity.size());
    std::printf("receivers among the casters: slicemap count off by %.4f surfaces, sprite length by %.5f units "
                "(means)\n", countError, lengthError);
    // A receiver within a slice of a surface may count it or not: a few percent of the receivers.
    EXPECT_LE(countError, 0.05);
    EXPECT_LE(lengthError, 0.01);
}

// E&D's foliage: open leaves. The slicemap pair needs closed casters (its
// inner-voxel rule does), so leaves go in double-sided, and each counts as a
// front and a back surface; the slicing voxelization takes them as they are,
// one fragment per leaf and column.
TEST_F(TransmittanceTest, LeavesCountPerLeaf) {
    const float depths[3] = {0.15f, 0.35f, 0.6f};
    TriangleMesh oneSided, twoSided;
    for (float z : depths) {
        for (TriangleMesh* m : {&oneSided, &twoSided}) {
            const auto b = std::uint32_t(m->positions.size());
            m->positions.insert(m->positions.end(), {{0, 0, z}, {1, 0, z}, {1, 1, z}, {0, 1, z}});
            m->triangles.push_back({b, b + 1, b + 2});
            m->triangles.push_back({b, b + 2, b + 3});
            if (m == &twoSided) {
                m->triangles.push_back({b, b + 2, b + 1});
                m->triangles.push_back({b, b + 3, b + 2});
            }
        }
    }
    const Box box{{-0.5f, -0.5f, 0.0f}, {1.5f, 1.5f, 1.0f}};
    const Slicemap map = buildSlicemap(gl(), twoSided, box, 16);
    EXPECT_EQ(slicemapSurfacesInFront(map, {0.5f, 0.5f, 0.9f}), 6u);
    EXPECT_EQ(slicemapSurfacesInFront(map, {0.5f, 0.5f, 0.45f}), 4u);
    EXPECT_EQ(slicemapSurfacesInFront(map, {0.5f, 0.5f, 0.05f}), 0u);
    EXPECT_EQ(slicemapSurfacesInFront(map, {1.3f, 0.5f, 0.9f}), 0u);
    SlicingOptions so;
    so.absorptionPerFragment = 0.25f;
    const SlicedVoxels voxels = voxelizeSlices(gl(), oneSided, makeVoxelGrid(box, 16), so);
    EXPECT_FLOAT_EQ(absorptionInFront(voxels, {0.5f, 0.5f, 0.9f}), 0.75f);
    EXPECT_FLOAT_EQ(absorptionInFront(voxels, {0.5f, 0.5f, 0.45f}), 0.5f);

    // The same through the GPU, on a plane behind the leaves (light along +z).
    const LightFrame frame = makeLightFrame({0, 0, 1});
    ReceiverPlane plane;
    plane.origin = {-0.5f, -0.5f, 0.9f};
    plane.u = {2.0f, 0.0f, 0.0f};
    plane.v = {0.0f, 2.0f, 0.0f};
    plane.width = plane.height = 16;
    TransmittanceParameters params;
    params.sigma = 0.5f;
    const TransmittanceImage image = renderTransmittance(gl(), GpuTransmittanceCaster(map), frame, plane, params);
    EXPECT_EQ(image.quantity[8 * 16 + 8], 6.0f); // (0.5625, 0.5625)
    // pow(1 - sigma, 6) on the GPU: GLSL gives pow exp2's precision, 3 + 2|x|
    // ulps at x = 6 log2(1 - sigma) = -6 (GLSL 4.30, section 4.7.1): NVIDIA's
    // driver gives 0.015625009, 5 ulps above 1/64.
    const float ulp = std::ldexp(1.0f, -6 - 23); // of floats in [2^-6, 2^-5)
    EXPECT_NEAR(image.transmittance[8 * 16 + 8], 1.0f / 64.0f, (3.0f + 2.0f * 6.0f) * ulp);
    EXPECT_EQ(image.quantity[0], 0.0f);
    EXPECT_EQ(image.transmittance[0], 1.0f);
}

TEST_F(TransmittanceTest, BadInput) {
    const TriangleMesh box = solids::box({0, 0, 0}, {1, 1, 1}).mesh;
    BakeOptions bo;
    bo.resolution = 16;
    bo.axis = Axis::X;
    const Sprite sideways = bake(gl(), box, bo);
    EXPECT_THROW(GpuTransmittanceCaster{sideways}, InvalidArgument);
    EXPECT_THROW(spriteThicknessInFront(sideways, {0.5f, 0.5f, 0.5f}), InvalidArgument);
    bo.axis = Axis::Z;
    const GpuTransmittanceCaster caster{bake(gl(), box, bo)};
    ReceiverPlane empty;
    empty.width = 0;
    EXPECT_THROW(renderTransmittance(gl(), caster, makeLightFrame({0, 0, 1}), empty, {}), InvalidArgument);
}

} // namespace
} // namespace vds::voxel
