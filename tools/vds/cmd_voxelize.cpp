#include <algorithm>
#include <chrono>
#include <cstdio>
#include <optional>
#include <vector>

#include <vds/exact.h>
#include <vds/mesh_io.h>
#include <vds/npy.h>
#include <vds/occupancy.h>
#include <vds/vds_file.h>

#include "cli.h"

namespace cli {

namespace {

struct VoxelizeArgs {
    std::string input, output;
    std::uint32_t dims = 0;
    std::vector<std::uint32_t> dimsXyz;
    std::vector<float> box;
    vds::ClassifyOptions options;
    bool packed = false, verbose = false, quiet = false;
};

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void voxelize(VoxelizeArgs& a) {
    if ((a.dims == 0) == a.dimsXyz.empty()) throw CLI::ValidationError("give --dims N or --dims-xyz NX NY NZ");
    const auto progress = progressPrinter(a.quiet);
    const auto phase = [&](const char* what, double seconds) {
        if (a.verbose) std::fprintf(stderr, "vds voxelize: %-8s %8.3f s\n", what, seconds);
    };
    auto start = std::chrono::steady_clock::now();
    const bool fromSprite = a.input.size() > 4 && a.input.compare(a.input.size() - 4, 4, ".vds") == 0;
    vds::TriangleMesh mesh;
    vds::Sprite sprite;
    vds::Box bounds;
    if (fromSprite) {
        sprite = vds::readSprite(a.input);
        bounds = sprite.grid.box;
    } else {
        mesh = vds::loadMesh(a.input);
        phase("read", secondsSince(start));
        start = std::chrono::steady_clock::now();
        const vds::MeshReport report = vds::validateMesh(mesh);
        vds::requireUsable(report, a.input);
        vds::requireVolume(report, a.input);
        bounds = report.bounds;
        const std::string open = vds::openMeshMessage(report, a.input, a.options.rule);
        if (!open.empty()) std::fprintf(stderr, "vds voxelize: warning: %s\n", open.c_str());
    }
    phase(fromSprite ? "read" : "validate", secondsSince(start));
    vds::Grid grid;
    grid.box = bounds;
    if (!a.box.empty()) grid.box = vds::Box{{a.box[0], a.box[1], a.box[2]}, {a.box[3], a.box[4], a.box[5]}};
    if (a.dims) {
        grid.dims = glm::uvec3(a.dims);
    } else {
        grid.dims = glm::uvec3(a.dimsXyz[0], a.dimsXyz[1], a.dimsXyz[2]);
    }
    vds::checkGrid(grid);
    progress("labelling " + std::to_string(grid.dims.x) + "x" + std::to_string(grid.dims.y) + "x" +
             std::to_string(grid.dims.z) + " cells " + (fromSprite ? "from the sprite" : "exactly from the mesh"));
    // The mesh's exact classifier is built once (every slab sweeps through it).
    std::optional<vds::ExactClassifier> exact;
    if (!fromSprite) {
        start = std::chrono::steady_clock::now();
        exact.emplace(mesh, vds::Axis::Z);
        phase("index", secondsSince(start));
    }
    const auto label = [&](const vds::Grid& g, std::uint8_t* out) {
        if (fromSprite) vds::occupancy(sprite, g, out, a.options);
        else exact->occupancy(g, out, a.options);
    };
    // --packed labels the grid a slab of x layers at a time (at most 2^26
    // cells), packing each slab's rows as it goes: the unpacked grid is never
    // held whole. Slabs have the whole grid's cell centres (Grid::slabX), so
    // the labels are the same as in one call.
    const std::size_t layer = std::size_t(grid.dims.y) * grid.dims.z;
    const std::uint32_t slab =
        a.packed ? std::uint32_t(std::clamp<std::size_t>((std::size_t(1) << 26) / layer, 1, grid.dims.x)) : grid.dims.x;
    const std::size_t rowBytes = (std::size_t(grid.dims.z) + 7) / 8, rows = std::size_t(grid.dims.x) * grid.dims.y;
    std::vector<std::uint8_t> cells, bits;
    start = std::chrono::steady_clock::now();
    try {
        cells.resize(std::size_t(slab) * layer);
        if (a.packed) bits.resize(rows * rowBytes);
    } catch (const std::bad_alloc&) {
        throw vds::OutOfMemory("not enough memory for " + std::to_string(grid.cellCount()) + " cells");
    }
    phase("allocate", secondsSince(start));
    start = std::chrono::steady_clock::now();
    std::size_t inside = 0;
    for (std::uint32_t i0 = 0; i0 < grid.dims.x; i0 += slab) {
        const std::uint32_t i1 = std::min(grid.dims.x, i0 + slab);
        label(slab == grid.dims.x ? grid : grid.slabX(i0, i1), cells.data());
        const std::size_t count = std::size_t(i1 - i0) * layer;
        for (std::size_t c = 0; c < count; ++c) inside += cells[c];
        if (a.packed) // numpy.packbits(cells, axis=-1): each z row packed on its own
            for (std::size_t r = 0; r < std::size_t(i1 - i0) * grid.dims.y; ++r)
                vds::packLabels(cells.data() + r * grid.dims.z, grid.dims.z,
                                bits.data() + (std::size_t(i0) * grid.dims.y + r) * rowBytes);
    }
    const double sweep = secondsSince(start);
    phase("sweep", sweep);
    start = std::chrono::steady_clock::now();
    if (a.packed)
        vds::writeNpy(a.output, "|u1", {grid.dims.x, grid.dims.y, rowBytes}, bits.data(), bits.size());
    else
        vds::writeNpy(a.output, "|b1", {grid.dims.x, grid.dims.y, grid.dims.z}, cells.data(), cells.size());
    phase("write", secondsSince(start));
    std::printf("wrote %s: %ux%ux%u cells, %zu inside, %s rule, swept in %.3f s (%.0f M cells/s)\n", a.output.c_str(),
                grid.dims.x, grid.dims.y, grid.dims.z, inside, vds::toString(a.options.rule), sweep,
                double(grid.cellCount()) / std::max(sweep, 1e-9) * 1e-6);
}

} // namespace

void addVoxelize(CLI::App& app) {
    const auto [c, a] = addCommand<VoxelizeArgs>(
        app, "voxelize", "label every cell of a grid inside or outside, into a numpy .npy file",
        "Cell (i, j, k) has the centre lo + (i + 1/2, j + 1/2, k + 1/2) * (hi - lo) / (NX, NY, NZ),\n"
        "box [lo, hi] the mesh's (or the sprite's) bounding box unless --box is given. GRID.npy is a\n"
        "C-order boolean array of shape (NX, NY, NZ), indexed [i][j][k] along x, y, z; with\n"
        "--packed, a uint8 array of shape (NX, NY, ceil(NZ / 8)): each z row eight cells to a byte,\n"
        "first cell in the highest bit (numpy.packbits(cells, axis=-1); numpy.unpackbits(a, axis=-1,\n"
        "count=NZ) gives the cells back). From a mesh the labels are exact (equal to 'vds classify --exact' on\n"
        "the cell centres); from a SPRITE.vds they are the sprite's answers.",
        voxelize);
    c->add_option("INPUT", a->input, "a mesh (OBJ, PLY, STL, OFF) or a sprite (.vds)")->required()->type_name("");
    c->add_option("-o,--output", a->output, "output .npy (written whole or not at all)")->required()->type_name("FILE");
    c->add_option("--dims", a->dims, "cells along each axis")
        ->transform(wholeNumber(1, vds::kMaxResolution))
        ->type_name("N");
    c->add_option("--dims-xyz", a->dimsXyz, "cells along x, y and z")
        ->expected(3)
        ->transform(wholeNumber(1, vds::kMaxResolution))
        ->type_name("NX NY NZ");
    c->add_option("--box", a->box, "the grid's box instead of the input's bounds")
        ->expected(6)
        ->type_name("X0 Y0 Z0 X1 Y1 Z1");
    addEnum(*c, "--rule", a->options.rule, "parity, non-zero winding, or generalized winding (closed meshes)");
    addCount(*c, "--threads", a->options.threads, "CPU threads, 0: all");
    c->add_flag("--packed", a->packed, "eight cells to a byte");
    c->add_flag("--verbose", a->verbose, "print the time of each phase");
}

} // namespace cli
