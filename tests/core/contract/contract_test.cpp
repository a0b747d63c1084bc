// The contract room on its own, without GL: the method table, points views
// of every layout, grids (cell centres, slabs, refusals, packed labels) and
// the Classifier base class's batch, point and grid shapes, held against an
// analytic solid (a ball) that derives from Classifier as a user's would.
#include <cmath>
#include <cstdint>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <vds/classify.h>
#include <vds/error.h>
#include <vds/grid.h>
#include <vds/mesh.h>

namespace vds {
namespace {

/// A ball of radius r about the origin: inside is |p| < r, for parity and
/// winding alike (a user's own classifier, Method::Custom).
class Ball final : public Classifier {
public:
    explicit Ball(float r) : r_(r) {}
    Method method() const override { return Method::Custom; }
    std::size_t memoryBytes() const override { return sizeof(*this); }
    std::uint8_t rules() const override { return 1u << unsigned(Rule::Parity); }
    static bool inside(const glm::vec3& p, float r) { return p.x * p.x + p.y * p.y + p.z * p.z < r * r; }

protected:
    void classifyFloats(const float* xyz, std::size_t count, std::size_t strideBytes, std::uint8_t* labels,
                        const ClassifyOptions&) const override {
        const char* at = reinterpret_cast<const char*>(xyz);
        for (std::size_t k = 0; k < count; ++k, at += strideBytes) {
            const float* p = reinterpret_cast<const float*>(at);
            labels[k] = inside({p[0], p[1], p[2]}, r_) ? 1 : 0;
        }
    }

private:
    float r_;
};

std::vector<glm::vec3> lattice() {
    std::vector<glm::vec3> points;
    for (int i = -6; i <= 6; ++i)
        for (int j = -6; j <= 6; ++j)
            for (int k = -6; k <= 6; ++k) points.emplace_back(0.17f * i, 0.13f * j + 0.01f, 0.11f * k - 0.02f);
    return points;
}

TEST(MethodTable, EveryMethodIsNamedOnceInOrderAndItsFormsPair) {
    std::set<std::string> names;
    for (std::size_t m = 0; m < kMethodCount; ++m) {
        const MethodInfo& info = methodTable()[m];
        EXPECT_EQ(std::size_t(info.method), m);
        EXPECT_EQ(&methodInfo(info.method), &info);
        EXPECT_STREQ(info.name, enumName(info.method));
        EXPECT_EQ(parseEnum<Method>(info.name), info.method);
        EXPECT_TRUE(names.insert(info.name).second) << info.name;
        EXPECT_FALSE(cpuForm(info.method) != info.method && methodInfo(cpuForm(info.method)).gpu) << info.name;
        if (info.gpu && info.builtIn()) {
            EXPECT_EQ(gpuForm(cpuForm(info.method)), info.method) << info.name;
        }
    }
    EXPECT_EQ(cpuForm(Method::SpriteGpu), Method::Sprite);
    EXPECT_EQ(gpuForm(Method::Solid), Method::SolidGpu);
    EXPECT_THROW(parseEnum<Method>("sprit"), InvalidArgument);
    EXPECT_TRUE(answers(Method::Exact, Rule::GeneralizedWinding));
    EXPECT_THROW(requireRule(Method::Slicemap, Rule::Winding), InvalidArgument);
}

TEST(PointsView, FloatsDoublesAndRecordsGiveTheSameLabels) {
    const Ball ball(0.6f);
    const std::vector<glm::vec3> points = lattice();
    std::vector<std::uint8_t> expected(points.size());
    for (std::size_t k = 0; k < points.size(); ++k) expected[k] = Ball::inside(points[k], 0.6f);
    std::vector<double> doubles;
    struct Record {
        std::uint32_t id;
        float xyz[3];
        float weight;
    };
    std::vector<Record> records;
    for (const glm::vec3& p : points) {
        doubles.insert(doubles.end(), {double(p.x), double(p.y), double(p.z)});
        records.push_back({7u, {p.x, p.y, p.z}, 1.0f});
    }
    const PointsView views[] = {PointsView(points), PointsView::doubles(doubles.data(), points.size()),
                                PointsView::floats(records[0].xyz, records.size(), sizeof(Record))};
    for (const PointsView& view : views) {
        std::vector<std::uint8_t> labels(points.size(), 9);
        ball.classify(view, labels.data());
        EXPECT_EQ(labels, expected);
        EXPECT_EQ(view[5], points[5]);
        const PointsView tail = view.slice(100, 20);
        EXPECT_EQ(tail.count, 20u);
        EXPECT_EQ(tail[0], points[100]);
    }
    for (std::size_t k = 0; k < points.size(); k += 97) EXPECT_EQ(ball.contains(points[k]), expected[k] == 1);
}

TEST(Classifier, ARuleItDoesNotAnswerIsRefusedBeforeAnyLabel) {
    const Ball ball(0.5f);
    const std::vector<glm::vec3> points = lattice();
    std::vector<std::uint8_t> labels(points.size(), 9);
    EXPECT_THROW(ball.classify(points, labels.data(), {Rule::Winding}), InvalidArgument);
    EXPECT_EQ(labels, std::vector<std::uint8_t>(points.size(), 9));
    EXPECT_THROW(ball.contains({0.0f, 0.0f, 0.0f}, Rule::GeneralizedWinding), InvalidArgument);
    ClassifyStats stats;
    ball.classify(points, labels.data(), {Rule::Parity, 1, &stats});
    EXPECT_EQ(stats.certain, points.size()); // an approximate method counts its own answers
    EXPECT_EQ(stats.exact, 0u);
}

TEST(Grid, CellCentresAreTheMidpointsOfEqualCells) {
    Grid grid;
    grid.box = {{-1.0f, 0.0f, 2.0f}, {1.0f, 3.0f, 2.5f}};
    grid.dims = {4u, 3u, 5u};
    EXPECT_EQ(grid.cellCount(), 60u);
    EXPECT_EQ(grid.index(1, 2, 3), (1u * 3 + 2) * 5 + 3);
    for (std::uint32_t i = 0; i < 4; ++i)
        for (std::uint32_t j = 0; j < 3; ++j)
            for (std::uint32_t k = 0; k < 5; ++k) {
                const glm::vec3 c = grid.cellCentre(i, j, k);
                EXPECT_FLOAT_EQ(c.x, -1.0f + 0.5f * (float(i) + 0.5f));
                EXPECT_FLOAT_EQ(c.y, 1.0f * (float(j) + 0.5f));
                EXPECT_FLOAT_EQ(c.z, 2.0f + 0.1f * (float(k) + 0.5f));
            }
    const Grid slab = grid.slabX(1, 3);
    EXPECT_EQ(slab.dims, glm::uvec3(2u, 3u, 5u));
    EXPECT_EQ(slab.cellCentre(0, 2, 4), grid.cellCentre(1, 2, 4));
    const Grid cubic = cubicGrid({{0.0f, 0.0f, 0.0f}, {4.0f, 1.0f, 2.0f}}, 8);
    EXPECT_EQ(cubic.dims, glm::uvec3(8u, 2u, 4u));
}

TEST(Grid, ZeroHugeAndNonFiniteGridsAreRefused) {
    Grid grid;
    grid.box = {{0.0f, 0.0f, 0.0f}, {1.0f, 1.0f, 1.0f}};
    grid.dims = {2u, 0u, 2u};
    EXPECT_THROW(checkGrid(grid), InvalidArgument);
    grid.dims = {1u << 12, 1u << 12, 1u << 11}; // 2^35 cells
    EXPECT_THROW(checkGrid(grid), InvalidArgument);
    grid.dims = {2u, 2u, 2u};
    EXPECT_NO_THROW(checkGrid(grid));
    grid.box.hi.y = std::nanf("");
    EXPECT_THROW(checkGrid(grid), InvalidArgument);
}

TEST(Classifier, OccupancyLabelsEveryCellCentreAndSlabsAgree) {
    const Ball ball(0.7f);
    Grid grid;
    grid.box = {{-1.0f, -0.9f, -0.8f}, {1.0f, 0.9f, 0.8f}};
    grid.dims = {9u, 7u, 6u};
    std::vector<std::uint8_t> cells(grid.cellCount(), 9), slab(grid.slabX(3, 7).cellCount(), 9);
    ball.occupancy(grid, cells.data());
    for (std::uint32_t i = 0; i < 9; ++i)
        for (std::uint32_t j = 0; j < 7; ++j)
            for (std::uint32_t k = 0; k < 6; ++k)
                ASSERT_EQ(cells[grid.index(i, j, k)], Ball::inside(grid.cellCentre(i, j, k), 0.7f) ? 1 : 0);
    const Grid part = grid.slabX(3, 7);
    occupancy(ball, part, slab.data());
    for (std::uint32_t i = 0; i < 4; ++i)
        for (std::uint32_t j = 0; j < 7; ++j)
            for (std::uint32_t k = 0; k < 6; ++k) ASSERT_EQ(slab[part.index(i, j, k)], cells[grid.index(i + 3, j, k)]);
}

TEST(Grid, PackedLabelsPutTheFirstCellInTheHighBit) {
    const std::uint8_t cells[11] = {1, 0, 0, 0, 0, 0, 0, 1, 0, 1, 1};
    std::uint8_t bits[2] = {0xFF, 0xFF};
    packLabels(cells, 11, bits);
    EXPECT_EQ(bits[0], 0x81);
    EXPECT_EQ(bits[1], 0x60); // 0 1 1, then zeros
}

TEST(MeshBounds, OnlyReferencedVerticesCount) {
    const std::vector<glm::vec3> positions = {{0, 0, 0}, {1, 0, 0}, {0, 2, 0}, {9, 9, 9}, {0, 0, -3}};
    const std::vector<glm::uvec3> triangles = {{0, 1, 2}, {0, 2, 4}, {0, 1, 7}};
    MeshView view;
    view.positions = positions.data();
    view.positionCount = positions.size();
    view.triangles = triangles.data();
    view.triangleCount = triangles.size();
    const Box b = meshBounds(view);
    EXPECT_EQ(b.lo, glm::vec3(0.0f, 0.0f, -3.0f));
    EXPECT_EQ(b.hi, glm::vec3(1.0f, 2.0f, 0.0f));
}

} // namespace
} // namespace vds
