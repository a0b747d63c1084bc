// The lens, styles and gallery samples and the clip sample's --with, run as
// a user runs them: real files in a temporary directory, exit codes and
// one-line messages checked, the pictures and the gallery's table read back.
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include "../support/run_program.h"
#include <nlohmann/json.hpp>

#include <vds/eval/image.h>

#include "../support/image_compare.h"

namespace {

namespace fs = std::filesystem;

using vds::test::Result;
using vds::test::run;

class Samples : public ::testing::Test {
protected:
    void SetUp() override {
        dir = fs::temp_directory_path() / ("vds-samples-" + std::to_string(::getpid()));
        fs::create_directories(dir);
    }
    void TearDown() override { fs::remove_all(dir); }
    std::string p(const std::string& name) const { return (dir / name).string(); }
    fs::path dir;
};

TEST_F(Samples, BadCommandLinesExitTwoWithOneLine) {
    const std::string lens = VDS_LENS, styles = VDS_STYLES, gallery = VDS_GALLERY, clip = VDS_CLIP;
    const std::string spot = VDS_SAMPLES_DATA "/spot.obj", sphere = VDS_SAMPLES_DATA "/lens.obj";
    for (const std::string& command : std::vector<std::string>{
             lens, lens + " -o d --frames 0", lens + " -o d --with voxels", lens + " -o d --size 8",
             styles, styles + " -o x.png --with octree", styles + " -o x.png --resolution 4",
             gallery, gallery + " -o d --scenes teapot", gallery + " -o d --size 0",
             clip + " " + spot + " --clip a.vds -o x.png --with solid",
             clip + " " + spot + " --solid " + sphere + " -o x.png --combine xor"}) {
        const Result r = run(command);
        EXPECT_EQ(r.code, 2) << command << ": " << r.output;
        EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << command << ": " << r.output;
    }
    for (const std::string& program : {lens, styles, gallery}) {
        const Result r = run(program + " --help");
        EXPECT_EQ(r.code, 0) << r.output;
        EXPECT_NE(r.output.find("usage: vds_"), std::string::npos) << r.output;
        if (program != gallery) {
            EXPECT_NE(r.output.find("slicemap-local"), std::string::npos) << r.output;
        }
    }
    // A missing mesh is an error of the run, not of the command line.
    const Result r = run(styles + " -o " + p("x.png") + " --data " + p("nowhere"));
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
}

// At coarse bands the sprite errs along the cut (red on the left); the
// certified-gpu panel, on the right, is exact on every pixel.
TEST_F(Samples, ExactSliceIsExactWhereTheCoarseSpriteIsNot) {
    const Result r = run(std::string(VDS_EXACT_SLICE) + " " VDS_SAMPLES_DATA "/spot.obj -o " + p("slice.png") +
                         " --resolution 24 --size 96 --axis x");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("certified-gpu on 0 "), std::string::npos) << r.output;
    const vds::eval::Image image = vds::eval::readPng(p("slice.png"));
    ASSERT_EQ(image.width, 192u);
    std::size_t redLeft = 0, redRight = 0;
    for (std::uint32_t y = 0; y < image.height; ++y)
        for (std::uint32_t x = 0; x < image.width; ++x) {
            const std::uint8_t* px = image.at(x, y);
            const bool red = px[0] == 220 && px[1] == 30;
            (x < 96 ? redLeft : redRight) += red;
        }
    EXPECT_GT(redLeft, 0u);
    EXPECT_EQ(redRight, 0u);
    const Result bad = run(std::string(VDS_EXACT_SLICE) + " " + p("nowhere.obj") + " -o " + p("x.png"));
    EXPECT_EQ(bad.code, 1) << bad.output;
    EXPECT_EQ(std::count(bad.output.begin(), bad.output.end(), '\n'), 1) << bad.output;
}

// The lens moves between frames (no re-bake), so consecutive frames differ,
// and each frame equals the exact reference closely.
TEST_F(Samples, LensFramesMoveAndMatchTheExactReference) {
    ASSERT_EQ(run(std::string(VDS_LENS) + " -o " + p("vds") + " --frames 3 --size 96").code, 0);
    const Result r = run(std::string(VDS_LENS) + " -o " + p("exact") + " --frames 3 --size 96 --with exact");
    ASSERT_EQ(r.code, 0) << r.output;
    std::vector<vds::eval::Image> frames;
    for (int f = 0; f < 3; ++f) {
        const std::string name = "/lens-0" + std::to_string(f) + ".png";
        frames.push_back(vds::eval::readPng(p("vds") + name));
        const vds::test::ImageDelta d = vds::test::compareImages(frames.back(), vds::eval::readPng(p("exact") + name));
        EXPECT_LT(d.pixels, 40u) << name; // the lens's silhouette, 1 % of the 96 x 96 picture's cow
    }
    EXPECT_GT(vds::test::compareImages(frames[0], frames[1]).pixels, 200u);
    EXPECT_GT(vds::test::compareImages(frames[1], frames[2]).pixels, 200u);
}

// A solid re-baked every frame (vds::Baker) cuts the mesh as the exact
// classifier of the moved solid does, and the cut moves.
TEST_F(Samples, AnimatedSolidFramesMatchTheExactReference) {
    const std::string base = std::string(VDS_ANIMATE) + " --frames 3 --size 96 --resolution 128";
    ASSERT_EQ(run(base + " -o " + p("vds")).code, 0);
    const Result r = run(base + " -o " + p("exact") + " --with exact");
    ASSERT_EQ(r.code, 0) << r.output;
    std::vector<vds::eval::Image> frames;
    for (int f = 0; f < 3; ++f) {
        const std::string name = "00" + std::to_string(f) + ".png";
        frames.push_back(vds::eval::readPng(p("vds") + name));
        const vds::test::ImageDelta d = vds::test::compareImages(frames.back(), vds::eval::readPng(p("exact") + name));
        EXPECT_LT(d.pixels, 40u) << name; // the blob's silhouette on the cow
    }
    EXPECT_GT(vds::test::compareImages(frames[0], frames[1]).pixels, 100u);
    EXPECT_GT(vds::test::compareImages(frames[1], frames[2]).pixels, 100u);
    const Result bad = run(std::string(VDS_ANIMATE) + " -o x --frames 0");
    EXPECT_EQ(bad.code, 2) << bad.output;
}

// The gallery's table: one row per lookup and budget, each with its images,
// shares between 0 and 1, and the equal-memory voxel grids within the VDS's bytes.
TEST_F(Samples, GalleryWritesPicturesAndTable) {
    const Result r = run(std::string(VDS_GALLERY) + " -o " + p("g") + " --scenes lens --size 64 --resolution 32 --repeats 1");
    ASSERT_EQ(r.code, 0) << r.output;
    std::ifstream in(p("g/gallery.json"));
    const nlohmann::json doc = nlohmann::json::parse(in);
    ASSERT_EQ(doc["rows"].size(), 7u); // vds + 3 voxel lookups x 2 budgets
    EXPECT_TRUE(fs::exists(p("g/lens-exact.png")));
    std::size_t vdsBytes = 0;
    for (const auto& row : doc["rows"]) {
        EXPECT_TRUE(fs::exists(p("g/" + row["image"].get<std::string>())));
        EXPECT_TRUE(fs::exists(p("g/" + row["difference"].get<std::string>())));
        EXPECT_GE(row["differing_share"].get<double>(), 0.0);
        EXPECT_LE(row["differing_share"].get<double>(), 1.0);
        EXPECT_GT(row["covered_pixels"].get<std::size_t>(), 500u);
        if (row["lookup"] == "vds") vdsBytes = row["memory_bytes"].get<std::size_t>();
        else if (row["budget"] == "mem") {
            EXPECT_LE(row["memory_bytes"].get<std::size_t>(), vdsBytes) << row.dump();
        }
    }
    EXPECT_GT(vdsBytes, 0u);
    std::ifstream md(p("g/gallery.md"));
    const std::string table((std::istreambuf_iterator<char>(md)), std::istreambuf_iterator<char>());
    EXPECT_EQ(std::count(table.begin(), table.end(), '\n'), 2 + 1 + 7);
}

// The clip sample with a mesh solid through a voxel grid and exactly.
TEST_F(Samples, ClipWithSolidMeshesRendersThroughEachLookup) {
    const std::string base = std::string(VDS_CLIP) + " " VDS_SAMPLES_DATA "/spot.obj --solid " VDS_SAMPLES_DATA
                             "/lens.obj --size 96 --resolution 96";
    ASSERT_EQ(run(base + " -o " + p("exact.png") + " --with exact").code, 0);
    const vds::eval::Image exact = vds::eval::readPng(p("exact.png"));
    for (const char* with : {"vds", "slicemap", "slicemap-local", "solid"}) {
        const Result r = run(base + " -o " + p(std::string(with) + ".png") + " --with " + with);
        ASSERT_EQ(r.code, 0) << r.output;
        const vds::test::ImageDelta d = vds::test::compareImages(vds::eval::readPng(p(std::string(with) + ".png")), exact);
        EXPECT_LT(d.pixels, 60u) << with; // along the cut only: 2 % of the cow's pixels
    }
    // --keep keeps what the solid holds: the complement of the clip, so most pixels change.
    ASSERT_EQ(run(base + " -o " + p("keep.png") + " --with exact --keep").code, 0);
    EXPECT_GT(vds::test::compareImages(vds::eval::readPng(p("keep.png")), exact).pixels, 1000u);
}

/// The clip band's orange (scene.bandColour times the light), told from the
/// front colour (grey-beige) and the cut colour (red) by its hue.
bool orange(const std::uint8_t* rgba) {
    const int r = rgba[0], g = rgba[1], b = rgba[2];
    return r > 30 && b * 10 < r * 3 && g * 20 > r * 9 && g * 5 < r * 4;
}

// --band draws the band along the cut from the solid's distance grid: every
// pixel it changes turns orange, and there are many of them; the soft lens
// edge changes the lens frames. Without --with vds both are refused.
TEST_F(Samples, ClipBandAndSoftLensEdgeComeFromTheDistanceGrid) {
    const std::string base = std::string(VDS_CLIP) + " " VDS_SAMPLES_DATA "/spot.obj --solid " VDS_SAMPLES_DATA
                             "/lens.obj --size 128 --resolution 96";
    ASSERT_EQ(run(base + " -o " + p("plain.png")).code, 0);
    const Result r = run(base + " -o " + p("band.png") + " --band 0.05 --distance-resolution 48");
    ASSERT_EQ(r.code, 0) << r.output;
    const vds::eval::Image plain = vds::eval::readPng(p("plain.png")), band = vds::eval::readPng(p("band.png"));
    std::size_t changed = 0, orangeChanged = 0, orangeBefore = 0;
    for (std::uint32_t y = 0; y < band.height; ++y)
        for (std::uint32_t x = 0; x < band.width; ++x) {
            orangeBefore += orange(plain.at(x, y));
            if (std::equal(plain.at(x, y), plain.at(x, y) + 4, band.at(x, y))) continue;
            ++changed;
            orangeChanged += orange(band.at(x, y));
        }
    EXPECT_EQ(orangeBefore, 0u);
    EXPECT_GT(changed, 100u);
    EXPECT_EQ(orangeChanged, changed);

    const std::string lens = std::string(VDS_LENS) + " --frames 1 --size 96 --resolution 64";
    ASSERT_EQ(run(lens + " -o " + p("hard")).code, 0);
    const Result soft = run(lens + " -o " + p("soft") + " --soft-edge 0.08");
    ASSERT_EQ(soft.code, 0) << soft.output;
    EXPECT_GT(vds::test::compareImages(vds::eval::readPng(p("hard/lens-00.png")), vds::eval::readPng(p("soft/lens-00.png")))
                  .pixels,
              100u);

    for (const std::string& command : {base + " -o x.png --band 0.03 --with solid",
                                       lens + " -o d --soft-edge 0.05 --with exact", base + " -o x.png --band -1"}) {
        const Result bad = run(command);
        EXPECT_EQ(bad.code, 2) << command << ": " << bad.output;
        EXPECT_EQ(std::count(bad.output.begin(), bad.output.end(), '\n'), 1) << command << ": " << bad.output;
    }
}

} // namespace
