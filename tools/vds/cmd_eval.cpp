#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <vector>

#include <vds/error.h>
#include <vds/eval/accuracy.h>
#include <vds/mesh_io.h>

#include "cli.h"

namespace cli {

namespace {
const char* kHelp =
    "usage: vds eval MESH [options]\n"
    "\n"
    "How wrong is a sprite, and where? Bakes MESH at each resolution and\n"
    "classifies the same points with the sprite and with the exact classifier:\n"
    "uniform random points in the box grown by 10%, and points within 4 texels\n"
    "of the surface. Reports the misclassification rate, how far the wrong\n"
    "points are from the surface (in texels), bake time, memory, file size and\n"
    "query throughput; writes JSON and slice images (grey inside, white outside,\n"
    "red: sprite says inside wrongly, blue: sprite says outside wrongly).\n"
    "\n"
    "options:\n"
    "  --resolutions LIST   comma-separated (default 256,512,1024,2048)\n"
    "  --points N           uniform points (default 1000000)\n"
    "  --surface-points N   near-surface points per resolution (default 1000000)\n"
    "  --axis x|y|z         view axis (default z)\n"
    "  --rule parity|winding (default parity)\n"
    "  --method lists|peel|cpu  baker (default lists)\n"
    "  --json FILE          write the report as JSON\n"
    "  --images PREFIX      write PREFIX-<resolution>-<x|y|z>.png slices through the box centre\n"
    "  --seed N             random seed (default 1)\n"
    "  --quiet              no progress messages\n";

} // namespace

int eval(int argc, char** argv) {
    const Args args(argc, argv,
                    {"--resolutions", "--points", "--surface-points", "--axis", "--rule", "--method", "--json",
                     "--images", "--seed"},
                    {"--help", "--quiet"});
    if (args.has("--help")) {
        std::fputs(kHelp, stdout);
        return 0;
    }
    args.expectPositional(1, "one mesh file");
    const bool quiet = args.has("--quiet");
    vds::eval::EvalOptions options;
    if (args.has("--resolutions")) options.resolutions = parseResolutions(args.get("--resolutions"));
    options.uniformPoints = args.getUint("--points", 1000000);
    options.surfacePoints = args.getUint("--surface-points", 1000000);
    options.seed = args.getUint("--seed", 1);
    try {
        options.axis = vds::parseAxis(args.get("--axis", "z"));
        options.rule = vds::parseRule(args.get("--rule", "parity"));
        options.method = vds::parseBakeMethod(args.get("--method", "lists"));
    } catch (const vds::InvalidArgument& e) {
        throw UsageError(e.what());
    }
    options.imagePrefix = args.get("--images");

    const std::string& path = args.positional()[0];
    const vds::TriangleMesh mesh = vds::loadMesh(path);
    const vds::MeshReport report = vds::validateMesh(mesh);
    vds::requireUsable(report, path);
    if (!report.closed())
        throw vds::InvalidMesh(path + " is " + report.summary() +
                               ": inside is not defined, so there is no exact answer to compare with");
    const vds::eval::EvalReport r =
        vds::eval::evaluate(mesh, options, nullptr, [quiet](const std::string& s) { progress(quiet, s); });

    std::fputs(vds::eval::toTable(r).c_str(), stdout);
    if (args.has("--json")) {
        writeTextFile(args.get("--json"), vds::eval::toJson(r));
        std::printf("\nwrote %s\n", args.get("--json").c_str());
    }
    for (const auto& w : r.rows)
        for (const auto& image : w.images) std::printf("wrote %s\n", image.c_str());
    return 0;
}

} // namespace cli
