#include <chrono>
#include <cstdio>
#include <vector>

#include <vds/bake.h>
#include <vds/exact.h>
#include <vds/gl_context.h>
#include <vds/gpu_sprite.h>
#include <vds/mesh_io.h>
#include <vds/vds_file.h>
#include <vds/voxel/representation.h>

#include "cli.h"

namespace cli {

namespace {

// --with's default resolution for the voxel representations: their memory
// grows with its cube, a sprite's with its square.
constexpr std::uint32_t kVoxelResolution = 256;

struct ClassifyArgs {
    std::vector<std::string> files; // [SPRITE] POINTS
    std::string output, mesh, with = "vds";
    std::uint32_t resolution = 0; // 0: not given (CLI11 refuses 0 given)
    vds::ClassifyOptions options;
    bool gpu = false, exact = false, allowOpen = false, quiet = false;
    const CLI::Option* withGiven = nullptr;
};

void writeLabels(const std::string& path, const std::vector<std::uint8_t>& labels) {
    std::string text(labels.size() * 2, '\n');
    for (std::size_t i = 0; i < labels.size(); ++i) text[2 * i] = labels[i] ? '1' : '0';
    writeTextFile(path, text);
}

// What CLI11's option relations cannot say.
void checkCombination(ClassifyArgs& a) {
    const bool fromMesh = !a.mesh.empty();
    if (a.files.size() != (fromMesh ? 1u : 2u))
        throw CLI::ValidationError(fromMesh ? "expected one points file (with --mesh)"
                                            : "expected a sprite file and a points file");
    if (fromMesh && !a.exact && !a.withGiven->count())
        throw CLI::ValidationError("--mesh needs --exact or --with REPRESENTATION");
    if (a.with != "vds" && a.options.rule == vds::Rule::Winding)
        throw CLI::ValidationError("--rule winding needs a sprite (--with vds)");
    if (a.resolution == 0) a.resolution = a.with == "vds" ? vds::BakeOptions{}.resolution : kVoxelResolution;
}

void classify(ClassifyArgs& a) {
    checkCombination(a);
    const auto progress = progressPrinter(a.quiet);
    const std::string& pointsPath = a.files.back();
    const std::vector<glm::vec3> points = vds::loadPoints(pointsPath);
    progress("read " + std::to_string(points.size()) + " points from " + pointsPath);
    std::vector<std::uint8_t> labels(points.size());
    // Only the classification is timed; loading, baking and building are not.
    std::chrono::steady_clock::time_point start;
    auto startClock = [&start] { start = std::chrono::steady_clock::now(); };
    std::string method;
    vds::TriangleMesh mesh;
    if (!a.mesh.empty()) mesh = vds::loadMesh(a.mesh);

    if (a.exact) {
        const vds::MeshReport report = vds::validateMesh(mesh);
        vds::requireUsable(report, a.mesh);
        if (!report.closed()) {
            if (!a.allowOpen)
                throw vds::InvalidMesh(a.mesh + " is " + report.summary() +
                                       ": inside is not defined (--allow-open classifies by crossing count anyway)");
            std::fprintf(stderr, "vds classify: warning: %s is %s; inside is not well defined\n", a.mesh.c_str(),
                         report.summary().c_str());
        }
        const vds::ExactClassifier exact(mesh);
        startClock();
        exact.classify(points.data(), points.size(), labels.data(), a.options);
        method = "exact";
    } else if (a.with != "vds") {
        vds::GlContext gl;
        vds::voxel::ModelOptions modelOptions;
        modelOptions.resolution = a.resolution;
        const vds::voxel::Model model =
            vds::voxel::buildModel(mesh, vds::voxel::parseRepresentation(a.with), modelOptions, &gl);
        progress("built " + model.summary());
        startClock();
        if (a.gpu) {
            vds::voxel::classifyOnGpu(gl, model, points.data(), points.size(), labels.data());
            method = a.with + " on the GPU (" + gl.info().renderer + ")";
        } else {
            model.classify(points.data(), points.size(), labels.data(), a.options.threads);
            method = a.with + " on the CPU";
        }
    } else {
        vds::Sprite sprite;
        if (!a.mesh.empty()) {
            vds::BakeOptions bakeOptions;
            bakeOptions.resolution = a.resolution;
            bakeOptions.sourceName = mesh.name;
            sprite = vds::bake(mesh, bakeOptions);
        } else {
            sprite = vds::readSprite(a.files.front());
        }
        if (sprite.status == vds::SolidStatus::Open)
            std::fprintf(stderr, "vds classify: warning: the sprite was baked from an open mesh (%s)\n",
                         sprite.validation.c_str());
        if (a.gpu) {
            vds::GlContext gl;
            const vds::GpuSprite gpu(sprite);
            const vds::GpuClassifier classifier(gl);
            startClock();
            classifier.classify(gpu, points.data(), points.size(), labels.data(), a.options.rule);
            method = "GPU (" + gl.info().renderer + ")";
        } else {
            startClock();
            vds::classify(sprite, points.data(), points.size(), labels.data(), a.options);
            method = "CPU";
        }
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    writeLabels(a.output, labels);
    std::size_t inside = 0;
    for (auto l : labels) inside += l;
    std::printf("wrote %s: %zu points, %zu inside, %s, %s rule, classified in %.3f s\n", a.output.c_str(),
                points.size(), inside, method.c_str(), vds::toString(a.options.rule), seconds);
}

} // namespace

void addClassify(CLI::App& app) {
    const auto [c, a] = addCommand<ClassifyArgs>(
        app, "classify", "label points 1 inside / 0 outside",
        "  vds classify SPRITE.vds POINTS -o LABELS.txt\n"
        "  vds classify --exact --mesh MESH POINTS -o LABELS.txt\n"
        "  vds classify --mesh MESH --with REPRESENTATION POINTS -o LABELS.txt\n"
        "Labels each point 1 (inside) or 0 (outside), one line per point, in the order given. POINTS\n"
        "is a text file of lines 'x y z' in the mesh's coordinates ('#' comments and blank lines\n"
        "skipped) or a PLY file's vertices. Points outside the sprite's box are outside. --with builds\n"
        "the representation from the mesh in memory first: vds (a sprite), slicemap, slicemap-local\n"
        "(front/back slicemap pair, uniform or local slicing), solid, solid-compute (solid voxels by\n"
        "rasterization or in compute); see docs/voxel.md.",
        classify);
    c->add_option("FILES", a->files, "a sprite file and a points file; with --mesh, the points file")
        ->required()
        ->option_text("[SPRITE.vds] POINTS");
    c->add_option("-o,--output", a->output, "output labels (written whole or not at all)")
        ->required()
        ->type_name("FILE");
    addEnum(*c, "--rule", a->options.rule, "crossings rule: the paper's parity or non-zero winding");
    c->add_flag("--gpu", a->gpu, "classify with the GL compute shader instead of the CPU");
    addCount(*c, "--threads", a->options.threads, "CPU threads, 0: all");
    CLI::Option* mesh =
        c->add_option("--mesh", a->mesh, "classify against a mesh: --exact, or --with")->type_name("MESH");
    CLI::Option* exact = c->add_flag("--exact", a->exact, "exact classification on the mesh's triangles")->needs(mesh);
    c->add_flag("--allow-open", a->allowOpen, "let --exact classify an open mesh by crossing count");
    std::vector<std::string> with = vds::enumNames<vds::voxel::Representation>();
    with.insert(with.begin(), "vds");
    a->withGiven =
        addChoice(*c, "--with", a->with, with, "build this from the mesh first")->needs(mesh)->excludes(exact);
    addResolution(*c, a->resolution, "texels or voxels on the box's longest side for --with")
        ->default_str(std::to_string(vds::BakeOptions{}.resolution) + " for vds, " + std::to_string(kVoxelResolution) +
                      " for the others");
}

} // namespace cli
