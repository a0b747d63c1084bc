// .npy files: round trips, the byte layouts numpy writes, damaged files.
#include <vds/npy.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include <vds/error.h>

namespace vds {
namespace {

namespace fs = std::filesystem;

class NpyTest : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() / ("vds_npy_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
                                            "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }
    std::string path(const std::string& name) const { return (dir_ / name).string(); }
    void write(const std::string& name, const std::string& bytes) const {
        std::ofstream(path(name), std::ios::binary) << bytes;
    }
    // A version-1.0 file with `header` (padded as numpy pads) and `data`.
    std::string npy(std::string header, const std::string& data) const {
        const std::size_t total = 10 + header.size() + 1;
        header.append((64 - total % 64) % 64, ' ');
        header += '\n';
        std::string out("\x93NUMPY\x01\x00", 8);
        out += char(header.size() & 0xff);
        out += char(header.size() >> 8);
        return out + header + data;
    }
    fs::path dir_;
};

TEST_F(NpyTest, PointsRoundTripAsFloat32AndFloat64InEitherByteOrder) {
    const float f[6] = {1.5f, -2.0f, 3.25f, 0.0f, 1e-3f, -7.0f};
    writeNpy(path("f4.npy"), "<f4", {2, 3}, f, sizeof f);
    auto points = npyPoints(readNpy(path("f4.npy")), "f4");
    ASSERT_EQ(points.size(), 2u);
    EXPECT_EQ(points[0], glm::vec3(1.5f, -2.0f, 3.25f));
    EXPECT_EQ(points[1], glm::vec3(0.0f, 1e-3f, -7.0f));

    double d[6];
    for (int k = 0; k < 6; ++k) d[k] = f[k];
    std::string big(sizeof d, '\0');
    for (int k = 0; k < 6; ++k)
        for (int b = 0; b < 8; ++b) big[std::size_t(8 * k + b)] = reinterpret_cast<const char*>(&d[k])[7 - b];
    write("f8be.npy", npy("{'descr': '>f8', 'fortran_order': False, 'shape': (2, 3), }", big));
    points = npyPoints(readNpy(path("f8be.npy")), "f8be");
    EXPECT_EQ(points[1], glm::vec3(0.0f, 1e-3f, -7.0f));

    // Fortran order (numpy.asfortranarray): the x column, then y, then z.
    const float columns[6] = {1.5f, 0.0f, -2.0f, 1e-3f, 3.25f, -7.0f};
    write("fortran.npy", npy("{'descr': '<f4', 'fortran_order': True, 'shape': (2, 3), }",
                             std::string(reinterpret_cast<const char*>(columns), sizeof columns)));
    points = npyPoints(readNpy(path("fortran.npy")), "fortran");
    ASSERT_EQ(points.size(), 2u);
    EXPECT_EQ(points[0], glm::vec3(1.5f, -2.0f, 3.25f));
    EXPECT_EQ(points[1], glm::vec3(0.0f, 1e-3f, -7.0f));
}

TEST_F(NpyTest, LabelsAreWrittenAsNumpyReadsThem) {
    const std::uint8_t labels[5] = {1, 0, 1, 1, 0};
    writeNpy(path("b.npy"), "|b1", {5}, labels, sizeof labels);
    std::ifstream in(path("b.npy"), std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    ASSERT_EQ(bytes.size() % 64, 5u) << "data starts at a multiple of 64 bytes";
    EXPECT_NE(bytes.find("'descr': '|b1', 'fortran_order': False, 'shape': (5,), }"), std::string::npos);
    EXPECT_EQ(bytes.substr(bytes.size() - 5), std::string("\x01\x00\x01\x01\x00", 5));
    const NpyArray a = readNpy(path("b.npy"));
    EXPECT_EQ(a.shape, std::vector<std::uint64_t>{5});
    EXPECT_EQ(a.descr, "|b1");
}

TEST_F(NpyTest, BadFilesGetOneLineErrors) {
    const std::string header = "{'descr': '<f4', 'fortran_order': False, 'shape': (2, 3), }";
    const std::string data(24, '\0');
    write("empty.npy", "");
    write("magic.npy", "NUMPY not really a numpy file");
    write("truncated.npy", npy(header, data).substr(0, 70));
    write("short.npy", npy(header, data.substr(0, 20)));
    write("absurd.npy", npy("{'descr': '<f4', 'fortran_order': False, 'shape': (99999999999, 3), }", data));
    write("overflow.npy", npy("{'descr': '<f4', 'fortran_order': False, 'shape': (18446744073709551615, 3), }", data));
    write("noshape.npy", npy("{'descr': '<f4', 'fortran_order': False, }", data));
    for (const char* name : {"empty.npy", "magic.npy", "truncated.npy", "short.npy", "absurd.npy", "overflow.npy",
                             "noshape.npy"}) {
        try {
            readNpy(path(name));
            ADD_FAILURE() << name << " was accepted";
        } catch (const FormatError& e) {
            const std::string what = e.what();
            EXPECT_EQ(what.find('\n'), std::string::npos) << what;
            EXPECT_NE(what.find(name), std::string::npos) << what;
        }
    }
    EXPECT_THROW(readNpy(path("missing.npy")), IoError);
    EXPECT_THROW(readNpy(dir_.string()), IoError);

    const float nan[6] = {0, 0, 0, 1, std::nanf(""), 2};
    writeNpy(path("nan.npy"), "<f4", {2, 3}, nan, sizeof nan);
    EXPECT_THROW(npyPoints(readNpy(path("nan.npy")), "nan"), FormatError);
    const std::int32_t ints[3] = {1, 2, 3};
    writeNpy(path("int.npy"), "<i4", {1, 3}, ints, sizeof ints);
    EXPECT_THROW(npyPoints(readNpy(path("int.npy")), "int"), FormatError);
    writeNpy(path("flat.npy"), "<f4", {6}, nan, sizeof nan);
    EXPECT_THROW(npyPoints(readNpy(path("flat.npy")), "flat"), FormatError);
}

} // namespace
} // namespace vds
