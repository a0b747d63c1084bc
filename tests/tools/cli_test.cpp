// The vds tool and the clip sample, run as a user runs them: real files in a
// temporary directory, exit codes and one-line messages checked.
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include "cli_fixture.h"

#include <vds/distance.h>
#include <vds/eval/image.h>
#include <vds/exact.h>
#include <vds/mesh_io.h>
#include <vds/npy.h>
#include <vds/occupancy.h>
#include <vds/vds_file.h>

#include "../support/image_compare.h"
#include "solids.h"

namespace {

namespace fs = std::filesystem;

using vds::test::Result;
using vds::test::readFile;
using vds::test::run;
using vds::test::writeObj;

std::string lastLine(const std::string& text) {
    std::string t = text;
    while (!t.empty() && t.back() == '\n') t.pop_back();
    const auto n = t.rfind('\n');
    return n == std::string::npos ? t : t.substr(n + 1);
}

class Cli : public vds::test::ToolDirectory {
protected:
    Cli() : ToolDirectory("vds_cli_test_") {}
    void SetUp() override {
        ToolDirectory::SetUp();
        writeObj(dir / "box.obj", vds::solids::box({-1, -1, -1}, {1, 0.5f, 2}).mesh);
        std::ofstream pts(dir / "points.txt");
        pts << "0 0 0\n0.9 0.4 1.9\n1.1 0 0\n0 0.6 0\n-0.5 -0.5 -1.5\n# a comment\n0.5 0 1\n";
    }
};

TEST_F(Cli, BakeInfoClassifyRoundTrip) {
    // --opt=value, and a leading zero read as decimal (not octal 52).
    Result r = vds("bake " + p("box.obj") + " -o " + p("box.vds") + " --resolution=064 --axis z --quiet");
    ASSERT_EQ(r.code, 0) << r.output;
    r = vds("info " + p("box.vds"));
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("depth complexity:  2"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("box.obj, 12 triangles"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("resolution:        64 x 48 texels"), std::string::npos) << r.output;
    for (const char* extra : {"", " --gpu", " --rule winding", " --threads 1"}) {
        r = vds("classify " + p("box.vds") + " " + p("points.txt") + " -o " + p("labels.txt") + extra + " --quiet");
        ASSERT_EQ(r.code, 0) << extra << ": " << r.output;
        EXPECT_EQ(readFile(dir / "labels.txt"), "1\n1\n0\n0\n0\n1\n") << extra;
    }
    r = vds("classify --exact --mesh " + p("box.obj") + " " + p("points.txt") + " -o " + p("exact.txt") + " --quiet");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(readFile(dir / "exact.txt"), "1\n1\n0\n0\n0\n1\n");
    r = vds("classify --mesh " + p("box.obj") + " --with vds --resolution 32 " + p("points.txt") + " -o " +
            p("with.txt") + " --quiet");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(readFile(dir / "with.txt"), "1\n1\n0\n0\n0\n1\n");
}

// --distance stores the exact signed distance grid (format version 3), which
// info reports; every cell is the exact distance of its centre.
TEST_F(Cli, BakeStoresTheExactDistanceGrid) {
    Result r = vds("bake " + p("box.obj") + " -o " + p("d.vds") + " --resolution 32 --distance 12 --quiet");
    ASSERT_EQ(r.code, 0) << r.output;
    r = vds("info " + p("d.vds"));
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("format version:    3"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("distance grid:     10 x 8 x 12 cells"), std::string::npos) << r.output;
    const vds::Sprite sprite = vds::readSprite(p("d.vds"));
    const vds::SignedDistance exact(vds::loadMesh(p("box.obj")), vds::Rule::Parity); // every command's default
    const vds::Grid& g = sprite.distance.grid;
    ASSERT_EQ(sprite.distance.cells.size(), g.cellCount());
    std::size_t same = 0;
    for (std::uint32_t i = 0; i < g.dims.x; ++i)
        for (std::uint32_t j = 0; j < g.dims.y; ++j)
            for (std::uint32_t k = 0; k < g.dims.z; ++k)
                same += sprite.distance.cells[g.index(i, j, k)] == float(exact.distance(g.cellCentre(i, j, k)));
    EXPECT_EQ(same, g.cellCount());
    for (const char* bad : {" --distance 3", " --distance 1025", " --distance-rule odd"}) {
        r = vds("bake " + p("box.obj") + " -o " + p("x.vds") + bad);
        EXPECT_EQ(r.code, 2) << bad << ": " << r.output;
        EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << bad << ": " << r.output;
    }
    EXPECT_FALSE(fs::exists(dir / "x.vds"));
}

TEST_F(Cli, AllBakeMethodsWriteTheSameSprite) {
    for (const char* m : {"lists", "peel", "cpu"}) {
        const Result r = vds(std::string("bake ") + p("box.obj") + " -o " + p(std::string(m) + ".vds") +
                             " --resolution 40 --axis y --quiet --method " + m);
        ASSERT_EQ(r.code, 0) << m << ": " << r.output;
    }
    EXPECT_EQ(readFile(dir / "lists.vds"), readFile(dir / "peel.vds"));
    const Result a = vds("info " + p("lists.vds")), b = vds("info " + p("cpu.vds"));
    EXPECT_EQ(a.output.substr(a.output.find("depth complexity")), b.output.substr(b.output.find("depth complexity")));
}

TEST_F(Cli, EvalReportsAndWritesJsonAndSlices) {
    const Result r = vds("eval " + p("box.obj") + " --resolutions 16,32 --points 20000 --surface-points 20000 --json " +
                         p("eval.json") + " --images " + p("slice") + " --quiet");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("| 32 | 32x24x2 |"), std::string::npos) << r.output;
    const std::string json = readFile(dir / "eval.json");
    EXPECT_NE(json.find("\"rows\": ["), std::string::npos) << json;
    for (const char* axis : {"x", "y", "z"}) {
        const vds::eval::Image slice = vds::eval::readPng(p(std::string("slice-32-") + axis + ".png"));
        EXPECT_GT(slice.width, 100u);
    }
    EXPECT_EQ(vds("eval " + p("box.obj") + " --resolutions 0").code, 2);
}

TEST_F(Cli, EveryRepresentationAnswersTheSameQueries) {
    for (const char* with : {"slicemap", "slicemap-local", "solid", "solid-compute"})
        for (const char* gpu : {"", " --gpu"}) {
            const Result r = vds("classify --mesh " + p("box.obj") + " --with " + with + " --resolution 32 " +
                                 p("points.txt") + " -o " + p("w.txt") + gpu + " --quiet");
            ASSERT_EQ(r.code, 0) << with << gpu << ": " << r.output;
            EXPECT_EQ(readFile(dir / "w.txt"), "1\n1\n0\n0\n0\n1\n") << with << gpu;
        }
    EXPECT_EQ(vds("classify --mesh " + p("box.obj") + " --with voxels " + p("points.txt") + " -o " + p("w.txt")).code, 2);
    EXPECT_EQ(vds("classify --mesh " + p("box.obj") + " --with solid --resolution 0 " + p("points.txt") + " -o " +
                  p("w.txt")).code, 2);
}

TEST_F(Cli, CompareWritesTableJsonAndChart) {
    const Result r = vds("compare " + p("box.obj") + " --resolutions 16 --points=5000 --surface-points 2000 --json " +
                         p("c.json") + " --chart " + p("c.svg") + " --quiet");
    ASSERT_EQ(r.code, 0) << r.output;
    const std::string svg = readFile(dir / "c.svg");
    EXPECT_EQ(svg.rfind("<svg ", 0), 0u) << svg.substr(0, 100);
    EXPECT_EQ(svg.substr(svg.size() - 7), "</svg>\n");
    for (const char* method : {"sprite", "sprite/winding", "slicemap", "slicemap-local", "solid", "solid-compute"}) {
        EXPECT_NE(r.output.find(method), std::string::npos) << method;
        EXPECT_NE(svg.find(std::string(">") + method + "</text>"), std::string::npos) << method;
    }
    EXPECT_NE(readFile(dir / "c.json").find("solid-compute"), std::string::npos);
    EXPECT_NE(r.output.find("wrote " + p("c.svg")), std::string::npos) << r.output;
}

TEST_F(Cli, CompareOnAnOpenMeshByTheGeneralizedWindingNumber) {
    // A cup upside down: its open side faces -z, where the sprite's rays
    // start, so parity calls the cup's inside outside.
    writeObj(dir / "cup.obj", vds::solids::without(vds::solids::sphere({0, 0, 0}, 1.0f, 32).mesh,
                                                   [](const glm::vec3& c) { return c.z < -0.5f; }));
    const std::string args = " --resolutions 16 --points 4000 --surface-points 1000 --quiet";
    // The default comparison needs a solid: one clear line.
    Result r = vds("compare " + p("cup.obj") + args);
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
    EXPECT_NE(r.output.find("generalized-winding"), std::string::npos) << r.output;
    r = vds("compare " + p("cup.obj") + args + " --rule generalized-winding --json " + p("cup.json"));
    ASSERT_EQ(r.code, 0) << r.output;
    for (const char* method : {"sprite ", "sprite/winding", "sprite/generalized-winding"})
        EXPECT_NE(r.output.find(method), std::string::npos) << method << " in\n" << r.output;
    EXPECT_EQ(r.output.find("\nslicemap"), std::string::npos) << r.output; // they need a closed mesh
    EXPECT_EQ(r.output.find("\nsolid"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("the VDS only"), std::string::npos) << r.output;
    EXPECT_NE(readFile(dir / "cup.json").find("\"truth\": \"generalized-winding\""), std::string::npos);
    // Against the exact GWN the sprite's GWN is nearly right (wrong only
    // next to the surface or the rim) and parity is not. Table columns: method series target
    // res cells memory(2) gpu(2) build Mpts/s err% unif% ...
    double gwnError = -1.0, parityError = -1.0;
    std::istringstream table(r.output);
    for (std::string line; std::getline(table, line);) {
        std::istringstream in(line);
        std::vector<std::string> t{std::istream_iterator<std::string>(in), std::istream_iterator<std::string>()};
        if (t.size() < 13 || t[1] != "resolution") continue;
        if (t[0] == "sprite/generalized-winding") gwnError = std::stod(t[12]);
        if (t[0] == "sprite") parityError = std::stod(t[12]);
    }
    EXPECT_GE(gwnError, 0.0);
    EXPECT_LT(gwnError, 4.0) << r.output; // per cent: the 16-texel sprite errs within a texel of the surface
    EXPECT_GT(parityError, 5.0 * gwnError + 1.0);
    // eval measures the sprite's GWN against the exact one on open meshes too.
    r = vds("eval " + p("cup.obj") + " --resolutions 16 --points 500 --surface-points 100 --quiet"
            " --rule generalized-winding");
    EXPECT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("rule generalized-winding"), std::string::npos) << r.output;
}

TEST_F(Cli, ClassifyOnTheGpuByTheGeneralizedWindingNumberOfAnOpenSprite) {
    writeObj(dir / "cup.obj", vds::solids::sphereCup());
    ASSERT_EQ(vds("bake " + p("cup.obj") + " -o " + p("cup.vds") + " --resolution 48 --quiet").code, 0);
    {
        std::mt19937 rng(4);
        std::uniform_real_distribution<float> u(-1.1f, 1.1f);
        std::ofstream pts(dir / "many.txt");
        for (int k = 0; k < 3000; ++k) pts << u(rng) << ' ' << u(rng) << ' ' << u(rng) << '\n';
    }
    const std::string args = p("cup.vds") + " " + p("many.txt") + " --rule generalized-winding --quiet -o ";
    Result r = vds("classify " + args + p("cpu.txt"));
    ASSERT_EQ(r.code, 0) << r.output;
    r = vds("classify --gpu " + args + p("gpu.txt"));
    ASSERT_EQ(r.code, 0) << r.output;
    const std::string cpu = readFile(dir / "cpu.txt");
    EXPECT_EQ(readFile(dir / "gpu.txt"), cpu); // float on the GPU: equal unless a point sits within ~1e-5 of w = 1/2
    EXPECT_GT(std::count(cpu.begin(), cpu.end(), '1'), 300);
}

TEST_F(Cli, EveryCommandHasHelp) {
    for (const char* c :
         {"--help", "help", "bake --help", "classify --help", "info --help", "eval --help", "compare --help"}) {
        const Result r = vds(c);
        EXPECT_EQ(r.code, 0) << c;
        EXPECT_NE(r.output.find("usage: vds"), std::string::npos) << c;
    }
    const Result none = vds("");
    EXPECT_EQ(none.code, 2);
    EXPECT_NE(none.output.find("usage: vds"), std::string::npos) << none.output;
}

#if defined(VDS_CLIP) || defined(VDS_EXACT_BENCH)
// The sample and the benchmark (those built) read their command lines like
// the tool: help exits 0, a wrong command line 2 with one line.
void expectToolCommandLines(const std::vector<std::string>& programs, const std::vector<std::string>& bad) {
    for (const std::string& program : programs) {
        const Result r = run(program + " --help");
        EXPECT_EQ(r.code, 0) << program << ": " << r.output;
        EXPECT_NE(r.output.find("usage: vds_"), std::string::npos) << r.output;
    }
    for (const std::string& command : bad) {
        const Result r = run(command);
        EXPECT_EQ(r.code, 2) << command << ": " << r.output;
        EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << command << ": " << r.output;
    }
}
#endif

#ifdef VDS_CLIP
TEST_F(Cli, SampleCommandLines) {
    const std::string mesh = p("box.obj"), clip = mesh + " --clip a.vds -o x.png";
    std::vector<std::string> bad;
    for (const std::string& args : std::vector<std::string>{
             "", "--clip a.vds -o x.png", mesh + " -o x.png", mesh + " --clip a.vds", clip + " --size 8",
             clip + " --size=abc", clip + " --view w", clip + " --rule odd", mesh + " " + clip,
             mesh + " -o x.png --clip 1 --clip 2 --clip 3 --clip 4 --clip 5 --clip 6 --clip 7 --clip 8 --clip 9"})
        bad.push_back(std::string(VDS_CLIP) + " " + args);
    expectToolCommandLines({VDS_CLIP}, bad);
}
#endif

#ifdef VDS_EXACT_BENCH
TEST_F(Cli, BenchmarkCommandLines) {
    std::vector<std::string> bad;
    for (const char* args : {"--points 0", "--sample=-1", "--points abc", "--bogus"})
        bad.push_back(std::string(VDS_EXACT_BENCH) + " " + args);
    expectToolCommandLines({VDS_EXACT_BENCH}, bad);
}
#endif

// Defaults in the help are the library's option structs' own, and the
// choices are the enums' names.
TEST_F(Cli, HelpShowsDefaultsAndChoices) {
    const std::string bake = vds("bake --help").output;
    for (const char* shown : {"--resolution 1..16384=1024", "--axis x|y|z|auto=auto", "--method auto|lists|peel|cpu=auto"})
        EXPECT_NE(bake.find(shown), std::string::npos) << shown << " in\n" << bake;
    const std::string eval = vds("eval --help").output;
    for (const char* shown :
         {"--resolutions N,N=[256,512,1024,2048]", "--points N=1000000", "--rule parity|winding|generalized-winding=parity", "--seed N=1"})
        EXPECT_NE(eval.find(shown), std::string::npos) << shown << " in\n" << eval;
    const std::string compare = vds("compare --help").output;
    for (const char* shown :
         {"--resolutions N,N=[32,64,128]", "each 1..4096", "--points N=100000", "--surface-points N=50000"})
        EXPECT_NE(compare.find(shown), std::string::npos) << shown << " in\n" << compare;
    const std::string classify = vds("classify --help").output;
    for (const char* shown : {"--method sprite|exact|certified|sprite-gpu|slicemap|slicemap-local|solid|solid-compute|"
                              "slicemap-gpu|slicemap-local-gpu|solid-gpu|solid-compute-gpu|certified-gpu=sprite",
                              "=1024 for sprites and certified bands, 256 for voxels", "--threads N=0"})
        EXPECT_NE(classify.find(shown), std::string::npos) << shown << " in\n" << classify;
}

TEST_F(Cli, BadCommandLinesExitTwoWithOneLine) {
    const std::string box = p("box.obj"), points = p("points.txt"), sprite = p("box.vds");
    const std::vector<std::string> bad = {
        "bake",
        "bake " + box,
        "bake " + box + " -o x.vds --resolution 0",
        "bake " + box + " -o x.vds --resolution 100000",
        "bake " + box + " -o x.vds --resolution abc",
        "bake " + box + " -o x.vds --resolution=-3",
        "bake " + box + " -o x.vds --resolution 0x40",
        "bake " + box + " -o x.vds --axis w",
        "bake " + box + " -o x.vds --method=gpu",
        "bake " + box + " -o x.vds --bogus",
        "bake " + box + " " + box + " -o x.vds",
        "classify " + sprite,
        "classify --exact " + points + " -o x.txt",
        "classify --method exact " + sprite + " " + points + " -o x.txt",
        "classify --method slicemap --gpu --exact --mesh " + box + " " + points + " -o x.txt",
        "classify --method exact --gpu --mesh " + box + " " + points + " -o x.txt",
        "classify --method sprite --resolution 64 " + sprite + " " + points + " -o x.txt",
        "classify --mesh " + box + " --with solid --rule winding " + points + " -o x.txt",
        "classify --with solid " + sprite + " " + points + " -o x.txt",
        "classify --mesh " + box + " --with solid --resolution 20000 " + points + " -o x.txt",
        "classify " + sprite + " " + points + " -o x.txt --threads -1",
        "info",
        "info " + sprite + " --resolution 4",
        "eval " + box + " --resolutions 16,0",
        "eval " + box + " --resolutions=",
        "eval " + box + " --points -5",
        "eval " + box + " --points 99999999999999999999999",
        "eval " + box + " --rule even-odd",
        "compare " + box + " --resolutions 5000", // above kMaxCompareResolution, within kMaxResolution
        "compare " + box + " --resolutions=0",
        "compare " + box + " --seed x",
        "frobnicate",
    };
    for (const std::string& args : bad) {
        const Result r = vds(args);
        EXPECT_EQ(r.code, 2) << args << ": " << r.output;
        EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << args << ": " << r.output;
    }
}

TEST_F(Cli, BadInputFilesExitOneWithOneLineAndLoseNothing) {
    ASSERT_EQ(vds("bake " + p("box.obj") + " -o " + p("box.vds") + " --resolution 16 --quiet").code, 0);
    std::ofstream(dir / "empty.obj").close();
    std::ofstream(dir / "nan.obj") << "v 0 0 0\nv 1 0 0\nv nan 1 0\nv 0 0 1\nf 1 2 3\nf 1 2 4\nf 1 3 4\nf 2 3 4\n";
    std::ofstream(dir / "nan.txt") << "0 0 0\nnan 1 2\n";
    std::ofstream(dir / "corrupt.vds") << "this is not an OpenEXR file";
    const std::string vdsBytes = readFile(dir / "box.vds");
    std::ofstream(dir / "truncated.vds", std::ios::binary) << vdsBytes.substr(0, vdsBytes.size() / 2);
    std::ofstream(dir / "labels.txt") << "previous\n";
    const std::vector<std::string> bad = {
        "bake " + p("missing.obj") + " -o " + p("out.vds"),
        "bake " + p("empty.obj") + " -o " + p("out.vds"),
        "bake " + p("nan.obj") + " -o " + p("out.vds"),
        "bake " + p("box.obj") + " -o " + p("no/such/dir/out.vds"),
        "info " + p("corrupt.vds"),
        "info " + p("truncated.vds"),
        "classify " + p("truncated.vds") + " " + p("points.txt") + " -o " + p("labels.txt"),
        "classify " + p("box.vds") + " " + p("nan.txt") + " -o " + p("labels.txt"),
        "classify " + p("box.vds") + " " + p("missing.txt") + " -o " + p("labels.txt"),
        "classify --exact --mesh " + p("box.obj") + " " + p("nan.txt") + " -o " + p("labels.txt"),
        "classify --exact --mesh " + p("empty.obj") + " " + p("points.txt") + " -o " + p("labels.txt"),
        "eval " + p("empty.obj") + " --resolutions 16",
        "eval " + p("nan.obj") + " --resolutions 16",
    };
    for (const auto& args : bad) {
        const Result r = vds(args + " --quiet");
        EXPECT_EQ(r.code, 1) << args << ": " << r.output;
        EXPECT_NE(lastLine(r.output).find("error: "), std::string::npos) << args << ": " << r.output;
        EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << args << ": " << r.output;
    }
    EXPECT_FALSE(fs::exists(dir / "out.vds"));
    EXPECT_EQ(readFile(dir / "labels.txt"), "previous\n"); // a failed run leaves the old output alone
    for (const auto& entry : fs::directory_iterator(dir))
        EXPECT_EQ(entry.path().filename().string().find(".tmp-"), std::string::npos) << entry.path();
}

TEST_F(Cli, OpenMeshIsBakedWithAWarningAndRecorded) {
    auto box = vds::solids::box({0, 0, 0}, {1, 1, 1}).mesh;
    box.triangles.pop_back();
    writeObj(dir / "open.obj", box);
    Result r = vds("bake " + p("open.obj") + " -o " + p("open.vds") + " --resolution 16 --quiet");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("warning: "), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("3 boundary edges"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("--rule generalized-winding"), std::string::npos) << r.output; // points to what answers
    // voxelize treats it as classify, distance and sdf do: refused by parity, unless asked for.
    r = vds("voxelize " + p("open.obj") + " --dims 4 -o " + p("open.npy"));
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_NE(r.output.find("--rule generalized-winding"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir / "open.npy"));
    r = vds("voxelize " + p("open.obj") + " --dims 4 -o " + p("open.npy") + " --allow-open");
    ASSERT_EQ(r.code, 0) << r.output;
    r = vds("info " + p("open.vds"));
    EXPECT_NE(r.output.find("NOT A SOLID"), std::string::npos) << r.output;
    // Exact answers and accuracy need a solid: refused, unless asked for.
    r = vds("classify --exact --mesh " + p("open.obj") + " " + p("points.txt") + " -o " + p("l.txt") + " --quiet");
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_NE(r.output.find("--allow-open"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir / "l.txt"));
    r = vds("classify --exact --allow-open --mesh " + p("open.obj") + " " + p("points.txt") + " -o " + p("l.txt") + " --quiet");
    EXPECT_EQ(r.code, 0) << r.output;
    r = vds("eval " + p("open.obj") + " --resolutions 16 --points 100 --surface-points 100 --quiet");
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
}

// A flat mesh gets one message, the same in every command that needs a volume, and nothing is written.
TEST_F(Cli, FlatMeshesGetOneMessageEverywhere) {
    {
        std::ofstream out(dir / "sheet.obj");
        out << "v 0 0 1\nv 1 0 1\nv 0 1 1\nv 1 1 1\nf 1 2 3\nf 3 2 4\n";
    }
    const std::string sheet = p("sheet.obj");
    const std::string expected = "sheet.obj is flat (no extent along z): it bounds no volume";
    for (const std::string& command :
         {"bake " + sheet + " -o " + p("flat.vds"), "bake " + sheet + " -o " + p("flat.vds") + " --axis x",
          "classify --mesh " + sheet + " " + p("points.txt") + " -o " + p("flat.txt"),
          "classify --method exact --mesh " + sheet + " " + p("points.txt") + " -o " + p("flat.txt"),
          "voxelize " + sheet + " --dims 8 -o " + p("flat.npy"), "compare " + sheet + " --resolutions 8"}) {
        const Result r = vds(command + " --quiet");
        EXPECT_EQ(r.code, 1) << command << "\n" << r.output;
        EXPECT_NE(r.output.find(expected), std::string::npos) << command << "\n" << r.output;
        EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << command << "\n" << r.output;
    }
    for (const char* out : {"flat.vds", "flat.txt", "flat.npy"}) EXPECT_FALSE(fs::exists(dir / out)) << out;
}

// Typos get the nearest command or option named; swapped files say which comes first.
TEST_F(Cli, TyposAndSwappedArgumentsNameTheFix) {
    Result r = vds("clasify " + p("box.vds"));
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("'clasify' is not a vds command (did you mean 'classify'?)"), std::string::npos) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
    r = vds("frobnicate");
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_EQ(r.output.find("did you mean"), std::string::npos) << r.output; // nothing near: no guess
    r = vds("bake " + p("box.obj") + " -o " + p("t.vds") + " --resoltion 32");
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("(did you mean '--resolution'?)"), std::string::npos) << r.output;
    r = vds("classify --metod exact --mesh " + p("box.obj") + " " + p("points.txt") + " -o " + p("t.txt"));
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("(did you mean '--method'?)"), std::string::npos) << r.output;
    ASSERT_EQ(vds("bake " + p("box.obj") + " -o " + p("s.vds") + " --resolution 16 --quiet").code, 0);
    r = vds("classify " + p("points.txt") + " " + p("s.vds") + " -o " + p("t.txt"));
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_NE(r.output.find("the sprite comes first"), std::string::npos) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
    EXPECT_FALSE(fs::exists(dir / "t.txt"));
}

TEST_F(Cli, NoGlGivesAClearErrorAndTheCpuBakerStillWorks) {
    // glvnd finds no EGL vendor: as on a machine without any GL driver.
    const std::string noGl = "__EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent.json __EGL_VENDOR_LIBRARY_DIRS=/nonexistent ";
    Result r = run(noGl + VDS_TOOL + " bake " + p("box.obj") + " -o " + p("gl.vds") + " --method lists --quiet");
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_NE(r.output.find("no OpenGL"), std::string::npos) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
    EXPECT_FALSE(fs::exists(dir / "gl.vds"));
    r = run(noGl + VDS_TOOL + " bake " + p("box.obj") + " -o " + p("cpu.vds") + " --method cpu --resolution 32 --quiet");
    EXPECT_EQ(r.code, 0) << r.output;
    // The default, --method auto, bakes on the CPU where there is no GL, and says why with --verbose.
    r = run(noGl + VDS_TOOL + " bake " + p("box.obj") + " -o " + p("auto.vds") + " --resolution 32 --verbose --quiet");
    EXPECT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("bake method auto: cpu, because no GL is available"), std::string::npos) << r.output;
    EXPECT_TRUE(fs::exists(dir / "auto.vds"));
    r = run(noGl + VDS_TOOL + " classify " + p("cpu.vds") + " " + p("points.txt") + " -o " + p("l.txt") + " --quiet");
    EXPECT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(readFile(dir / "l.txt"), "1\n1\n0\n0\n0\n1\n");
}

#ifdef VDS_CLIP
// The sample's picture: a thin plate facing the camera, clipped by a sphere
// sprite through its middle. Pixels whose plate point lies inside the sphere
// (by more than two texels) must show the background; those outside, the plate.
TEST_F(Cli, ClipSampleRemovesExactlyThePixelsInsideTheSprite) {
    writeObj(dir / "plate.obj", vds::solids::box({-1, -1, -0.02f}, {1, 1, 0.02f}).mesh);
    const auto sphere = vds::solids::sphere({0.2f, -0.1f, 0}, 0.6f, 96);
    writeObj(dir / "sphere.obj", sphere.mesh);
    ASSERT_EQ(vds("bake " + p("sphere.obj") + " -o " + p("sphere.vds") + " --resolution 256 --quiet").code, 0);
    const Result r = run(std::string(VDS_CLIP) + " " + p("plate.obj") + " --clip " + p("sphere.vds") + " -o " +
                         p("clip.png") + " --size 200 --view z");
    ASSERT_EQ(r.code, 0) << r.output;
    const vds::eval::Image image = vds::eval::readPng(p("clip.png"));
    ASSERT_EQ(image.width, 200u);
    // The camera fits the plate's box: its bounding sphere's radius spans half the image.
    const float radius = 0.5f * std::sqrt(2.0f * 2.0f * 2 + 0.04f * 0.04f);
    const float texel = 1.2f / 256.0f;
    std::size_t clipped = 0, kept = 0, wrong = 0;
    for (std::uint32_t y = 0; y < 200; ++y)
        for (std::uint32_t x = 0; x < 200; ++x) {
            const float wx = -radius + 2.0f * radius * (float(x) + 0.5f) / 200.0f;
            const float wy = radius - 2.0f * radius * (float(y) + 0.5f) / 200.0f;
            if (std::fabs(wx) > 0.98f || std::fabs(wy) > 0.98f) continue; // plate rim
            const float d = std::hypot(wx - 0.2f, wy + 0.1f) - std::sqrt(0.36f - 0.02f * 0.02f);
            if (std::fabs(d) < 2.0f * texel + sphere.tessellationError + 2.0f * radius / 200.0f) continue;
            const bool background = image.at(x, y)[0] == 255 && image.at(x, y)[1] == 255 && image.at(x, y)[2] == 255;
            if (d < 0) { ++clipped; wrong += !background; }
            else { ++kept; wrong += background; }
        }
    EXPECT_GT(clipped, 5000u);
    EXPECT_GT(kept, 5000u);
    EXPECT_EQ(wrong, 0u);
    // And against the stored picture (made on llvmpipe): rasterizers may
    // differ along the cut and the plate's edges only, so a whole pixel may
    // change there (max 255) but the mean stays small.
    EXPECT_TRUE(vds::test::imageMatchesReference(image, VDS_TEST_DATA "/clip-plate-sphere.png", 255, 1.0));
}
#endif

} // namespace

namespace {

// `vds voxelize` from a mesh writes the exact classifier's answers at the
// cell centres; from a sprite, the sprite's; --packed the same bits.
TEST_F(Cli, VoxelizeWritesExactGridsAsNpy) {
    writeObj(dir / "torus.obj", vds::solids::torus({0.1f, 0.2f, 0.3f}, 1.0f, 0.35f, 40).mesh);
    const vds::TriangleMesh mesh = vds::loadMesh(p("torus.obj"));
    Result r = vds("voxelize " + p("torus.obj") + " --dims-xyz 23 19 11 -o " + p("grid.npy") + " --quiet");
    ASSERT_EQ(r.code, 0) << r.output;
    const vds::NpyArray grid = vds::readNpy(p("grid.npy"));
    EXPECT_EQ(grid.descr, "|b1");
    ASSERT_EQ(grid.shape, (std::vector<std::uint64_t>{23, 19, 11}));
    const vds::Grid cells{vds::meshBounds(mesh), {23, 19, 11}};
    const vds::ExactClassifier exact(mesh);
    std::size_t wrong = 0, inside = 0;
    for (std::uint32_t i = 0; i < 23; ++i)
        for (std::uint32_t j = 0; j < 19; ++j)
            for (std::uint32_t k = 0; k < 11; ++k) {
                const bool expected = exact.contains(cells.cellCentre(i, j, k));
                wrong += (grid.data[cells.index(i, j, k)] != 0) != expected;
                inside += expected;
            }
    EXPECT_EQ(wrong, 0u);
    EXPECT_GT(inside, 100u);

    r = vds("voxelize " + p("torus.obj") + " --dims-xyz 23 19 11 --packed -o " + p("bits.npy") + " --quiet");
    ASSERT_EQ(r.code, 0) << r.output;
    const vds::NpyArray bits = vds::readNpy(p("bits.npy"));
    // numpy.packbits(cells, axis=-1): shape (23, 19, 2), each row of 11 z cells in two bytes, first in the high bit.
    EXPECT_EQ(bits.shape, (std::vector<std::uint64_t>{23, 19, 2}));
    ASSERT_EQ(bits.data.size(), std::size_t(23 * 19 * 2));
    std::size_t bitWrong = 0;
    for (std::size_t row = 0; row < std::size_t(23 * 19); ++row)
        for (std::size_t k = 0; k < 11; ++k) {
            const bool bit = (std::uint8_t(bits.data[row * 2 + k / 8]) >> (7 - k % 8)) & 1;
            bitWrong += bit != (grid.data[row * 11 + k] != 0);
        }
    EXPECT_EQ(bitWrong, 0u);
    EXPECT_EQ(std::uint8_t(bits.data[1]) & 0x1f, 0); // the 5 padding bits of a row are 0

    ASSERT_EQ(vds("bake " + p("torus.obj") + " -o " + p("torus.vds") + " --method cpu --resolution 64 --quiet").code, 0);
    r = vds("voxelize " + p("torus.vds") + " --dims 16 -o " + p("sprite.npy") + " --quiet");
    ASSERT_EQ(r.code, 0) << r.output;
    const vds::Sprite sprite = vds::readSprite(p("torus.vds"));
    const vds::NpyArray fromSprite = vds::readNpy(p("sprite.npy"));
    const vds::Grid g16{sprite.grid.box, {16, 16, 16}};
    wrong = 0;
    for (std::uint32_t i = 0; i < 16; ++i)
        for (std::uint32_t j = 0; j < 16; ++j)
            for (std::uint32_t k = 0; k < 16; ++k)
                wrong += (fromSprite.data[g16.index(i, j, k)] != 0) != sprite.contains(g16.cellCentre(i, j, k));
    EXPECT_EQ(wrong, 0u);

    for (const char* bad : {"--dims 0", "--dims 8 --dims-xyz 1 2 3", "", "--dims-xyz 1 2", "--dims 99999"}) {
        r = vds("voxelize " + p("torus.obj") + " " + bad + " -o " + p("bad.npy"));
        EXPECT_EQ(r.code, 2) << bad << ": " << r.output;
    }
    r = vds("voxelize " + p("missing.obj") + " --dims 4 -o " + p("bad.npy"));
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_FALSE(fs::exists(p("bad.npy")));
}

// Points from .npy, labels to .npy; --certified and its GPU form answer as --exact does.
TEST_F(Cli, ClassifyReadsAndWritesNpyAndCertifiedEqualsExact) {
    writeObj(dir / "shell.obj", vds::solids::shell({0, 0, 0}, 1.0f, 0.6f, 24).mesh);
    std::vector<float> xyz;
    std::mt19937 rng(4);
    std::uniform_real_distribution<float> u(-1.2f, 1.2f);
    for (int k = 0; k < 9000; ++k) xyz.push_back(u(rng));
    vds::writeNpy(p("points.npy"), "<f4", {3000, 3}, xyz.data(), xyz.size() * sizeof(float));
    for (const char* rule : {"parity", "winding"}) {
        Result r = vds(std::string("classify --exact --mesh ") + p("shell.obj") + " " + p("points.npy") + " -o " +
                       p("exact.npy") + " --quiet --rule " + rule);
        ASSERT_EQ(r.code, 0) << r.output;
        // The CPU form, and the GPU form by both spellings.
        for (const char* method : {"--certified", "--certified --gpu", "--method certified-gpu"}) {
            r = vds(std::string("classify ") + method + " --resolution 64 --mesh " + p("shell.obj") + " " +
                    p("points.npy") + " -o " + p("certified.npy") + " --quiet --rule " + rule);
            ASSERT_EQ(r.code, 0) << r.output;
            const vds::NpyArray a = vds::readNpy(p("exact.npy")), b = vds::readNpy(p("certified.npy"));
            EXPECT_EQ(a.shape, std::vector<std::uint64_t>{3000});
            EXPECT_EQ(a.data, b.data) << rule << " " << method;
            EXPECT_GT(std::count(a.data.begin(), a.data.end(), 1), 100);
        }
    }
    // An open mesh: refused by crossing rules, answered by the generalized winding number.
    auto cup = vds::solids::sphere({0, 0, 0}, 1.0f, 16).mesh;
    cup.triangles.resize(cup.triangles.size() - 8);
    writeObj(dir / "cup.obj", cup);
    Result r = vds("classify --exact --mesh " + p("cup.obj") + " " + p("points.npy") + " -o " + p("cup.npy"));
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_NE(r.output.find("generalized-winding"), std::string::npos) << r.output;
    r = vds("classify --exact --rule generalized-winding --mesh " + p("cup.obj") + " " + p("points.npy") + " -o " +
            p("cup.npy") + " --quiet");
    EXPECT_EQ(r.code, 0) << r.output;
}

} // namespace

namespace {

TEST_F(Cli, BakeVerbosePrintsEveryPhase) {
    Result r = vds("bake " + p("box.obj") + " -o " + p("v.vds") + " --resolution 32 --method lists --verbose --quiet");
    ASSERT_EQ(r.code, 0) << r.output;
    for (const char* phase : {"validation", "upload", "raster", "scan", "sort", "read-back", "total", "before the bake: read "})
        EXPECT_NE(r.output.find(phase), std::string::npos) << phase << " missing in:\n" << r.output;
    // The defaults, axis and method auto, say what they measured and chose
    // (a box has two layers along every axis: the tie goes to fewer crossings).
    r = vds("bake " + p("box.obj") + " -o " + p("a.vds") + " --resolution 32 --verbose --quiet");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("bake method auto: "), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(" layers (x "), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(" at 32 texels): the fewest layers"), std::string::npos) << r.output;
}

} // namespace

namespace {

// A closed mesh with a non-manifold edge (two cubes sharing an edge) is
// classified exactly, with a note (not a warning: inside is defined) that
// counts the edge.
TEST_F(Cli, ClosedNonManifoldMeshesAreClassifiedWithANote) {
    writeObj(dir / "two.obj", vds::solids::boxesSharingAnEdge({0, 0, 0}, 1.0f).mesh);
    std::ofstream(dir / "in.txt") << "0.5 0.5 0.5\n1.5 1.5 0.5\n1.5 0.5 0.5\n";
    const Result r = vds("classify --exact --mesh " + p("two.obj") + " " + p("in.txt") + " -o " + p("two.txt"));
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("vds classify: note: "), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("1 non-manifold edge"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("warning"), std::string::npos) << r.output;
    EXPECT_EQ(readFile(dir / "two.txt"), "1\n1\n0\n");
}

} // namespace

namespace {

// The six points of points.txt, and the box's answers for them.
const std::vector<std::array<double, 3>> kBoxPoints = {{0, 0, 0},     {0.9, 0.4, 1.9},     {1.1, 0, 0},
                                                       {0, 0.6, 0},   {-0.5, -0.5, -1.5}, {0.5, 0, 1}};
const char* const kBoxLabels = "1\n1\n0\n0\n0\n1\n";

// A binary PLY of points (vertex x, y, z of `type` float or double) in the given byte order.
std::string binaryPly(const std::vector<std::array<double, 3>>& points, bool bigEndian, bool doubles) {
    const char* type = doubles ? "double" : "float";
    std::string ply = std::string("ply\nformat ") + (bigEndian ? "binary_big_endian" : "binary_little_endian") +
                      " 1.0\ncomment points\nelement vertex " + std::to_string(points.size()) + "\nproperty " + type +
                      " x\nproperty " + type + " y\nproperty " + type + " z\nend_header\n";
    for (const auto& point : points)
        for (double v : point) {
            char bytes[8];
            const float f = float(v);
            const std::size_t size = doubles ? 8 : 4;
            std::memcpy(bytes, doubles ? static_cast<const void*>(&v) : static_cast<const void*>(&f), size);
            if (bigEndian) std::reverse(bytes, bytes + size); // the test machine is little-endian
            ply.append(bytes, size);
        }
    return ply;
}

TEST_F(Cli, ClassifyReadsBinaryPlyPointsOfEitherByteOrder) {
    ASSERT_EQ(vds("bake " + p("box.obj") + " -o " + p("box.vds") + " --resolution 32 --method cpu --quiet").code, 0);
    for (bool bigEndian : {false, true})
        for (bool doubles : {false, true}) {
            const std::string name = std::string(bigEndian ? "be" : "le") + (doubles ? "64" : "32");
            std::ofstream(dir / (name + ".ply"), std::ios::binary) << binaryPly(kBoxPoints, bigEndian, doubles);
            Result r = vds("classify " + p("box.vds") + " " + p(name + ".ply") + " -o " + p(name + ".txt") + " --quiet");
            ASSERT_EQ(r.code, 0) << name << ": " << r.output;
            EXPECT_EQ(readFile(dir / (name + ".txt")), kBoxLabels) << name;
            r = vds("classify --exact --mesh " + p("box.obj") + " " + p(name + ".ply") + " -o " + p(name + ".txt") +
                    " --quiet");
            ASSERT_EQ(r.code, 0) << name << ": " << r.output;
            EXPECT_EQ(readFile(dir / (name + ".txt")), kBoxLabels) << name;
        }
    // Truncated binary data: one line naming the file, exit 1, no output.
    const std::string ply = binaryPly(kBoxPoints, false, false);
    std::ofstream(dir / "short.ply", std::ios::binary) << ply.substr(0, ply.size() - 5);
    const Result r = vds("classify " + p("box.vds") + " " + p("short.ply") + " -o " + p("short.txt"));
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_NE(r.output.find("short.ply"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(p("short.txt")));
}

TEST_F(Cli, ClassifyReadsStdinAndWritesStdout) {
    ASSERT_EQ(vds("bake " + p("box.obj") + " -o " + p("box.vds") + " --resolution 32 --method cpu --quiet").code, 0);
    // The tool with stdin from `in` and stdout to `out`; stderr is what run() captures.
    auto piped = [this](const std::string& args, const std::string& in, const std::string& out) {
        return run(std::string("(") + VDS_TOOL + " " + args + " < " + p(in) + " > " + p(out) + ")");
    };
    std::vector<float> xyz;
    for (const auto& point : kBoxPoints)
        for (double v : point) xyz.push_back(float(v));
    vds::writeNpy(p("points.npy"), "<f4", {kBoxPoints.size(), 3}, xyz.data(), xyz.size() * sizeof(float));
    std::ofstream(dir / "points.ply", std::ios::binary) << binaryPly(kBoxPoints, true, true);
    // Text, .npy and PLY on stdin, told apart by their first bytes; text labels on stdout.
    for (const char* input : {"points.txt", "points.npy", "points.ply"}) {
        const Result r = piped("classify " + p("box.vds") + " - -o -", input, "out.txt");
        ASSERT_EQ(r.code, 0) << input << ": " << r.output;
        EXPECT_EQ(readFile(dir / "out.txt"), kBoxLabels) << input;
        EXPECT_NE(r.output.find("wrote -: 6 points, 3 inside"), std::string::npos) << r.output; // on stderr
    }
    // A .npy array of labels on stdout, as numpy writes it; the exact path reads stdin too.
    Result r = piped("classify --exact --mesh " + p("box.obj") + " - -o - --output-format npy --quiet", "points.txt",
                        "out.npy");
    ASSERT_EQ(r.code, 0) << r.output;
    const vds::NpyArray labels = vds::readNpy(p("out.npy"));
    EXPECT_EQ(labels.descr, "|b1");
    EXPECT_EQ(labels.shape, std::vector<std::uint64_t>{6});
    EXPECT_EQ(labels.data, (std::vector<char>{1, 1, 0, 0, 0, 1}));
    // --output-format text beats a .npy name.
    r = vds("classify " + p("box.vds") + " " + p("points.txt") + " -o " + p("named.npy") +
            " --output-format text --quiet");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(readFile(dir / "named.npy"), kBoxLabels);
    // Bad stdin: one line naming <stdin>, exit 1, nothing on stdout.
    std::ofstream(dir / "bad.npy", std::ios::binary) << std::string("\x93NUMPY\x01\x00\x05\x00{'de", 14);
    for (const char* bad : {"bad.npy", "box.vds"}) {
        r = piped("classify " + p("box.vds") + " - -o -", bad, "bad.txt");
        EXPECT_EQ(r.code, 1) << bad << ": " << r.output;
        EXPECT_NE(r.output.find("<stdin>"), std::string::npos) << r.output;
        EXPECT_EQ(readFile(dir / "bad.txt"), "") << bad;
    }
}

} // namespace
