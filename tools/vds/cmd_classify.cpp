#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <memory>
#include <vector>

#include <vds/all.h>
#include <vds/mesh_check.h>
#include <vds/mesh_io.h>
#include <vds/npy.h>
#include <vds/vds_file.h>
#include <vds/voxel/representation.h>

#include "cli.h"
#include "outputs.h"

namespace cli {

namespace {

struct ClassifyArgs {
    std::vector<std::string> files; // [SPRITE] POINTS
    std::string output, mesh, with, outputFormat = "auto";
    std::uint32_t resolution = 0; // 0: the method's default (CLI11 refuses 0 given)
    vds::ClassifyOptions options;
    vds::Method method = vds::Method::Sprite;
    bool gpu = false, exact = false, certified = false, allowOpen = false, quiet = false;
    const CLI::Option* methodGiven = nullptr;
};

bool endsWith(const std::string& s, const std::string& tail) {
    return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

// The first bytes of a file ("" where it cannot be read).
std::string firstBytes(const std::string& path, std::size_t n) {
    std::ifstream in(path, std::ios::binary);
    std::string bytes(n, '\0');
    in.read(&bytes[0], std::streamsize(n));
    bytes.resize(std::size_t(in.gcount()));
    return bytes;
}

// A .vds file is OpenEXR: its magic number.
bool looksLikeSprite(const std::string& path) { return path != kStdio && firstBytes(path, 4) == "\x76\x2f\x31\x01"; }

// A .npy file (N x 3 float32 or float64) or what vds::loadPoints reads; from
// stdin ("-") any of these, told apart by their first bytes.
std::vector<glm::vec3> readPoints(const std::string& path) {
    try {
        return readPointsFile(path);
    } catch (const vds::FormatError& e) {
        if (!looksLikeSprite(path)) throw;
        throw vds::FormatError(std::string(e.what()) + "; " + path +
                               " is a sprite file: the sprite comes first (vds classify SPRITE.vds POINTS -o LABELS)");
    }
}

// Labels as a boolean .npy array, or one "0"/"1" line per point, into the
// claimed output (a file written atomically, or stdout for "-"). `format`
// "auto": .npy by the name.
void writeLabels(Outputs& outputs, std::size_t output, const std::string& path, const std::string& format,
                 const std::vector<std::uint8_t>& labels) {
    const bool npy = format == "npy" || (format == "auto" && endsWith(path, ".npy"));
    if (npy) {
        outputs.write(output, vds::npyHeader("|b1", {labels.size()}), labels.data(), labels.size());
        return;
    }
    std::string text(labels.size() * 2, '\n');
    for (std::size_t i = 0; i < labels.size(); ++i) text[2 * i] = labels[i] ? '1' : '0';
    outputs.write(output, text, nullptr, 0);
}

// The old spellings (--exact, --certified, --with NAME, --gpu) as the
// method they name, then what CLI11's option relations cannot say.
void resolveMethod(ClassifyArgs& a) {
    const int spellings = int(a.methodGiven->count() > 0) + int(a.exact) + int(a.certified) + int(!a.with.empty());
    if (spellings > 1) throw CLI::ValidationError("--method, --exact, --certified and --with name one method: give one");
    if (a.exact) a.method = vds::Method::Exact;
    if (a.certified) a.method = vds::Method::Certified;
    if (!a.with.empty()) a.method = a.with == "vds" ? vds::Method::Sprite : vds::parseEnum<vds::Method>(a.with);
    if (a.gpu) {
        const vds::Method gpu = vds::gpuForm(a.method);
        const vds::MethodInfo& named = vds::methodInfo(a.method);
        if (gpu == a.method && !named.gpu)
            throw CLI::ValidationError(std::string("--gpu: method '") + named.name + "' has no GPU form");
        a.method = gpu;
    }
    const vds::MethodInfo& info = vds::methodInfo(a.method);
    if (!info.builtIn()) throw CLI::ValidationError("method 'custom' is for classifiers defined in C++, not the CLI");
    const bool fromMesh = !a.mesh.empty();
    if (a.files.size() != (fromMesh ? 1u : 2u))
        throw CLI::ValidationError(fromMesh ? "expected one points file (with --mesh)"
                                            : "expected a sprite file and a points file");
    if (!fromMesh && !info.fromSprite)
        throw CLI::ValidationError(std::string("method '") + info.name + "' is built from a mesh: give --mesh MESH");
    if (!fromMesh && a.resolution != 0)
        throw CLI::ValidationError("--resolution needs --mesh (a sprite file has its own)");
    try {
        vds::requireRule(a.method, a.options.rule);
    } catch (const vds::InvalidArgument& e) {
        throw CLI::ValidationError(e.what());
    }
}

// Refuses or warns about a mesh that bounds no solid, by the rule asked.
void checkMesh(const ClassifyArgs& a, const vds::TriangleMesh& mesh) {
    const vds::MeshReport report = vds::validateMesh(mesh);
    vds::requireUsable(report, a.mesh);
    vds::requireVolume(report, a.mesh);
    const vds::MeshFlags flags = meshFlags(true);
    if (!a.allowOpen && !vds::methodInfo(a.method).needsClosedMesh)
        vds::requireInsideDefined(report, a.mesh, a.options.rule, flags);
    tellAboutMesh("classify", a.mesh, report, a.options.rule, flags);
}

void classify(ClassifyArgs& a) {
    resolveMethod(a);
    Outputs outputs;
    const std::size_t output = outputs.claim("-o", a.output);
    const auto progress = progressPrinter(a.quiet);
    const std::string& pointsPath = a.files.back();
    const std::vector<glm::vec3> points = readPoints(pointsPath);
    progress("read " + std::to_string(points.size()) + " points from " + pointsPath);

    // One dispatch: the method built from the mesh or the sprite file.
    std::unique_ptr<vds::Classifier> classifier;
    if (!a.mesh.empty()) {
        const vds::TriangleMesh mesh = vds::loadMesh(a.mesh);
        checkMesh(a, mesh);
        vds::MethodOptions options;
        options.resolution = a.resolution;
        options.threads = a.options.threads;
        options.sourceName = mesh.name;
        classifier = vds::makeClassifier(mesh, a.method, options);
    } else {
        vds::Sprite sprite;
        try {
            sprite = vds::readSprite(a.files.front());
        } catch (const vds::FormatError& e) {
            if (!looksLikeSprite(a.files.back())) throw;
            throw vds::FormatError(std::string(e.what()) + "; the second file is the sprite: the sprite comes first "
                                                            "(vds classify SPRITE.vds POINTS -o LABELS)");
        }
        // The generalized winding number answers open meshes: no warning then.
        if (sprite.status != vds::SolidStatus::Closed && a.options.rule != vds::Rule::GeneralizedWinding)
            std::fprintf(stderr, "vds classify: warning: %s\n",
                         vds::openSpriteMessage(sprite.validation, a.options.rule, meshFlags()).c_str());
        classifier = vds::makeClassifier(std::move(sprite), a.method);
    }
    progress("built " + classifier->summary());

    std::vector<std::uint8_t> labels(points.size());
    vds::ClassifyStats stats;
    a.options.stats = &stats;
    // Only the classification is timed; loading, baking and building are not.
    const auto start = std::chrono::steady_clock::now();
    classifier->classify(points, labels.data(), a.options);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::string method = classifier->summary();
    if (a.method == vds::Method::Certified)
        method += " (" + std::to_string(stats.exact) + " of " + std::to_string(points.size()) +
                  " points by the exact path)";
    writeLabels(outputs, output, a.output, a.outputFormat, labels);
    outputs.commit();
    std::size_t inside = 0;
    for (auto l : labels) inside += l;
    // With the labels on stdout, the summary goes to stderr.
    std::fprintf(a.output == kStdio ? stderr : stdout,
                 "wrote %s: %zu points, %zu inside, %s, %s rule, classified in %.3f s\n", a.output.c_str(),
                 points.size(), inside, method.c_str(), vds::enumName(a.options.rule), seconds);
}

} // namespace

void addClassify(CLI::App& app) {
    std::string methods;
    for (const vds::MethodInfo* m = vds::methodTable(); m != vds::methodTable() + vds::kMethodCount; ++m)
        if (m->builtIn())
            methods += std::string("  ") + m->name + std::string(20 - std::min<std::size_t>(19, std::strlen(m->name)), ' ') +
                   m->summary + (m->fromSprite ? "" : " (--mesh)") + "\n";
    const auto [c, a] = addCommand<ClassifyArgs>(
        app, "classify", "label points 1 inside / 0 outside",
        "  vds classify SPRITE.vds POINTS -o LABELS.txt [--method sprite|sprite-gpu]\n"
        "  vds classify --mesh MESH POINTS -o LABELS.txt --method METHOD [--resolution N]\n"
        "Labels each point 1 (inside) or 0 (outside), one line per point, in the order given (or a\n"
        "boolean .npy array when LABELS ends in .npy). POINTS is a .npy array of N x 3 float32 or\n"
        "float64, a text file of lines 'x y z' in the mesh's coordinates ('#' comments and blank lines\n"
        "skipped) or a PLY file's vertices (ascii or binary, either byte order). POINTS '-' reads stdin, any of\n"
        "these told apart by their first bytes; LABELS '-' writes to stdout (text, or .npy with\n"
        "--output-format npy), with the summary line on stderr. Points outside the sprite's box are outside.\n"
        "Methods (built from the mesh in memory, or read from a sprite file where noted):\n" +
            methods +
            "The older spellings still work: --exact (= --method exact), --certified (= --method certified),\n"
            "--with NAME (= --method NAME; vds = sprite), and --gpu (the method's GPU form).\n"
            "The voxel representations answer the parity rule only; docs/voxel.md compares them.",
        classify);
    c->add_option("FILES", a->files, "a sprite file and a points file; with --mesh, the points file")
        ->required()
        ->option_text("[SPRITE.vds] POINTS");
    c->add_option("-o,--output", a->output, "output labels (written whole or not at all); '-': stdout")
        ->required()
        ->type_name("FILE");
    addChoice(*c, "--output-format", a->outputFormat, {"auto", "text", "npy"},
              "labels as text lines or a boolean .npy array; auto: .npy when LABELS ends in .npy");
    std::vector<std::string> builtIn;
    for (const vds::MethodInfo* m = vds::methodTable(); m != vds::methodTable() + vds::kMethodCount; ++m)
        if (m->builtIn()) builtIn.push_back(m->name);
    a->methodGiven = addEnum(*c, "--method", a->method, "how to answer (see below); default sprite", builtIn);
    addEnum(*c, "--rule", a->options.rule,
            "the paper's parity, non-zero winding, or the generalized winding number (open meshes)");
    c->add_flag("--gpu", a->gpu, "the method's GPU form (sprite -> sprite-gpu, certified -> certified-gpu, ...)");
    addCount(*c, "--threads", a->options.threads, "CPU threads, 0: all");
    c->add_option("--mesh", a->mesh, "build the method from this mesh")->type_name("MESH");
    c->add_flag("--exact", a->exact, "= --method exact");
    c->add_flag("--certified", a->certified, "= --method certified");
    c->add_flag("--allow-open", a->allowOpen, "classify an open mesh by crossing count anyway");
    std::vector<std::string> with = vds::enumNames<vds::voxel::Representation>();
    with.insert(with.begin(), "vds");
    addChoice(*c, "--with", a->with, with, "= --method NAME (vds: sprite)");
    addResolution(*c, a->resolution, "texels or cells on the box's longest side (with --mesh)")
        ->default_str("1024 for sprites and certified bands, 256 for voxels");
}

} // namespace cli
