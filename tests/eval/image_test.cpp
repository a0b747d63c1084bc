// PNG files: pixels survive a round trip exactly; missing, foreign, truncated
// and unwritable files give IoError or FormatError, and a failed write leaves
// no file behind.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "../support/image_compare.h"

#include <vds/error.h>
#include <vds/eval/image.h>

namespace vds::eval {
namespace {

namespace fs = std::filesystem;

class PngTest : public ::testing::Test {
protected:
    void SetUp() override {
        dir = fs::path(::testing::TempDir()) /
              ("vds_png_test_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
        fs::remove_all(dir);
        fs::create_directories(dir);
    }
    void TearDown() override { fs::remove_all(dir); }
    std::string p(const std::string& name) const { return (dir / name).string(); }
    fs::path dir;
};

// A 7x3 image whose every byte differs from its neighbours, alpha included.
Image pattern() {
    Image image(7, 3);
    for (std::size_t k = 0; k < image.rgba.size(); ++k) image.rgba[k] = std::uint8_t(k * 37 + 11);
    return image;
}

TEST_F(PngTest, PixelsSurviveARoundTrip) {
    const Image image = pattern();
    writePng(image, p("a.png"));
    const Image back = readPng(p("a.png"));
    EXPECT_EQ(back.width, 7u);
    EXPECT_EQ(back.height, 3u);
    EXPECT_EQ(back.rgba, image.rgba);
    EXPECT_EQ(back.at(6, 2)[3], std::uint8_t((7 * 3 * 4 - 1) * 37 + 11));
    // Overwriting replaces the old file whole and leaves no temporary beside it.
    Image other(2, 2);
    other.rgba.assign(16, 200);
    writePng(other, p("a.png"));
    EXPECT_EQ(readPng(p("a.png")).rgba, other.rgba);
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
}

TEST_F(PngTest, BadFilesGiveIoOrFormatErrors) {
    EXPECT_THROW(readPng(p("missing.png")), IoError);
    std::ofstream(p("text.png")) << "this is not a PNG file";
    EXPECT_THROW(readPng(p("text.png")), FormatError);
    std::ofstream(p("empty.png")).close();
    EXPECT_THROW(readPng(p("empty.png")), FormatError);

    // A valid header with half of the image data cut off (noise, so that the
    // data does not compress to a few bytes).
    Image big(64, 64);
    std::mt19937 random(7);
    for (auto& byte : big.rgba) byte = std::uint8_t(random());
    writePng(big, p("whole.png"));
    std::stringstream bytes;
    bytes << std::ifstream(p("whole.png"), std::ios::binary).rdbuf();
    const std::string whole = bytes.str();
    ASSERT_GT(whole.size(), 64u * 64u * 4u);
    std::ofstream(p("truncated.png"), std::ios::binary) << whole.substr(0, whole.size() / 2);
    try {
        readPng(p("truncated.png"));
        ADD_FAILURE() << "a truncated PNG was read";
    } catch (const FormatError& e) {
        EXPECT_EQ(std::string(e.what()).rfind(p("truncated.png") + ": ", 0), 0u) << e.what();
    }
}

TEST_F(PngTest, AFailedWriteLeavesNothing) {
    EXPECT_THROW(writePng(pattern(), p("no/such/dir/a.png")), IoError);
    EXPECT_THROW(writePng(Image(), p("empty.png")), InvalidArgument);
    EXPECT_TRUE(fs::is_empty(dir));
}

} // namespace
} // namespace vds::eval

namespace {

// The reference-image comparison used by the rendering tests measures what it says.
TEST(ImageCompare, MeasuresTheLargestAndMeanDifference) {
    vds::eval::Image a(4, 2), b(4, 2);
    b.at(1, 1)[0] = 200; // one channel of one pixel
    b.at(3, 0)[2] = 10;
    const vds::test::ImageDelta d = vds::test::compareImages(a, b);
    EXPECT_EQ(d.max, 200);
    EXPECT_EQ(d.pixels, 2u);
    EXPECT_DOUBLE_EQ(d.mean, 210.0 / 32.0);
}

} // namespace
