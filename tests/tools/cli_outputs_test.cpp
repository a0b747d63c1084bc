// The vds tool's outputs and messages as a new user meets them: what -o lands
// on (a symlink, a FIFO, a directory), one account of a mis-oriented or open
// mesh in every command, flags named only where they exist.
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

#include <gtest/gtest.h>
#include "cli_fixture.h"

#include <vds/mesh.h>
#include <vds/mesh_check.h>
#include <vds/mesh_io.h>
#include <vds/vds_file.h>

#include "solids.h"

namespace {

namespace fs = std::filesystem;
using vds::test::Result;
using vds::test::readFile;
using vds::test::run;
using vds::test::writeObj;

std::size_t lines(const std::string& text) { return std::size_t(std::count(text.begin(), text.end(), '\n')); }

class CliOutputs : public vds::test::ToolDirectory {
protected:
    CliOutputs() : ToolDirectory("vds_cli_outputs_") {}
    void SetUp() override {
        ToolDirectory::SetUp();
        writeObj(dir / "box.obj", vds::solids::box({-1, -1, -1}, {1, 0.5f, 2}).mesh);
        std::ofstream pts(dir / "points.txt");
        pts << "0 0 0\n0.9 0.4 1.9\n1.1 0 0\n0 0.6 0\n";
    }
};

// -o through a symlink writes the file it names and keeps the link; the same
// for text labels, .npy grids and sprites.
TEST_F(CliOutputs, SymlinkOutputsAreWrittenThrough) {
    fs::create_directories(dir / "real");
    for (const char* name : {"labels.txt", "grid.npy", "box.vds"}) {
        std::ofstream(dir / "real" / name) << "old";
        fs::create_symlink(std::string("real/") + name, dir / name);
    }
    Result r = vds("classify --method exact --mesh " + p("box.obj") + " " + p("points.txt") + " -o " + p("labels.txt") +
                   " --quiet");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(readFile(dir / "real" / "labels.txt"), "1\n1\n0\n0\n");
    r = vds("voxelize " + p("box.obj") + " --dims 4 -o " + p("grid.npy") + " --quiet");
    ASSERT_EQ(r.code, 0) << r.output;
    r = vds("bake " + p("box.obj") + " -o " + p("box.vds") + " --resolution 16 --method cpu --quiet");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NO_THROW(vds::readSprite(p("real/box.vds")));
    for (const char* name : {"labels.txt", "grid.npy", "box.vds"}) {
        EXPECT_TRUE(fs::is_symlink(dir / name)) << name;
        EXPECT_NE(readFile(dir / "real" / name), "old") << name;
    }
    EXPECT_EQ(std::distance(fs::directory_iterator(dir / "real"), fs::directory_iterator()), 3); // no temporaries
}

// -o on a FIFO writes into it (a reader waiting on it gets the labels); the
// FIFO stays a FIFO. A directory is refused with one line.
TEST_F(CliOutputs, FifoIsWrittenAndDirectoryRefused) {
    ASSERT_EQ(::mkfifo(p("pipe").c_str(), 0600), 0);
    std::string got;
    std::thread reader([&] { got = readFile(dir / "pipe"); });
    const Result r = vds("classify --method exact --mesh " + p("box.obj") + " " + p("points.txt") + " -o " + p("pipe") +
                         " --quiet");
    reader.join();
    EXPECT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(got, "1\n1\n0\n0\n");
    EXPECT_TRUE(fs::is_fifo(dir / "pipe"));

    // A full device of the test's own (where devices can be made): written
    // to, so the write fails and says so; the device stays a device.
    if (::mknod(p("full").c_str(), S_IFCHR | 0666, makedev(1, 7)) == 0) {
        const Result f = vds("classify --method exact --mesh " + p("box.obj") + " " + p("points.txt") + " -o " +
                             p("full") + " --quiet");
        EXPECT_EQ(f.code, 1) << f.output;
        EXPECT_NE(f.output.find("full: cannot write"), std::string::npos) << f.output;
        EXPECT_TRUE(fs::is_character_file(dir / "full"));
    }

    fs::create_directories(dir / "out.npy");
    const Result d = vds("voxelize " + p("box.obj") + " --dims 4 -o " + p("out.npy") + " --quiet");
    EXPECT_EQ(d.code, 1) << d.output;
    EXPECT_NE(d.output.find("out.npy: is a directory"), std::string::npos) << d.output;
    EXPECT_EQ(lines(d.output), 1u) << d.output;
    EXPECT_TRUE(fs::is_directory(dir / "out.npy"));
}

/// Two closed boxes, the second inside out, and one triangle of the first
/// reversed: closed, 3 conflicting edges and an inside-out part (the multibody case).
vds::TriangleMesh multibody() {
    vds::TriangleMesh a = vds::solids::box({0, 0, 0}, {1, 1, 1}).mesh, b = vds::solids::box({2, 0, 0}, {3, 1, 1}).mesh;
    for (glm::uvec3& t : b.triangles) std::swap(t.y, t.z);
    std::swap(a.triangles[0].y, a.triangles[0].z);
    return vds::solids::merge(a, b);
}

// A closed but mis-oriented mesh: bake says so with what each rule answers,
// info and bake say the same word, and the exact classifier's count is the
// validation's.
TEST_F(CliOutputs, MisorientedMeshIsToldWithWhatEachRuleAnswers) {
    writeObj(dir / "multibody.obj", multibody());
    const vds::MeshReport report = vds::validateMesh(multibody());
    ASSERT_STREQ(report.status(), "mis-oriented");
    Result r = vds("bake " + p("multibody.obj") + " -o " + p("m.vds") + " --resolution 16 --method cpu --quiet");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(lines(r.output), 2u) << r.output; // the warning and "wrote"
    for (const char* says : {"warning: ", "multibody.obj is closed but mis-oriented (3 inconsistently oriented edges, "
                                          "1 inside-out part)",
                             "the parity rule", "the winding rule does not define inside",
                             "the generalized winding number sees an inside-out part as outside", "flip"})
        EXPECT_NE(r.output.find(says), std::string::npos) << says << "\n" << r.output;
    EXPECT_NE(r.output.find(report.summary()), std::string::npos) << r.output;
    r = vds("info " + p("m.vds"));
    EXPECT_NE(r.output.find("status:            mis-oriented"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(report.summary()), std::string::npos) << r.output;
    r = vds("classify --method exact --rule generalized-winding --mesh " + p("multibody.obj") + " " + p("points.txt") +
            " -o " + p("l.txt") + " --quiet");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find(vds::windingBoundaryText(report.windingBoundaryEdges)), std::string::npos) << r.output;
    EXPECT_NE(report.summary().find(vds::windingBoundaryText(report.windingBoundaryEdges)), std::string::npos);
}

// A message names a flag only where the command has it: --allow-open in
// classify's, which accepts it; bake, voxelize, eval and compare name none.
TEST_F(CliOutputs, FlagsAreNamedOnlyWhereTheyExist) {
    auto box = vds::solids::box({0, 0, 0}, {1, 1, 1}).mesh;
    box.triangles.pop_back();
    writeObj(dir / "open.obj", box);
    const std::string open = p("open.obj");
    for (const std::string& command :
         {"bake " + open + " -o " + p("o.vds") + " --resolution 8 --method cpu", "voxelize " + open + " --dims 4 -o " + p("o.npy"),
          "eval " + open + " --resolutions 8 --points 10 --surface-points 10", "compare " + open + " --resolutions 8"}) {
        const Result r = vds(command + " --quiet");
        EXPECT_NE(r.output.find("open (3 boundary edges)"), std::string::npos) << command << "\n" << r.output;
        EXPECT_EQ(r.output.find("--allow-open"), std::string::npos) << command << "\n" << r.output;
        EXPECT_EQ(r.output.find("winding rule"), r.output.find("not defined by the winding rule")) << r.output;
    }
    // compare's default (parity) is named as the rule that does not answer.
    Result r = vds("compare " + open + " --resolutions 8 --quiet");
    EXPECT_NE(r.output.find("not defined by the parity rule"), std::string::npos) << r.output;
    r = vds("classify --mesh " + open + " " + p("points.txt") + " -o " + p("l.txt") + " --quiet");
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_NE(r.output.find("(--allow-open)"), std::string::npos) << r.output;
    r = vds("classify --allow-open --mesh " + open + " " + p("points.txt") + " -o " + p("l.txt") + " --quiet");
    EXPECT_EQ(r.code, 0) << r.output;
    // The warning for answering anyway says so, not that parity defines inside.
    EXPECT_NE(r.output.find("answered anyway"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("still defined"), std::string::npos) << r.output;
}

// An edge-on sheet (the tilted plane x = y, seen along z) is refused as flat,
// as an axis-aligned one is; option values get the nearest name suggested and
// the method list holds only what the CLI takes.
TEST_F(CliOutputs, EdgeOnSheetsAndOptionValuesAreToldClearly) {
    {
        std::ofstream out(dir / "tilted.obj");
        out << "v 0 0 0\nv 1 1 0\nv 0 0 1\nv 1 1 1\nf 1 2 3\nf 3 2 4\n";
    }
    Result r = vds("bake " + p("tilted.obj") + " -o " + p("t.vds") + " --axis z --method cpu --quiet");
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_NE(r.output.find("tilted.obj is flat (all its triangles lie in one plane)"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir / "t.vds"));

    r = vds("classify --method exakt --mesh " + p("box.obj") + " " + p("points.txt") + " -o " + p("l.txt"));
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("unknown method 'exakt'"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("(did you mean 'exact'?)"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("custom"), std::string::npos) << r.output; // the CLI refuses it: not offered
    EXPECT_EQ(lines(r.output), 1u) << r.output;
    r = vds("voxelize " + p("box.obj") + " --dims 4 -o " + p("g.npy") + " --rule paraty");
    EXPECT_NE(r.output.find("(did you mean 'parity'?)"), std::string::npos) << r.output;
    r = vds("classify --output-format txt --mesh " + p("box.obj") + " " + p("points.txt") + " -o " + p("l.txt"));
    EXPECT_NE(r.output.find("(did you mean 'text'?)"), std::string::npos) << r.output;
    r = vds("classify --help");
    EXPECT_EQ(r.output.find("custom"), std::string::npos) << r.output;
    // voxelize's help: the generalized winding number is the rule for open meshes, not "closed meshes".
    r = vds("voxelize --help");
    EXPECT_EQ(r.output.find("(closed meshes)"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("open meshes"), std::string::npos) << r.output;
}

} // namespace
