// vds_axis_bench: what a bake spends before its own phases, against the
// bake itself: the mesh's validation and the auto axis's layer count
// (chooseViewAxis), apart and in one call, then the CPU bake along the
// chosen axis, alternately in one run, best of --runs each (the machine's
// load moves them alike).
//   vds_axis_bench [--resolution 2048] [--runs 5] [--sphere] [--no-bake] [MESH ...]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include <vds/bake.h>
#include <vds/mesh.h>
#include <vds/mesh_check.h>
#include <vds/mesh_io.h>
#include "solids.h"

namespace {

template <class F>
double seconds(const F& f) {
    const auto start = std::chrono::steady_clock::now();
    f();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The floor of any count that looks at every triangle along every axis: one
// thread reads each triangle's vertices and finds its projected box and
// orientation along x, y and z (what the count does before its first row).
double projectionPass(const vds::TriangleMesh& mesh) {
    double sum = 0.0;
    for (int axis = 0; axis < 3; ++axis) {
        const int s = (axis + 1) % 3, t = (axis + 2) % 3;
        for (const auto& tri : mesh.triangles) {
            const glm::vec3 &a = mesh.positions[tri[0]], &b = mesh.positions[tri[1]], &c = mesh.positions[tri[2]];
            const float area = (b[s] - a[s]) * (c[t] - a[t]) - (b[t] - a[t]) * (c[s] - a[s]);
            sum += double(std::max({a[s], b[s], c[s]}) - std::min({a[s], b[s], c[s]})) +
                   double(std::max({a[t], b[t], c[t]}) - std::min({a[t], b[t], c[t]})) + (area > 0.0f);
        }
    }
    return sum;
}

void measure(const vds::TriangleMesh& mesh, std::uint32_t resolution, int runs, bool withBake) {
    double validate = 1e30, axis = 1e30, both = 1e30, bake = withBake ? 1e30 : 0.0, pass = 1e30, sink = 0.0;
    vds::AxisChoice choice;
    for (int run = 0; run < runs; ++run) {
        vds::MeshReport report;
        validate = std::min(validate, seconds([&] { report = vds::validateMesh(mesh); }));
        axis = std::min(axis, seconds([&] { choice = vds::chooseViewAxis(mesh, report, resolution); }));
        // One call validating and counting, as the bakes do: validation's
        // grouping of edges serves the count too.
        both = std::min(both, seconds([&] { choice = vds::chooseViewAxis(mesh, resolution); }));
        pass = std::min(pass, seconds([&] { sink += projectionPass(mesh); }));
        vds::BakeOptions o;
        o.resolution = resolution;
        o.axis = choice.axis;
        if (withBake) bake = std::min(bake, seconds([&] { (void)vds::bakeCpu(mesh, o); }));
    }
    std::printf("| %s | %zu | %u | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f%% | %s |\n", mesh.name.c_str(),
                mesh.triangles.size(), resolution, 1e3 * validate, 1e3 * axis, 1e3 * both, 1e3 * pass + 0.0 * sink,
                1e3 * bake, 100.0 * both / (both + bake), choice.summary().c_str());
}

} // namespace

int main(int argc, char** argv) {
    CLI::App app{"vds_axis_bench: validation and the auto axis's count against the CPU bake"};
    std::uint32_t resolution = 2048;
    int runs = 5;
    bool sphere = false, noBake = false;
    std::vector<std::string> files;
    app.add_option("--resolution", resolution, "bake resolution (default 2048)");
    app.add_option("--runs", runs, "runs of each step; the best is reported (default 5)");
    app.add_flag("--sphere", sphere, "add a generated UV sphere of 1,002,000 triangles");
    app.add_flag("--no-bake", noBake, "time validation and the count only (the bake column reads 0)");
    app.add_option("meshes", files, "mesh files");
    CLI11_PARSE(app, argc, argv);
    std::puts("| mesh | triangles | resolution | validation ms | axis count ms | both in one call ms | one projection pass ms | "
              "CPU bake ms | before the bake | choice |");
    std::puts("|---|---:|---:|---:|---:|---:|---:|---:|---:|---|");
    for (const std::string& file : files) measure(vds::loadMesh(file), resolution, runs, !noBake);
    if (sphere) {
        vds::TriangleMesh mesh = vds::solids::sphere({0, 0, 0}, 1.0f, 1002).mesh;
        mesh.name = "UV sphere (generated)";
        measure(mesh, resolution, runs, !noBake);
    }
    return 0;
}
