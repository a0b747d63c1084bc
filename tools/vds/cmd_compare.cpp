#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <vector>

#include <vds/error.h>
#include <vds/mesh_io.h>
#include <vds/sprite.h>
#include <vds/eval/compare.h>

#include "cli.h"

namespace cli {

namespace {
const char* kHelp =
    "usage: vds compare MESH [options]\n"
    "\n"
    "Compares the VDS (parity and winding) with slicemaps (uniform and local)\n"
    "and solid voxels (raster and compute) on the same points, at equal\n"
    "resolution and at equal memory: misclassification rate against the exact\n"
    "classifier, worst error distance in cells, build time, query throughput,\n"
    "memory. Prints a table; writes JSON and an SVG chart of error against memory.\n"
    "\n"
    "options:\n"
    "  --resolutions LIST   comma-separated (default 32,64,128)\n"
    "  --points N           uniform points in the padded box (default 100000)\n"
    "  --surface-points N   points near the surface (default 50000)\n"
    "  --json FILE          write the result as JSON\n"
    "  --chart FILE.svg     write the error-against-memory chart (SVG)\n"
    "  --seed N             random seed (default 1)\n"
    "  --quiet              no progress messages\n";

} // namespace

int compare(int argc, char** argv) {
    const Args args(argc, argv, {"--resolutions", "--points", "--surface-points", "--json", "--chart", "--seed"},
                    {"--help", "--quiet"});
    if (args.has("--help")) {
        std::fputs(kHelp, stdout);
        return 0;
    }
    args.expectPositional(1, "one mesh file");
    const bool quiet = args.has("--quiet");
    vds::eval::CompareOptions options;
    if (args.has("--resolutions")) options.resolutions = parseResolutions(args.get("--resolutions"));
    options.uniformPoints = args.getUint("--points", 100000);
    options.surfacePoints = args.getUint("--surface-points", 50000);
    options.seed = args.getUint("--seed", 1);
    options.progress = [quiet](const std::string& s) { progress(quiet, s); };
    const std::string& path = args.positional()[0];
    const vds::TriangleMesh mesh = vds::loadMesh(path);
    options.meshName = mesh.name;
    const vds::eval::CompareResult result = vds::eval::compare(mesh, options);
    std::fputs(result.table().c_str(), stdout);
    if (args.has("--json")) {
        writeTextFile(args.get("--json"), result.json());
        std::printf("wrote %s\n", args.get("--json").c_str());
    }
    if (args.has("--chart")) {
        writeTextFile(args.get("--chart"), vds::eval::errorChart(result));
        std::printf("wrote %s\n", args.get("--chart").c_str());
    }
    return 0;
}

} // namespace cli
