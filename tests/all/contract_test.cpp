// The one classify contract (<vds/classify.h>) held for every method of the
// method table, made by `vds::makeClassifier` (<vds/all.h>): each answers the
// rules its table row names and refuses the others, exact methods equal the
// exact classifier on every point, approximate ones away from the surface,
// float and strided double points give the same labels, and `occupancy`
// equals `classify` of the cell centres. A classifier defined outside the
// library (Method::Custom) gets the same contract.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include <vds/all.h>
#include <vds/error.h>

#include "gl_fixture.h"
#include "points.h"
#include "solids.h"

namespace vds {
namespace {

using test::GlTest;

constexpr Rule kRules[] = {Rule::Parity, Rule::Winding, Rule::GeneralizedWinding};
constexpr std::uint32_t kResolution = 48;

class Contract : public GlTest {
protected:
    void SetUp() override {
        GlTest::SetUp();
        if (IsSkipped() || HasFatalFailure()) return;
        sphere_ = solids::sphere({0.1f, -0.2f, 0.3f}, 1.0f, 48);
        points_ = test::randomPoints(meshBounds(sphere_.mesh), 3000, 0.15f, 7);
    }
    // The exact classifier's labels of `points_` by `rule`.
    std::vector<std::uint8_t> exact(Rule rule) const {
        const ExactClassifier e(sphere_.mesh);
        std::vector<std::uint8_t> labels(points_.size());
        ClassifyOptions o;
        o.rule = rule;
        e.classify(points_, labels.data(), o);
        return labels;
    }
    solids::Solid sphere_;
    std::vector<glm::vec3> points_;
};

// Points farther than this from the sphere's surface are answered right by
// every method at kResolution (a few cells of the longest side, 2 / 48).
constexpr float kFarFromSurface = 0.15f;

TEST_F(Contract, EveryMethodAnswersItsRulesAndRefusesTheOthers) {
    MethodOptions options;
    options.resolution = kResolution;
    for (const MethodInfo* info = methodTable(); info != methodTable() + kMethodCount; ++info) {
        if (!info->builtIn()) continue;
        SCOPED_TRACE(info->name);
        const std::unique_ptr<Classifier> c = makeClassifier(gl(), sphere_.mesh, info->method, options);
        EXPECT_EQ(c->method(), info->method);
        EXPECT_GT(c->memoryBytes(), 0u);
        EXPECT_FALSE(c->summary().empty());
        for (Rule rule : kRules) {
            SCOPED_TRACE(enumName(rule));
            std::vector<std::uint8_t> labels(points_.size(), 7);
            ClassifyOptions o;
            o.rule = rule;
            ClassifyStats stats;
            o.stats = &stats;
            if (!answers(info->method, rule)) {
                EXPECT_THROW(c->classify(points_, labels.data(), o), InvalidArgument);
                EXPECT_EQ(labels[0], 7) << "a refused rule touched the labels";
                continue;
            }
            c->classify(points_, labels.data(), o);
            EXPECT_EQ(stats.certain + stats.exact, points_.size());
            const std::vector<std::uint8_t> truth = exact(rule);
            std::size_t wrong = 0, wrongFar = 0;
            for (std::size_t k = 0; k < points_.size(); ++k) {
                ASSERT_LE(labels[k], 1);
                if (labels[k] == truth[k]) continue;
                ++wrong;
                wrongFar += std::abs(sphere_.distance(points_[k])) > kFarFromSurface;
            }
            if (info->exact) {
                EXPECT_EQ(wrong, 0u);
            }
            EXPECT_EQ(wrongFar, 0u);

            // The same points as doubles inside 40-byte records.
            struct Record {
                double xyz[3];
                double pad[2];
            };
            std::vector<Record> records(points_.size());
            for (std::size_t k = 0; k < points_.size(); ++k)
                records[k] = {{points_[k].x, points_[k].y, points_[k].z}, {-1.0, -1.0}};
            std::vector<std::uint8_t> fromDoubles(points_.size());
            o.stats = nullptr;
            c->classify(PointsView::doubles(records[0].xyz, records.size(), sizeof(Record)), fromDoubles.data(), o);
            EXPECT_EQ(fromDoubles, labels);

            // Occupancy equals classify of the cell centres, in the grid's order.
            const Grid grid{meshBounds(sphere_.mesh), {11, 9, 13}};
            std::vector<std::uint8_t> cells(grid.cellCount(), 7), centresLabels(grid.cellCount());
            std::vector<glm::vec3> centres(grid.cellCount());
            for (std::uint32_t i = 0; i < grid.dims.x; ++i)
                for (std::uint32_t j = 0; j < grid.dims.y; ++j)
                    for (std::uint32_t k = 0; k < grid.dims.z; ++k) centres[grid.index(i, j, k)] = grid.cellCentre(i, j, k);
            c->occupancy(grid, cells.data(), o);
            c->classify(centres, centresLabels.data(), o);
            EXPECT_EQ(cells, centresLabels);
        }
    }
}

TEST_F(Contract, SpriteMethodsFromASpriteAndMeshMethodsRefuseOne) {
    BakeOptions bake;
    bake.method = BakeMethod::Cpu;
    bake.resolution = kResolution;
    const Sprite sprite = vds::bake(sphere_.mesh, bake);
    const auto cpu = makeClassifier(sprite, Method::Sprite);
    const auto gpu = makeClassifier(gl(), sprite, Method::SpriteGpu);
    std::vector<std::uint8_t> a(points_.size()), b(points_.size());
    cpu->classify(points_, a.data());
    gpu->classify(points_, b.data());
    EXPECT_EQ(a, b);
    EXPECT_EQ(gpu->method(), Method::SpriteGpu);
    for (Method m : {Method::Exact, Method::Certified, Method::Solid, Method::SlicemapGpu})
        EXPECT_THROW(makeClassifier(sprite, m), InvalidArgument) << enumName(m);
}

TEST_F(Contract, VoxelMethodsRefuseOpenMeshesAndTheExactGwnTakesThem) {
    const TriangleMesh cup = solids::sphereCup();
    MethodOptions options;
    options.resolution = 16;
    for (Method m : {Method::Slicemap, Method::SlicemapLocal, Method::Solid, Method::SolidComputeGpu})
        EXPECT_THROW(makeClassifier(gl(), cup, m, options), InvalidMesh) << enumName(m);
    const auto exactGwn = makeClassifier(cup, Method::Exact);
    ClassifyOptions o;
    o.rule = Rule::GeneralizedWinding;
    // The centre of the cup (the sphere with its top cut off) is inside by the GWN.
    const glm::vec3 centre(0.0f);
    std::uint8_t label = 0;
    exactGwn->classify(PointsView(&centre, 1), &label, o);
    EXPECT_EQ(label, 1);
}

// A classifier written outside the library: an analytic ball, parity only.
class Ball final : public Classifier {
public:
    Method method() const override { return Method::Custom; }
    std::uint8_t rules() const override { return 1u << unsigned(Rule::Parity); }
    std::size_t memoryBytes() const override { return sizeof(*this); }
    std::string summary() const override { return "the unit ball"; }

protected:
    void classifyFloats(const float* xyz, std::size_t count, std::size_t strideBytes, std::uint8_t* labels,
                        const ClassifyOptions&) const override {
        for (std::size_t k = 0; k < count; ++k) {
            const float* p = reinterpret_cast<const float*>(reinterpret_cast<const char*>(xyz) + k * strideBytes);
            labels[k] = p[0] * p[0] + p[1] * p[1] + p[2] * p[2] < 1.0f;
        }
    }
};

TEST(CustomClassifier, GetsTheContractAndMakeClassifierRefusesIt) {
    const Ball ball;
    const Grid grid{{glm::vec3(-1.5f), glm::vec3(1.5f)}, {8, 8, 8}};
    std::vector<std::uint8_t> cells(grid.cellCount());
    occupancy(ball, grid, cells.data());
    std::size_t inside = 0;
    for (std::uint32_t i = 0; i < 8; ++i)
        for (std::uint32_t j = 0; j < 8; ++j)
            for (std::uint32_t k = 0; k < 8; ++k) {
                const glm::vec3 c = grid.cellCentre(i, j, k);
                EXPECT_EQ(cells[grid.index(i, j, k)], c.x * c.x + c.y * c.y + c.z * c.z < 1.0f);
                inside += cells[grid.index(i, j, k)];
            }
    EXPECT_GT(inside, 0u);
    std::uint8_t label = 0;
    ClassifyOptions winding;
    winding.rule = Rule::Winding;
    const glm::vec3 origin(0.0f);
    try {
        ball.classify(PointsView(&origin, 1), &label, winding);
        FAIL() << "a rule the classifier narrowed away was answered";
    } catch (const InvalidArgument& e) {
        EXPECT_NE(std::string(e.what()).find("the unit ball cannot answer the winding rule"), std::string::npos)
            << e.what();
    }
    EXPECT_TRUE(ball.contains(origin));
    EXPECT_FALSE(methodInfo(Method::Custom).builtIn());
    EXPECT_THROW(makeClassifier(solids::box({0, 0, 0}, {1, 1, 1}).mesh, Method::Custom), InvalidArgument);
}

} // namespace
} // namespace vds
