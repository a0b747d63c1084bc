// The interactive viewer, run as a user scripts it under Xvfb (this test runs
// inside xvfb-run): its screenshots against the offline samples' pictures of
// the same scene, and, after the mouse moved a solid, against its own exact
// lookup, within the gallery's limit (at most 1 % of the covered pixels off
// by more than 8 in a channel); bad input exits 1 with one line.
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include "../support/run_program.h"

#include <vds/eval/image.h>

namespace {

namespace fs = std::filesystem;

using vds::test::Result;
using vds::test::run;

// The gallery's measure: pixels with a channel off by more than 8, and the
// pixels that are not white background in either picture.
struct Difference {
    std::size_t pixels = 0, covered = 0;
    double share() const { return covered ? double(pixels) / double(covered) : 0.0; }
};

Difference difference(const vds::eval::Image& a, const vds::eval::Image& b) {
    Difference d;
    EXPECT_EQ(a.width, b.width);
    EXPECT_EQ(a.height, b.height);
    if (a.width != b.width || a.height != b.height) return d;
    for (std::size_t p = 0; p < a.rgba.size() / 4; ++p) {
        int most = 0;
        bool background = true;
        for (std::size_t c = 0; c < 3; ++c) {
            most = std::max(most, std::abs(int(a.rgba[4 * p + c]) - int(b.rgba[4 * p + c])));
            background = background && a.rgba[4 * p + c] == 255 && b.rgba[4 * p + c] == 255;
        }
        d.pixels += most > 8;
        d.covered += !background;
    }
    return d;
}

constexpr double kGalleryLimit = 0.01;

class Viewer : public ::testing::Test {
protected:
    void SetUp() override {
        dir = fs::temp_directory_path() / ("vds-viewer-" + std::to_string(::getpid()));
        fs::create_directories(dir);
    }
    void TearDown() override { fs::remove_all(dir); }
    std::string p(const std::string& name) const { return (dir / name).string(); }
    std::string script(const std::string& name, const std::string& text) const {
        std::ofstream(p(name)) << text;
        return p(name);
    }
    vds::eval::Image png(const std::string& name) const { return vds::eval::readPng(p(name)); }
    fs::path dir;
    const std::string viewer = VDS_VIEWER, data = VDS_SAMPLES_DATA;
};

TEST_F(Viewer, ClipSessionMatchesTheClipSampleAndTheExactLookupAfterADrag) {
    const std::string spot = data + "/spot.obj", sphere = data + "/lens.obj";
    const Result clip = run(std::string(VDS_CLIP) + " " + spot + " --solid " + sphere + " -o " + p("clip.png") +
                            " --size 160 --resolution 96");
    ASSERT_EQ(clip.code, 0) << clip.output;
    const std::string s = script("clip.txt", "# the start, then the clip solid dragged right and up\n"
                                             "screenshot " + p("start.png") + "\n"
                                             "drag 60 60 100 40 right\n"
                                             "wait 2 frames\n"
                                             "screenshot " + p("moved.png") + "\n"
                                             "key 5\n"
                                             "screenshot " + p("moved-exact.png") + "\n");
    const Result r = run(viewer + " " + spot + " --solid " + sphere + " --size 160x160 --resolution 96 --script " + s);
    ASSERT_EQ(r.code, 0) << r.output;
    const Difference start = difference(png("start.png"), png("clip.png"));
    EXPECT_GT(start.covered, 5000u);
    EXPECT_LE(start.share(), kGalleryLimit) << start.pixels << " of " << start.covered;
    const Difference moved = difference(png("moved.png"), png("moved-exact.png"));
    EXPECT_LE(moved.share(), kGalleryLimit) << moved.pixels << " of " << moved.covered;
    EXPECT_GT(difference(png("moved.png"), png("start.png")).pixels, 300u); // the cut went with the mouse
}

TEST_F(Viewer, LensSceneMatchesTheLensSampleThenFollowsTheMouseInAWideWindow) {
    const Result lens = run(std::string(VDS_LENS) + " -o " + p("lens") + " --frames 1 --size 160 --resolution 96");
    ASSERT_EQ(lens.code, 0) << lens.output;
    const std::string s = script("lens.txt", "screenshot " + p("start.png") + "\n"
                                             "drag 80 60 110 90\n"
                                             "scroll 2\n"
                                             "screenshot " + p("moved.png") + "\n"
                                             "key 4\n"
                                             "screenshot " + p("moved-solid.png") + "\n"
                                             "key 5\n"
                                             "screenshot " + p("moved-exact.png") + "\n"
                                             "key b\n"
                                             "key L\n"
                                             "screenshot " + p("restyled.png") + "\n"
                                             "quit\n");
    const Result square = run(viewer + " --scene lens --size 160x160 --resolution 96 --script " + s);
    ASSERT_EQ(square.code, 0) << square.output;
    const Difference start = difference(png("start.png"), vds::eval::readPng(p("lens/lens-00.png")));
    EXPECT_GT(start.covered, 5000u);
    EXPECT_LE(start.share(), kGalleryLimit) << start.pixels << " of " << start.covered;
    EXPECT_GT(difference(png("moved.png"), png("start.png")).pixels, 300u);
    for (const char* with : {"moved.png", "moved-solid.png"}) {
        const Difference d = difference(png(with), png("moved-exact.png"));
        EXPECT_LE(d.share(), kGalleryLimit) << with << ": " << d.pixels << " of " << d.covered;
    }
    EXPECT_GT(difference(png("restyled.png"), png("moved-exact.png")).pixels, 1000u);

    // A wider window sees the same scene across its height, with more on the sides.
    const Result wide = run(viewer + " --scene lens --size 224x160 --resolution 96 --script " + s);
    ASSERT_EQ(wide.code, 0) << wide.output;
    const vds::eval::Image picture = png("moved.png");
    EXPECT_EQ(picture.width, 224u);
    EXPECT_EQ(picture.height, 160u);
    const Difference d = difference(picture, png("moved-exact.png"));
    EXPECT_LE(d.share(), kGalleryLimit) << d.pixels << " of " << d.covered;
}

TEST_F(Viewer, OpensABakedSpriteAndKeepsTheVdsLookupForIt) {
    const std::string spot = data + "/spot.obj", sprite = p("sphere.vds");
    const Result bake = run(std::string(VDS_TOOL) + " bake " + data + "/lens.obj -o " + sprite + " --resolution 96 --quiet");
    ASSERT_EQ(bake.code, 0) << bake.output;
    const Result clip = run(std::string(VDS_CLIP) + " " + spot + " --clip " + sprite + " -o " + p("clip.png") +
                            " --size 160 --keep");
    ASSERT_EQ(clip.code, 0) << clip.output;
    const std::string s = script("sprite.txt", "key k\nscreenshot " + p("keep.png") + "\nkey 2\nscreenshot " +
                                                   p("still-vds.png") + "\n");
    const Result r = run(viewer + " " + spot + " --clip " + sprite + " --size 160x160 --script " + s);
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("is a sprite only"), std::string::npos) << r.output; // no voxels without its mesh
    const Difference keep = difference(png("keep.png"), png("clip.png"));
    EXPECT_GT(keep.covered, 1000u);
    EXPECT_LE(keep.share(), kGalleryLimit) << keep.pixels << " of " << keep.covered;
    EXPECT_EQ(difference(png("still-vds.png"), png("keep.png")).pixels, 0u);
}

TEST_F(Viewer, BadInputExitsOneWithOneLine) {
    const std::string missing = p("no-such.obj");
    const std::vector<std::pair<std::string, std::string>> cases = {
        {viewer + " --size 0x10", "--size"},
        {viewer + " --size 640", "--size"},
        {viewer + " --with octree", "--with"},
        {viewer + " --scene lens " + data + "/spot.obj", "--scene"},
        {viewer + " --clip " + p("a.vds") + " --with solid", "--with vds only"},
        {viewer + " --size 64x64 --solid " + data + "/spot.obj --solid " + data + "/spot.obj --solid " + data +
             "/spot.obj --solid " + data + "/spot.obj --solid " + data + "/spot.obj --solid " + data +
             "/spot.obj --solid " + data + "/spot.obj --solid " + data + "/spot.obj --lens " + data + "/lens.obj",
         "at most 8 solids"},
        {viewer + " " + missing, "no-such.obj"},
        {viewer + " --script " + p("none.txt"), "none.txt"},
        {viewer + " --script " + script("bad.txt", "key 1\nfly 3\n"), "bad.txt:2: unknown command 'fly'"},
        {viewer + " --script " + script("bad-key.txt", "key F12\n"), "bad-key.txt:1:"},
        {viewer + " --script " + script("bad-drag.txt", "drag 1 2 3\n"), "bad-drag.txt:1:"},
        {viewer + " --script " + script("bad-wait.txt", "wait 3 seconds\n"), "bad-wait.txt:1:"},
    };
    for (const auto& [command, says] : cases) {
        const Result r = run(command);
        EXPECT_EQ(r.code, 1) << command << "\n" << r.output;
        EXPECT_NE(r.output.find(says), std::string::npos) << command << "\n" << r.output;
        EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << command << "\n" << r.output;
    }
    const Result help = run(viewer + " --help");
    EXPECT_EQ(help.code, 0);
    EXPECT_NE(help.output.find("screenshot FILE.png"), std::string::npos) << help.output;
}

} // namespace
