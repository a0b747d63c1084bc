#include <cstdio>

#include <vds/eval/accuracy.h>
#include <vds/mesh_check.h>
#include <vds/mesh_io.h>

#include "cli.h"

namespace cli {

namespace {

struct EvalArgs {
    std::string mesh, json;
    vds::eval::EvalOptions options;
    bool quiet = false;
};

void eval(EvalArgs& a) {
    const vds::TriangleMesh mesh = vds::loadMesh(a.mesh);
    const vds::MeshReport report = vds::validateMesh(mesh);
    vds::requireInsideDefined(report, a.mesh, a.options.rule, meshFlags());
    tellAboutMesh("eval", a.mesh, report, a.options.rule, meshFlags());
    const vds::eval::EvalReport r = vds::eval::evaluate(mesh, a.options, nullptr, progressPrinter(a.quiet));

    std::fputs(vds::eval::toTable(r).c_str(), stdout);
    if (!a.json.empty()) {
        writeTextFile(a.json, vds::eval::toJson(r));
        std::printf("\nwrote %s\n", a.json.c_str());
    }
    for (const auto& w : r.rows)
        for (const auto& image : w.images) std::printf("wrote %s\n", image.c_str());
}

} // namespace

void addEval(CLI::App& app) {
    const auto [c, a] = addCommand<EvalArgs>(
        app, "eval", "accuracy of sprites against the exact classifier",
        "How wrong is a sprite, and where? Bakes MESH at each resolution and classifies the same points\n"
        "with the sprite and with the exact classifier: uniform random points in the box grown by 10%,\n"
        "and points within 4 texels of the surface. Reports the misclassification rate, how far the\n"
        "wrong points are from the surface (in texels), bake time, memory, file size and query\n"
        "throughput; writes JSON and slice images (grey inside, white outside, red: sprite says inside\n"
        "wrongly, blue: sprite says outside wrongly).",
        eval);
    addMesh(*c, a->mesh);
    vds::eval::EvalOptions& o = a->options;
    addResolutions(*c, o.resolutions);
    addCount(*c, "--points", o.uniformPoints, "uniform points");
    addCount(*c, "--surface-points", o.surfacePoints, "near-surface points per resolution");
    addEnum(*c, "--axis", o.axis, "view axis");
    addEnum(*c, "--rule", o.rule, "crossings rule");
    addEnum(*c, "--method", o.method, "baker");
    c->add_option("--json", a->json, "write the report as JSON")->type_name("FILE");
    c->add_option("--images", o.imagePrefix, "write PREFIX-<resolution>-<x|y|z>.png slices through the box centre")
        ->type_name("PREFIX");
    addCount(*c, "--seed", o.seed, "random seed");
}

} // namespace cli
