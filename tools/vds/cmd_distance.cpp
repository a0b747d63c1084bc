// vds distance: the signed distance of points to a mesh's surface, signed by
// a rule, and optionally their closest points and triangles.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <optional>
#include <algorithm>
#include <string>
#include <vector>

#include <vds/distance.h>
#include <vds/mesh_check.h>
#include <vds/mesh_io.h>
#include <vds/npy.h>

#include "cli.h"
#include "outputs.h"

namespace cli {

namespace {

struct DistanceArgs {
    std::string mesh, points, output, closestPoints, triangles, outputFormat = "auto";
    vds::Rule rule = vds::Rule::Parity;
    unsigned threads = 0;
    bool allowOpen = false, quiet = false, isUnsigned = false;
};

// An output of `rows` rows of `columns` values, as `path`'s extension (or
// --output-format for -o) says: a .npy array of `descr`, or text lines.
struct Column {
    std::size_t output;
    OutputFormat format;
};

Column claimColumn(Outputs& outputs, const std::string& option, const std::string& path, OutputFormat stdio) {
    const OutputFormat format =
        outputFormat(option, path, {OutputFormat::Npy, OutputFormat::Text, OutputFormat::Csv}, stdio);
    return {outputs.claim(option, path), format};
}

template <class T>
void writeColumn(Outputs& outputs, const Column& column, const char* descr, const std::vector<T>& values,
                 std::size_t columns) {
    const std::size_t rows = values.size() / columns;
    if (column.format != OutputFormat::Npy) {
        outputs.write(column.output, textRows(values.data(), rows, columns, column.format), nullptr, 0);
        return;
    }
    std::vector<std::uint64_t> shape{rows};
    if (columns > 1) shape.push_back(columns);
    outputs.write(column.output, vds::npyHeader(descr, shape), values.data(), values.size() * sizeof(T));
}

// The points or x layers a step: a run past a second says how far it got.
constexpr std::uint32_t kProgressSteps = 16;

void distance(DistanceArgs& a) {
    // Every output is claimed before the work and written all or none.
    Outputs outputs;
    const OutputFormat stdio = a.outputFormat == "npy" ? OutputFormat::Npy : OutputFormat::Text;
    const Column values = a.outputFormat == "auto" ? claimColumn(outputs, "-o", a.output, stdio)
                                                   : Column{outputs.claim("-o", a.output), stdio};
    std::optional<Column> closestOut, trianglesOut;
    if (!a.closestPoints.empty()) closestOut = claimColumn(outputs, "--closest-points", a.closestPoints, OutputFormat::Text);
    if (!a.triangles.empty()) trianglesOut = claimColumn(outputs, "--triangles", a.triangles, OutputFormat::Text);
    const auto progress = progressPrinter(a.quiet);
    const std::vector<glm::vec3> points = readPointsFile(a.points);
    progress("read " + std::to_string(points.size()) + " points from " + (a.points == kStdio ? "<stdin>" : a.points));
    const vds::TriangleMesh mesh = vds::loadMesh(a.mesh);
    // Any usable mesh has distances, a flat one (a sheet) too; a sign needs
    // a mesh whose inside the rule defines.
    const vds::SignedDistance query(mesh, a.rule, a.mesh);
    if (!a.isUnsigned) {
        try {
            checkSignedMesh(mesh, a.mesh, a.rule, a.allowOpen, "distance");
        } catch (const vds::InvalidMesh& e) {
            if (query.hasSign()) throw;
            throw vds::InvalidMesh(std::string(e.what()) + ": it has distances but no sign (--unsigned)");
        }
    }
    // Unsigned, the rule plays no part: the summary says so rather than "signed by RULE".
    std::string built = query.summary();
    const std::size_t signedBy = built.find("signed by ");
    if (a.isUnsigned && signedBy != std::string::npos) built = built.substr(0, signedBy) + "unsigned";
    progress("built " + built);
    vds::DistanceOptions options;
    options.threads = a.threads;
    const auto start = std::chrono::steady_clock::now();
    std::vector<double> d(points.size());
    std::vector<vds::ClosestPoint> closest((closestOut || trianglesOut) ? points.size() : 0);
    const std::size_t step = std::max<std::size_t>(1, (points.size() + kProgressSteps - 1) / kProgressSteps);
    for (std::size_t k0 = 0; k0 < points.size(); k0 += step) {
        const std::size_t k1 = std::min(points.size(), k0 + step);
        const vds::PointsView slice(points.data() + k0, k1 - k0);
        if (a.isUnsigned) query.unsignedDistance(slice, d.data() + k0, options);
        else query.distance(slice, d.data() + k0, options);
        if (!closest.empty()) query.closestPoints(slice, closest.data() + k0, options);
        reportSteps(progress, "measured", k1, points.size(), "points", secondsSince(start));
    }
    const double seconds = secondsSince(start);
    writeColumn(outputs, values, "<f8", d, 1);
    if (closestOut) {
        std::vector<double> xyz;
        for (const vds::ClosestPoint& c : closest) xyz.insert(xyz.end(), {c.point.x, c.point.y, c.point.z});
        writeColumn(outputs, *closestOut, "<f8", xyz, 3);
    }
    if (trianglesOut) {
        std::vector<std::uint32_t> triangles;
        for (const vds::ClosestPoint& c : closest) triangles.push_back(c.triangle);
        writeColumn(outputs, *trianglesOut, "<u4", triangles, 1);
    }
    outputs.commit();
    std::size_t inside = 0;
    for (double v : d) inside += std::signbit(v);
    const std::string sign = a.isUnsigned ? std::string("unsigned")
                                          : std::to_string(inside) + " inside, " + vds::toString(a.rule) + " rule";
    // With the distances on stdout, the summary goes to stderr.
    std::fprintf(a.output == kStdio ? stderr : stdout, "wrote %s: %zu points, %s, measured in %.3f s\n",
                 a.output.c_str(), points.size(), sign.c_str(), seconds);
}

} // namespace

void fillDistanceGrid(const vds::SignedDistance& query, const vds::Grid& grid, float* cells,
                      const vds::DistanceGridOptions& options, const std::function<void(const std::string&)>& progress) {
    // A propagated grid spreads across the whole grid: one call.
    const std::uint32_t slab = options.far == vds::FarCells::Propagated
                                   ? grid.dims.x
                                   : std::max<std::uint32_t>(1, (grid.dims.x + kProgressSteps - 1) / kProgressSteps);
    const std::size_t layer = std::size_t(grid.dims.y) * grid.dims.z;
    const auto start = std::chrono::steady_clock::now();
    for (std::uint32_t i0 = 0; i0 < grid.dims.x; i0 += slab) {
        const std::uint32_t i1 = std::min(grid.dims.x, i0 + slab);
        query.grid(slab == grid.dims.x ? grid : grid.slabX(i0, i1), cells + std::size_t(i0) * layer, options);
        reportSteps(progress, "measured", i1, grid.dims.x, "x layers", secondsSince(start));
    }
}

void checkSignedMesh(const vds::TriangleMesh& mesh, const std::string& name, vds::Rule rule, bool allowOpen,
                     const char* command) {
    const vds::MeshReport report = vds::validateMesh(mesh);
    vds::requireUsable(report, name);
    vds::requireVolume(report, name);
    if (!allowOpen) vds::requireInsideDefined(report, name, rule, meshFlags(true));
    tellAboutMesh(command, name, report, rule, meshFlags(true));
}

void addDistance(CLI::App& app) {
    const auto [c, a] = addCommand<DistanceArgs>(
        app, "distance", "signed distance of points to a mesh's surface, into a numpy .npy file or text",
        "  vds distance MESH POINTS -o D.npy [--rule RULE] [--closest-points P.npy] [--triangles T.npy]\n"
        "D.npy: float64, one distance a point in the order given, in mesh units: negative exactly where\n"
        "'vds classify --exact' with the same rule says inside (-0.0 for an inside point on the surface).\n"
        "The distance is exact up to double rounding (docs/distance.md). POINTS: a .npy array of N x 3\n"
        "float32 or float64, a text file of lines 'x y z' or a PLY file's vertices; points are rounded to\n"
        "float first, as classify does. P.npy: the closest points, N x 3 float64; T.npy: the index of the\n"
        "triangle each lies on, uint32. Each output is a .npy array, or text lines when its name ends in\n"
        ".txt (values separated by spaces) or .csv (by commas); all are written, or none. POINTS '-' reads\n"
        "stdin (told apart by its first bytes), D '-' writes to stdout (text, or .npy with --output-format\n"
        "npy), with the summary line on stderr. An open mesh needs --rule generalized-winding; a flat one\n"
        "(a sheet) has distances and closest points but no sign: --unsigned.",
        distance);
    addMesh(*c, a->mesh);
    c->add_option("POINTS", a->points, "points file (.npy, text, PLY; '-': stdin)")->required()->type_name("");
    c->add_option("-o,--output", a->output, "output distances (.npy, .txt, .csv; '-': stdout)")
        ->required()
        ->type_name("FILE");
    addChoice(*c, "--output-format", a->outputFormat, {"auto", "text", "npy"},
              "the distances as text lines or a .npy array; auto: by the name's extension, text for '-'");
    c->add_option("--closest-points", a->closestPoints, "also write the closest points (N x 3 float64 .npy)")
        ->type_name("FILE");
    c->add_option("--triangles", a->triangles, "also write the closest points' triangles (uint32 .npy)")->type_name("FILE");
    addEnum(*c, "--rule", a->rule, "what is inside (negative): parity, winding, or generalized-winding (open meshes)");
    c->add_flag("--allow-open", a->allowOpen, "sign an open mesh by crossing count anyway");
    c->add_flag("--unsigned", a->isUnsigned,
                "distances without a sign: any mesh, a flat one (a sheet) too, which has no inside to sign by");
    addCount(*c, "--threads", a->threads, "CPU threads, 0: all");
}

} // namespace cli
