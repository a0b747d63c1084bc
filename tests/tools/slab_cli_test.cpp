// `vds voxelize` and `vds sdf` write their grid slab by slab: forced into
// many slabs (the hidden --slab-cells), the file equals the library's
// whole-grid call on the same grid cell for cell, packed or not, full grid or
// band; a failure mid-way leaves no file.
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <vds/distance.h>
#include <vds/exact.h>
#include <vds/mesh_io.h>
#include <vds/npy.h>
#include <vds/occupancy.h>

#include "cli_fixture.h"
#include "solids.h"

namespace {

namespace fs = std::filesystem;
using vds::test::Result;
using vds::test::writeObj;

class SlabCli : public vds::test::ToolDirectory {
protected:
    SlabCli() : ToolDirectory("vds_slab_cli_") {}
    void SetUp() override {
        ToolDirectory::SetUp();
        writeObj(dir / "torus.obj", vds::solids::torus({0.1f, 0.2f, 0.3f}, 1.0f, 0.35f, 40).mesh);
        mesh = vds::loadMesh(p("torus.obj"));
    }
    /// The data of the .npy `name` after running `command` on the torus, checking its dtype and shape.
    std::vector<char> written(const std::string& command, const std::string& name, const std::string& descr,
                              std::vector<std::uint64_t> shape) const {
        const Result r = vds(command + " " + p("torus.obj") + " -o " + p(name) + " --quiet");
        EXPECT_EQ(r.code, 0) << command << ": " << r.output;
        const vds::NpyArray a = vds::readNpy(p(name));
        EXPECT_EQ(a.descr, descr) << command;
        EXPECT_EQ(a.shape, shape) << command;
        return a.data;
    }
    vds::TriangleMesh mesh;
};

// 23 x layers of 19 x 11 cells: 627 cells hold three layers (eight slabs, the
// last of two); 1 cell still holds one layer (23 slabs).
TEST_F(SlabCli, VoxelizeInSlabsEqualsTheWholeGridCall) {
    const vds::Grid grid{vds::meshBounds(mesh), {23, 19, 11}};
    std::vector<std::uint8_t> whole(grid.cellCount());
    vds::ExactClassifier(mesh, vds::Axis::Z).occupancy(grid, whole.data(), {});
    std::vector<std::uint8_t> packed(23 * 19 * 2);
    for (std::size_t row = 0; row < 23 * 19; ++row) vds::packLabels(whole.data() + row * 11, 11, packed.data() + row * 2);
    std::size_t inside = 0;
    for (std::uint8_t c : whole) inside += c;
    ASSERT_GT(inside, 100u);
    for (const char* slab : {"1", "627", "100000"}) {
        const std::string voxelize = std::string("voxelize --dims-xyz 23 19 11 --slab-cells ") + slab;
        const std::vector<char> cells = written(voxelize, "cells.npy", "|b1", {23, 19, 11});
        ASSERT_EQ(cells.size(), whole.size());
        EXPECT_EQ(std::memcmp(cells.data(), whole.data(), whole.size()), 0) << slab;
        const std::vector<char> bits = written(voxelize + " --packed", "bits.npy", "|u1", {23, 19, 2});
        ASSERT_EQ(bits.size(), packed.size());
        EXPECT_EQ(std::memcmp(bits.data(), packed.data(), packed.size()), 0) << slab;
    }
    // "-": the same array streamed to stdout, the summary on stderr (a subshell keeps them apart).
    const Result r = vds::test::run("(" + std::string(VDS_TOOL) + " voxelize " + p("torus.obj") +
                                    " --dims-xyz 23 19 11 --slab-cells 627 -o - > " + p("stdout.npy") + ")");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("wrote -: 23x19x11 cells"), std::string::npos) << r.output;
    const vds::NpyArray streamed = vds::readNpy(p("stdout.npy"));
    ASSERT_EQ(streamed.data.size(), whole.size());
    EXPECT_EQ(std::memcmp(streamed.data.data(), whole.data(), whole.size()), 0);
}

TEST_F(SlabCli, SdfInSlabsEqualsTheWholeGridCall) {
    const vds::Grid grid{vds::meshBounds(mesh), {23, 19, 11}};
    const vds::SignedDistance query(mesh, vds::Rule::Parity);
    for (const double band : {0.0, 0.1}) {
        vds::DistanceGridOptions options;
        options.band = band;
        std::vector<float> whole(grid.cellCount());
        query.grid(grid, whole.data(), options);
        const std::string bandArg = band > 0 ? " --band 0.1" : "";
        for (const char* slab : {"1", "627"}) {
            const std::vector<char> cells = written(std::string("sdf --dims-xyz 23 19 11 --slab-cells ") + slab + bandArg,
                                                    "sdf.npy", "<f4", {23, 19, 11});
            ASSERT_EQ(cells.size(), whole.size() * sizeof(float));
            EXPECT_EQ(std::memcmp(cells.data(), whole.data(), cells.size()), 0) << slab << bandArg;
        }
    }
}

// A .npz holds the .npy's bytes verbatim (a stored member), written slab by
// slab into the same file whatever the slab; numpy's reading of it, and its
// geometry, are python/tests/test_grid_files.py's.
TEST_F(SlabCli, NpzHoldsTheNpyWhateverTheSlab) {
    for (const std::string command : {"voxelize --packed", "voxelize", "sdf", "sdf --band 0.1"}) {
        const std::string grid = command + " " + p("torus.obj") + " --dims-xyz 23 19 11 --quiet -o ";
        ASSERT_EQ(vds(grid + p("g.npy")).code, 0) << command;
        ASSERT_EQ(vds(grid + p("whole.npz")).code, 0) << command;
        ASSERT_EQ(vds(grid + p("slabs.npz") + " --slab-cells 1").code, 0) << command;
        const std::string npy = vds::test::readFile(p("g.npy")), npz = vds::test::readFile(p("whole.npz"));
        EXPECT_EQ(npz.substr(0, 2), "PK") << command;
        EXPECT_NE(npz.find(npy), std::string::npos) << command;
        EXPECT_EQ(vds::test::readFile(p("slabs.npz")), npz) << command;
    }
}

// An output whose directory is missing fails before any work, and a bad
// --slab-cells is a command-line error; neither leaves a file.
TEST_F(SlabCli, BadOutputsAndSlabSizesAreRefused) {
    Result r = vds("voxelize " + p("torus.obj") + " --dims 8 -o " + p("none/g.npy"));
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_NE(r.output.find("none/g.npy"), std::string::npos) << r.output;
    r = vds("sdf " + p("torus.obj") + " --dims 8 -o " + p("none/s.npy"));
    EXPECT_EQ(r.code, 1) << r.output;
    for (const char* command : {"voxelize ", "sdf "}) {
        r = vds(command + p("torus.obj") + " --dims 8 -o " + p("none/g.npz"));
        EXPECT_EQ(r.code, 1) << r.output;
        EXPECT_NE(r.output.find("none/g.npz"), std::string::npos) << r.output;
    }
    for (const char* bad : {"0", "-3", "x"}) {
        r = vds("voxelize " + p("torus.obj") + " --dims 8 --slab-cells " + bad + " -o " + p("g.npy"));
        EXPECT_EQ(r.code, 2) << bad << ": " << r.output;
    }
    EXPECT_FALSE(fs::exists(p("g.npy")));
    // Past 2^34 cells: written in slabs, a grid is checked a layer at a time; held whole (a propagated SDF), refused.
    r = vds("sdf " + p("torus.obj") + " --dims 4096 --propagated -o " + p("s.npy"));
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_NE(r.output.find("too large (at most 2^34 cells)"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(p("s.npy")));
    // Hidden: a knob for tests, not in the help.
    EXPECT_EQ(vds("voxelize --help").output.find("slab-cells"), std::string::npos);
    EXPECT_EQ(vds("sdf --help").output.find("zip64-above"), std::string::npos);
}

} // namespace
