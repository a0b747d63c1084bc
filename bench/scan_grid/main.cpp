// vds_scan_grid_bench: generalized-winding grids of open scans, the case
// users met as slow: real scans (bench/fetch-meshes.sh --scans) or, without
// files, a generated one (a bumpy sphere seen from above, its underside cut
// away, about 1% of its triangles dropped at random).
//
//   vds_scan_grid_bench [--dims 256] [--threads 2] [--band 3] [--drop 0.01] [mesh ...]
//
// Prints a table row a mesh: its counts (validateMesh); the wall time of the
// occupancy grid over its box as `vds voxelize --dims N --rule
// generalized-winding` takes it (the exact classifier built once, the grid
// swept in 16 slabs of x layers), the classifier's build apart; and of the
// ±band-cell signed-distance band as `vds sdf --band` (the same slabs, its
// classifier and hierarchy built once) beside the full grid as `vds sdf
// --propagated` (builds included). docs/benchmarks.md keeps the figures.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include <vds/distance.h>
#include <vds/error.h>
#include <vds/exact.h>
#include <vds/mesh.h>
#include <vds/mesh_check.h>
#include <vds/mesh_io.h>

#include "solids.h"

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

/// A hash of a position in [0, 1): which triangles a scan misses, the same every run.
double scatter(const glm::vec3& c) {
    std::uint64_t h = std::uint64_t(std::int64_t(c.x * 1e6f)) * 0x9E3779B97F4A7C15ull ^
                      std::uint64_t(std::int64_t(c.y * 1e6f)) * 0xC2B2AE3D27D4EB4Full ^
                      std::uint64_t(std::int64_t(c.z * 1e6f)) * 0x165667B19E3779F9ull;
    h = (h ^ (h >> 31)) * 0xBF58476D1CE4E5B9ull;
    return double(h >> 11) / double(std::uint64_t(1) << 53);
}

vds::TriangleMesh generatedScan(double drop) {
    constexpr float kCut = -0.5f; // the underside a scanner above does not see
    vds::TriangleMesh m = vds::solids::openSphere(128, 256, [&](const glm::vec3& c) {
        return c.z > kCut && scatter(c) >= drop;
    });
    for (glm::vec3& p : m.positions) // bumps, as a real surface has
        p *= 1.0f + 0.03f * std::sin(7.0f * p.x) * std::cos(5.0f * p.y + 3.0f * p.z);
    return m;
}

/// Slabs of x layers, as the CLI sweeps a grid (tools/vds: 16 for progress).
constexpr std::uint32_t kSlabs = 16;

/// `fill(slab, cells)` over `grid` a slab of x layers at a time.
template <class Fill, class Cell>
void inSlabs(const vds::Grid& grid, std::vector<Cell>& cells, const Fill& fill) {
    const std::uint32_t slab = std::max<std::uint32_t>(1, (grid.dims.x + kSlabs - 1) / kSlabs);
    const std::size_t layer = std::size_t(grid.dims.y) * grid.dims.z;
    for (std::uint32_t i0 = 0; i0 < grid.dims.x; i0 += slab) {
        const std::uint32_t i1 = std::min(grid.dims.x, i0 + slab);
        fill(grid.slabX(i0, i1), cells.data() + i0 * layer);
    }
}

struct Settings {
    std::uint32_t dims = 256;
    unsigned threads = 2;
    double band = 3.0;
};

void measure(const std::string& name, const vds::TriangleMesh& mesh, const Settings& s) {
    const vds::MeshReport report = vds::validateMesh(mesh);
    vds::Grid grid; // dims^3 cells over the mesh's box (as `vds voxelize --dims`)
    grid.box = report.bounds;
    grid.dims = glm::uvec3(s.dims);
    const vds::ClassifyOptions options{vds::Rule::GeneralizedWinding, s.threads};
    std::vector<std::uint8_t> cells(grid.cellCount());
    Clock::time_point start = Clock::now();
    const vds::ExactClassifier exact(mesh);
    const double build = secondsSince(start);
    start = Clock::now();
    inSlabs(grid, cells, [&](const vds::Grid& g, std::uint8_t* out) { exact.occupancy(g, out, options); });
    const double sweep = secondsSince(start);
    std::size_t inside = 0;
    for (std::uint8_t c : cells) inside += c;
    std::vector<float> distances(grid.cellCount());
    const glm::vec3 cell = (grid.box.hi - grid.box.lo) / glm::vec3(grid.dims);
    vds::DistanceGridOptions band;
    band.threads = s.threads;
    band.band = s.band * double(std::max({cell.x, cell.y, cell.z}));
    start = Clock::now();
    const vds::SignedDistance distance(mesh, vds::Rule::GeneralizedWinding);
    inSlabs(grid, distances, [&](const vds::Grid& g, float* out) { distance.grid(g, out, band); });
    const double banded = secondsSince(start);
    vds::DistanceGridOptions full; // the whole grid (as `vds sdf --propagated`): one call, held whole
    full.threads = s.threads;
    full.far = vds::FarCells::Propagated;
    start = Clock::now();
    const vds::SignedDistance again(mesh, vds::Rule::GeneralizedWinding);
    again.grid(grid, distances.data(), full);
    const double whole = secondsSince(start);
    std::printf("| %s | %zu | %zu | %zu | %u³ | %u | %zu | %.2f + %.2f = %.2f | %.1f | %.2f | %.2f | %.2f |\n",
                name.c_str(), report.triangleCount, report.boundaryEdges, report.nonManifoldEdges, s.dims, s.threads,
                inside, build, sweep, build + sweep, double(cells.size()) / (build + sweep) * 1e-6, banded, whole,
                banded / whole);
    std::fflush(stdout);
}

} // namespace

int main(int argc, char** argv) {
    CLI::App app("vds_scan_grid_bench: generalized-winding grids of open scans");
    Settings s;
    double drop = 0.01;
    std::vector<std::string> meshes;
    app.add_option("--dims", s.dims, "cells along each axis of the grid over the scan's box");
    app.add_option("--threads", s.threads, "CPU threads (0: all)");
    app.add_option("--band", s.band, "the band's half-width in cells (of the longest cell side)");
    app.add_option("--drop", drop, "the share of triangles the generated scan misses (no mesh files)");
    app.add_option("meshes", meshes, "mesh files (bench/fetch-meshes.sh --scans); none: the generated scan");
    CLI11_PARSE(app, argc, argv);
    std::printf("| mesh | triangles | boundary edges | non-manifold edges | grid | threads | inside | GWN occupancy: "
                "build + sweep = s | M cells/s | ±%g-cell SDF band, s | full SDF grid (propagated), s | band / full |\n"
                "|---|---:|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|\n", s.band);
    try {
        if (meshes.empty()) measure("generated scan (" + std::to_string(drop) + " dropped)", generatedScan(drop), s);
        for (const std::string& path : meshes)
            measure(path.substr(path.find_last_of('/') + 1), vds::loadMesh(path), s);
    } catch (const vds::Error& e) {
        std::fprintf(stderr, "vds_scan_grid_bench: %s\n", e.what());
        return 1;
    }
    return 0;
}
