// .vdb output (<vds/vdb.h>) read back with OpenVDB itself: a sparse band's
// level set holds the band's value in every cell, its band cells active,
// the level-set class (and OpenVDB's own level-set diagnosis), its
// background and metadata, and a transform that
// puts every voxel's centre on the vds cell's; occupancy reads back as the
// labels, whole blocks as tiles. Without OpenVDB the build has no reader:
// the writer must then refuse, in one line.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <vds/distance.h>
#include <vds/error.h>
#include <vds/sparse_band.h>
#include <vds/vdb.h>

#include "solids.h"

#if VDS_TEST_OPENVDB
#include <openvdb/tools/Diagnostics.h>

#include "vdb_read.h"
#endif

namespace vds {
namespace {

namespace fs = std::filesystem;

struct TempDir {
    TempDir() : path(fs::temp_directory_path() / ("vds_vdb_test_" + std::to_string(::getpid()))) {
        fs::create_directories(path);
    }
    ~TempDir() { fs::remove_all(path); }
    std::string file(const std::string& name) const { return (path / name).string(); }
    fs::path path;
};

Grid gridAround(const TriangleMesh& mesh, std::uint32_t n) {
    Box box = meshBounds(mesh);
    box.lo -= glm::vec3(0.2f);
    box.hi += glm::vec3(0.2f);
    return cubicGrid(box, n);
}

TEST(Vdb, AvailabilityIsTheBuilds) {
    EXPECT_EQ(vdbAvailable(), bool(VDS_TEST_OPENVDB));
    EXPECT_EQ(vdbLibrary().rfind(vdbAvailable() ? "OpenVDB " : "no OpenVDB", 0), 0u) << vdbLibrary();
    EXPECT_FALSE(vdsVersion().empty());
    if (vdbAvailable()) return;
    TempDir dir;
    const Grid grid = gridAround(solids::sphere(glm::vec3(0.0f), 1.0f, 8).mesh, 8);
    const std::vector<std::uint8_t> cells(grid.cellCount(), 1);
    try {
        writeVdb(dir.file("a.vdb"), grid, cells.data(), Rule::Parity);
        FAIL() << "a build without OpenVDB wrote a .vdb";
    } catch (const InvalidArgument& e) {
        EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
        EXPECT_NE(std::string(e.what()).find("without OpenVDB"), std::string::npos) << e.what();
    }
    EXPECT_FALSE(fs::exists(dir.file("a.vdb")));
}

#if VDS_TEST_OPENVDB

using test::readOnlyGrid;

TEST(Vdb, ALevelSetReadsBackWithItsValuesTransformAndClass) {
    TempDir dir;
    const TriangleMesh mesh = solids::torus(glm::vec3(0.1f, 0.2f, -0.3f), 1.0f, 0.4f, 32).mesh;
    const SignedDistance distance(mesh, Rule::Parity);
    const Grid grid = gridAround(mesh, 48);
    const double cell = double(grid.box.hi.x - grid.box.lo.x) / grid.dims.x;
    const SparseBand band = sparseBand(distance, mesh, grid, SparseBandOptions{2, 3.0 * cell});
    writeVdb(dir.file("torus.vdb"), band, VdbOptions{"", "torus.obj"});
    const auto read = readOnlyGrid<openvdb::FloatGrid>(dir.file("torus.vdb"));
    ASSERT_TRUE(read);
    EXPECT_EQ(read->getName(), "sdf");
    EXPECT_EQ(read->getGridClass(), openvdb::GRID_LEVEL_SET);
    EXPECT_EQ(read->background(), float(band.halfWidth));
    EXPECT_EQ(read->metaValue<std::string>("rule"), "parity");
    EXPECT_EQ(read->metaValue<std::string>("source"), "torus.obj");
    EXPECT_EQ(read->metaValue<std::string>("vds_version"), vdsVersion());
    EXPECT_EQ(read->activeVoxelCount(), band.values.size());
    // OpenVDB's own diagnosis of a narrow-band level set: float, class,
    // uniform voxels, background n voxels, no active tiles, finite values,
    // active ones within +-background, inactive ones at +-background, and
    // gradients of norm near one (the Eikonal equation).
    EXPECT_EQ(openvdb::tools::checkLevelSet(*read, 9), "");
    const openvdb::FloatGrid::ConstAccessor access = read->getConstAccessor();
    for (std::uint32_t i = 0; i < grid.dims.x; ++i)
        for (std::uint32_t j = 0; j < grid.dims.y; ++j)
            for (std::uint32_t k = 0; k < grid.dims.z; ++k) {
                const openvdb::Coord c{int(i), int(j), int(k)};
                const float expected = band.value(i, j, k);
                ASSERT_EQ(access.getValue(c), expected) << i << " " << j << " " << k;
                ASSERT_EQ(access.isValueOn(c), std::abs(expected) < float(band.halfWidth));
            }
    // A voxel's world centre is the vds cell's centre.
    for (const glm::uvec3 at : {glm::uvec3(0u), glm::uvec3(47u, 3u, 20u), grid.dims - 1u}) {
        const openvdb::Vec3d world = read->indexToWorld(openvdb::Coord(int(at.x), int(at.y), int(at.z)));
        const glm::vec3 centre = grid.cellCentre(at.x, at.y, at.z);
        for (int a = 0; a < 3; ++a) EXPECT_NEAR(world[a], centre[a], 1e-6) << a;
    }
    EXPECT_NEAR(read->voxelSize()[0], cell, 1e-7);
}

TEST(Vdb, OccupancyReadsBackAsItsLabelsWithWholeBlocksAsTiles) {
    TempDir dir;
    const TriangleMesh mesh = solids::sphere(glm::vec3(0.0f), 1.0f, 24).mesh;
    const SignedDistance distance(mesh, Rule::Winding);
    const Grid grid = gridAround(mesh, 45);
    std::vector<std::uint8_t> labels(grid.cellCount());
    ClassifyOptions classify;
    classify.rule = Rule::Winding;
    distance.classifier().occupancy(grid, labels.data(), classify);
    writeVdb(dir.file("sphere.vdb"), grid, labels.data(), Rule::Winding);
    const auto read = readOnlyGrid<openvdb::BoolGrid>(dir.file("sphere.vdb"));
    ASSERT_TRUE(read);
    EXPECT_EQ(read->getName(), "occupancy");
    EXPECT_EQ(read->metaValue<std::string>("rule"), "winding");
    EXPECT_GT(read->tree().activeTileCount(), 0u);
    std::size_t inside = 0;
    std::vector<bool> blockInside(std::size_t(6 * 6 * 6)); // 45 cells: 6 blocks an axis
    const openvdb::BoolGrid::ConstAccessor access = read->getConstAccessor();
    for (std::uint32_t i = 0; i < grid.dims.x; ++i)
        for (std::uint32_t j = 0; j < grid.dims.y; ++j)
            for (std::uint32_t k = 0; k < grid.dims.z; ++k) {
                const bool label = labels[grid.index(i, j, k)] != 0;
                ASSERT_EQ(access.isValueOn(openvdb::Coord(int(i), int(j), int(k))), label) << i << " " << j << " " << k;
                inside += label;
                if (label) blockInside[(i / 8 * 6 + j / 8) * 6 + k / 8] = true;
            }
    EXPECT_EQ(read->activeVoxelCount(), inside);
    // Whole blocks are tiles, not leaves of 512 voxels: fewer leaves than
    // blocks with a cell inside.
    EXPECT_LT(read->tree().leafCount(), std::size_t(std::count(blockInside.begin(), blockInside.end(), true)));
}

TEST(Vdb, AFileThatCannotBeWrittenIsRefusedAndNothingIsLeft) {
    TempDir dir;
    const Grid grid = gridAround(solids::sphere(glm::vec3(0.0f), 1.0f, 8).mesh, 8);
    const std::vector<std::uint8_t> cells(grid.cellCount(), 1);
    EXPECT_THROW(writeVdb(dir.file("missing/a.vdb"), grid, cells.data(), Rule::Parity), IoError);
    EXPECT_THROW(writeVdb(dir.file("a.vdb"), grid.slabX(0, 4), cells.data(), Rule::Parity), InvalidArgument);
    EXPECT_TRUE(fs::is_empty(dir.path));
}

#endif

} // namespace
} // namespace vds
