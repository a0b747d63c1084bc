// What `vds distance`, `vds sdf` and `vds bake --distance` write, and what
// they refuse before any work: several outputs written all or none, one file
// named twice, "-" for stdin and stdout, formats by extension, the distance
// grid's limit, and the grid's geometry in the summary.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <vds/distance.h>
#include <vds/grid.h>
#include <vds/mesh_io.h>
#include <vds/npy.h>
#include <vds/vds_file.h>

#include "cli_fixture.h"
#include "solids.h"

namespace {

namespace fs = std::filesystem;
using vds::test::Result;
using vds::test::readFile;
using vds::test::writeObj;

std::size_t lines(const std::string& text) { return std::size_t(std::count(text.begin(), text.end(), '\n')); }

// The values of text lines separated by `separator`, row by row.
std::vector<double> textValues(const std::string& text, char separator) {
    std::string spaced = text;
    std::replace(spaced.begin(), spaced.end(), separator, ' ');
    std::istringstream in(spaced);
    std::vector<double> values;
    std::string word;
    while (in >> word) values.push_back(std::strtod(word.c_str(), nullptr));
    return values;
}

class DistanceOutputs : public vds::test::ToolDirectory {
protected:
    DistanceOutputs() : ToolDirectory("vds_distance_outputs_") {}
    void SetUp() override {
        ToolDirectory::SetUp();
        writeObj(dir / "torus.obj", vds::solids::torus(glm::vec3(0.1f, 0.0f, -0.2f), 1.0f, 0.35f, 24).mesh);
        std::ofstream(dir / "points.txt") << "0 0 0\n1.1 0 -0.2\n0.3 0.2 0.1\n-1.2 0.4 0\n2 2 2\n0.9 -0.3 0.25\n";
        mesh = vds::loadMesh(p("torus.obj"));
        points = vds::loadPoints(p("points.txt"));
        const vds::SignedDistance query(mesh, vds::Rule::Parity);
        expected.resize(points.size());
        query.distance(points, expected.data());
        closest.resize(points.size());
        query.closestPoints(points, closest.data());
    }
    // Files holding "old", to see that a refused run leaves them so.
    void writeOld(std::initializer_list<const char*> names) const {
        for (const char* name : names) std::ofstream(dir / name) << "old";
    }
    vds::TriangleMesh mesh;
    std::vector<glm::vec3> points;
    std::vector<double> expected;
    std::vector<vds::ClosestPoint> closest;
};

// An output that cannot be written fails the run before any other output is
// replaced: the distances already computed are not half delivered.
TEST_F(DistanceOutputs, AFailedOutputLeavesEveryOutputAsItWas) {
    writeOld({"d.npy", "t.npy", "c.npy"});
    fs::create_directory(dir / "dir.npy");
    const std::string base = "distance " + p("torus.obj") + " " + p("points.txt") + " --quiet";
    const std::vector<std::string> failing = {
        " -o " + p("d.npy") + " --closest-points " + p("nodir/c.npy") + " --triangles " + p("t.npy"),
        " -o " + p("d.npy") + " --closest-points " + p("c.npy") + " --triangles " + p("nodir/t.npy"),
        " -o " + p("nodir/d.npy") + " --closest-points " + p("c.npy") + " --triangles " + p("t.npy"),
        " -o " + p("d.npy") + " --triangles " + p("dir.npy"), // a directory
    };
    for (const std::string& outputs : failing) {
        const Result r = vds(base + outputs);
        EXPECT_EQ(r.code, 1) << outputs << ": " << r.output;
        EXPECT_EQ(lines(r.output), 1u) << outputs << ": " << r.output;
        for (const char* name : {"d.npy", "t.npy", "c.npy"}) EXPECT_EQ(readFile(dir / name), "old") << outputs << name;
    }
    // Nothing is left beside them either (no temporary files).
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 6);
}

// One file named by two outputs is refused before any work, whatever the
// spelling (./, a symlink), and stdout can take one output only.
TEST_F(DistanceOutputs, OneFileNamedTwiceIsRefused) {
    writeOld({"out.npy"});
    fs::create_symlink("out.npy", dir / "link.npy");
    const std::string base = "distance " + p("torus.obj") + " " + p("points.txt") + " -o " + p("out.npy");
    for (const std::string& twice : {" --closest-points " + p("out.npy"), " --triangles " + (dir / "." / "out.npy").string(),
                                     " --closest-points " + p("link.npy")}) {
        const Result r = vds(base + twice);
        EXPECT_EQ(r.code, 2) << twice << ": " << r.output;
        EXPECT_EQ(lines(r.output), 1u) << twice << ": " << r.output;
        EXPECT_NE(r.output.find("name the same file"), std::string::npos) << r.output;
        EXPECT_EQ(readFile(dir / "out.npy"), "old") << twice;
    }
    const Result r = vds("distance " + p("torus.obj") + " " + p("points.txt") + " -o - --triangles - --quiet");
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("name the same file (standard output)"), std::string::npos) << r.output;
}

// The outputs all land, each in the format its extension names.
TEST_F(DistanceOutputs, TextAndCsvOutputsHoldTheLibrarysValues) {
    const Result r = vds("distance " + p("torus.obj") + " " + p("points.txt") + " -o " + p("d.txt") +
                         " --closest-points " + p("c.csv") + " --triangles " + p("t.npy") + " --quiet");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(textValues(readFile(dir / "d.txt"), ' '), expected);
    const std::string csv = readFile(dir / "c.csv");
    EXPECT_EQ(lines(csv), points.size());
    EXPECT_EQ(std::count(csv.begin(), csv.end(), ','), long(2 * points.size()));
    const std::vector<double> xyz = textValues(csv, ',');
    ASSERT_EQ(xyz.size(), 3 * points.size());
    const vds::NpyArray triangles = vds::readNpy(p("t.npy"));
    EXPECT_EQ(triangles.descr, "<u4");
    for (std::size_t k = 0; k < points.size(); ++k) {
        EXPECT_EQ(glm::dvec3(xyz[3 * k], xyz[3 * k + 1], xyz[3 * k + 2]), closest[k].point) << k;
        std::uint32_t t = 0;
        std::memcpy(&t, triangles.data.data() + 4 * k, 4);
        EXPECT_EQ(t, closest[k].triangle) << k;
    }
}

// A name whose extension is no format is refused, naming those there are,
// before any work: it used to get .npy bytes.
TEST_F(DistanceOutputs, AnUnknownExtensionIsRefusedNamingTheFormats) {
    const std::string distance = "distance " + p("torus.obj") + " " + p("points.txt");
    const std::vector<std::string> refused = {
        distance + " -o " + p("d.vdb"), distance + " -o " + p("d.npy") + " --closest-points " + p("c.ply"),
        "sdf " + p("torus.obj") + " --dims 8 -o " + p("d.vdb"), "sdf " + p("torus.obj") + " --dims 8 -o " + p("d.txt")};
    for (const std::string& args : refused) {
        const Result r = vds(args + " --quiet");
        EXPECT_EQ(r.code, 2) << args << ": " << r.output;
        EXPECT_EQ(lines(r.output), 1u) << args << ": " << r.output;
        EXPECT_NE(r.output.find("supported: .npy"), std::string::npos) << r.output;
    }
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 2);
}

// "-" reads the points from stdin and writes the distances to stdout (text,
// or .npy with --output-format npy), the summary on stderr.
TEST_F(DistanceOutputs, DashIsStdinAndStdout) {
    // In a subshell, so that only stdout goes to the file and stderr to the result.
    const auto toFile = [&](const std::string& args, const char* name) {
        return vds::test::run("(" + std::string(VDS_TOOL) + " " + args + " > " + p(name) + ")");
    };
    Result r = toFile("distance " + p("torus.obj") + " - -o - < " + p("points.txt"), "d.txt");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("wrote -: 6 points"), std::string::npos) << r.output;
    EXPECT_EQ(textValues(readFile(dir / "d.txt"), ' '), expected);
    r = toFile("distance " + p("torus.obj") + " " + p("points.txt") + " -o - --output-format npy --quiet", "d.npy");
    ASSERT_EQ(r.code, 0) << r.output;
    const vds::NpyArray d = vds::readNpy(p("d.npy"));
    ASSERT_EQ(d.shape, (std::vector<std::uint64_t>{points.size()}));
    std::vector<double> values(points.size());
    std::memcpy(values.data(), d.data.data(), d.data.size());
    EXPECT_EQ(values, expected);
    r = toFile("sdf " + p("torus.obj") + " --dims 6 -o - --quiet", "grid.npy");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(vds::readNpy(p("grid.npy")).shape, (std::vector<std::uint64_t>{6, 6, 6}));
}

// --cubic: N cells along the longest side and cubic cells, as vds.Grid.cubic
// places them; the summary gives the box and the cell size.
TEST_F(DistanceOutputs, SdfCubicCellsAndItsGeometryInTheSummary) {
    const Result r = vds("sdf " + p("torus.obj") + " --dims 12 --cubic -o " + p("g.npy") + " --quiet");
    ASSERT_EQ(r.code, 0) << r.output;
    const vds::Grid grid = vds::cubicGrid(vds::meshBounds(mesh), 12);
    const vds::NpyArray a = vds::readNpy(p("g.npy"));
    ASSERT_EQ(a.shape, (std::vector<std::uint64_t>{grid.dims.x, grid.dims.y, grid.dims.z}));
    EXPECT_EQ(grid.dims.x, 12u);
    EXPECT_LT(grid.dims.z, 6u); // the torus is flat along z: a cubic grid has few cells there
    std::vector<float> cells(grid.cellCount());
    vds::SignedDistance(mesh, vds::Rule::Parity).grid(grid, cells.data());
    EXPECT_EQ(std::memcmp(cells.data(), a.data.data(), a.data.size()), 0);
    char box[160];
    std::snprintf(box, sizeof box, "box [%.9g, %.9g, %.9g] to [%.9g, %.9g, %.9g]", grid.box.lo.x, grid.box.lo.y,
                  grid.box.lo.z, grid.box.hi.x, grid.box.hi.y, grid.box.hi.z);
    EXPECT_NE(r.output.find(box), std::string::npos) << box << "\n" << r.output;
    const glm::vec3 cell = (grid.box.hi - grid.box.lo) / glm::vec3(grid.dims);
    EXPECT_NEAR(cell.z, cell.x, 1e-6f * cell.x); // cubic, up to the box's float rounding
    char size[96];
    std::snprintf(size, sizeof size, "cells %.9g x %.9g x %.9g", cell.x, cell.y, cell.z);
    EXPECT_NE(r.output.find(size), std::string::npos) << size << "\n" << r.output;
    EXPECT_EQ(vds("sdf " + p("torus.obj") + " --dims-xyz 4 4 4 --cubic -o " + p("x.npy")).code, 2);
}

// bake --distance is refused at argument time where its grid cannot fit the
// file (it used to bake for minutes first), --help says the real range and no
// default of 0, and --distance-rule without --distance is refused.
TEST_F(DistanceOutputs, BakeDistanceLimitsBeforeAnyWork) {
    for (const char* extra : {" --distance 1024", " --distance 813", " --distance 3", " --distance-rule parity"}) {
        const Result r = vds("bake " + p("torus.obj") + " -o " + p("t.vds") + " --method cpu" + extra);
        EXPECT_EQ(r.code, 2) << extra << ": " << r.output;
        EXPECT_EQ(lines(r.output), 1u) << extra << ": " << r.output;
        EXPECT_FALSE(fs::exists(p("t.vds"))) << extra;
    }
    const Result help = vds("bake --help");
    EXPECT_NE(help.output.find("--distance 4..812 "), std::string::npos) << help.output;
    const Result sdfHelp = vds("sdf --help");
    EXPECT_EQ(sdfHelp.output.find("--band W=0"), std::string::npos) << sdfHelp.output;
    const Result r = vds("bake " + p("torus.obj") + " -o " + p("t.vds") + " --resolution 16 --method cpu --distance 8 "
                         "--distance-rule parity --quiet");
    EXPECT_EQ(r.code, 0) << r.output;
}

// A flat mesh (a sheet) has distances and closest points: --unsigned gives
// them; signed, it is refused with why and what answers it.
TEST_F(DistanceOutputs, UnsignedDistanceOnAFlatMesh) {
    std::ofstream(p("sheet.obj")) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    std::ofstream(p("near.txt")) << "0.25 0.25 2\n-3 0 4\n";
    Result r = vds("distance " + p("sheet.obj") + " " + p("near.txt") + " --unsigned -o " + p("d.txt") +
                   " --closest-points " + p("c.txt") + " --quiet");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("2 points, unsigned"), std::string::npos) << r.output;
    EXPECT_EQ(textValues(readFile(dir / "d.txt"), ' '), (std::vector<double>{2.0, 5.0}));
    EXPECT_EQ(textValues(readFile(dir / "c.txt"), ' '), (std::vector<double>{0.25, 0.25, 0.0, 0.0, 0.0, 0.0}));
    r = vds("distance " + p("sheet.obj") + " " + p("near.txt") + " --rule generalized-winding -o " + p("s.npy") + " --quiet");
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_EQ(lines(r.output), 1u) << r.output;
    EXPECT_NE(r.output.find("no sign (--unsigned)"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(p("s.npy")));
}

// One default rule: distance, sdf, voxelize and bake --distance sign (or
// label) by parity unless told otherwise, and say so in their help; bake's
// distance grid is that rule's.
TEST_F(DistanceOutputs, OneDefaultRuleEverywhere) {
    for (const char* command : {"distance --help", "sdf --help", "voxelize --help", "bake --help", "classify --help"}) {
        const Result r = vds(command);
        EXPECT_NE(r.output.find("parity|winding|generalized-winding=parity"), std::string::npos) << command << r.output;
    }
    // An open cup, where the rules differ: the bake warns and signs by parity.
    const vds::TriangleMesh cup = vds::solids::sphereCup();
    writeObj(dir / "cup.obj", cup);
    const Result r = vds("bake " + p("cup.obj") + " -o " + p("c.vds") + " --resolution 16 --method cpu --distance 10 --quiet");
    ASSERT_EQ(r.code, 0) << r.output;
    const vds::Sprite sprite = vds::readSprite(p("c.vds"));
    const vds::SpriteDistance parity = vds::bakeDistance(cup, sprite.grid.box, 10, vds::Rule::Parity);
    const vds::SpriteDistance gwn = vds::bakeDistance(cup, sprite.grid.box, 10, vds::Rule::GeneralizedWinding);
    EXPECT_NE(parity.cells, gwn.cells);
    EXPECT_EQ(sprite.distance.grid.dims, parity.grid.dims);
    EXPECT_EQ(sprite.distance.cells, parity.cells);
}

} // namespace
