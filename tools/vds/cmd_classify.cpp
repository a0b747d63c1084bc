#include <algorithm>
#include <chrono>
#include <cstdio>
#include <vector>

#include <vds/bake.h>
#include <vds/certified.h>
#include <vds/exact.h>
#include <vds/gl/context.h>
#include <vds/gl/sprite.h>
#include <vds/mesh_io.h>
#include <vds/npy.h>
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
    std::string output, mesh, with = "vds", outputFormat = "auto";
    std::uint32_t resolution = 0; // 0: not given (CLI11 refuses 0 given)
    vds::ClassifyOptions options;
    bool gpu = false, exact = false, certified = false, allowOpen = false, quiet = false;
    const CLI::Option* withGiven = nullptr;
};

bool endsWith(const std::string& s, const std::string& tail) {
    return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

// "-": standard input or output.
constexpr const char* kStdio = "-";

std::vector<char> readStdin() {
    std::vector<char> bytes;
    char buffer[1 << 16];
    std::size_t n;
    while ((n = std::fread(buffer, 1, sizeof buffer, stdin)) > 0) bytes.insert(bytes.end(), buffer, buffer + n);
    if (std::ferror(stdin)) throw vds::IoError("<stdin>: cannot read");
    return bytes;
}

bool startsWith(const std::vector<char>& bytes, const char* magic, std::size_t size) {
    return bytes.size() >= size && std::equal(magic, magic + size, bytes.begin());
}

// A .npy file (N x 3 float32 or float64) or what vds::loadPoints reads; from
// stdin ("-") any of these, told apart by their first bytes.
std::vector<glm::vec3> readPoints(const std::string& path) {
    if (path == kStdio) {
        const std::vector<char> bytes = readStdin();
        if (startsWith(bytes, "\x93NUMPY", 6)) return vds::npyPoints(vds::parseNpy(bytes.data(), bytes.size(), "<stdin>"), "<stdin>");
        const bool ply = startsWith(bytes, "ply\n", 4) || startsWith(bytes, "ply\r\n", 5);
        return vds::parsePoints(bytes.data(), bytes.size(), ply ? vds::PointFormat::Ply : vds::PointFormat::Text, "<stdin>");
    }
    if (endsWith(path, ".npy")) return vds::npyPoints(vds::readNpy(path), path);
    return vds::loadPoints(path);
}

void writeStdout(const std::string& bytes) {
    if (std::fwrite(bytes.data(), 1, bytes.size(), stdout) != bytes.size() || std::fflush(stdout) != 0)
        throw vds::IoError("<stdout>: cannot write");
}

// Labels as a boolean .npy array, or one "0"/"1" line per point; to a file
// (written atomically) or to stdout ("-"). `format` "auto": .npy by the name.
void writeLabels(const std::string& path, const std::string& format, const std::vector<std::uint8_t>& labels) {
    const bool npy = format == "npy" || (format == "auto" && endsWith(path, ".npy"));
    if (npy && path != kStdio) {
        vds::writeNpy(path, "|b1", {labels.size()}, labels.data(), labels.size());
        return;
    }
    if (npy) {
        writeStdout(vds::npyHeader("|b1", {labels.size()}) + std::string(labels.begin(), labels.end()));
        return;
    }
    std::string text(labels.size() * 2, '\n');
    for (std::size_t i = 0; i < labels.size(); ++i) text[2 * i] = labels[i] ? '1' : '0';
    if (path == kStdio) {
        writeStdout(text);
        return;
    }
    writeTextFile(path, text);
}

// What CLI11's option relations cannot say.
void checkCombination(ClassifyArgs& a) {
    const bool fromMesh = !a.mesh.empty();
    if (a.files.size() != (fromMesh ? 1u : 2u))
        throw CLI::ValidationError(fromMesh ? "expected one points file (with --mesh)"
                                            : "expected a sprite file and a points file");
    if (fromMesh && !a.exact && !a.certified && !a.withGiven->count())
        throw CLI::ValidationError("--mesh needs --exact, --certified or --with REPRESENTATION");
    if (a.exact && a.certified) throw CLI::ValidationError("--exact and --certified exclude each other");
    if (!a.exact && !a.certified && a.with != "vds" && a.options.rule != vds::Rule::Parity)
        throw CLI::ValidationError(std::string("--rule ") + vds::toString(a.options.rule) +
                                   " needs a sprite (--with vds), --exact or --certified");
    if (a.resolution == 0) a.resolution = a.with == "vds" ? vds::BakeOptions{}.resolution : kVoxelResolution;
}

void classify(ClassifyArgs& a) {
    checkCombination(a);
    const auto progress = progressPrinter(a.quiet);
    const std::string& pointsPath = a.files.back();
    const std::vector<glm::vec3> points = readPoints(pointsPath);
    progress("read " + std::to_string(points.size()) + " points from " + pointsPath);
    std::vector<std::uint8_t> labels(points.size());
    // Only the classification is timed; loading, baking and building are not.
    std::chrono::steady_clock::time_point start;
    auto startClock = [&start] { start = std::chrono::steady_clock::now(); };
    std::string method;
    vds::TriangleMesh mesh;
    if (!a.mesh.empty()) mesh = vds::loadMesh(a.mesh);

    if (a.exact || a.certified) {
        const vds::MeshReport report = vds::validateMesh(mesh);
        if (a.allowOpen) {
            vds::requireUsable(report, a.mesh);
        } else {
            try {
                vds::requireInsideDefined(report, a.mesh, a.options.rule);
            } catch (const vds::InvalidMesh& e) {
                throw vds::InvalidMesh(std::string(e.what()) + " (--allow-open classifies by crossing count anyway)");
            }
        }
        const std::string warning = vds::insideWarning(report, a.options.rule);
        if (!warning.empty()) std::fprintf(stderr, "vds classify: warning: %s: %s\n", a.mesh.c_str(), warning.c_str());
        if (a.allowOpen && !report.closed() && a.options.rule != vds::Rule::GeneralizedWinding)
            std::fprintf(stderr, "vds classify: warning: %s is %s; inside is not well defined by this rule "
                         "(--rule generalized-winding answers for open meshes)\n", a.mesh.c_str(),
                         report.summary().c_str());
        if (a.certified) {
            vds::CertifiedOptions certifiedOptions;
            certifiedOptions.resolution = a.resolution;
            certifiedOptions.threads = a.options.threads;
            const vds::CertifiedClassifier certified(mesh, certifiedOptions);
            progress("built the certified bands at " + std::to_string(a.resolution));
            startClock();
            const vds::CertifiedStats stats =
                certified.classify({points.data(), points.size()}, labels.data(), a.options);
            method = "certified (" + std::to_string(stats.exact) + " of " + std::to_string(points.size()) +
                     " points by the exact path)";
        } else {
            const vds::ExactClassifier exact(mesh);
            startClock();
            exact.classify({points.data(), points.size()}, labels.data(), a.options);
            method = "exact";
        }
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
            model.classify({points.data(), points.size()}, labels.data(), a.options.threads);
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
        // The generalized winding number answers open meshes: no warning then.
        if (sprite.status == vds::SolidStatus::Open && a.options.rule != vds::Rule::GeneralizedWinding)
            std::fprintf(stderr, "vds classify: warning: the sprite was baked from an open mesh (%s)\n",
                         sprite.validation.c_str());
        if (a.gpu) {
            vds::GlContext gl;
            const vds::GpuSprite gpu(sprite);
            vds::GpuClassifier classifier(gl);
            startClock();
            classifier.classify(gpu, points.data(), points.size(), labels.data(), a.options.rule);
            method = "GPU (" + gl.info().renderer + ")";
        } else {
            startClock();
            vds::classify(sprite, {points.data(), points.size()}, labels.data(), a.options);
            method = "CPU";
        }
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    writeLabels(a.output, a.outputFormat, labels);
    std::size_t inside = 0;
    for (auto l : labels) inside += l;
    // With the labels on stdout, the summary goes to stderr.
    std::fprintf(a.output == kStdio ? stderr : stdout, "wrote %s: %zu points, %zu inside, %s, %s rule, classified in %.3f s\n", a.output.c_str(),
                points.size(), inside, method.c_str(), vds::toString(a.options.rule), seconds);
}

} // namespace

void addClassify(CLI::App& app) {
    const auto [c, a] = addCommand<ClassifyArgs>(
        app, "classify", "label points 1 inside / 0 outside",
        "  vds classify SPRITE.vds POINTS -o LABELS.txt\n"
        "  vds classify --exact --mesh MESH POINTS -o LABELS.txt\n"
        "  vds classify --certified --mesh MESH POINTS -o LABELS.npy\n"
        "  vds classify --mesh MESH --with REPRESENTATION POINTS -o LABELS.txt\n"
        "Labels each point 1 (inside) or 0 (outside), one line per point, in the order given (or a\n"
        "boolean .npy array when LABELS ends in .npy). POINTS is a .npy array of N x 3 float32 or\n"
        "float64, a text file of lines 'x y z' in the mesh's coordinates ('#' comments and blank lines\n"
        "skipped) or a PLY file's vertices (ascii or binary, either byte order). POINTS '-' reads stdin, any of\n"
        "these told apart by their first bytes; LABELS '-' writes to stdout (text, or .npy with\n"
        "--output-format npy), with the summary line on stderr. Points outside the sprite's box are outside. --certified\n"
        "gives the exact classifier's answers at close to a sprite's speed (docs/accuracy.md). --with builds\n"
        "the representation from the mesh in memory first: vds (a sprite), slicemap, slicemap-local\n"
        "(front/back slicemap pair, uniform or local slicing), solid, solid-compute (solid voxels by\n"
        "rasterization or in compute); see docs/voxel.md.",
        classify);
    c->add_option("FILES", a->files, "a sprite file and a points file; with --mesh, the points file")
        ->required()
        ->option_text("[SPRITE.vds] POINTS");
    c->add_option("-o,--output", a->output, "output labels (written whole or not at all); '-': stdout")
        ->required()
        ->type_name("FILE");
    addChoice(*c, "--output-format", a->outputFormat, {"auto", "text", "npy"},
              "labels as text lines or a boolean .npy array; auto: .npy when LABELS ends in .npy");
    addEnum(*c, "--rule", a->options.rule,
            "the paper's parity, non-zero winding, or the generalized winding number (open meshes; --exact)");
    c->add_flag("--gpu", a->gpu, "classify with the GL compute shader instead of the CPU");
    addCount(*c, "--threads", a->options.threads, "CPU threads, 0: all");
    CLI::Option* mesh =
        c->add_option("--mesh", a->mesh, "classify against a mesh: --exact, or --with")->type_name("MESH");
    CLI::Option* exact = c->add_flag("--exact", a->exact, "exact classification on the mesh's triangles")->needs(mesh);
    CLI::Option* certified =
        c->add_flag("--certified", a->certified, "exact answers, most from certified bands at --resolution")->needs(mesh);
    c->add_flag("--allow-open", a->allowOpen, "let --exact classify an open mesh by crossing count");
    std::vector<std::string> with = vds::enumNames<vds::voxel::Representation>();
    with.insert(with.begin(), "vds");
    a->withGiven =
        addChoice(*c, "--with", a->with, with, "build this from the mesh first")->needs(mesh)->excludes(exact)->excludes(certified);
    addResolution(*c, a->resolution, "texels or voxels on the box's longest side for --with and --certified")
        ->default_str(std::to_string(vds::BakeOptions{}.resolution) + " for vds, " + std::to_string(kVoxelResolution) +
                      " for the others");
}

} // namespace cli
