// The comparison table on a small solid: every method in both series, error
// figures that make sense, JSON and the SVG chart.
#include <algorithm>
#include <cstdio>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <vds/error.h>
#include "solids.h"
#include <vds/eval/compare.h>

#include "../support/gl_fixture.h"

namespace vds::eval {
namespace {

class CompareTest : public vds::test::GlTest {};

std::size_t count(const std::string& text, const std::string& what) {
    std::size_t n = 0;
    for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
}

// Tags nest and close in order (<a ...>...</a> or <a .../>), the way XML
// wants; enough to catch a chart a viewer would refuse.
bool closesEveryTag(const std::string& xml) {
    std::vector<std::string> open;
    for (std::size_t at = xml.find('<'); at != std::string::npos; at = xml.find('<', at + 1)) {
        const std::size_t end = xml.find('>', at);
        if (end == std::string::npos) return false;
        const std::string tag = xml.substr(at + 1, end - at - 1);
        if (tag.empty()) return false;
        if (tag[0] == '/') {
            if (open.empty() || open.back() != tag.substr(1)) return false;
            open.pop_back();
        } else if (tag.back() != '/') {
            open.push_back(tag.substr(0, tag.find(' ')));
        }
    }
    return open.empty();
}

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

    const std::set<std::string> methods = {"sprite",         "sprite/winding", "slicemap",
                                           "slicemap-local", "solid",          "solid-compute"};
    std::set<std::string> atResolution, atMemory;
    for (const CompareRow& r : result.rows) {
        ASSERT_TRUE(methods.count(r.name())) << r.name();
        (r.series == "resolution" ? atResolution : atMemory).insert(r.name());
        EXPECT_GT(r.memoryBytes, 0u) << r.name();
        EXPECT_GT(r.pointsPerSecond, 0.0) << r.name();
        EXPECT_GE(r.buildSeconds, 0.0) << r.name();
        EXPECT_LT(r.errorRate, 0.2) << r.name() << " " << r.series << " " << r.target;
        EXPECT_EQ(r.uniformWrong + r.surfaceWrong == 0, r.worstErrorDistance == 0.0) << r.name();
        EXPECT_NEAR(r.worstErrorCells, r.worstErrorDistance / r.cellSize, 1e-9) << r.name();
        if (r.series == "memory") {
            EXPECT_LE(r.memoryBytes, r.target) << r.name();
        } else if (r.method != Method::Sprite) {
            EXPECT_EQ(r.resolution, r.target);
        }
    }
    EXPECT_EQ(atResolution, methods);
    EXPECT_EQ(atMemory, methods);

    // Finer grids are better; raster and compute solids answer alike.
    const auto find = [&](const std::string& method, std::uint64_t target) -> const CompareRow& {
        for (const CompareRow& r : result.rows)
            if (r.name() == method && r.series == "resolution" && r.target == target) return r;
        throw std::runtime_error("no row " + method);
    };
    for (const char* m : {"solid", "slicemap", "sprite"})
        EXPECT_LT(find(m, 48).errorRate, find(m, 16).errorRate) << m;
    EXPECT_EQ(find("solid", 48).uniformWrong, find("solid-compute", 48).uniformWrong);
    EXPECT_EQ(find("solid", 48).surfaceWrong, find("solid-compute", 48).surfaceWrong);
    // Errors stay near the surface: within a couple of cells.
    for (const CompareRow& r : result.rows) EXPECT_LT(r.worstErrorCells, 3.0) << r.name() << " " << r.series;

    const std::string json = result.json();
    EXPECT_NE(json.find("\"mesh\": \"torus\""), std::string::npos);
    EXPECT_NE(json.find("\"method\": \"slicemap-local\""), std::string::npos);
    EXPECT_NE(json.find("\"worst_error_cells\""), std::string::npos);
    const std::string table = result.table();
    EXPECT_EQ(std::size_t(std::count(table.begin(), table.end(), '\n')), result.rows.size() + 1);

    const std::string svg = errorChart(result, 640, 400);
    EXPECT_EQ(svg.rfind("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"640\" height=\"400\"", 0), 0u) << svg;
    EXPECT_TRUE(closesEveryTag(svg)) << svg;
    // One line per method's resolution series, through its two resolutions.
    EXPECT_EQ(count(svg, "<polyline "), methods.size());
    for (std::size_t at = svg.find("<polyline "); at != std::string::npos; at = svg.find("<polyline ", at + 1)) {
        const std::size_t begin = svg.find("points=\"", at) + 8;
        EXPECT_EQ(std::count(svg.begin() + begin, svg.begin() + svg.find('"', begin), ','), 2) << svg.substr(at, 200);
    }
    // A dot per resolution row, a ring per memory row, each with its figures;
    // plus the legend's six dots, one for "resolution" and one ring.
    std::size_t memoryRows = 0;
    for (const CompareRow& r : result.rows) {
        memoryRows += r.series == "memory";
        char figures[64];
        std::snprintf(figures, sizeof figures, ", resolution %u: ", r.resolution);
        EXPECT_NE(svg.find("<title>" + r.name() + (r.series == "memory" ? ", budget " : figures)), std::string::npos)
            << r.name() << " " << r.series;
        std::snprintf(figures, sizeof figures, "%.3f %% wrong</title>", 100.0 * r.errorRate);
        EXPECT_NE(svg.find(figures), std::string::npos) << r.name() << " " << r.series << ": " << figures;
    }
    EXPECT_EQ(count(svg, "<circle "), result.rows.size() + methods.size() + 2);
    EXPECT_EQ(count(svg, "fill=\"none\" stroke-width=\"2\""), memoryRows + 1);
    for (const std::string& method : methods)
        EXPECT_EQ(count(svg, ">" + method + "</text>"), 1u) << method;
    EXPECT_NE(svg.find(">memory budget</text>"), std::string::npos);
    EXPECT_NE(svg.find(": torus</text>"), std::string::npos);
    EXPECT_NE(svg.find(" KiB</text>"), std::string::npos); // memory ticks
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

// With the generalized winding number as truth a closed mesh keeps every
// row (the voxel rows answer parity, the note says so), and on a closed,
// consistently oriented mesh the GWN is the winding rule: the sprite's GWN
// scores as its winding rule does, point for point.
TEST_F(CompareTest, GeneralizedWindingTruthKeepsVoxelRowsOnClosedMeshes) {
    const auto two = solids::overlappingBoxes({-1, -1, -1}, {0.3f, 0.3f, 0.3f}, {-0.3f, -0.3f, -0.3f}, {1, 1, 1});
    CompareOptions options;
    options.resolutions = {16};
    options.memoryBudgets = {8192};
    options.uniformPoints = 3000;
    options.surfacePoints = 1000;
    options.rule = Rule::GeneralizedWinding;
    const CompareResult result = compare(two.mesh, options, &gl());
    EXPECT_EQ(result.truth, "generalized-winding");
    EXPECT_NE(result.note.find("answer parity"), std::string::npos) << result.note;
    std::set<std::string> methods;
    const CompareRow *gwn = nullptr, *winding = nullptr, *parity = nullptr;
    for (const CompareRow& r : result.rows) {
        methods.insert(r.name());
        if (r.series != "resolution" || r.method != Method::Sprite) continue;
        if (r.rule == Rule::GeneralizedWinding) gwn = &r;
        if (r.rule == Rule::Winding) winding = &r;
        if (r.rule == Rule::Parity) parity = &r;
    }
    EXPECT_EQ(methods.size(), 7u);
    ASSERT_TRUE(gwn && winding && parity);
    EXPECT_EQ(gwn->uniformWrong, winding->uniformWrong);
    EXPECT_EQ(gwn->surfaceWrong, winding->surfaceWrong);
    // Parity calls the boxes' overlap (0.6^3 of the 2.4^3 padded box: ~47 of 3000 points) outside.
    EXPECT_GT(parity->uniformWrong, gwn->uniformWrong + 30);
    EXPECT_NE(result.table().find(result.note), std::string::npos);
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
