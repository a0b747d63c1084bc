// vds_scan_grid_bench: a generalized-winding occupancy grid of a messy open
// scan, the case that was slow: a bumpy sphere seen from above (its underside
// cut away) with about 1% of its triangles dropped at random, so that
// hundreds of small holes give it more than a thousand boundary edges.
//
//   vds_scan_grid_bench [--dims 256] [--threads 2] [--drop 0.01]
//
// Prints one table row: the mesh's counts (validateMesh), the grid, the wall
// time of vds::occupancy (the exact classifier's build included) and the
// rate. docs/benchmarks.md keeps the figures.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <vector>

#include <CLI/CLI.hpp>

#include <vds/error.h>
#include <vds/mesh.h>
#include <vds/mesh_check.h>
#include <vds/occupancy.h>

#include "solids.h"

namespace {

/// A hash of a position in [0, 1): which triangles a scan misses, the same every run.
double scatter(const glm::vec3& c) {
    std::uint64_t h = std::uint64_t(std::int64_t(c.x * 1e6f)) * 0x9E3779B97F4A7C15ull ^
                      std::uint64_t(std::int64_t(c.y * 1e6f)) * 0xC2B2AE3D27D4EB4Full ^
                      std::uint64_t(std::int64_t(c.z * 1e6f)) * 0x165667B19E3779F9ull;
    h = (h ^ (h >> 31)) * 0xBF58476D1CE4E5B9ull;
    return double(h >> 11) / double(std::uint64_t(1) << 53);
}

vds::TriangleMesh openScan(double drop) {
    constexpr float kCut = -0.5f; // the underside a scanner above does not see
    vds::TriangleMesh m = vds::solids::openSphere(128, 256, [&](const glm::vec3& c) {
        return c.z > kCut && scatter(c) >= drop;
    });
    for (glm::vec3& p : m.positions) // bumps, as a real surface has
        p *= 1.0f + 0.03f * std::sin(7.0f * p.x) * std::cos(5.0f * p.y + 3.0f * p.z);
    return m;
}

} // namespace

int main(int argc, char** argv) {
    CLI::App app("vds_scan_grid_bench: a generalized-winding grid of a messy open scan");
    std::uint32_t dims = 256;
    unsigned threads = 2;
    double drop = 0.01;
    app.add_option("--dims", dims, "cells along each axis of the grid over the scan's box");
    app.add_option("--threads", threads, "CPU threads (0: all)");
    app.add_option("--drop", drop, "the share of triangles the scan misses");
    CLI11_PARSE(app, argc, argv);
    try {
        const vds::TriangleMesh scan = openScan(drop);
        const vds::MeshReport report = vds::validateMesh(scan);
        vds::Grid grid; // dims^3 cells over the scan's box (as `vds voxelize --dims`)
        grid.box = report.bounds;
        grid.dims = glm::uvec3(dims);
        std::vector<std::uint8_t> cells(grid.cellCount());
        const auto start = std::chrono::steady_clock::now();
        vds::occupancy(scan, grid, cells.data(), {vds::Rule::GeneralizedWinding, threads});
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        std::size_t inside = 0;
        for (std::uint8_t c : cells) inside += c;
        std::printf("| mesh | triangles | boundary edges | grid | threads | inside | seconds | M cells/s |\n"
                    "|---|---:|---:|---|---:|---:|---:|---:|\n");
        std::printf("| open scan (%.1f%% dropped) | %zu | %zu | %ux%ux%u GWN | %u | %zu | %.2f | %.1f |\n", 100.0 * drop,
                    report.triangleCount, report.boundaryEdges, grid.dims.x, grid.dims.y, grid.dims.z, threads,
                    inside, seconds, double(cells.size()) / seconds * 1e-6);
    } catch (const vds::Error& e) {
        std::fprintf(stderr, "vds_scan_grid_bench: %s\n", e.what());
        return 1;
    }
    return 0;
}
