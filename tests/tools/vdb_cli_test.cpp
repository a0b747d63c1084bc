// `vds sdf ... --band W -o X.vdb` and `vds voxelize ... -o X.vdb`, read back
// with OpenVDB: the level set holds the same values as the .npy band of the
// same command, the occupancy grid the same labels as the .npy grid; bad
// requests are refused in one line before any work, nothing written. In a
// build without OpenVDB, every .vdb is refused in one line and
// `vds --version` says so.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <vds/npy.h>

#include "cli_fixture.h"
#include "solids.h"

#if VDS_TEST_OPENVDB
#include "vdb_read.h"
#endif

namespace {

namespace fs = std::filesystem;
using vds::test::Result;
using vds::test::writeObj;

std::size_t lines(const std::string& text) { return std::size_t(std::count(text.begin(), text.end(), '\n')); }

class VdbCli : public vds::test::ToolDirectory {
protected:
    VdbCli() : ToolDirectory("vds_vdb_cli_") {}
    void SetUp() override {
        ToolDirectory::SetUp();
        writeObj(dir / "torus.obj", vds::solids::torus(glm::vec3(0.1f, 0.0f, -0.2f), 1.0f, 0.35f, 24).mesh);
    }
};

TEST_F(VdbCli, TheVersionSaysWhetherVdbIsWritten) {
    const Result r = vds("--version");
    EXPECT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(lines(r.output), 1u) << r.output;
    EXPECT_NE(r.output.find(VDS_TEST_OPENVDB ? "writes .vdb" : ".vdb output refused"), std::string::npos) << r.output;
}

TEST_F(VdbCli, BadVdbRequestsAreRefusedInOneLineBeforeAnyWork) {
    const std::string sdf = "sdf " + p("torus.obj") + " -o " + p("t.vdb") + " --quiet";
    std::vector<std::string> refused = {sdf + " --dims 16",                       // no band
                                        sdf + " --dims-xyz 8 8 8 --band 0.1",     // not cubic
                                        sdf + " --dims 8 --voxel-size 0.1 --band 0.1",
                                        sdf + " --voxel-size 0 --band 0.1",
                                        "voxelize " + p("torus.obj") + " --dims 8 --packed -o " + p("t.vdb")};
    if (!VDS_TEST_OPENVDB) refused = {sdf + " --dims 16 --band 0.1", "voxelize " + p("torus.obj") + " --dims 8 -o " + p("t.vdb")};
    for (const std::string& args : refused) {
        const Result r = vds(args);
        EXPECT_EQ(r.code, 2) << args << ": " << r.output;
        EXPECT_EQ(lines(r.output), 1u) << args << ": " << r.output;
        if (!VDS_TEST_OPENVDB) {
            EXPECT_NE(r.output.find("without OpenVDB"), std::string::npos) << r.output;
        }
    }
    EXPECT_FALSE(fs::exists(dir / "t.vdb"));
}

#if VDS_TEST_OPENVDB

using vds::test::readOnlyGrid;

TEST_F(VdbCli, ALevelSetHoldsTheValuesOfTheNpyBand) {
    const std::string common = "sdf " + p("torus.obj") + " --dims 40 --cubic --band 0.15 --quiet";
    const Result npy = vds(common + " -o " + p("t.npy"));
    ASSERT_EQ(npy.code, 0) << npy.output;
    const Result vdb = vds(common + " -o " + p("t.vdb"));
    ASSERT_EQ(vdb.code, 0) << vdb.output;
    EXPECT_NE(vdb.output.find("band cells in"), std::string::npos) << vdb.output;
    const vds::NpyArray dense = vds::readNpy(p("t.npy"));
    ASSERT_EQ(dense.shape.size(), 3u);
    const auto level = readOnlyGrid<openvdb::FloatGrid>(p("t.vdb"));
    ASSERT_TRUE(level);
    EXPECT_EQ(level->getGridClass(), openvdb::GRID_LEVEL_SET);
    EXPECT_EQ(level->background(), 0.15f);
    EXPECT_EQ(level->metaValue<std::string>("source"), p("torus.obj"));
    const openvdb::FloatGrid::ConstAccessor access = level->getConstAccessor();
    std::size_t band = 0;
    for (std::size_t i = 0; i < dense.shape[0]; ++i)
        for (std::size_t j = 0; j < dense.shape[1]; ++j)
            for (std::size_t k = 0; k < dense.shape[2]; ++k) {
                float expected;
                std::memcpy(&expected, dense.data.data() + 4 * ((i * dense.shape[1] + j) * dense.shape[2] + k), 4);
                const openvdb::Coord c{int(i), int(j), int(k)};
                ASSERT_EQ(access.getValue(c), expected) << i << " " << j << " " << k;
                band += std::abs(expected) < 0.15f;
            }
    EXPECT_EQ(level->activeVoxelCount(), band);
    EXPECT_GT(band, 0u);
}

TEST_F(VdbCli, AnOccupancyGridHoldsTheLabelsOfTheNpyGrid) {
    const std::string common = "voxelize " + p("torus.obj") + " --dims 40";
    ASSERT_EQ(vds(common + " -o " + p("t.npy")).code, 0);
    const Result r = vds(common + " -o " + p("t.vdb"));
    ASSERT_EQ(r.code, 0) << r.output;
    const vds::NpyArray labels = vds::readNpy(p("t.npy"));
    const auto occupancy = readOnlyGrid<openvdb::BoolGrid>(p("t.vdb"));
    ASSERT_TRUE(occupancy);
    const openvdb::BoolGrid::ConstAccessor access = occupancy->getConstAccessor();
    std::size_t inside = 0;
    for (std::size_t n = 0; n < labels.data.size(); ++n) {
        const int i = int(n / 1600), j = int(n / 40 % 40), k = int(n % 40);
        ASSERT_EQ(access.isValueOn(openvdb::Coord(i, j, k)), labels.data[n] != 0) << n;
        inside += labels.data[n] != 0;
    }
    EXPECT_EQ(occupancy->activeVoxelCount(), inside);
}

#endif

} // namespace
