// vds distance: the signed distance of points to a mesh's surface, signed by
// a rule, and optionally their closest points and triangles.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <vds/distance.h>
#include <vds/mesh_check.h>
#include <vds/mesh_io.h>
#include <vds/npy.h>

#include "cli.h"

namespace cli {

namespace {

struct DistanceArgs {
    std::string mesh, points, output, closestPoints, triangles;
    vds::Rule rule = vds::Rule::Parity;
    unsigned threads = 0;
    bool allowOpen = false, quiet = false;
};

// A .npy array of N x 3 float32 or float64, or what vds::loadPoints reads.
std::vector<glm::vec3> readPoints(const std::string& path) {
    if (path.size() > 4 && path.compare(path.size() - 4, 4, ".npy") == 0) return vds::npyPoints(vds::readNpy(path), path);
    return vds::loadPoints(path);
}

void distance(DistanceArgs& a) {
    const auto progress = progressPrinter(a.quiet);
    const std::vector<glm::vec3> points = readPoints(a.points);
    progress("read " + std::to_string(points.size()) + " points from " + a.points);
    const vds::TriangleMesh mesh = vds::loadMesh(a.mesh);
    checkSignedMesh(mesh, a.mesh, a.rule, a.allowOpen, "distance");
    const vds::SignedDistance query(mesh, a.rule, a.mesh);
    progress("built " + query.summary());
    vds::DistanceOptions options;
    options.threads = a.threads;
    const auto start = std::chrono::steady_clock::now();
    std::vector<double> d(points.size());
    query.distance(points, d.data(), options);
    std::vector<vds::ClosestPoint> closest;
    if (!a.closestPoints.empty() || !a.triangles.empty()) {
        closest.resize(points.size());
        query.closestPoints(points, closest.data(), options);
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    // Every output is computed before the first is written.
    std::vector<double> xyz;
    std::vector<std::uint32_t> triangles;
    for (const vds::ClosestPoint& c : closest) {
        xyz.insert(xyz.end(), {c.point.x, c.point.y, c.point.z});
        triangles.push_back(c.triangle);
    }
    vds::writeNpy(a.output, "<f8", {d.size()}, d.data(), d.size() * sizeof(double));
    if (!a.closestPoints.empty())
        vds::writeNpy(a.closestPoints, "<f8", {closest.size(), 3}, xyz.data(), xyz.size() * sizeof(double));
    if (!a.triangles.empty())
        vds::writeNpy(a.triangles, "<u4", {triangles.size()}, triangles.data(), triangles.size() * sizeof(std::uint32_t));
    std::size_t inside = 0;
    for (double v : d) inside += std::signbit(v);
    std::printf("wrote %s: %zu points, %zu inside, %s rule, measured in %.3f s\n", a.output.c_str(), points.size(),
                inside, vds::toString(a.rule), seconds);
}

} // namespace

void checkSignedMesh(const vds::TriangleMesh& mesh, const std::string& name, vds::Rule rule, bool allowOpen,
                     const char* command) {
    const vds::MeshReport report = vds::validateMesh(mesh);
    vds::requireUsable(report, name);
    vds::requireVolume(report, name);
    if (!allowOpen) vds::requireInsideDefined(report, name, rule, meshFlags());
    const std::string warning = vds::insideWarning(report, rule, meshFlags());
    if (!warning.empty()) std::fprintf(stderr, "vds %s: warning: %s: %s\n", command, name.c_str(), warning.c_str());
}

void addDistance(CLI::App& app) {
    const auto [c, a] = addCommand<DistanceArgs>(
        app, "distance", "signed distance of points to a mesh's surface, into a numpy .npy file",
        "  vds distance MESH POINTS -o D.npy [--rule RULE] [--closest-points P.npy] [--triangles T.npy]\n"
        "D.npy: float64, one distance a point in the order given, in mesh units: negative exactly where\n"
        "'vds classify --exact' with the same rule says inside (-0.0 for an inside point on the surface).\n"
        "The distance is exact up to double rounding (docs/distance.md). POINTS: a .npy array of N x 3\n"
        "float32 or float64, a text file of lines 'x y z' or a PLY file's vertices; points are rounded to\n"
        "float first, as classify does. P.npy: the closest points, N x 3 float64; T.npy: the index of the\n"
        "triangle each lies on, uint32. An open mesh needs --rule generalized-winding.",
        distance);
    addMesh(*c, a->mesh);
    c->add_option("POINTS", a->points, "points file (.npy, text, PLY)")->required()->type_name("");
    c->add_option("-o,--output", a->output, "output distances .npy (written whole or not at all)")
        ->required()
        ->type_name("FILE");
    c->add_option("--closest-points", a->closestPoints, "also write the closest points (N x 3 float64 .npy)")
        ->type_name("FILE");
    c->add_option("--triangles", a->triangles, "also write the closest points' triangles (uint32 .npy)")->type_name("FILE");
    addEnum(*c, "--rule", a->rule, "what is inside (negative): parity, winding, or generalized-winding (open meshes)");
    c->add_flag("--allow-open", a->allowOpen, "sign an open mesh by crossing count anyway");
    addCount(*c, "--threads", a->threads, "CPU threads, 0: all");
}

} // namespace cli
