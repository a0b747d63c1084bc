// The sprite's grid and the VPT on the CPU, on sprites built by hand.
#include <algorithm>
#include <cmath>
#include <random>
#include <utility>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <vds/bake.h>
#include <vds/distance.h>
#include <vds/error.h>
#include <vds/exact.h>
#include <vds/mesh_check.h>
#include <vds/sprite.h>

#include "solids.h"

namespace vds {
namespace {

// A 4x2 sprite over the box [0,4]x[0,2]x[0,10] along z with hand-made columns.
Sprite handMade() {
    Sprite s;
    s.grid = makeGrid(Box{{0, 0, 0}, {4, 2, 10}}, Axis::Z, 4);
    s.offsets.assign(9, 0);
    // column 0: one solid interval [0.2, 0.4]; column 5: two nested shells.
    std::vector<std::vector<float>> columns(8);
    columns[0] = {encodeCrossing(0.2f, true), encodeCrossing(0.4f, false)};
    columns[5] = {encodeCrossing(0.1f, true), encodeCrossing(0.2f, true), encodeCrossing(0.3f, false),
                  encodeCrossing(0.5f, false)};
    for (std::size_t c = 0; c < 8; ++c) {
        s.offsets[c + 1] = s.offsets[c] + std::uint32_t(columns[c].size());
        s.crossings.insert(s.crossings.end(), columns[c].begin(), columns[c].end());
    }
    s.depthComplexity = 4;
    s.checkConsistent();
    return s;
}

TEST(SpriteGrid, TexelsAreSquareAndCoverTheBox) {
    const SpriteGrid g = makeGrid(Box{{-1, 0, 2}, {3, 1, 4}}, Axis::Z, 100);
    EXPECT_EQ(g.width, 100u);
    EXPECT_EQ(g.height, 25u);
    EXPECT_FLOAT_EQ(g.texelSize, 0.04f);
    EXPECT_EQ(g.toTexture({-1, 0, 2}), glm::vec3(0, 0, 0));
    const glm::vec3 far = g.toTexture({3, 1, 4});
    EXPECT_NEAR(far.x, 1.0f, 1e-6f);
    EXPECT_NEAR(far.y, 1.0f, 1e-6f);
    EXPECT_NEAR(far.z, 1.0f, 1e-6f);
    const SpriteGrid gx = makeGrid(Box{{0, 0, 0}, {1, 2, 4}}, Axis::X, 64); // s = y, t = z
    EXPECT_EQ(gx.width, 32u);
    EXPECT_EQ(gx.height, 64u);
    const glm::vec3 c = gx.texelCentre(0, 0, 0.5f);
    EXPECT_FLOAT_EQ(c.x, 0.5f);
    EXPECT_FLOAT_EQ(c.y, 0.5f * gx.texelSize);
    EXPECT_FLOAT_EQ(c.z, 0.5f * gx.texelSize);
}

TEST(SpriteGrid, AbsurdResolutionsAndFlatBoxesAreRefused) {
    const Box box{{0, 0, 0}, {1, 1, 1}};
    EXPECT_THROW(makeGrid(box, Axis::Z, 0), InvalidArgument);
    EXPECT_THROW(makeGrid(box, Axis::Z, kMaxResolution + 1), InvalidArgument);
    EXPECT_NO_THROW(makeGrid(box, Axis::Z, 1));
    EXPECT_THROW(makeGrid(Box{{0, 0, 0}, {1, 1, 0}}, Axis::Z, 8), InvalidArgument);
    EXPECT_THROW(makeGrid(Box{{0, 0, 0}, {0, 0, 1}}, Axis::Z, 8), InvalidArgument);
    EXPECT_THROW(makeGrid(Box{{0, 0, 0}, {INFINITY, 1, 1}}, Axis::Z, 8), InvalidArgument);
}

TEST(Sprite, ParityAndWindingCountOnlyCrossingsInFront) {
    const Sprite s = handMade();
    // column 0 = texel (0,0): x in [0,1), y in [0,1); depth r = z / 10.
    EXPECT_FALSE(s.contains({0.5f, 0.5f, 1.0f}));
    EXPECT_TRUE(s.contains({0.5f, 0.5f, 3.0f}));
    EXPECT_FALSE(s.contains({0.5f, 0.5f, 5.0f}));
    EXPECT_FALSE(s.contains({0.5f, 0.5f, 2.0f})); // on an entering surface: outside
    EXPECT_TRUE(s.contains({0.5f, 0.5f, 4.0f}));  // on a leaving surface: inside
    // column 5 = texel (1,1): nested shells, winding 2 between 0.2 and 0.3.
    const glm::vec3 deep(1.5f, 1.5f, 2.5f);
    EXPECT_FALSE(s.contains(deep, Rule::Parity));
    EXPECT_TRUE(s.contains(deep, Rule::Winding));
    EXPECT_TRUE(s.contains({1.5f, 1.5f, 1.5f}, Rule::Parity));
    EXPECT_TRUE(s.contains({1.5f, 1.5f, 4.0f}, Rule::Winding));
    EXPECT_FALSE(s.contains({1.5f, 1.5f, 6.0f}, Rule::Winding));
    // Outside the box: outside, whatever the column holds.
    EXPECT_FALSE(s.contains({-0.1f, 0.5f, 3.0f}));
    EXPECT_FALSE(s.contains({0.5f, 0.5f, -1.0f}));
    EXPECT_FALSE(s.contains({0.5f, 0.5f, 10.5f}));
    EXPECT_FALSE(s.contains({4.0f, 0.5f, 3.0f}));
}

TEST(Sprite, TransformMovesTheAnswers) {
    Sprite s = handMade();
    const glm::mat4 m = glm::rotate(glm::translate(glm::mat4(1.0f), {10, 0, 0}), glm::radians(90.0f), {0, 0, 1});
    s.transform(m);
    const glm::vec3 inside(0.5f, 0.5f, 3.0f);
    EXPECT_FALSE(s.contains(inside));
    EXPECT_TRUE(s.contains(glm::vec3(m * glm::vec4(inside, 1.0f))));
    EXPECT_THROW(s.transform(glm::mat4(0.0f)), InvalidArgument);
}

TEST(Sprite, BatchClassifyEqualsSinglePointsOnAnyThreadCount) {
    const Sprite s = handMade();
    std::vector<glm::vec3> points;
    for (int i = 0; i < 20000; ++i)
        points.push_back({float(i % 41) * 0.1f, float(i % 23) * 0.1f, float(i % 113) * 0.1f});
    for (unsigned threads : {1u, 2u, 3u})
        for (QueryLayout layout : {QueryLayout::Auto, QueryLayout::Offsets, QueryLayout::Packed})
            for (Rule rule : {Rule::Parity, Rule::Winding}) {
                std::vector<std::uint8_t> labels(points.size(), 9);
                ClassifyOptions o;
                o.threads = threads;
                o.rule = rule;
                classify(s, {points.data(), points.size()}, labels.data(), o, {layout});
                for (std::size_t k = 0; k < points.size(); ++k)
                    ASSERT_EQ(labels[k], s.contains(points[k], rule) ? 1 : 0) << k << " layout " << int(layout);
            }
}

// A sprite over `box` with random sorted columns of `crossingsOf(c)`
// crossings (depth 0 and 1 and repeated depths included), and points on
// every column: at each stored depth exactly, between them, at the ends,
// off the box, and uniform ones.
template <class Count>
std::pair<Sprite, std::vector<glm::vec3>> randomColumns(const Box& box, Axis axis, std::uint32_t resolution,
                                                        const Count& crossingsOf) {
    Sprite s;
    s.grid = makeGrid(box, axis, resolution);
    const std::size_t columns = std::size_t(s.grid.width) * s.grid.height;
    s.offsets.assign(columns + 1, 0);
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::vector<glm::vec3> points;
    for (std::size_t c = 0; c < columns; ++c) {
        const std::uint32_t n = crossingsOf(c);
        std::vector<float> depths(n);
        for (std::uint32_t k = 0; k < n; ++k) depths[k] = k % 7 == 3 && k > 0 ? depths[k - 1] : u(rng);
        if (n > 0 && c % 3 == 0) depths[0] = 0.0f;
        if (n > 1 && c % 5 == 0) depths[n - 1] = 1.0f;
        std::sort(depths.begin(), depths.end());
        for (std::uint32_t k = 0; k < n; ++k) s.crossings.push_back(encodeCrossing(depths[k], (rng() & 1) != 0));
        s.offsets[c + 1] = std::uint32_t(s.crossings.size());
        s.depthComplexity = std::max(s.depthComplexity, n);
        const std::uint32_t i = std::uint32_t(c % s.grid.width), j = std::uint32_t(c / s.grid.width);
        for (float r : depths) {
            points.push_back(s.grid.texelCentre(i, j, r));
            points.push_back(s.grid.texelCentre(i, j, std::nextafter(r, 2.0f)));
        }
        for (float r : {0.0f, 1.0f, 0.5f, -0.01f, 1.01f, u(rng)}) points.push_back(s.grid.texelCentre(i, j, r));
    }
    s.checkConsistent();
    const glm::vec3 size = box.hi - box.lo;
    for (int k = 0; k < 20000; ++k)
        points.push_back(box.lo + glm::vec3(u(rng), u(rng), u(rng)) * 1.2f * size - 0.1f * size);
    return {std::move(s), std::move(points)};
}

// The packed table (four or eight crossings a record, deeper columns read
// from the sprite) against the sprite's own arrays, point by point, for
// sprites as baked and moved ones, both rules and 1 or 2 threads.
TEST(Sprite, PackedLayoutEqualsOffsetsLayoutOnEveryPoint) {
    const Box box{{-1.0f, 2.0f, 0.5f}, {3.0f, 4.0f, 2.0f}};
    const auto few = [](std::size_t c) { return std::uint32_t(c % 97 == 0 ? 9 + c % 7 : c % 5); }; // 4-wide records
    const auto many = [](std::size_t c) { return std::uint32_t(c % 14); };                         // 8-wide records
    for (Axis axis : {Axis::Z, Axis::X, Axis::Y})
        for (bool deep : {false, true}) {
            auto [s, points] = deep ? randomColumns(box, axis, 48, many) : randomColumns(box, axis, 48, few);
            for (bool moved : {false, true}) {
                if (moved) { // the points move with the sprite
                    const glm::mat4 model =
                        glm::rotate(glm::translate(glm::mat4(1.0f), {0.3f, -2.0f, 1.0f}), 0.7f, {1.0f, 2.0f, 0.5f});
                    s.transform(model);
                    for (glm::vec3& p : points) p = glm::vec3(model * glm::vec4(p, 1.0f));
                }
                for (Rule rule : {Rule::Parity, Rule::Winding})
                    for (unsigned threads : {1u, 2u}) {
                        std::vector<std::uint8_t> offsets(points.size(), 9), packed(points.size(), 7);
                        classify(s, {points.data(), points.size()}, offsets.data(), {rule, threads}, {QueryLayout::Offsets});
                        classify(s, {points.data(), points.size()}, packed.data(), {rule, threads}, {QueryLayout::Packed});
                        std::size_t inside = 0;
                        for (std::size_t k = 0; k < points.size(); ++k) {
                            ASSERT_EQ(packed[k], offsets[k]) << "point " << k << " axis " << toString(axis) << " deep "
                                                             << deep << " moved " << moved << " " << toString(rule);
                            ASSERT_EQ(offsets[k], s.contains(points[k], rule) ? 1 : 0) << k;
                            inside += offsets[k];
                        }
                        // Both answers occur, so the comparison says something.
                        EXPECT_GT(inside, points.size() / 20);
                        EXPECT_LT(inside, points.size() - points.size() / 20);
                    }
            }
        }
}

// Points inside larger records (x y z plus a fourth float, stride 16 bytes),
// for the sprite and the exact classifier: the same answers as one by one.
TEST(Sprite, StridedPointsGiveTheSameAnswers) {
    const Sprite s = handMade();
    const auto box = solids::box({0.5f, 0.25f, 1.0f}, {3.5f, 1.75f, 9.0f});
    const ExactClassifier exact(box.mesh);
    std::vector<float> records;
    for (int i = 0; i < 5000; ++i) {
        const float p[4] = {float(i % 41) * 0.1f, float(i % 23) * 0.1f, float(i % 113) * 0.1f, -1.0f};
        records.insert(records.end(), p, p + 4);
    }
    const std::size_t n = records.size() / 4;
    std::vector<std::uint8_t> labels(n, 9), exactLabels(n, 9);
    classify(s, PointsView::floats(records.data(), n, 4 * sizeof(float)), labels.data(), {Rule::Parity, 2});
    exact.classify(PointsView::floats(records.data(), n, 4 * sizeof(float)), exactLabels.data(), {Rule::Parity, 2});
    std::size_t inside = 0;
    for (std::size_t k = 0; k < n; ++k) {
        const glm::vec3 p(records[4 * k], records[4 * k + 1], records[4 * k + 2]);
        ASSERT_EQ(labels[k], s.contains(p) ? 1 : 0) << k;
        ASSERT_EQ(exactLabels[k], exact.contains(p) ? 1 : 0) << k;
        inside += exactLabels[k];
    }
    EXPECT_GT(inside, n / 10); // the box holds a good share of the points
}

TEST(Sprite, InconsistentArraysAreDetected) {
    Sprite s = handMade();
    s.depthComplexity = 3;
    EXPECT_THROW(s.checkConsistent(), FormatError);
    s = handMade();
    std::swap(s.crossings[0], s.crossings[1]); // unsorted column
    EXPECT_THROW(s.checkConsistent(), FormatError);
    s = handMade();
    s.crossings[2] = 1.5f;
    EXPECT_THROW(s.checkConsistent(), FormatError);
    s = handMade();
    s.offsets.pop_back();
    EXPECT_THROW(s.checkConsistent(), FormatError);
    EXPECT_EQ(handMade().denseBytes(), 8u * 4u * 4u);
}

TEST(Sprite, CrossingEncodingKeepsFacingAtDepthZero) {
    EXPECT_TRUE(crossingEnters(encodeCrossing(0.0f, true)));
    EXPECT_FALSE(crossingEnters(encodeCrossing(0.0f, false)));
    EXPECT_EQ(crossingDepth(encodeCrossing(0.25f, false)), 0.25f);
}

} // namespace
} // namespace vds

namespace {

// The distance grid a sprite carries: cubic cells, `resolution` along the
// longest side, two cells past the baked box on every side, and every cell
// the analytic signed distance of a box at its centre (inside negative).
TEST(SpriteDistanceTest, BakedGridIsTheExactDistanceOverThePaddedBox) {
    const glm::vec3 lo(-1.0f, -0.5f, -0.25f), hi(1.0f, 0.5f, 0.25f);
    const vds::TriangleMesh mesh = vds::solids::box(lo, hi).mesh;
    const vds::SpriteDistance d = vds::bakeDistance(mesh, {lo, hi}, 24, vds::Rule::Winding, 2);
    EXPECT_EQ(d.grid.dims.x, 24u);
    ASSERT_EQ(d.cells.size(), d.grid.cellCount());
    const float cell = (d.grid.box.hi.x - d.grid.box.lo.x) / 24.0f;
    EXPECT_NEAR(d.grid.box.lo.x, lo.x - 2.0f * cell, 1e-5f);
    EXPECT_LE(d.grid.box.lo.z, lo.z - 2.0f * cell + 1e-5f);
    EXPECT_GE(d.grid.box.hi.y, hi.y + 2.0f * cell - 1e-5f);
    for (std::uint32_t i = 0; i < d.grid.dims.x; ++i)
        for (std::uint32_t j = 0; j < d.grid.dims.y; ++j)
            for (std::uint32_t k = 0; k < d.grid.dims.z; ++k) {
                const glm::vec3 p = d.grid.cellCentre(i, j, k);
                const glm::vec3 q = glm::max(glm::abs(p) - hi, glm::vec3(0.0f)); // outside part, per axis
                const glm::vec3 in = glm::abs(p) - hi;
                const double analytic = glm::length(glm::dvec3(q)) +
                                        std::min(0.0, double(std::max(in.x, std::max(in.y, in.z))));
                EXPECT_NEAR(d.cells[d.grid.index(i, j, k)], analytic, 1e-6) << i << " " << j << " " << k;
            }
    EXPECT_THROW(vds::bakeDistance(mesh, {lo, hi}, 3, vds::Rule::Winding), vds::InvalidArgument);
    EXPECT_THROW(vds::bakeDistance(mesh, {lo, hi}, vds::kMaxDistanceResolution + 1, vds::Rule::Winding),
                 vds::InvalidArgument);
}

} // namespace
