#include <algorithm>
#include <chrono>
#include <cstdio>
#include <optional>
#include <vector>

#include <vds/exact.h>
#include <vds/mesh_check.h>
#include <vds/mesh_io.h>
#include <vds/npy.h>
#include <vds/occupancy.h>
#include <vds/vdb.h>
#include <vds/vds_file.h>

#include "cli.h"

namespace cli {

namespace {

struct VoxelizeArgs {
    std::string input, output;
    GridArgs grid;
    vds::ClassifyOptions options;
    bool packed = false, verbose = false, quiet = false, allowOpen = false;
};

/// Reads the sprite INPUT names, warns where its answers are a surface's; its box.
vds::Box loadSprite(const VoxelizeArgs& a, vds::Sprite& sprite) {
    sprite = vds::readSprite(a.input);
    if (sprite.status != vds::SolidStatus::Closed && a.options.rule != vds::Rule::GeneralizedWinding)
        std::fprintf(stderr, "vds voxelize: warning: %s\n", vds::openSpriteMessage(sprite.validation, a.options.rule, meshFlags()).c_str());
    return sprite.grid.box;
}

/// Validates the mesh INPUT names as distance and sdf do (`checkSignedMesh`):
/// refuses one with no volume, and one whose inside the rule does not define
/// unless --allow-open; its bounds.
vds::Box checkedBounds(const VoxelizeArgs& a, const vds::TriangleMesh& mesh) {
    checkSignedMesh(mesh, a.input, a.options.rule, a.allowOpen, "voxelize");
    return vds::meshBounds(mesh);
}

/// The x layers labelled a call. --packed labels the grid a slab at a time
/// (at most 2^26 cells), packing each slab's rows as it goes: the unpacked
/// grid is never held whole. Unpacked, the grid goes in kProgressSlabs
/// slabs, so that a sweep past a second (the generalized winding number of
/// a messy scan) reports progress. Slabs have the whole grid's cell centres
/// (Grid::slabX), so the labels are the same as in one call.
std::uint32_t slabLayers(bool packed, const vds::Grid& grid) {
    constexpr std::uint32_t kProgressSlabs = 16;
    const std::size_t layer = std::size_t(grid.dims.y) * grid.dims.z;
    return packed ? std::uint32_t(std::clamp<std::size_t>((std::size_t(1) << 26) / layer, 1, grid.dims.x))
                  : std::max<std::uint32_t>(1, (grid.dims.x + kProgressSlabs - 1) / kProgressSlabs);
}

/// True for an output named .vdb, which the build must be able to write
/// (refused now, before the work, otherwise).
bool vdbOutput(const VoxelizeArgs& a) {
    if (a.output.size() < 4 || a.output.compare(a.output.size() - 4, 4, ".vdb") != 0) return false;
    if (!vds::vdbAvailable())
        throw CLI::ValidationError("-o: " + a.output + ": this vds was built without OpenVDB (libopenvdb-dev): it cannot write .vdb files");
    if (a.packed) throw CLI::ValidationError("--packed: a .vdb keeps whole blocks as tiles already; leave it out");
    return true;
}

void voxelize(VoxelizeArgs& a) {
    requireGridSize(a.grid);
    const bool vdb = vdbOutput(a);
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
        bounds = loadSprite(a, sprite);
    } else {
        mesh = vds::loadMesh(a.input);
        phase("read", secondsSince(start));
        start = std::chrono::steady_clock::now();
        bounds = checkedBounds(a, mesh);
    }
    phase(fromSprite ? "read" : "validate", secondsSince(start));
    const vds::Grid grid = gridOf(a.grid, bounds);
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
    const std::size_t layer = std::size_t(grid.dims.y) * grid.dims.z;
    const std::uint32_t slab = slabLayers(a.packed, grid);
    const std::size_t rowBytes = (std::size_t(grid.dims.z) + 7) / 8, rows = std::size_t(grid.dims.x) * grid.dims.y;
    std::vector<std::uint8_t> cells, bits;
    start = std::chrono::steady_clock::now();
    try {
        cells.resize(a.packed ? std::size_t(slab) * layer : grid.cellCount());
        if (a.packed) bits.resize(rows * rowBytes);
    } catch (const std::bad_alloc&) {
        throw vds::OutOfMemory("not enough memory for " + std::to_string(grid.cellCount()) + " cells");
    }
    phase("allocate", secondsSince(start));
    start = std::chrono::steady_clock::now();
    std::size_t inside = 0;
    for (std::uint32_t i0 = 0; i0 < grid.dims.x; i0 += slab) {
        const std::uint32_t i1 = std::min(grid.dims.x, i0 + slab);
        // Unpacked, each slab lands in its place in the whole grid; packed, at the start of the slab buffer.
        std::uint8_t* slabCells = cells.data() + (a.packed ? 0 : std::size_t(i0) * layer);
        label(slab == grid.dims.x ? grid : grid.slabX(i0, i1), slabCells);
        const std::size_t count = std::size_t(i1 - i0) * layer;
        for (std::size_t c = 0; c < count; ++c) inside += slabCells[c];
        reportSteps(progress, "labelled", i1, grid.dims.x, "x layers", secondsSince(start));
        if (a.packed) // numpy.packbits(cells, axis=-1): each z row packed on its own
            for (std::size_t r = 0; r < std::size_t(i1 - i0) * grid.dims.y; ++r)
                vds::packLabels(slabCells + r * grid.dims.z, grid.dims.z,
                                bits.data() + (std::size_t(i0) * grid.dims.y + r) * rowBytes);
    }
    const double sweep = secondsSince(start);
    phase("sweep", sweep);
    start = std::chrono::steady_clock::now();
    if (vdb) {
        vds::VdbOptions options;
        options.source = a.input;
        vds::writeVdb(a.output, grid, cells.data(), a.options.rule, options);
    } else if (a.packed)
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
        "the cell centres); from a SPRITE.vds they are the sprite's answers. A mesh whose inside the rule\n"
        "does not define (an open mesh by parity or winding) is refused, as classify, distance and sdf\n"
        "refuse it: --rule generalized-winding answers it, --allow-open counts crossings anyway.\n"
        "GRID.vdb (a build with OpenVDB, 'vds --version'): an OpenVDB BoolGrid 'occupancy', the inside\n"
        "cells active, an 8^3 block wholly inside one active tile; voxel (i, j, k) centred on cell (i, j, k).",
        voxelize);
    c->add_option("INPUT", a->input, "a mesh (OBJ, PLY, STL, OFF) or a sprite (.vds)")->required()->type_name("");
    c->add_option("-o,--output", a->output, "output .npy, or .vdb (written whole or not at all)")->required()->type_name("FILE");
    addGridOptions(*c, a->grid, "the grid's box instead of the input's bounds");
    addEnum(*c, "--rule", a->options.rule,
            "parity, non-zero winding, or the generalized winding number (open meshes and soups too)");
    c->add_flag("--allow-open", a->allowOpen, "label an open mesh by crossing count anyway");
    addCount(*c, "--threads", a->options.threads, "CPU threads, 0: all");
    c->add_flag("--packed", a->packed, "eight cells to a byte");
    c->add_flag("--verbose", a->verbose, "print the time of each phase");
}

} // namespace cli
