#include <chrono>
#include <cstdio>
#include <future>
#include <memory>
#include <optional>

#include <vds/all.h>
#include <vds/bake.h>
#include <vds/distance.h>
#include <vds/mesh_check.h>
#include <vds/mesh_io.h>
#include <vds/vds_file.h>

#include "cli.h"

namespace cli {

namespace {

// A GL bake's context, made on another thread while this one reads the mesh,
// validates it and counts the axis (EGL's start is tens of milliseconds, as
// long as that work), then released there for this thread to take.
std::future<std::unique_ptr<vds::GlContext>> contextInBackground() {
    return std::async(std::launch::async, [] {
        const vds::CurrentContext none; // none is current on a new thread: its end releases the context
        return std::make_unique<vds::GlContext>();
    });
}

struct BakeArgs {
    std::string mesh, output, axis = "auto";
    vds::BakeOptions options;
    bool quiet = false, verbose = false;
    std::uint32_t distance = 0; ///< cells of the distance grid along its longest side, 0: none
    vds::Rule distanceRule = vds::Rule::Parity; ///< every command's default rule
};

// The largest --distance whose grid fits the file whatever the mesh's shape:
// a cube's N^3 cells at most vds::kMaxDistanceCells.
std::uint32_t maxDistanceResolution() {
    std::uint32_t n = vds::kMaxDistanceResolution;
    while (std::size_t(n) * n * n > vds::kMaxDistanceCells) --n;
    return n;
}

// Milliseconds since `from`, and `from` moved to now.
double lap(std::chrono::steady_clock::time_point& from) {
    const auto now = std::chrono::steady_clock::now();
    const double ms = std::chrono::duration<double, std::milli>(now - from).count();
    from = now;
    return ms;
}

void bake(BakeArgs& a) {
    const auto progress = progressPrinter(a.quiet);
    const auto start = std::chrono::steady_clock::now();
    auto at = start;
    double before[4] = {}; // read, validate, axis count, waiting for the GL context (ms)
    const bool onGl = a.options.method == vds::BakeMethod::Lists || a.options.method == vds::BakeMethod::Peel;
    std::optional<std::future<std::unique_ptr<vds::GlContext>>> context;
    if (onGl) context = contextInBackground();
    const vds::TriangleMesh mesh = vds::loadMesh(a.mesh);
    a.options.sourceName = mesh.name;
    before[0] = lap(at);
    // Validation finds what the axis count would find again (the edges'
    // partners, the facings): one grouping of the edges, not two.
    const vds::MeshValidation validation(mesh);
    const vds::MeshReport& report = validation.report();
    vds::requireUsable(report, a.mesh);
    vds::requireVolume(report, a.mesh);
    before[1] = lap(at);
    if (a.axis == "auto") {
        const vds::AxisChoice choice = vds::chooseViewAxis(mesh, validation, a.options.resolution);
        a.options.axis = choice.axis;
        before[2] = lap(at);
        if (a.verbose) std::fprintf(stderr, "%s: the fewest layers\n", choice.summary().c_str());
    } else {
        a.options.axis = vds::parseAxis(a.axis);
    }
    if (vds::solidStatus(report) != vds::SolidStatus::Closed) {
        // The sprite answers by the generalized winding number through classify's --rule.
        const std::string warning = report.closed() ? vds::misorientedMessage(report, a.mesh)
                                                    : vds::openMeshMessage(report, a.mesh, vds::Rule::Parity,
                                                                           {"vds classify --rule generalized-winding", ""});
        std::fprintf(stderr, "vds bake: warning: %s (%s)\n", warning.c_str(), report.summary().c_str());
    }
    if (a.options.method == vds::BakeMethod::Auto) {
        std::string why;
        a.options.method = vds::chooseBakeMethod(&why);
        if (a.verbose) std::fprintf(stderr, "%s\n", why.c_str());
    }
    a.options.progress = progress;
    vds::BakeTimings timings;
    if (a.verbose) a.options.timings = &timings;
    progress("baking " + a.mesh + " (" + std::to_string(mesh.triangles.size()) + " triangles) at " +
             std::to_string(a.options.resolution) + " along " + vds::toString(*a.options.axis) + " with " +
             vds::toString(a.options.method));
    std::unique_ptr<vds::GlContext> gl;
    if (context) {
        gl = context->get(); // rethrows GL's refusal, as the bake would have
        gl->makeCurrent();
        before[3] = lap(at);
    }
    if (a.verbose)
        std::fprintf(stderr, "before the bake: read %.2f ms, validation %.2f ms, axis count %.2f ms, GL context wait %.2f ms\n",
                     before[0], before[1], before[2], before[3]);
    vds::Sprite sprite = gl ? vds::bake(*gl, mesh, a.options) : vds::bake(mesh, a.options);
    if (a.distance > 0) {
        progress("distance grid of " + std::to_string(a.distance) + " cells along the longest side, " +
                 vds::toString(a.distanceRule) + " rule");
        sprite.distance.grid = vds::spriteDistanceGrid(sprite.grid.box, a.distance);
        const vds::SignedDistance query(mesh, a.distanceRule, a.mesh);
        sprite.distance.cells.resize(sprite.distance.grid.cellCount());
        fillDistanceGrid(query, sprite.distance.grid, sprite.distance.cells.data(), {}, progress);
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (a.verbose) std::fputs(timings.report().c_str(), stderr);
    vds::writeSprite(sprite, a.output);
    std::printf("wrote %s: %ux%u texels, depth complexity %u, %zu crossings%s, baked in %.3f s\n", a.output.c_str(),
                sprite.width(), sprite.height(), sprite.depthComplexity, sprite.crossings.size(),
                sprite.distance.empty() ? "" : ", a signed distance grid", seconds);
}

} // namespace

void addBake(CLI::App& app) {
    const auto [c, a] =
        addCommand<BakeArgs>(app, "bake", "bake a mesh (OBJ, PLY, STL, OFF) into a sprite",
                             "An open or mis-oriented mesh is baked with a warning, and the file records that its\n"
                             "answers are a surface's, not a solid's; a closed mesh whose parts touch along\n"
                             "non-manifold edges bounds a solid like any other.",
                             bake);
    addMesh(*c, a->mesh);
    c->add_option("-o,--output", a->output, "output sprite (written whole or not at all)")
        ->required()
        ->type_name("FILE");
    addResolution(*c, a->options.resolution, "texels on the longer side of the view");
    std::vector<std::string> axes = vds::enumNames<vds::Axis>();
    axes.push_back("auto");
    addChoice(*c, "--axis", a->axis, axes,
              "view direction; auto: the axis with the fewest layers at this resolution, counted exactly");
    addEnum(*c, "--method", a->options.method,
            "auto: GL fragment lists on a GPU, the CPU baker on a software renderer or without GL; or lists, "
            "peel (depth peeling), cpu (exact ray casting)");
    const std::uint32_t most = maxDistanceResolution();
    CLI::Option* distance =
        c->add_option("--distance", a->distance,
                      "also store a signed distance grid of N cells along the longest side, cubic cells (exact "
                      "distances, for vdsDistance in GLSL; format version 3); at most " + std::to_string(most) +
                          ", so that a cube's N^3 cells fit one attribute of the file")
            ->transform(wholeNumber(4, most))
            ->type_name("4.." + std::to_string(most))
            ->default_str(""); // none unless given: 0 is no size
    addEnum(*c, "--distance-rule", a->distanceRule,
            "the sign of the distance grid: parity, winding, or generalized-winding (open meshes too)")
        ->needs(distance);
    c->add_flag("--verbose", a->verbose,
                "say which axis and bake method auto chose and why, and the time of each phase (validation, "
                "upload, raster, scan, sort, read-back...)");
}

} // namespace cli
