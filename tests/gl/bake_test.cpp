// The GL bakers on analytic solids: peeling and fragment lists must agree bit
// for bit, and the sprites must classify every point farther than two texels
// from the ideal surface as the analytic solid does.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>

#include <gtest/gtest.h>

#include <vds/all.h>
#include <vds/bake.h>
#include <vds/error.h>
#include <vds/gl/bake.h>
#include "solids.h"

#include "../support/gl_fixture.h"
#include "points.h"

namespace vds {
namespace {

using test::GlTest;

Sprite bakeWith(GlContext& gl, const TriangleMesh& mesh, BakeMethod method, std::uint32_t resolution,
                Axis axis = Axis::Z, std::uint64_t maxNodes = 0) {
    BakeOptions o;
    o.method = method;
    o.resolution = resolution;
    o.axis = axis;
    GlBakeOptions glOptions;
    glOptions.maxListNodes = maxNodes;
    return bakeOnGl(gl, mesh, o, glOptions);
}

void expectIdentical(const Sprite& a, const Sprite& b) {
    ASSERT_EQ(a.width(), b.width());
    ASSERT_EQ(a.height(), b.height());
    EXPECT_EQ(a.depthComplexity, b.depthComplexity);
    ASSERT_EQ(a.offsets, b.offsets);
    ASSERT_EQ(a.crossings.size(), b.crossings.size());
    EXPECT_EQ(0, std::memcmp(a.crossings.data(), b.crossings.data(), a.crossings.size() * sizeof(float)))
        << "crossings differ";
}

// Every point whose distance to the ideal surface exceeds two texel
// diagonals plus the tessellation error is classified as the ideal solid.
void expectAnalytic(const Sprite& sprite, const solids::Solid& solid, Rule rule, std::size_t n = 20000) {
    const float margin = 2.0f * std::sqrt(3.0f) * sprite.grid.texelSize + solid.tessellationError;
    const auto points = test::randomPoints(sprite.grid.box, n, 0.1f, 7);
    std::size_t checked = 0, wrong = 0;
    for (const auto& p : points) {
        const float d = solid.distance(p);
        if (std::fabs(d) <= margin) continue;
        ++checked;
        if (sprite.contains(p, rule) != (d < 0.0f)) ++wrong;
    }
    EXPECT_GT(checked, n / 2);
    EXPECT_EQ(wrong, 0u) << "of " << checked << " points far from the surface";
}

class BakeTest : public GlTest {};

TEST_F(BakeTest, BoxColumnsHoldOneEnteringAndOneLeavingCrossing) {
    const auto box = solids::box({-1, -2, -0.5f}, {1, 1, 0.5f});
    for (BakeMethod m : {BakeMethod::Peel, BakeMethod::Lists}) {
        const Sprite s = bakeWith(gl(), box.mesh, m, 64);
        EXPECT_EQ(s.depthComplexity, 2u);
        EXPECT_EQ(s.status, SolidStatus::Closed);
        for (std::uint32_t j = 0; j < s.height(); ++j)
            for (std::uint32_t i = 0; i < s.width(); ++i) {
                const std::size_t c = std::size_t(j) * s.width() + i;
                const glm::vec3 centre = s.grid.texelCentre(i, j, 0.5f);
                const bool covered = centre.x < 1.0f && centre.y < 1.0f;
                ASSERT_EQ(s.offsets[c + 1] - s.offsets[c], covered ? 2u : 0u) << "column " << i << "," << j;
                if (!covered) continue;
                const float front = s.crossings[s.offsets[c]], back = s.crossings[s.offsets[c] + 1];
                EXPECT_TRUE(crossingEnters(front));
                EXPECT_FALSE(crossingEnters(back));
                EXPECT_EQ(crossingDepth(front), 0.0f);
                EXPECT_EQ(crossingDepth(back), 1.0f);
            }
    }
}

TEST_F(BakeTest, PeelingAndFragmentListsAgreeBitForBit) {
    const auto torus = solids::torus({0.1f, 0.2f, 0.3f}, 1.0f, 0.35f, 96);
    const auto shell = solids::shell({0, 0, 0}, 1.0f, 0.6f, 64);
    for (const TriangleMesh* mesh : {&torus.mesh, &shell.mesh})
        for (Axis axis : {Axis::X, Axis::Y, Axis::Z})
            expectIdentical(bakeWith(gl(), *mesh, BakeMethod::Peel, 96, axis),
                            bakeWith(gl(), *mesh, BakeMethod::Lists, 96, axis));
}

TEST_F(BakeTest, FragmentListsOverflowRetriesInBandsWithoutLosingCrossings) {
    const auto shell = solids::shell({0, 0, 0}, 1.0f, 0.6f, 48);
    const Sprite whole = bakeWith(gl(), shell.mesh, BakeMethod::Lists, 80);
    const Sprite banded = bakeWith(gl(), shell.mesh, BakeMethod::Lists, 80, Axis::Z, 700);
    expectIdentical(whole, banded);
    EXPECT_EQ(whole.depthComplexity, 4u);
}

// Twenty boxes stacked along the view: columns of 40 crossings, 38 of them
// through the node pool and sorted in place on the GPU (columns of one or
// two take another path); the pool kept from earlier bakes is freed first,
// so that it must grow.
TEST_F(BakeTest, DeepColumnsGrowThePoolAndSortLikePeeling) {
    TriangleMesh stack = solids::box({0, 0, 0}, {1, 1, 0.02f}).mesh;
    for (int k = 1; k < 20; ++k)
        stack = solids::merge(stack, solids::box({0.03f * float(k), 0, 0.05f * float(k)},
                                                 {1, 1 - 0.02f * float(k), 0.05f * float(k) + 0.02f}).mesh);
    gl().releaseScratch();
    BakeTimings timings;
    BakeOptions o;
    o.method = BakeMethod::Lists;
    o.axis = Axis::Z;
    o.resolution = 48;
    o.timings = &timings;
    const Sprite lists = bake(gl(), stack, o);
    EXPECT_EQ(lists.depthComplexity, 40u);
    EXPECT_EQ(timings[BakePhase::Raster].runs, 2u) << "the pool should have grown once";
    std::size_t pooled = 0; // the first two crossings of a column have places of their own
    for (std::size_t c = 0; c + 1 < lists.offsets.size(); ++c)
        pooled += std::max<std::uint32_t>(lists.offsets[c + 1] - lists.offsets[c], 2) - 2;
    EXPECT_EQ(timings.listNodes, pooled) << "grown to the exact need";
    EXPECT_EQ(timings.bands, 1u);
    expectIdentical(bakeWith(gl(), stack, BakeMethod::Peel, 48), lists);
}

// 512 x 512 columns take a prefix sum of four levels (64 values a chunk).
TEST_F(BakeTest, LargeImagesScanInSeveralLevelsLikePeeling) {
    const auto sphere = solids::sphere({0, 0, 0}, 1.0f, 64);
    expectIdentical(bakeWith(gl(), sphere.mesh, BakeMethod::Peel, 512),
                    bakeWith(gl(), sphere.mesh, BakeMethod::Lists, 512));
}

TEST_F(BakeTest, TimingsNameEveryPhaseOfEachBaker) {
    const auto torus = solids::torus({0, 0, 0}, 1.0f, 0.4f, 64);
    BakeTimings t;
    BakeOptions o;
    o.resolution = 64;
    o.timings = &t;
    o.method = BakeMethod::Lists;
    const Sprite lists = bake(gl(), torus.mesh, o);
    for (BakePhase p : {BakePhase::Validation, BakePhase::Upload, BakePhase::Raster, BakePhase::Scan, BakePhase::Sort,
                        BakePhase::ReadBack, BakePhase::Assembly}) {
        EXPECT_EQ(t[p].runs, 1u) << toString(p);
        EXPECT_GT(t[p].wallSeconds, 0.0) << toString(p);
    }
    EXPECT_EQ(t[BakePhase::TextureFill].runs, 0u);
    EXPECT_EQ(t.crossings, lists.crossings.size());
    EXPECT_EQ(t.renderer, gl().info().renderer);
    EXPECT_EQ(t.bands, 1u);
    EXPECT_GE(t.wallSeconds, t[BakePhase::Raster].wallSeconds + t[BakePhase::Sort].wallSeconds);
    EXPECT_NE(t.report().find("read-back"), std::string::npos) << t.report();

    o.method = BakeMethod::Peel;
    const Sprite peel = bake(gl(), torus.mesh, o);
    EXPECT_EQ(t[BakePhase::Raster].runs, peel.depthComplexity + 1) << "one pass per layer and one that finds none";
    EXPECT_EQ(t[BakePhase::ReadBack].runs, peel.depthComplexity);
    EXPECT_EQ(t[BakePhase::Sort].runs, 0u) << "the timings of the lists bake must be reset";

    o.method = BakeMethod::Cpu;
    bake(gl(), torus.mesh, o);
    EXPECT_EQ(t[BakePhase::Raster].runs, 1u);
    EXPECT_TRUE(t.renderer.empty());
    EXPECT_LT(t[BakePhase::Raster].gpuSeconds, 0.0) << "the CPU baker measures no GPU time";
}

// The exact CPU baker and the GL bakers, layer for layer. The rasterizer
// snaps vertex positions to 2^-b texel (b = GL_SUBPIXEL_BITS: 4 at least, 8
// on NVIDIA and llvmpipe), so:
//  - at a texel centre within 2^-b texel of a silhouette the two may see 0
//    and 2 crossings (an even difference), and where a centre lies on a
//    shared edge they may pick the other triangle of the edge (same depth,
//    same facing): a handful of such columns;
//  - each snapped vertex moves by at most 2^-(b+1) texel along s and t, so a
//    plane of depth slope g (depth units per texel, along s plus along t)
//    shifts by at most g * 2^-(b+1) at the centre; the GPU then interpolates
//    depth in float (a few ulps of 1 in [0,1]). The bound per crossing is
//    therefore g * 2^-(b+1) + 2^-18, with g estimated from the exact sprite as
//    the largest depth step to a neighbouring column at the same layer,
//    doubled. That estimate fails only where the neighbours lie on another
//    sheet or another triangle of very different slope: at most 0.5% of
//    crossings may exceed it, and none may be off by more than 2^-b times the
//    box depth per texel of the steepest triangle (here: 1e-2).
TEST_F(BakeTest, CpuBakerMatchesTheGlBakersLayerForLayer) {
    GLint subpixelBits = 0;
    glGetIntegerv(GL_SUBPIXEL_BITS, &subpixelBits);
    ASSERT_GE(subpixelBits, 4);
    const float snap = std::ldexp(1.0f, -(subpixelBits + 1));
    const auto torus = solids::torus({0.1f, 0.2f, 0.3f}, 1.0f, 0.35f, 96);
    const auto shell = solids::shell({0, 0, 0}, 1.0f, 0.6f, 64);
    const auto two = solids::overlappingBoxes({-1, -1, -1}, {0.5f, 0.5f, 0.5f}, {-0.5f, -0.3f, -0.2f}, {1, 1, 1});
    for (const TriangleMesh* mesh : {&torus.mesh, &shell.mesh, &two.mesh})
        for (Axis axis : {Axis::X, Axis::Y, Axis::Z}) {
            BakeOptions o;
            o.resolution = 128;
            o.axis = axis;
            o.method = BakeMethod::Cpu;
            const Sprite cpu = bake(*mesh, o);
            const Sprite gpu = bakeWith(gl(), *mesh, BakeMethod::Lists, 128, axis);
            ASSERT_EQ(cpu.width(), gpu.width());
            ASSERT_EQ(cpu.height(), gpu.height());
            EXPECT_EQ(cpu.depthComplexity, gpu.depthComplexity);
            const std::uint32_t w = cpu.width(), h = cpu.height();
            const auto count = [&](std::uint32_t i, std::uint32_t j) {
                const std::size_t c = std::size_t(j) * w + i;
                return cpu.offsets[c + 1] - cpu.offsets[c];
            };
            const auto depthAt = [&](std::uint32_t i, std::uint32_t j, std::uint32_t k) {
                return crossingDepth(cpu.crossings[cpu.offsets[std::size_t(j) * w + i] + k]);
            };
            std::size_t countDiffers = 0, facingDiffers = 0, compared = 0, beyondBound = 0;
            float worstDepth = 0.0f;
            for (std::uint32_t j = 0; j < h; ++j)
                for (std::uint32_t i = 0; i < w; ++i) {
                    const std::size_t c = std::size_t(j) * w + i;
                    const std::uint32_t n = count(i, j), m = gpu.offsets[c + 1] - gpu.offsets[c];
                    if (n != m) {
                        ++countDiffers;
                        EXPECT_EQ((n + m) % 2, 0u) << "odd difference in column " << c;
                        continue;
                    }
                    for (std::uint32_t k = 0; k < n; ++k) {
                        const float a = cpu.crossings[cpu.offsets[c] + k], b = gpu.crossings[gpu.offsets[c] + k];
                        facingDiffers += crossingEnters(a) != crossingEnters(b);
                        const float d = std::fabs(crossingDepth(a) - crossingDepth(b));
                        float slopeS = 0.0f, slopeT = 0.0f;
                        const float here = crossingDepth(a);
                        if (i > 0 && count(i - 1, j) == n) slopeS = std::max(slopeS, std::fabs(depthAt(i - 1, j, k) - here));
                        if (i + 1 < w && count(i + 1, j) == n) slopeS = std::max(slopeS, std::fabs(depthAt(i + 1, j, k) - here));
                        if (j > 0 && count(i, j - 1) == n) slopeT = std::max(slopeT, std::fabs(depthAt(i, j - 1, k) - here));
                        if (j + 1 < h && count(i, j + 1) == n) slopeT = std::max(slopeT, std::fabs(depthAt(i, j + 1, k) - here));
                        const float bound = 2.0f * (slopeS + slopeT) * snap + std::ldexp(1.0f, -18);
                        worstDepth = std::max(worstDepth, d);
                        beyondBound += d > bound;
                        ++compared;
                    }
                }
            const std::size_t columns = cpu.offsets.size() - 1;
            EXPECT_LE(countDiffers, columns / 1000) << mesh->name << " along " << toString(axis);
            EXPECT_LE(facingDiffers, columns / 1000) << mesh->name << " along " << toString(axis);
            EXPECT_LE(beyondBound, compared / 200) << mesh->name << " along " << toString(axis);
            EXPECT_LT(worstDepth, 1e-2f) << mesh->name << " along " << toString(axis);
        }
}

TEST_F(BakeTest, SphereClassifiesLikeTheAnalyticSolid) {
    const auto sphere = solids::sphere({0.5f, -0.25f, 2.0f}, 1.5f, 128);
    for (Axis axis : {Axis::X, Axis::Y, Axis::Z}) {
        const Sprite s = bakeWith(gl(), sphere.mesh, BakeMethod::Lists, 128, axis);
        EXPECT_EQ(s.depthComplexity, 2u);
        expectAnalytic(s, sphere, Rule::Parity);
        expectAnalytic(s, sphere, Rule::Winding);
    }
}

TEST_F(BakeTest, TorusAndShellClassifyLikeTheAnalyticSolids) {
    const auto torus = solids::torus({0, 0, 0}, 1.0f, 0.4f, 128);
    const auto shell = solids::shell({0, 0, 0}, 1.0f, 0.5f, 96);
    const Sprite t = bakeWith(gl(), torus.mesh, BakeMethod::Peel, 160, Axis::X);
    EXPECT_EQ(t.depthComplexity, 4u); // seen from the side, a ray crosses both tubes
    expectAnalytic(t, torus, Rule::Parity);
    const Sprite s = bakeWith(gl(), shell.mesh, BakeMethod::Lists, 160);
    EXPECT_EQ(s.depthComplexity, 4u);
    expectAnalytic(s, shell, Rule::Parity);
    expectAnalytic(s, shell, Rule::Winding);
}

TEST_F(BakeTest, OverlappingBoxesNeedTheWindingRule) {
    const auto two = solids::overlappingBoxes({-1, -1, -1}, {0.5f, 0.5f, 0.5f}, {-0.5f, -0.5f, -0.5f}, {1, 1, 1});
    const Sprite s = bakeWith(gl(), two.mesh, BakeMethod::Lists, 64);
    EXPECT_EQ(s.depthComplexity, 4u);
    const glm::vec3 overlap(0.0f, 0.0f, 0.0f), onlyA(-0.8f, -0.8f, -0.8f), outside(0.9f, -0.9f, 0.0f);
    EXPECT_FALSE(s.contains(overlap, Rule::Parity)); // crossed twice: parity says outside
    EXPECT_TRUE(s.contains(overlap, Rule::Winding));
    EXPECT_TRUE(s.contains(onlyA, Rule::Parity));
    EXPECT_TRUE(s.contains(onlyA, Rule::Winding));
    EXPECT_FALSE(s.contains(outside, Rule::Winding));
    expectAnalytic(s, two, Rule::Winding);
}

TEST_F(BakeTest, SolidsSharingAnEdgeAreASolidDespiteTheNonManifoldEdge) {
    const auto touching = solids::boxesSharingAnEdge({-1.0f, -1.0f, -0.5f}, 1.0f);
    for (Axis axis : {Axis::X, Axis::Z}) {
        const Sprite s = bakeWith(gl(), touching.mesh, BakeMethod::Lists, 64, axis);
        EXPECT_EQ(s.status, SolidStatus::Closed);
        EXPECT_NE(s.validation.find("1 non-manifold edge"), std::string::npos) << s.validation;
        expectAnalytic(s, touching, Rule::Parity);
        expectAnalytic(s, touching, Rule::Winding);
    }
}

// Sliver-heavy open and non-manifold inputs: the GL rasterizer snaps vertices
// to its subpixel grid, so next to a boundary edge its count could jump where
// the snapped edge lies while the boundary term jumps at the exact one (the
// generalized winding number then off by one). Every column's net crossing
// count (entering minus leaving) must equal the exact CPU bake's, by both GL
// bakers.
TEST_F(BakeTest, OpenSoupsAndNonManifoldFansCountLikeTheCpuBaker) {
    std::vector<TriangleMesh> meshes;
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    for (int soup = 0; soup < 3; ++soup) { // slivers: one side far shorter than the others
        TriangleMesh m;
        for (std::uint32_t k = 0; k < 300; ++k) {
            const glm::vec3 a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng));
            const glm::vec3 c = b + 0.004f * glm::vec3(u(rng), u(rng), u(rng));
            m.positions.insert(m.positions.end(), {a, b, c});
            m.triangles.push_back({3 * k, 3 * k + 1, 3 * k + 2});
        }
        meshes.push_back(m);
    }
    for (int fan = 0; fan < 3; ++fan) { // pages on one spine, thin fans around one apex, welded
        TriangleMesh m;
        const glm::vec3 p0(u(rng), u(rng), u(rng)), p1(u(rng), u(rng), u(rng));
        m.positions = {p0, p1};
        for (std::uint32_t k = 0; k < 40; ++k) {
            m.positions.push_back(0.5f * (p0 + p1) + glm::vec3(u(rng), u(rng), u(rng)));
            const std::uint32_t tip = std::uint32_t(m.positions.size() - 1);
            m.triangles.push_back(k % 3 ? glm::uvec3(0, 1, tip) : glm::uvec3(1, 0, tip));
            if (k > 0) m.triangles.push_back({0, tip - 1, tip}); // thin fans around p0 between pages
        }
        meshes.push_back(m);
    }
    for (const TriangleMesh& mesh : meshes)
        for (Axis axis : {Axis::X, Axis::Z}) {
            BakeOptions o;
            o.resolution = 200;
            o.axis = axis;
            o.method = BakeMethod::Cpu;
            const Sprite cpu = bake(mesh, o);
            ASSERT_EQ(cpu.status, SolidStatus::Open);
            for (BakeMethod method : {BakeMethod::Lists, BakeMethod::Peel}) {
                const Sprite gpu = bakeWith(gl(), mesh, method, 200, axis);
                ASSERT_EQ(gpu.offsets.size(), cpu.offsets.size());
                std::size_t differ = 0;
                for (std::size_t c = 0; c + 1 < cpu.offsets.size(); ++c) {
                    const auto net = [&](const Sprite& s) {
                        int n = 0;
                        for (std::uint32_t k = s.offsets[c]; k < s.offsets[c + 1]; ++k)
                            n += crossingEnters(s.crossings[k]) ? 1 : -1;
                        return n;
                    };
                    differ += net(cpu) != net(gpu);
                }
                EXPECT_EQ(differ, 0u) << toString(method) << " along " << toString(axis);
            }
        }
}

TEST_F(BakeTest, OpenMeshIsBakedAndMarkedNotSolid) {
    auto box = solids::box({0, 0, 0}, {1, 1, 1});
    box.mesh.triangles.pop_back();
    const Sprite s = bakeWith(gl(), box.mesh, BakeMethod::Lists, 16);
    EXPECT_EQ(s.status, SolidStatus::Open);
    EXPECT_NE(s.validation.find("open"), std::string::npos) << s.validation;
}

TEST_F(BakeTest, BadInputIsRefusedWithAClearError) {
    TriangleMesh empty;
    EXPECT_THROW(bakeWith(gl(), empty, BakeMethod::Lists, 16), InvalidMesh);
    auto nan = solids::box({0, 0, 0}, {1, 1, 1});
    nan.mesh.positions[3].y = std::nanf("");
    EXPECT_THROW(bakeWith(gl(), nan.mesh, BakeMethod::Peel, 16), InvalidMesh);
    auto badIndex = solids::box({0, 0, 0}, {1, 1, 1});
    badIndex.mesh.triangles[0].z = 99;
    EXPECT_THROW(bakeWith(gl(), badIndex.mesh, BakeMethod::Lists, 16), InvalidMesh);
    const auto box = solids::box({0, 0, 0}, {1, 1, 1});
    EXPECT_THROW(bakeWith(gl(), box.mesh, BakeMethod::Lists, 0), InvalidArgument);
    EXPECT_THROW(bakeWith(gl(), box.mesh, BakeMethod::Lists, 1u << 20), InvalidArgument);
    TriangleMesh flat; // a single triangle in the z = 0 plane has no extent along z
    flat.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    flat.triangles = {{0, 1, 2}};
    EXPECT_THROW(bakeWith(gl(), flat, BakeMethod::Lists, 16), InvalidMesh); // flat: bounds no volume
}

} // namespace
} // namespace vds
