// `vds distance` and `vds sdf` run as a user runs them: real files in a
// temporary directory, the values equal to the library's on the same points
// and cells, exit codes and one-line messages for bad input, nothing written.
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <vds/distance.h>
#include <vds/mesh_io.h>
#include <vds/npy.h>

#include "cli_fixture.h"
#include "solids.h"

namespace {

namespace fs = std::filesystem;
using vds::test::Result;
using vds::test::readFile;
using vds::test::run;
using vds::test::writeObj;

template <class T> std::vector<T> npyValues(const std::string& path, const std::string& descr) {
    const vds::NpyArray a = vds::readNpy(path);
    EXPECT_EQ(a.descr, descr) << path;
    std::vector<T> values(a.data.size() / sizeof(T));
    std::memcpy(values.data(), a.data.data(), values.size() * sizeof(T));
    return values;
}

class DistanceCli : public vds::test::ToolDirectory {
protected:
    DistanceCli() : ToolDirectory("vds_distance_cli_") {}
    void SetUp() override {
        ToolDirectory::SetUp();
        writeObj(dir / "torus.obj", vds::solids::torus(glm::vec3(0.1f, 0.0f, -0.2f), 1.0f, 0.35f, 24).mesh);
        writeObj(dir / "cup.obj", vds::solids::sphereCup());
        std::ofstream pts(dir / "points.txt");
        pts << "0 0 0\n1.1 0 -0.2\n0.3 0.2 0.1\n-1.2 0.4 0\n2 2 2\n0.9 -0.3 0.25\n";
    }
};

TEST_F(DistanceCli, DistanceEqualsTheLibraryOnTheSamePoints) {
    const Result r = vds("distance " + p("torus.obj") + " " + p("points.txt") + " -o " + p("d.npy") +
                         " --rule winding --closest-points " + p("q.npy") + " --triangles " + p("t.npy") + " --quiet");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("6 points, 1 inside"), std::string::npos) << r.output;
    const vds::TriangleMesh mesh = vds::loadMesh(p("torus.obj"));
    const std::vector<glm::vec3> points = vds::loadPoints(p("points.txt"));
    const vds::SignedDistance query(mesh, vds::Rule::Winding);
    std::vector<double> expected(points.size());
    query.distance(points, expected.data());
    std::vector<vds::ClosestPoint> closest(points.size());
    query.closestPoints(points, closest.data());
    EXPECT_EQ(npyValues<double>(p("d.npy"), "<f8"), expected);
    const std::vector<double> xyz = npyValues<double>(p("q.npy"), "<f8");
    const std::vector<std::uint32_t> triangles = npyValues<std::uint32_t>(p("t.npy"), "<u4");
    ASSERT_EQ(xyz.size(), 3 * points.size());
    for (std::size_t k = 0; k < points.size(); ++k) {
        EXPECT_EQ(glm::dvec3(xyz[3 * k], xyz[3 * k + 1], xyz[3 * k + 2]), closest[k].point) << k;
        EXPECT_EQ(triangles[k], closest[k].triangle) << k;
    }
}

TEST_F(DistanceCli, SdfEqualsTheLibraryOnTheSameCells) {
    Result r = vds("sdf " + p("cup.obj") + " --dims-xyz 11 9 7 --pad 0.1 --rule generalized-winding -o " +
                   p("full.npy") + " --quiet");
    ASSERT_EQ(r.code, 0) << r.output;
    r = vds("sdf " + p("cup.obj") + " --dims-xyz 11 9 7 --pad 0.1 --band 0.2 --rule generalized-winding -o " +
            p("band.npy") + " --quiet");
    ASSERT_EQ(r.code, 0) << r.output;
    r = vds("sdf " + p("cup.obj") + " --dims-xyz 11 9 7 --pad 0.1 --propagated --rule generalized-winding -o " +
            p("propagated.npy") + " --quiet");
    ASSERT_EQ(r.code, 0) << r.output;
    const vds::TriangleMesh mesh = vds::loadMesh(p("cup.obj"));
    vds::Grid grid;
    grid.box = vds::meshBounds(mesh);
    const glm::vec3 margin = 0.1f * (grid.box.hi - grid.box.lo);
    grid.box.lo -= margin;
    grid.box.hi += margin;
    grid.dims = glm::uvec3(11, 9, 7);
    const vds::SignedDistance query(mesh, vds::Rule::GeneralizedWinding);
    std::vector<float> full(grid.cellCount()), band(grid.cellCount()), propagated(grid.cellCount());
    query.grid(grid, full.data());
    query.grid(grid, band.data(), vds::DistanceGridOptions{0, 0.2});
    query.grid(grid, propagated.data(), vds::DistanceGridOptions{0, 0.0, vds::FarCells::Propagated});
    EXPECT_EQ(vds::readNpy(p("full.npy")).shape, (std::vector<std::uint64_t>{11, 9, 7}));
    EXPECT_EQ(npyValues<float>(p("full.npy"), "<f4"), full);
    EXPECT_EQ(npyValues<float>(p("band.npy"), "<f4"), band);
    EXPECT_EQ(npyValues<float>(p("propagated.npy"), "<f4"), propagated);
    EXPECT_NE(std::count(band.begin(), band.end(), 0.2f), 0);
}

TEST_F(DistanceCli, BadInputGetsOneLineAndWritesNothing) {
    std::ofstream(p("nan.txt")) << "0 0 0\nnan 0 0\n";
    std::ofstream(p("flat.obj")) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    std::ofstream(p("empty.obj")) << "# nothing\n";
    const std::string torus = p("torus.obj"), out = " -o " + p("out.npy");
    struct Bad {
        std::string args;
        int code;
    };
    const std::vector<Bad> bad = {
        {"distance " + torus + " " + p("nan.txt") + out, 1},
        {"distance " + p("cup.obj") + " " + p("points.txt") + out, 1}, // open: parity defines no inside
        {"sdf " + p("cup.obj") + " --dims 4" + out, 1},
        {"distance " + p("flat.obj") + " " + p("points.txt") + out + " --rule generalized-winding", 1},
        {"distance " + p("empty.obj") + " " + p("points.txt") + out, 1},
        {"distance " + torus + " " + p("missing.txt") + out, 1},
        {"distance " + torus + out, 2},
        {"sdf " + torus + " --dims 8 --band -1" + out, 2},
        {"sdf " + torus + " --dims 8 --band 0" + out, 2},
        {"sdf " + torus + " --dims 8 --band nan" + out, 2},
        {"sdf " + torus + " --dims 8 --band 0.1 --propagated" + out, 2},
        {"sdf " + torus + " --dims 0" + out, 2},
        {"sdf " + torus + out, 2},
        {"sdf " + p("flat.obj") + " --dims 8 --rule generalized-winding" + out, 1},
    };
    for (const Bad& b : bad) {
        const Result r = vds(b.args + " --quiet");
        EXPECT_EQ(r.code, b.code) << b.args << ": " << r.output;
        EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << b.args << ": " << r.output;
        EXPECT_FALSE(fs::exists(p("out.npy"))) << b.args;
    }
}

TEST_F(DistanceCli, CommandsHaveHelp) {
    for (const char* c : {"distance --help", "sdf --help"}) {
        const Result r = vds(c);
        EXPECT_EQ(r.code, 0) << c;
        EXPECT_NE(r.output.find("usage: vds"), std::string::npos) << c << r.output;
    }
}

} // namespace
