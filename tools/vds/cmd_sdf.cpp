// vds sdf: a signed distance grid of a mesh, full or a narrow band, into a
// float32 .npy file.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <vds/distance.h>
#include <vds/mesh_io.h>
#include <vds/npy.h>
#include <vds/sprite.h>

#include "cli.h"
#include "npy_slabs.h"
#include "outputs.h"

namespace cli {

namespace {

struct SdfArgs {
    std::string mesh, output;
    GridArgs grid;
    double pad = 0.0;
    double band = 0.0;
    const CLI::Option* bandGiven = nullptr;
    vds::Rule rule = vds::Rule::Parity;
    vds::DistanceGridOptions options;
    bool allowOpen = false, quiet = false, propagated = false, cubic = false;
    std::size_t slabCells = kSlabCells;
};

void checkArguments(const SdfArgs& a) {
    requireGridSize(a.grid);
    if (a.bandGiven->count() && !(std::isfinite(a.band) && a.band > 0.0))
        throw CLI::ValidationError("--band: the band's half-width must be a finite distance above 0 (leave it out "
                                   "for the full grid), not " + std::to_string(a.band));
    if (a.propagated && a.bandGiven->count())
        throw CLI::ValidationError("--propagated is a way to fill the full grid: leave out --band");
    if (!(std::isfinite(a.pad) && a.pad >= 0.0 && a.pad <= 10.0))
        throw CLI::ValidationError("--pad: a fraction of the box's size from 0 to 10, not " + std::to_string(a.pad));
    if (a.cubic && a.grid.dims == 0) throw CLI::ValidationError("--cubic takes the cells of the longest side from --dims N");
}

// "box [x0, y0, z0] to [x1, y1, z1], cells 0.1 x 0.1 x 0.1"
std::string geometry(const vds::Grid& grid) {
    const glm::vec3 cell = (grid.box.hi - grid.box.lo) / glm::vec3(grid.dims);
    char text[256];
    std::snprintf(text, sizeof text, "box [%.9g, %.9g, %.9g] to [%.9g, %.9g, %.9g], cells %.9g x %.9g x %.9g",
                  grid.box.lo.x, grid.box.lo.y, grid.box.lo.z, grid.box.hi.x, grid.box.hi.y, grid.box.hi.z, cell.x,
                  cell.y, cell.z);
    return text;
}

/// The signed distances of `grid`, a slab of x layers at a time appended to
/// `out` (a propagated grid spreads across the whole grid: one slab, held
/// whole). Returns the cells inside (negative).
std::size_t measureInSlabs(const SdfArgs& a, const vds::SignedDistance& query, const vds::Grid& grid,
                           NpySlabWriter& out) {
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

void sdf(SdfArgs& a) {
    checkArguments(a);
    outputFormat("-o", a.output, {OutputFormat::Npy}, OutputFormat::Npy);
    const auto progress = progressPrinter(a.quiet);
    const vds::TriangleMesh mesh = vds::loadMesh(a.mesh);
    checkSignedMesh(mesh, a.mesh, a.rule, a.allowOpen, "sdf");
    vds::Grid grid = gridOf(a.grid, vds::meshBounds(mesh), float(a.pad), true);
    if (a.cubic) grid = vds::cubicGrid(grid.box, a.grid.dims);
    if (a.propagated) vds::checkGrid(grid); // held whole
    NpySlabWriter out(a.output, "<f4", {grid.dims.x, grid.dims.y, grid.dims.z}, sizeof(float));
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
                 a.output.c_str(), grid.dims.x, grid.dims.y, grid.dims.z, geometry(grid).c_str(), inside,
                 a.band > 0.0 ? ("band " + std::to_string(a.band)).c_str()
                              : (a.propagated ? "full grid, propagated" : "full grid"),
                 vds::toString(a.rule), seconds);
}

} // namespace

void addSdf(CLI::App& app) {
    const auto [c, a] = addCommand<SdfArgs>(
        app, "sdf", "signed distance grid of a mesh (full or a narrow band), into a float32 .npy file",
        "  vds sdf MESH --dims N [--cubic] [--band W] -o SDF.npy [--rule RULE] [--box ...] [--pad F]\n"
        "SDF.npy: float32 of shape (NX, NY, NZ), indexed [i][j][k], the signed distance of the centre of\n"
        "cell (i, j, k), lo + (i + 1/2, j + 1/2, k + 1/2) * (hi - lo) / (NX, NY, NZ), as 'vds voxelize'\n"
        "places them: box [lo, hi] the mesh's bounds (or --box) grown by --pad times its size on every\n"
        "side. Negative exactly where 'vds voxelize' with the same rule says inside. With --band W\n"
        "(mesh units), cells farther than W from the surface hold -W or +W. With --propagated, the full\n"
        "grid as a closest-feature transform: exact within a cell diagonal of the surface, beyond it\n"
        "never below the distance and within 4 cell diagonals above it (many times faster). With --cubic,\n"
        "N cells along the box's longest side and as many cubic cells along the others as fit ('vds bake\n"
        "--distance' and vds.Grid.cubic place them so). The summary line gives the grid's box and cell size.\n"
        "SDF '-' writes the .npy to stdout, with the summary line on stderr. The grid is measured and\n"
        "written a slab of x layers at a time (at most 2^26 cells held; --propagated holds it whole).",
        sdf);
    addMesh(*c, a->mesh);
    c->add_option("-o,--output", a->output, "output .npy (written slab by slab into a temporary file, renamed into place once whole); '-': stdout")->required()->type_name("FILE");
    addGridOptions(*c, a->grid, "the grid's box instead of the mesh's bounds");
    c->add_flag("--cubic", a->cubic, "cubic cells: --dims N along the longest side, as many as fit along the others");
    c->add_option("--pad", a->pad, "grow the box by this fraction of its size on every side")->type_name("F");
    a->bandGiven = c->add_option("--band", a->band, "narrow band half-width W > 0, mesh units: farther cells hold +-W (default: the full grid)")
                       ->type_name("W")
                       ->default_str(""); // none unless given: 0 is no width
    c->add_flag("--propagated", a->propagated,
                "full grid: exact near the surface, within 4 cell diagonals beyond (a closest-feature transform)");
    addEnum(*c, "--rule", a->rule, "what is inside (negative): parity, winding, or generalized-winding (open meshes)");
    c->add_flag("--allow-open", a->allowOpen, "sign an open mesh by crossing count anyway");
    addCount(*c, "--threads", a->options.threads, "CPU threads, 0: all");
    addSlabCells(*c, a->slabCells);
}

} // namespace cli
