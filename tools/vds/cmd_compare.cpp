#include <cstdio>

#include <vds/eval/compare.h>
#include <vds/mesh_io.h>

#include "cli.h"

namespace cli {

namespace {

struct CompareArgs {
    std::string mesh, json, chart;
    vds::eval::CompareOptions options;
    bool quiet = false;
};

void compare(CompareArgs& a) {
    a.options.progress = progressPrinter(a.quiet);
    const vds::TriangleMesh mesh = vds::loadMesh(a.mesh);
    a.options.meshName = mesh.name;
    a.options.meshFlags = meshFlags();
    const vds::eval::CompareResult result = vds::eval::compare(mesh, a.options);
    std::fputs(result.table().c_str(), stdout);
    for (const auto& [path, text] : {std::pair{a.json, result.json()}, std::pair{a.chart, errorChart(result)}})
        if (!path.empty()) {
            writeTextFile(path, text);
            std::printf("wrote %s\n", path.c_str());
        }
}

} // namespace

void addCompare(CLI::App& app) {
    const auto [c, a] = addCommand<CompareArgs>(
        app, "compare", "the VDS against slicemaps and solid voxels: error, memory, speed",
        "Compares the VDS (parity and winding) with slicemaps (uniform and local) and solid voxels\n"
        "(raster and compute) on the same points, at equal resolution and at equal memory:\n"
        "misclassification rate against the exact classifier, worst error distance in cells, build\n"
        "time, query throughput, memory. Prints a table; writes JSON and an SVG chart of error\n"
        "against memory. --rule generalized-winding holds every row to the exact generalized winding\n"
        "number, adds a sprite/generalized-winding row and accepts open meshes (the VDS only: slicemaps and solid voxels\n"
        "need a closed mesh).",
        compare);
    addMesh(*c, a->mesh);
    vds::eval::CompareOptions& o = a->options;
    addResolutions(*c, o.resolutions, vds::eval::kMaxCompareResolution);
    addCount(*c, "--points", o.uniformPoints, "uniform points in the padded box");
    addCount(*c, "--surface-points", o.surfacePoints, "points near the surface");
    c->add_option("--json", a->json, "write the result as JSON")->type_name("FILE");
    c->add_option("--chart", a->chart, "write the error-against-memory chart (SVG)")->type_name("FILE.svg");
    addEnum(*c, "--rule", o.rule,
            "generalized-winding: every row against the exact generalized winding number (open meshes too); "
            "parity or winding: the default comparison");
    addCount(*c, "--seed", o.seed, "random seed");
}

} // namespace cli
