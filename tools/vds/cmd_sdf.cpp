// vds sdf: a signed distance grid of a mesh, full or a narrow band, into a
// float32 .npy file, or a narrow band computed sparsely into an OpenVDB
// level set (.vdb).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include <vds/atomic_file.h>
#include <vds/distance.h>
#include <vds/mesh_io.h>
#include <vds/npy.h>
#include <vds/sparse_band.h>
#include <vds/sprite.h>
#include <vds/vdb.h>

#include "cli.h"
#include "npy_slabs.h"
#include "outputs.h"

namespace cli {

namespace {

struct SdfArgs {
    std::string mesh, output;
    GridArgs grid;
    double pad = 0.0;
    double band = 0.0, voxelSize = 0.0;
    const CLI::Option* bandGiven = nullptr;
    const CLI::Option* voxelSizeGiven = nullptr;
    vds::Rule rule = vds::Rule::Parity;
    vds::DistanceGridOptions options;
    bool allowOpen = false, quiet = false, propagated = false, cubic = false;
    std::size_t slabCells = kSlabCells;
    std::uint64_t zip64Above = kZip64Above;
};

bool hasVdbExtension(const std::string& path) {
    return path.size() > 4 && path.compare(path.size() - 4, 4, ".vdb") == 0;
}

void checkArguments(const SdfArgs& a) {
    if (a.voxelSizeGiven->count()) {
        if (a.grid.dims || !a.grid.dimsXyz.empty())
            throw CLI::ValidationError("give --voxel-size or --dims N or --dims-xyz NX NY NZ, not more than one");
        if (!(std::isfinite(a.voxelSize) && a.voxelSize > 0.0))
            throw CLI::ValidationError("--voxel-size: a length above 0, not " + std::to_string(a.voxelSize));
    } else if ((a.grid.dims == 0) == a.grid.dimsXyz.empty()) {
        throw CLI::ValidationError("give --dims N, --dims-xyz NX NY NZ or --voxel-size H");
    }
    if (a.bandGiven->count() && !(std::isfinite(a.band) && a.band > 0.0))
        throw CLI::ValidationError("--band: the band's half-width must be a finite distance above 0 (leave it out "
                                   "for the full grid), not " + std::to_string(a.band));
    if (a.propagated && a.bandGiven->count())
        throw CLI::ValidationError("--propagated is a way to fill the full grid: leave out --band");
    if (!(std::isfinite(a.pad) && a.pad >= 0.0 && a.pad <= 10.0))
        throw CLI::ValidationError("--pad: a fraction of the box's size from 0 to 10, not " + std::to_string(a.pad));
    if (a.cubic && a.grid.dims == 0) throw CLI::ValidationError("--cubic takes the cells of the longest side from --dims N");
}

/// The signed distances of `grid`, a slab of x layers at a time appended to
/// `out` (a propagated grid spreads across the whole grid: one slab, held
/// whole). Returns the cells inside (negative).
std::size_t measureInSlabs(const SdfArgs& a, const vds::SignedDistance& query, const vds::Grid& grid,
                           GridSlabWriter& out) {
    constexpr std::uint32_t kProgressSlabs = 16;
    const std::size_t layer = std::size_t(grid.dims.y) * grid.dims.z;
    const std::uint32_t slab = a.propagated ? grid.dims.x : slabLayers(grid, a.slabCells, kProgressSlabs);
    std::vector<float> cells;
    try {
        cells.resize(std::size_t(slab) * layer);
    } catch (const std::bad_alloc&) {
        throw vds::OutOfMemory("not enough memory for a slab of " + std::to_string(std::size_t(slab) * layer) + " cells");
    }
    SlabProgress progress(progressPrinter(a.quiet), "measured", grid.dims.x);
    std::size_t inside = 0;
    for (std::uint32_t i0 = 0; i0 < grid.dims.x; i0 += slab) {
        const std::uint32_t i1 = std::min(grid.dims.x, i0 + slab);
        const std::size_t count = std::size_t(i1 - i0) * layer;
        query.grid(slab == grid.dims.x ? grid : grid.slabX(i0, i1), cells.data(), a.options);
        for (std::size_t c = 0; c < count; ++c) inside += std::signbit(cells[c]);
        out.append(cells.data(), count * sizeof(float));
        progress.done(i1);
    }
    return inside;
}

/// The grid asked for: --voxel-size h, or --dims (cubic with --cubic, and
/// always for a .vdb, whose voxels are cubes); a dense one within the dense
/// limit (`gridOf`), a sparse one within the sparse band's.
vds::Grid gridOfRun(const SdfArgs& a, const vds::Box& bounds, bool sparse) {
    const vds::Box box = boxOf(a.grid, bounds, float(a.pad));
    vds::Grid grid;
    if (a.voxelSizeGiven->count()) grid = vds::voxelSizeGrid(box, a.voxelSize);
    else if (a.cubic || sparse) grid = vds::cubicGrid(box, a.grid.dims);
    else return gridOf(a.grid, bounds, float(a.pad), !a.propagated);
    // A dense grid is written a slab of x layers at a time (a propagated one
    // is held whole): what is held is what is checked.
    if (!sparse) vds::checkGrid(a.propagated ? grid : grid.slabX(0, 1));
    return grid;
}

/// The band computed sparsely into a .vdb level set.
void sdfVdb(const SdfArgs& a, const vds::TriangleMesh& mesh, const vds::SignedDistance& query,
            const std::function<void(const std::string&)>& progress) {
    const vds::Grid grid = gridOfRun(a, vds::meshBounds(mesh), true);
    progress("banding " + std::to_string(grid.dims.x) + "x" + std::to_string(grid.dims.y) + "x" +
             std::to_string(grid.dims.z) + " cells sparsely");
    const auto start = std::chrono::steady_clock::now();
    const vds::SparseBand band = vds::sparseBand(query, mesh, grid, vds::SparseBandOptions{a.options.threads, a.band});
    const double seconds = secondsSince(start);
    vds::VdbOptions options;
    options.source = a.mesh;
    vds::writeVdb(a.output, band, options);
    std::printf("wrote %s: %ux%ux%u cells, %s, %zu band cells in %zu blocks (%.1f MB), band %s, %s rule, in %.3f s\n",
                a.output.c_str(), grid.dims.x, grid.dims.y, grid.dims.z, geometrySummary(grid).c_str(), band.values.size(),
                band.blocks.size(), double(band.memoryBytes()) * 1e-6, std::to_string(a.band).c_str(),
                vds::toString(a.rule), seconds);
}

void sdf(SdfArgs& a) {
    checkArguments(a);
    const bool banded = a.bandGiven->count() != 0;
    if (!banded && hasVdbExtension(a.output))
        throw CLI::ValidationError("-o: " + a.output + ": unsupported output format without --band (supported: .npy, "
                                   ".npz, or '-' for standard output; .vdb holds a narrow band: add --band W)");
    std::vector<OutputFormat> formats{OutputFormat::Npy, OutputFormat::Npz};
    if (banded) formats.push_back(OutputFormat::Vdb);
    const OutputFormat format = outputFormat("-o", a.output, formats, OutputFormat::Npy);
    if (format == OutputFormat::Vdb && !vds::vdbAvailable())
        throw CLI::ValidationError("-o: " + a.output + ": this vds was built without OpenVDB (libopenvdb-dev): it cannot write .vdb files");
    if (format == OutputFormat::Vdb && !a.grid.dimsXyz.empty())
        throw CLI::ValidationError("a .vdb level set has cubic voxels: give --dims N or --voxel-size, not --dims-xyz");
    const auto progress = progressPrinter(a.quiet);
    if (format == OutputFormat::Vdb) {
        vds::AtomicFile claim(a.output); // a missing directory fails now, not after the work
        const vds::TriangleMesh mesh = vds::loadMesh(a.mesh);
        checkSignedMesh(mesh, a.mesh, a.rule, a.allowOpen, "sdf");
        const vds::SignedDistance query(mesh, a.rule, a.mesh);
        progress("built " + query.summary());
        sdfVdb(a, mesh, query, progress);
        return;
    }
    const vds::TriangleMesh mesh = vds::loadMesh(a.mesh);
    checkSignedMesh(mesh, a.mesh, a.rule, a.allowOpen, "sdf");
    const vds::Grid grid = gridOfRun(a, vds::meshBounds(mesh), false);
    GridFileInfo info;
    info.grid = grid;
    info.kind = banded ? "band" : "sdf";
    info.rule = a.rule;
    info.band = a.band;
    info.zip64Above = a.zip64Above;
    GridSlabWriter out(a.output, "<f4", {grid.dims.x, grid.dims.y, grid.dims.z}, sizeof(float), info);
    const vds::SignedDistance query(mesh, a.rule, a.mesh);
    progress("built " + query.summary());
    a.options.band = a.band;
    a.options.far = a.propagated ? vds::FarCells::Propagated : vds::FarCells::Exact;
    const auto start = std::chrono::steady_clock::now();
    const std::size_t inside = measureInSlabs(a, query, grid, out);
    const double seconds = secondsSince(start);
    out.commit();
    // With the grid on stdout, the summary goes to stderr.
    std::fprintf(a.output == kStdio ? stderr : stdout, "wrote %s: %ux%ux%u cells, %s, %zu inside, %s, %s rule, in %.3f s\n",
                 a.output.c_str(), grid.dims.x, grid.dims.y, grid.dims.z, geometrySummary(grid).c_str(), inside,
                 a.band > 0.0 ? ("band " + std::to_string(a.band)).c_str()
                              : (a.propagated ? "full grid, propagated" : "full grid"),
                 vds::toString(a.rule), seconds);
}

} // namespace

void addSdf(CLI::App& app) {
    const auto [c, a] = addCommand<SdfArgs>(
        app, "sdf", "signed distance grid of a mesh (full or a narrow band), into a float32 .npy or .npz file",
        "  vds sdf MESH (--dims N [--cubic] | --dims-xyz NX NY NZ | --voxel-size H) [--band W | --propagated]\n"
        "      -o SDF.npy|SDF.npz [--rule RULE] [--box ...] [--pad F]\n"
        "  vds sdf MESH (--dims N | --voxel-size H) --band W -o SDF.vdb\n"
        "SDF.npy: float32 of shape (NX, NY, NZ), indexed [i][j][k], the signed distance of the centre of\n"
        "cell (i, j, k), lo + (i + 1/2, j + 1/2, k + 1/2) * (hi - lo) / (NX, NY, NZ), as 'vds voxelize'\n"
        "places them: box [lo, hi] the mesh's bounds (or --box) grown by --pad times its size on every\n"
        "side. Negative exactly where 'vds voxelize' with the same rule says inside. With --band W\n"
        "(mesh units), cells farther than W from the surface hold -W or +W. With --propagated, the full\n"
        "grid as a closest-feature transform: exact within a cell diagonal of the surface, beyond it\n"
        "never below the distance and within 4 cell diagonals above it (many times faster). With --cubic,\n"
        "N cells along the box's longest side and as many cubic cells along the others as cover it, the\n"
        "box's high corner grown to whole cells ('vds bake --distance' and vds.Grid.cubic place them so;\n"
        "--voxel-size H likewise). The summary line gives the grid's box and cell size.\n"
        "SDF '-' writes the .npy to stdout, with the summary line on stderr. The grid is measured and\n"
        "written a slab of x layers at a time (at most 2^26 cells held; --propagated holds it whole).\n"
        "SDF.npz: the same array as member 'values' of a numpy .npz (np.load(path); vds.load_grid(path)\n"
        "gives the array and its vds.Grid) with the grid's geometry beside it: 'lo', 'hi' (float64[3], the\n"
        "box), 'dims' (int64[3]), 'spacing' (float64[3], (hi - lo) / dims), 'kind' ('sdf', or 'band' with\n"
        "'band' W), 'rule', 'version'; uncompressed, written slab by slab as the .npy (docs/format.md).\n"
        "SDF.vdb (a build with OpenVDB, 'vds --version'): the band computed sparsely, only the cells\n"
        "within W of the surface, so grids far past the dense limit fit (4096^3 and more), written as an\n"
        "OpenVDB level set (FloatGrid 'sdf', background W, voxel (i, j, k) centred on cell (i, j, k),\n"
        "cubic cells: --dims N along the longest side or --voxel-size H), the same values as the .npy band.",
        sdf);
    addMesh(*c, a->mesh);
    c->add_option("-o,--output", a->output,
                  "output .npy, or .npz (the values and the grid's geometry), written slab by slab into a temporary "
                  "file, renamed into place once whole; or, with --band, .vdb (written whole or not at all); "
                  "'-': stdout (.npy)")
        ->required()
        ->type_name("FILE");
    addGridOptions(*c, a->grid, "the grid's box instead of the mesh's bounds");
    a->voxelSizeGiven = c->add_option("--voxel-size", a->voxelSize, "cubic cells of this side, mesh units, from the box's low corner (instead of --dims)")
                            ->type_name("H")
                            ->default_str("");
    c->add_flag("--cubic", a->cubic, "cubic cells: --dims N along the longest side, as many as cover the others (the box grows to whole cells)");
    c->add_option("--pad", a->pad, "grow the box by this fraction of its size on every side")->type_name("F");
    a->bandGiven = c->add_option("--band", a->band, "narrow band half-width W > 0, mesh units: farther cells hold +-W (default: the full grid)")
                       ->type_name("W")
                       ->default_str(""); // none unless given: 0 is no width
    c->add_flag("--propagated", a->propagated,
                "full grid: exact near the surface, within 4 cell diagonals beyond (a closest-feature transform)");
    addEnum(*c, "--rule", a->rule, "what is inside (negative): parity, winding, or generalized-winding (open meshes)");
    c->add_flag("--allow-open", a->allowOpen, "sign an open mesh by crossing count anyway");
    addCount(*c, "--threads", a->options.threads, "CPU threads, 0: all");
    addGridFileKnobs(*c, a->slabCells, a->zip64Above);
}

} // namespace cli
