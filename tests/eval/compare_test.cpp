// The comparison table on a small solid: every method in both series, error
// figures that make sense, JSON and chart output.
#include <cstdio>
#include <set>
#include <string>

#include <gtest/gtest.h>

#include <vds/error.h>
#include "solids.h"
#include <vds/eval/compare.h>

#include "../support/gl_fixture.h"

namespace vds::eval {
namespace {

class CompareTest : public vds::test::GlTest {};

TEST_F(CompareTest, TableHoldsEveryMethodAtEqualResolutionAndEqualMemory) {
    const auto torus = solids::torus({0, 0, 0}, 1.0f, 0.4f, 32);
    CompareOptions options;
    options.resolutions = {16, 48};
    options.uniformPoints = 20000;
    options.surfacePoints = 10000;
    options.meshName = "torus";
    std::size_t progressCalls = 0;
    options.progress = [&](const std::string&) { ++progressCalls; };
    const CompareResult result = compare(torus.mesh, options, &gl());
    EXPECT_GT(progressCalls, 3u);
    EXPECT_EQ(result.triangles, torus.mesh.triangles.size());
    EXPECT_EQ(result.uniformPoints, 20000u);
    EXPECT_EQ(result.surfacePoints, 10000u);
    EXPECT_GT(result.uniformInside, 2000u);
    EXPECT_GT(result.exactPointsPerSecond, 0.0);

    const std::set<std::string> methods = {"vds-parity",     "vds-winding", "slicemap",
                                           "slicemap-local", "solid",       "solid-compute"};
    std::set<std::string> atResolution, atMemory;
    for (const CompareRow& r : result.rows) {
        ASSERT_TRUE(methods.count(r.method)) << r.method;
        (r.series == "resolution" ? atResolution : atMemory).insert(r.method);
        EXPECT_GT(r.memoryBytes, 0u) << r.method;
        EXPECT_GT(r.pointsPerSecond, 0.0) << r.method;
        EXPECT_GE(r.buildSeconds, 0.0) << r.method;
        EXPECT_LT(r.errorRate, 0.2) << r.method << " " << r.series << " " << r.target;
        EXPECT_EQ(r.uniformWrong + r.surfaceWrong == 0, r.worstErrorDistance == 0.0) << r.method;
        EXPECT_NEAR(r.worstErrorCells, r.worstErrorDistance / r.cellSize, 1e-9) << r.method;
        if (r.series == "memory") {
            EXPECT_LE(r.memoryBytes, r.target) << r.method;
        } else if (r.method != "vds-parity" && r.method != "vds-winding") {
            EXPECT_EQ(r.resolution, r.target);
        }
    }
    EXPECT_EQ(atResolution, methods);
    EXPECT_EQ(atMemory, methods);

    // Finer grids are better; raster and compute solids answer alike.
    const auto find = [&](const std::string& method, std::uint64_t target) -> const CompareRow& {
        for (const CompareRow& r : result.rows)
            if (r.method == method && r.series == "resolution" && r.target == target) return r;
        throw std::runtime_error("no row " + method);
    };
    for (const char* m : {"solid", "slicemap", "vds-parity"})
        EXPECT_LT(find(m, 48).errorRate, find(m, 16).errorRate) << m;
    EXPECT_EQ(find("solid", 48).uniformWrong, find("solid-compute", 48).uniformWrong);
    EXPECT_EQ(find("solid", 48).surfaceWrong, find("solid-compute", 48).surfaceWrong);
    // Errors stay near the surface: within a couple of cells.
    for (const CompareRow& r : result.rows) EXPECT_LT(r.worstErrorCells, 3.0) << r.method << " " << r.series;

    const std::string json = result.json();
    EXPECT_NE(json.find("\"mesh\": \"torus\""), std::string::npos);
    EXPECT_NE(json.find("\"method\": \"slicemap-local\""), std::string::npos);
    EXPECT_NE(json.find("\"worst_error_cells\""), std::string::npos);
    const std::string table = result.table();
    EXPECT_EQ(std::size_t(std::count(table.begin(), table.end(), '\n')), result.rows.size() + 1);

    const Image chart = errorChart(result, 640, 400);
    ASSERT_EQ(chart.width, 640u);
    std::set<std::uint32_t> colours;
    for (std::size_t k = 0; k < chart.rgba.size(); k += 4)
        colours.insert(std::uint32_t(chart.rgba[k]) << 16 | std::uint32_t(chart.rgba[k + 1]) << 8 | chart.rgba[k + 2]);
    EXPECT_GE(colours.size(), 8u); // background, axes, grid and six method colours
    const std::string path = ::testing::TempDir() + "vds_compare_chart.png";
    writePng(chart, path);
    EXPECT_EQ(readPng(path).width, 640u);
    std::remove(path.c_str());
}

TEST_F(CompareTest, ClosedNonManifoldMeshesAreCompared) {
    const auto touching = solids::boxesSharingAnEdge({0, 0, 0}, 1.0f);
    CompareOptions options;
    options.resolutions = {16};
    options.uniformPoints = 2000;
    options.surfacePoints = 1000;
    const CompareResult result = compare(touching.mesh, options, &gl());
    EXPECT_NE(result.validation.find("closed, 1 non-manifold edge"), std::string::npos) << result.validation;
    EXPECT_FALSE(result.rows.empty());
    EXPECT_NE(result.json().find("\"validation\": \"closed, 1 non-manifold edge"), std::string::npos);
}

TEST_F(CompareTest, BadInputIsRejected) {
    auto open = solids::sphere({0, 0, 0}, 1.0f, 16).mesh;
    open.triangles.pop_back();
    EXPECT_THROW(compare(open, {}, &gl()), InvalidMesh);
    CompareOptions options;
    options.resolutions = {};
    EXPECT_THROW(compare(solids::sphere({0, 0, 0}, 1.0f, 16).mesh, options, &gl()), InvalidArgument);
    options.resolutions = {0};
    EXPECT_THROW(compare(solids::sphere({0, 0, 0}, 1.0f, 16).mesh, options, &gl()), InvalidArgument);
}

} // namespace
} // namespace vds::eval
