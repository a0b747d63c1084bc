#include <algorithm>
#include <chrono>
#include <functional>
#include <cstdio>
#include <optional>
#include <vector>

#include <vds/atomic_file.h>
#include <vds/exact.h>
#include <vds/mesh_check.h>
#include <vds/mesh_io.h>
#include <vds/npy.h>
#include <vds/occupancy.h>
#include <vds/vdb.h>
#include <vds/vds_file.h>

#include "cli.h"
#include "npy_slabs.h"
#include "outputs.h"

namespace cli {

namespace {

struct VoxelizeArgs {
    std::string input, output;
    GridArgs grid;
    vds::ClassifyOptions options;
    bool packed = false, verbose = false, quiet = false, allowOpen = false;
    std::size_t slabCells = kSlabCells;
    std::uint64_t zip64Above = kZip64Above;
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

using Labeller = std::function<void(const vds::Grid&, std::uint8_t*)>;

/// Labels `grid` a slab of x layers at a time (Grid::slabX: the whole grid's
/// cell centres, so the labels are those of one call), appending each slab to
/// `out`, packed row by row with --packed (numpy.packbits(cells, axis=-1)):
/// one slab's cells are held, never the grid's. Returns the cells inside.
std::size_t labelInSlabs(const VoxelizeArgs& a, const vds::Grid& grid, const Labeller& label, GridSlabWriter& out) {
    constexpr std::uint32_t kProgressSlabs = 16;
    const std::size_t layer = std::size_t(grid.dims.y) * grid.dims.z;
    const std::uint32_t slab = slabLayers(grid, a.slabCells, kProgressSlabs);
    const std::size_t rowBytes = (std::size_t(grid.dims.z) + 7) / 8;
    std::vector<std::uint8_t> cells, bits;
    try {
        cells.resize(std::size_t(slab) * layer);
        if (a.packed) bits.resize(std::size_t(slab) * grid.dims.y * rowBytes);
    } catch (const std::bad_alloc&) {
        throw vds::OutOfMemory("not enough memory for a slab of " + std::to_string(cells.size()) + " cells");
    }
    SlabProgress progress(progressPrinter(a.quiet), "labelled", grid.dims.x);
    std::size_t inside = 0;
    for (std::uint32_t i0 = 0; i0 < grid.dims.x; i0 += slab) {
        const std::uint32_t i1 = std::min(grid.dims.x, i0 + slab);
        label(slab == grid.dims.x ? grid : grid.slabX(i0, i1), cells.data());
        const std::size_t count = std::size_t(i1 - i0) * layer, rows = std::size_t(i1 - i0) * grid.dims.y;
        for (std::size_t c = 0; c < count; ++c) inside += cells[c];
        if (a.packed) {
            for (std::size_t r = 0; r < rows; ++r)
                vds::packLabels(cells.data() + r * grid.dims.z, grid.dims.z, bits.data() + r * rowBytes);
            out.append(bits.data(), rows * rowBytes);
        } else {
            out.append(cells.data(), count);
        }
        progress.done(i1);
    }
    return inside;
}

/// Labels `grid` whole into `cells` (a .vdb's grid); returns the cells inside.
std::size_t labelWhole(const vds::Grid& grid, const Labeller& label, std::vector<std::uint8_t>& cells) {
    try {
        cells.resize(grid.cellCount());
    } catch (const std::bad_alloc&) {
        throw vds::OutOfMemory("not enough memory for a grid of " + std::to_string(grid.cellCount()) + " cells");
    }
    label(grid, cells.data());
    return std::size_t(std::count(cells.begin(), cells.end(), std::uint8_t(1)));
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
    // A .vdb is written from the grid labelled whole; a .npy a slab at a time.
    const vds::Grid grid = gridOf(a.grid, bounds, 0.0f, !vdb);
    const std::uint64_t rowBytes = (std::uint64_t(grid.dims.z) + 7) / 8;
    std::optional<GridSlabWriter> out;
    std::optional<vds::AtomicFile> claim; // a missing directory fails now, not after the work
    GridFileInfo info;
    info.grid = grid;
    info.rule = a.options.rule;
    info.packed = a.packed;
    info.zip64Above = a.zip64Above;
    if (vdb) claim.emplace(a.output);
    else
        out.emplace(a.output, a.packed ? "|u1" : "|b1",
                    std::vector<std::uint64_t>{grid.dims.x, grid.dims.y, a.packed ? rowBytes : grid.dims.z}, 1, info);
    progress("labelling " + std::to_string(grid.dims.x) + "x" + std::to_string(grid.dims.y) + "x" +
             std::to_string(grid.dims.z) + " cells " + (fromSprite ? "from the sprite" : "exactly from the mesh"));
    // The mesh's exact classifier is built once (every slab sweeps through it).
    std::optional<vds::ExactClassifier> exact;
    if (!fromSprite) {
        start = std::chrono::steady_clock::now();
        exact.emplace(mesh, vds::Axis::Z);
        phase("index", secondsSince(start));
    }
    const Labeller label = [&](const vds::Grid& g, std::uint8_t* cells) {
        if (fromSprite) vds::occupancy(sprite, g, cells, a.options);
        else exact->occupancy(g, cells, a.options);
    };
    start = std::chrono::steady_clock::now();
    std::vector<std::uint8_t> whole;
    const std::size_t inside = vdb ? labelWhole(grid, label, whole) : labelInSlabs(a, grid, label, *out);
    const double sweep = secondsSince(start);
    phase("sweep", sweep);
    start = std::chrono::steady_clock::now();
    if (vdb) {
        claim.reset();
        vds::VdbOptions options;
        options.source = a.input;
        vds::writeVdb(a.output, grid, whole.data(), a.options.rule, options);
    } else {
        out->commit();
    }
    phase("write", secondsSince(start));
    // With the grid on stdout, the summary goes to stderr.
    std::fprintf(a.output == kStdio ? stderr : stdout,
                 "wrote %s: %ux%ux%u cells, %s, %zu inside, %s rule, swept in %.3f s (%.0f M cells/s)\n",
                 a.output.c_str(), grid.dims.x, grid.dims.y, grid.dims.z, geometrySummary(grid).c_str(), inside,
                 vds::toString(a.options.rule), sweep,
                 double(grid.cellCount()) / std::max(sweep, 1e-9) * 1e-6);
}

} // namespace

void addVoxelize(CLI::App& app) {
    const auto [c, a] = addCommand<VoxelizeArgs>(
        app, "voxelize", "label every cell of a grid inside or outside, into a numpy .npy or .npz (or OpenVDB .vdb) file",
        "Cell (i, j, k) has the centre lo + (i + 1/2, j + 1/2, k + 1/2) * (hi - lo) / (NX, NY, NZ),\n"
        "box [lo, hi] the mesh's (or the sprite's) bounding box unless --box is given. GRID.npy is a\n"
        "C-order boolean array of shape (NX, NY, NZ), indexed [i][j][k] along x, y, z; with\n"
        "--packed, a uint8 array of shape (NX, NY, ceil(NZ / 8)): each z row eight cells to a byte,\n"
        "first cell in the highest bit (numpy.packbits(cells, axis=-1); numpy.unpackbits(a, axis=-1,\n"
        "count=NZ) gives the cells back). From a mesh the labels are exact (equal to 'vds classify --exact' on\n"
        "the cell centres); from a SPRITE.vds they are the sprite's answers. A mesh whose inside the rule\n"
        "does not define (an open mesh by parity or winding) is refused, as classify, distance and sdf\n"
        "refuse it: --rule generalized-winding answers it, --allow-open counts crossings anyway. The grid\n"
        "is labelled and written a slab of x layers at a time (at most 2^26 cells held), so a grid larger\n"
        "than memory ('--dims 4096 --packed', 8.6 GB) needs only the disk for its file.\n"
        "GRID.npz: the same array as member 'values' of a numpy .npz (np.load(path); vds.load_grid(path)\n"
        "gives the array and its vds.Grid) with the grid's geometry beside it: 'lo', 'hi' (float64[3], the\n"
        "box), 'dims' (int64[3]), 'spacing' (float64[3], (hi - lo) / dims), 'kind' ('occupancy'),\n"
        "'packed', 'rule', 'version'; uncompressed, written slab by slab as the .npy (docs/format.md).\n"
        "GRID.vdb (a build with OpenVDB, 'vds --version'): an OpenVDB BoolGrid 'occupancy', the inside\n"
        "cells active, an 8^3 block wholly inside one active tile; voxel (i, j, k) centred on cell (i, j, k)\n"
        "(labelled whole before it is written).",
        voxelize);
    c->add_option("INPUT", a->input, "a mesh (OBJ, PLY, STL, OFF) or a sprite (.vds)")->required()->type_name("");
    c->add_option("-o,--output", a->output,
                  "output .npy, or .npz (the values and the grid's geometry), written slab by slab into a temporary "
                  "file, renamed into place once whole; or .vdb (written whole or not at all); '-': stdout (.npy)")
        ->required()
        ->type_name("FILE");
    addGridOptions(*c, a->grid, "the grid's box instead of the input's bounds");
    addEnum(*c, "--rule", a->options.rule,
            "parity, non-zero winding, or the generalized winding number (open meshes and soups too)");
    c->add_flag("--allow-open", a->allowOpen, "label an open mesh by crossing count anyway");
    addCount(*c, "--threads", a->options.threads, "CPU threads, 0: all");
    c->add_flag("--packed", a->packed, "eight cells to a byte");
    c->add_flag("--verbose", a->verbose, "print the time of each phase");
    addGridFileKnobs(*c, a->slabCells, a->zip64Above);
}

} // namespace cli
