// Benchmark of exact distances (<vds/distance.h>): vds's unsigned and signed
// distance on one thread (a batch, and one point a call: the search alone,
// without the batch's Morton order) against a brute-force loop over every triangle,
// CGAL's AABB tree, Embree's point query, libigl's AABB tree and fcpw's
// vectorized BVH (where they were found at configure time), on two point
// sets: uniform in and around each mesh's box, and near the surface (on a
// random triangle, area-weighted, moved along its normal by up to 1% of the
// diagonal either way); the rounds alternated (A B C, A B C, ...) and the
// best of each kept, timed in the thread's CPU time.
// Agreement: vds against brute force on a sample (the same closest-point
// kernel over every triangle: this checks the hierarchy's search), the sign
// against the exact classifier of the same rule on every point, and the
// peers' distances against vds's. Then signed distance grids (full and a
// band) on two threads.
//
// usage: vds_distance_bench [--points N] [--brute N] [--rounds N] [--sdf N] [--band CELLS] [--full-grid]
//                           [--generated sphere|trefoil|soup|holes ...] [mesh ...]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <functional>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <glm/geometric.hpp>

#include <vds/distance.h>
#include <vds/error.h>
#include <vds/mesh.h>
#include <vds/mesh_check.h>
#include <vds/mesh_io.h>

#include "points.h"
#include "solids.h"

#if defined(VDS_DISTANCE_CGAL) || defined(VDS_DISTANCE_EMBREE) || defined(VDS_DISTANCE_LIBIGL) || \
    defined(VDS_DISTANCE_FCPW)
#include "distance_peer.h"
#endif

namespace {

using Clock = std::chrono::steady_clock;

double seconds(Clock::time_point since) { return std::chrono::duration<double>(Clock::now() - since).count(); }

/// This thread's CPU time in seconds: the one-thread queries are timed by it,
/// which other programs on a shared machine disturb less than wall time.
double threadSeconds() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

struct Settings {
    std::size_t points = 100000, brute = 1000;
    int rounds = 3;
    std::uint32_t sdf = 256;
    double band = 3.0;
    bool fullGrid = false;
};

struct Contender {
    std::string name;
    std::function<void(const std::vector<glm::vec3>&, double*)> run;
    std::vector<double> out;
    double best = std::numeric_limits<double>::infinity();
};

vds::Rule ruleFor(const vds::TriangleMesh& mesh) {
    const vds::MeshReport report = vds::validateMesh(mesh);
    if (report.oriented()) return vds::Rule::Winding;
    return report.closed() ? vds::Rule::Parity : vds::Rule::GeneralizedWinding;
}

double bruteForce(const vds::TriangleMesh& mesh, const glm::vec3& p) {
    double best = std::numeric_limits<double>::infinity();
    for (const glm::uvec3& t : mesh.triangles)
        best = std::min(best, vds::closestPointOnTriangle(glm::dvec3(p), glm::dvec3(mesh.positions[t.x]),
                                                          glm::dvec3(mesh.positions[t.y]), glm::dvec3(mesh.positions[t.z]))
                                  .distance);
    return best;
}

std::vector<Contender> contenders(const vds::SignedDistance& vds, const vds::TriangleMesh& mesh) {
    std::vector<Contender> all;
    vds::DistanceOptions one;
    one.threads = 1;
    all.push_back({"vds unsigned", [&vds, one](const auto& p, double* o) { vds.unsignedDistance(p, o, one); }, {}});
    all.push_back({"vds signed", [&vds, one](const auto& p, double* o) { vds.distance(p, o, one); }, {}});
    // The search alone, in the points' own order: a batch of one a call, so
    // without the batch's Morton order and seeds.
    all.push_back({"vds unsigned, a point a call",
                   [&vds, one](const auto& p, double* o) {
                       for (std::size_t k = 0; k < p.size(); ++k) vds.unsignedDistance(vds::PointsView(&p[k], 1), o + k, one);
                   },
                   {}});
    auto start = Clock::now();
#if defined(VDS_DISTANCE_CGAL)
    std::shared_ptr<vds::peers::DistancePeer> cgal = vds::peers::makeCgalDistance(mesh);
    std::printf("  build %-34s %8.1f ms\n", cgal->name().c_str(), 1e3 * seconds(start));
    all.push_back({cgal->name(), [cgal](const auto& p, double* o) { cgal->distances(p, o); }, {}});
#endif
#if defined(VDS_DISTANCE_EMBREE)
    start = Clock::now();
    std::shared_ptr<vds::peers::DistancePeer> embree = vds::peers::makeEmbreeDistance(mesh);
    std::printf("  build %-34s %8.1f ms\n", embree->name().c_str(), 1e3 * seconds(start));
    all.push_back({embree->name(), [embree](const auto& p, double* o) { embree->distances(p, o); }, {}});
#endif
#if defined(VDS_DISTANCE_LIBIGL)
    start = Clock::now();
    std::shared_ptr<vds::peers::DistancePeer> libigl = vds::peers::makeLibiglDistance(mesh);
    std::printf("  build %-34s %8.1f ms\n", libigl->name().c_str(), 1e3 * seconds(start));
    all.push_back({libigl->name(), [libigl](const auto& p, double* o) { libigl->distances(p, o); }, {}});
#endif
#if defined(VDS_DISTANCE_FCPW)
    start = Clock::now();
    std::shared_ptr<vds::peers::DistancePeer> fcpw = vds::peers::makeFcpwDistance(mesh);
    std::printf("  build %-34s %8.1f ms\n", fcpw->name().c_str(), 1e3 * seconds(start));
    all.push_back({fcpw->name(), [fcpw](const auto& p, double* o) { fcpw->distances(p, o); }, {}});
#endif
    (void)mesh;
    (void)start;
    return all;
}

/// The first line of /proc/cpuinfo that names the CPU ("?" elsewhere).
std::string cpuModel() {
    std::ifstream in("/proc/cpuinfo");
    for (std::string line; std::getline(in, line);)
        if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
    return "?";
}

std::string loadAverage() {
    std::ifstream in("/proc/loadavg");
    std::string one, five, fifteen;
    in >> one >> five >> fifteen;
    return one + " " + five + " " + fifteen;
}

void agreement(const vds::TriangleMesh& mesh, const vds::SignedDistance& vds, const std::vector<glm::vec3>& points,
               const std::vector<Contender>& all, std::size_t bruteCount) {
    const vds::Box box = vds::meshBounds(mesh);
    const double diagonal = glm::length(glm::dvec3(box.hi) - glm::dvec3(box.lo));
    const std::vector<double>& d = all[0].out;
    const std::size_t sample = std::min(bruteCount, points.size());
    double worst = 0.0;
    const auto start = Clock::now();
    for (std::size_t k = 0; k < sample; ++k) worst = std::max(worst, std::abs(d[k] - bruteForce(mesh, points[k])));
    const double bruteSeconds = seconds(start) / double(std::max<std::size_t>(sample, 1));
    std::printf("  brute force: %8.0f ns/point (%zu points), ratio %.0fx; vds - brute max %.2e of the diagonal\n",
                1e9 * bruteSeconds, sample, bruteSeconds * double(points.size()) / all[0].best, worst / diagonal);
    std::vector<std::uint8_t> inside(points.size());
    vds::ClassifyOptions classify;
    classify.rule = vds.rule();
    vds.classifier().classify(points, inside.data(), classify);
    std::size_t signs = 0;
    for (std::size_t k = 0; k < points.size(); ++k) signs += std::signbit(all[1].out[k]) != (inside[k] != 0);
    std::printf("  sign vs exact classifier (%s): %zu of %zu points differ\n", vds::toString(vds.rule()), signs,
                points.size());
    for (std::size_t c = 2; c < all.size(); ++c) {
        double diff = 0.0;
        for (std::size_t k = 0; k < points.size(); ++k) diff = std::max(diff, std::abs(all[c].out[k] - d[k]));
        std::printf("  %-34s - vds max %.2e of the diagonal\n", all[c].name.c_str(), diff / diagonal);
    }
}

/// The SDF grids at n cells on the longest side, 2 threads: the band, the
/// full propagated one and (with --full-grid) the full exact one, whose
/// cells the propagated ones are then compared with.
void grids(const vds::SignedDistance& vds, const vds::TriangleMesh& mesh, std::uint32_t n, double bandCells,
           bool fullGrid) {
    vds::Box box = vds::meshBounds(mesh);
    const glm::vec3 pad = 0.05f * (box.hi - box.lo);
    box.lo -= pad;
    box.hi += pad;
    const vds::Grid grid = vds::cubicGrid(box, n);
    std::vector<float> exact(grid.cellCount()), propagated(grid.cellCount()), band(grid.cellCount());
    const double cell = double(box.hi.x - box.lo.x) / grid.dims.x;
    struct Variant {
        const char* name;
        double band;
        vds::FarCells far;
        std::vector<float>* cells;
    };
    for (const Variant& v : {Variant{"full, exact", 0.0, vds::FarCells::Exact, &exact},
                             Variant{"full, propagated", 0.0, vds::FarCells::Propagated, &propagated},
                             Variant{"band", bandCells * cell, vds::FarCells::Exact, &band}}) {
        if (v.cells == &exact && !fullGrid) continue;
        vds::DistanceGridOptions options;
        options.threads = 2;
        options.band = v.band;
        options.far = v.far;
        const auto start = Clock::now();
        vds.grid(grid, v.cells->data(), options);
        std::printf("  sdf %u x %u x %u, %s, 2 threads: %.2f s\n", grid.dims.x, grid.dims.y, grid.dims.z, v.name,
                    seconds(start));
    }
    if (!fullGrid) return;
    std::vector<double> error(exact.size());
    std::size_t differ = 0;
    for (std::size_t k = 0; k < exact.size(); ++k) {
        error[k] = std::abs(double(propagated[k]) - double(exact[k])) / cell;
        differ += propagated[k] != exact[k];
    }
    double mean = 0.0;
    for (const double e : error) mean += e / double(error.size());
    std::sort(error.begin(), error.end());
    std::printf("  propagated - exact, in cells: %zu of %zu cells differ; mean %.1e, 99.9th percentile %.1e, max %.2f\n",
                differ, exact.size(), mean, error[error.size() * 999 / 1000], error.back());
}

/// `n` points near the surface: on a random triangle (by area), at uniform
/// barycentric coordinates, moved along its normal by up to `reach` either way.
std::vector<glm::vec3> nearSurfacePoints(const vds::TriangleMesh& mesh, std::size_t n, double reach, std::uint32_t seed) {
    std::vector<double> area(mesh.triangles.size());
    for (std::size_t t = 0; t < area.size(); ++t) {
        const glm::uvec3 v = mesh.triangles[t];
        const glm::dvec3 a(mesh.positions[v.x]), b(mesh.positions[v.y]), c(mesh.positions[v.z]);
        area[t] = glm::length(glm::cross(b - a, c - a)) + 1e-30;
    }
    std::mt19937 rng(seed);
    std::discrete_distribution<std::size_t> pick(area.begin(), area.end());
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<glm::vec3> points(n);
    for (glm::vec3& p : points) {
        const glm::uvec3 v = mesh.triangles[pick(rng)];
        const glm::dvec3 a(mesh.positions[v.x]), b(mesh.positions[v.y]), c(mesh.positions[v.z]);
        double r = u(rng), s = u(rng);
        if (r + s > 1.0) r = 1.0 - r, s = 1.0 - s;
        const glm::dvec3 normal = glm::cross(b - a, c - a);
        const double length = glm::length(normal);
        const glm::dvec3 offset = length > 0.0 ? normal * (reach * (2.0 * u(rng) - 1.0) / length) : glm::dvec3(0.0);
        p = glm::vec3(a + (b - a) * r + (c - a) * s + offset);
    }
    return points;
}

void timePoints(const char* label, const std::vector<glm::vec3>& points, std::vector<Contender>& all,
                const Settings& settings) {
    for (Contender& c : all) c.best = std::numeric_limits<double>::infinity();
    for (int round = 0; round < settings.rounds; ++round)
        for (Contender& c : all) {
            c.out.assign(points.size(), 0.0);
            const double start = threadSeconds();
            c.run(points, c.out.data());
            c.best = std::min(c.best, threadSeconds() - start);
        }
    std::printf("  %zu points %s:\n", points.size(), label);
    for (const Contender& c : all)
        std::printf("  %-34s %8.0f ns/point  %5.2fx vds unsigned's time\n", c.name.c_str(),
                    1e9 * c.best / double(points.size()), c.best / all[0].best);
}

void run(const std::string& name, const vds::TriangleMesh& mesh, const Settings& settings) {
    const vds::Box box = vds::meshBounds(mesh);
    const double diagonal = glm::length(glm::dvec3(box.hi) - glm::dvec3(box.lo));
    const auto uniform = vds::test::randomPoints(box, settings.points, 0.1f, 2008);
    const auto near = nearSurfacePoints(mesh, settings.points, 0.01 * diagonal, 2009);
    std::printf("%s: %zu triangles\n", name.c_str(), mesh.triangles.size());
    auto start = Clock::now();
    const vds::SignedDistance vds(mesh, ruleFor(mesh), name);
    std::printf("  build %-34s %8.1f ms (%s)\n", "vds", 1e3 * seconds(start), vds.summary().c_str());
    std::vector<Contender> all = contenders(vds, mesh);
    timePoints("uniform in the box grown by 10%", uniform, all, settings);
    agreement(mesh, vds, uniform, all, settings.brute);
    timePoints("within 1% of the diagonal of the surface", near, all, settings);
    agreement(mesh, vds, near, all, settings.brute);
    if (settings.sdf > 0 && mesh.triangles.size() >= 50000) grids(vds, mesh, settings.sdf, settings.band, settings.fullGrid);
}

} // namespace

int main(int argc, char** argv) {
    CLI::App app("vds_distance_bench: exact distances against brute force, CGAL, Embree, libigl and fcpw");
    Settings settings;
    std::vector<std::string> meshes;
    app.add_option("--points", settings.points, "random points of each set (uniform, near the surface)");
    app.add_option("--brute", settings.brute, "of them, checked against brute force");
    app.add_option("--rounds", settings.rounds, "alternated rounds, the best kept");
    app.add_option("--sdf", settings.sdf, "cells of the SDF grids on the longest side (0: none), meshes of 50k triangles up");
    app.add_option("--band", settings.band, "the band grid's half-width in cells");
    app.add_flag("--full-grid", settings.fullGrid, "the full exact SDF grid too (minutes), and the propagated one checked against it");
    std::vector<std::string> generated;
    app.add_option("--generated", generated, "generated meshes to run (default without mesh files: all four)")
        ->check(CLI::IsMember({"sphere", "trefoil", "soup", "holes"}));
    app.add_option("meshes", meshes, "mesh files (default: the generated meshes)");
    CLI11_PARSE(app, argc, argv);
    std::printf("%s, load average %s\n", cpuModel().c_str(), loadAverage().c_str());
    try {
        if (meshes.empty() && generated.empty()) generated = {"sphere", "trefoil", "soup", "holes"};
        for (const std::string& g : generated) {
            if (g == "sphere") run("sphere", vds::solids::sphere(glm::vec3(0.0f), 1.0f, 316).mesh, settings);
            else if (g == "trefoil")
                run("trefoil", vds::solids::torusKnot(glm::vec3(0.0f), 1.0f, 2, 3, 0.25f, 800, 64).mesh, settings);
            else if (g == "soup") run("soup (open)", vds::solids::looseTriangles(20000, 0.05f, 9), settings);
            else run("sphere with holes (open)", vds::solids::sphereWithHoles(), settings);
        }
        for (const std::string& path : meshes) run(path, vds::loadMesh(path), settings);
    } catch (const vds::Error& e) {
        std::fprintf(stderr, "vds_distance_bench: %s\n", e.what());
        return 1;
    }
    return 0;
}
