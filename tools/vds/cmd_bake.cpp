#include <chrono>
#include <cstdio>

#include <vds/bake.h>
#include <vds/error.h>
#include <vds/mesh_io.h>
#include <vds/vds_file.h>

#include "cli.h"

namespace cli {

namespace {
const char* kHelp =
    "usage: vds bake MESH -o OUT.vds [options]\n"
    "\n"
    "Bakes a closed triangle mesh (OBJ, PLY, STL, OFF) into a volumetric depth\n"
    "sprite. An open or non-manifold mesh is baked with a warning, and the file\n"
    "records that its answers are a surface's, not a solid's.\n"
    "\n"
    "options:\n"
    "  -o FILE             output sprite (written whole or not at all)\n"
    "  --resolution N      texels on the longer side of the view, 1..16384 (default 1024)\n"
    "  --axis x|y|z|auto   view direction (default z); auto picks the axis with the fewest layers\n"
    "  --method lists|peel|cpu\n"
    "                      fragment lists (default), depth peeling, or exact CPU ray casting\n"
    "  --quiet             no progress messages\n";
}

int bake(int argc, char** argv) {
    const Args args(argc, argv, {"-o", "--resolution", "--axis", "--method"}, {"--help", "--quiet"});
    if (args.has("--help")) {
        std::fputs(kHelp, stdout);
        return 0;
    }
    args.expectPositional(1, "one mesh file");
    if (!args.has("-o")) throw UsageError("missing -o OUT.vds");
    const bool quiet = args.has("--quiet");
    vds::BakeOptions options;
    options.resolution = args.getUint("--resolution", 1024);
    try {
        if (args.get("--axis") != "auto") options.axis = vds::parseAxis(args.get("--axis", "z"));
        options.method = vds::parseBakeMethod(args.get("--method", "lists"));
    } catch (const vds::InvalidArgument& e) {
        throw UsageError(e.what());
    }
    if (options.resolution == 0 || options.resolution > vds::kMaxResolution)
        throw UsageError("--resolution must be 1.." + std::to_string(vds::kMaxResolution));

    const std::string& path = args.positional()[0];
    const auto start = std::chrono::steady_clock::now();
    const vds::TriangleMesh mesh = vds::loadMesh(path);
    options.sourceName = mesh.name;
    const vds::MeshReport report = vds::validateMesh(mesh);
    vds::requireUsable(report, path);
    if (args.get("--axis") == "auto") {
        options.axis = vds::chooseViewAxis(mesh);
        progress(quiet, std::string("axis auto: ") + vds::toString(options.axis) + " has the fewest layers");
    }
    if (!report.closed())
        std::fprintf(stderr, "vds bake: warning: %s is %s; the sprite answers for a surface, not a solid\n",
                     path.c_str(), report.summary().c_str());
    options.progress = [quiet](const std::string& what) { progress(quiet, what); };
    progress(quiet, "baking " + path + " (" + std::to_string(mesh.triangles.size()) + " triangles) at " +
                        std::to_string(options.resolution) + " along " + vds::toString(options.axis) + " with " +
                        vds::toString(options.method));
    const vds::Sprite sprite = vds::bake(mesh, options);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    vds::writeSprite(sprite, args.get("-o"));
    std::printf("wrote %s: %ux%u texels, depth complexity %u, %zu crossings, baked in %.2f s\n",
                args.get("-o").c_str(), sprite.width(), sprite.height(), sprite.depthComplexity,
                sprite.crossings.size(), seconds);
    return 0;
}

} // namespace cli
