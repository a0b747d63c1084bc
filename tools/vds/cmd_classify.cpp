#include <chrono>
#include <cstdio>
#include <memory>
#include <vector>

#include <vds/bake.h>
#include <vds/error.h>
#include <vds/exact.h>
#include <vds/gl_context.h>
#include <vds/gpu_sprite.h>
#include <vds/mesh_io.h>
#include <vds/vds_file.h>
#include <vds/voxel/representation.h>

#include "cli.h"

namespace cli {

namespace {
const char* kHelp =
    "usage: vds classify SPRITE.vds POINTS -o LABELS.txt [options]\n"
    "       vds classify --exact --mesh MESH POINTS -o LABELS.txt [options]\n"
    "       vds classify --mesh MESH --with REPRESENTATION --resolution N POINTS -o LABELS.txt [options]\n"
    "\n"
    "Labels each point 1 (inside) or 0 (outside), one line per point, in the\n"
    "order given. POINTS is a text file of lines 'x y z' in the mesh's\n"
    "coordinates ('#' comments and blank lines skipped) or a PLY file's vertices.\n"
    "Points outside the sprite's box are outside.\n"
    "\n"
    "options:\n"
    "  -o FILE               output labels (written whole or not at all)\n"
    "  --rule parity|winding crossings rule: the paper's parity (default) or non-zero winding\n"
    "  --gpu                 classify with the GL compute shader instead of the CPU\n"
    "  --threads N           CPU threads (default: all)\n"
    "  --exact               exact classification on the mesh's triangles (needs --mesh);\n"
    "                        an open mesh is refused unless --allow-open is given\n"
    "  --mesh MESH           classify against a mesh: --exact, or --with REPRESENTATION\n"
    "  --with REPRESENTATION build it from the mesh in memory first, at --resolution:\n"
    "                        vds (a sprite), slicemap, slicemap-local (front/back slicemap pair,\n"
    "                        uniform or local slicing), solid, solid-compute (solid voxels by\n"
    "                        rasterization or in compute); see docs/voxel.md\n"
    "  --resolution N        texels or voxels on the box's longest side for --with\n"
    "                        (default 1024 for vds, 256 for the others)\n"
    "  --quiet               no progress messages\n";

void writeLabels(const std::string& path, const std::vector<std::uint8_t>& labels) {
    std::string text(labels.size() * 2, '\n');
    for (std::size_t i = 0; i < labels.size(); ++i) text[2 * i] = labels[i] ? '1' : '0';
    writeTextFile(path, text);
}
} // namespace

int classify(int argc, char** argv) {
    const Args args(argc, argv, {"-o", "--rule", "--threads", "--mesh", "--with", "--resolution"},
                    {"--help", "--gpu", "--exact", "--quiet", "--allow-open"});
    if (args.has("--help")) {
        std::fputs(kHelp, stdout);
        return 0;
    }
    const bool quiet = args.has("--quiet");
    const bool fromMesh = args.has("--mesh");
    if (fromMesh) args.expectPositional(1, "one points file (with --mesh)");
    else args.expectPositional(2, "a sprite file and a points file");
    if (!args.has("-o")) throw UsageError("missing -o LABELS.txt");
    if (args.has("--exact") && !fromMesh) throw UsageError("--exact needs --mesh MESH");
    if (fromMesh && !args.has("--exact") && !args.has("--with"))
        throw UsageError("--mesh needs --exact or --with REPRESENTATION");
    vds::ClassifyOptions options;
    try {
        options.rule = vds::parseRule(args.get("--rule", "parity"));
    } catch (const vds::InvalidArgument& e) {
        throw UsageError(e.what());
    }
    options.threads = args.getUint("--threads", 0);
    const std::string with = args.get("--with", "vds");
    vds::voxel::Representation representation{};
    if (with != "vds") {
        try {
            representation = vds::voxel::parseRepresentation(with);
        } catch (const vds::InvalidArgument& e) {
            throw UsageError(std::string(e.what()) + " (or vds)");
        }
    }
    const std::uint32_t resolution = args.getUint("--resolution", with == "vds" ? 1024 : 256);
    if (resolution == 0 || resolution > vds::kMaxResolution)
        throw UsageError("--resolution must be 1.." + std::to_string(vds::kMaxResolution));

    const std::string pointsPath = args.positional().back();
    const std::vector<glm::vec3> points = vds::loadPoints(pointsPath);
    progress(quiet, "read " + std::to_string(points.size()) + " points from " + pointsPath);
    std::vector<std::uint8_t> labels(points.size());
    // Only the classification is timed; loading, baking and building are not.
    std::chrono::steady_clock::time_point start;
    auto startClock = [&start] { start = std::chrono::steady_clock::now(); };
    std::string method;

    if (args.has("--exact")) {
        const vds::TriangleMesh mesh = vds::loadMesh(args.get("--mesh"));
        const vds::MeshReport report = vds::validateMesh(mesh);
        vds::requireUsable(report, args.get("--mesh"));
        if (!report.closed()) {
            if (!args.has("--allow-open"))
                throw vds::InvalidMesh(args.get("--mesh") + " is " + report.summary() +
                                       ": inside is not defined (--allow-open classifies by crossing count anyway)");
            std::fprintf(stderr, "vds classify: warning: %s is %s; inside is not well defined\n",
                         args.get("--mesh").c_str(), report.summary().c_str());
        }
        const vds::ExactClassifier exact(mesh);
        startClock();
        exact.classify(points.data(), points.size(), labels.data(), options);
        method = "exact";
    } else if (with != "vds") {
        if (options.rule == vds::Rule::Winding) throw UsageError("--rule winding needs a sprite (--with vds)");
        const vds::TriangleMesh mesh = vds::loadMesh(args.get("--mesh"));
        vds::GlContext gl;
        vds::voxel::ModelOptions modelOptions;
        modelOptions.resolution = resolution;
        const vds::voxel::Model model = vds::voxel::buildModel(mesh, representation, modelOptions, &gl);
        progress(quiet, "built " + model.summary());
        startClock();
        if (args.has("--gpu")) {
            vds::voxel::classifyOnGpu(gl, model, points.data(), points.size(), labels.data());
            method = with + " on the GPU (" + gl.info().renderer + ")";
        } else {
            model.classify(points.data(), points.size(), labels.data(), options.threads);
            method = with + " on the CPU";
        }
    } else {
        vds::Sprite sprite;
        if (fromMesh) {
            const vds::TriangleMesh mesh = vds::loadMesh(args.get("--mesh"));
            vds::BakeOptions bakeOptions;
            bakeOptions.resolution = resolution;
            bakeOptions.sourceName = mesh.name;
            sprite = vds::bake(mesh, bakeOptions);
        } else {
            sprite = vds::readSprite(args.positional()[0]);
        }
        if (sprite.status == vds::SolidStatus::Open)
            std::fprintf(stderr, "vds classify: warning: the sprite was baked from an open mesh (%s)\n",
                         sprite.validation.c_str());
        if (args.has("--gpu")) {
            vds::GlContext gl;
            const vds::GpuSprite gpu(sprite);
            vds::GpuClassifier classifier(gl);
            startClock();
            classifier.classify(gpu, points.data(), points.size(), labels.data(), options.rule);
            method = "GPU (" + gl.info().renderer + ")";
        } else {
            startClock();
            vds::classify(sprite, points.data(), points.size(), labels.data(), options);
            method = "CPU";
        }
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    writeLabels(args.get("-o"), labels);
    std::size_t inside = 0;
    for (auto l : labels) inside += l;
    std::printf("wrote %s: %zu points, %zu inside, %s, %s rule, classified in %.3f s\n", args.get("-o").c_str(), points.size(),
                inside, method.c_str(), vds::toString(options.rule), seconds);
    return 0;
}

} // namespace cli
