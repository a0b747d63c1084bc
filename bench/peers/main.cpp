// vds_peers_bench: vds against the inside tests people use today, side by
// side in one run, on the same points, each answer checked against the exact
// classifier. Prints Markdown tables; asserts nothing about speed.
//
//   vds_peers_bench [--points N] [--grids 128,256,512] [--full] [--threads T]
//                   [--resolution R] [--cgal-limit N] [--no-generated] [MESH ...]
//
// Methods, every one a vds::Classifier driven through the library's one
// contract (<vds/classify.h>); a peer is compiled in only when CMake found it:
//  - vds exact:     Method::Exact (<vds/exact.h>), the reference for "wrong";
//  - vds certified: Method::Certified (<vds/certified.h>): sprite-like bands
//                   at R, the exact classifier where they cannot decide;
//                   exact answers (its "wrong" is counted like the others');
//  - vds sprite:    Method::Sprite, baked on the CPU at R (default 1024),
//                   QueryLayout::Auto, on 1 and on T threads;
//  - vds sprite sweep: grids only, `Classifier::occupancy` of the same
//                   sprite: one walk per column, the same answers as vds
//                   sprite on every cell;
//  - vds exact sweep: grids only, vds::occupancy of the mesh: the exact
//                   column sweep, no sprite (its build is part of its query time);
//  - Embree:        ray parity as in trimesh (embree_parity.h), TBB threads;
//  - CGAL:          Side_of_triangle_mesh on a Surface_mesh<Epick> (cgal_side.h),
//                   one thread, as users get it.
// vds's methods are made by `vds::makeClassifier` and named by their
// `MethodInfo`; the peers are Method::Custom classifiers.
// Point sets, per mesh: N uniform random points in the mesh box grown by 10 %
// on each side, then the cell centres of n^3 grids over the mesh box
// (vds::Grid: centre lo + (i+1/2, j+1/2, k+1/2) (hi - lo) / n).
//
// Timing: std::chrono::steady_clock; one warm-up run, then the best of three.
// A run whose warm-up took more than 1 s is timed on that run alone (marked).
// Build times are one run each. The per-point methods classify grids of more
// than 2^24 cells in slabs of x layers, their times summed; the sweeps label
// the whole grid in one call.
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <CLI/CLI.hpp>

#include <vds/all.h>
#include <vds/bake.h>
#include <vds/certified.h>
#include <vds/error.h>
#include <vds/exact.h>
#include <vds/mesh.h>
#include <vds/mesh_check.h>
#include <vds/mesh_io.h>
#include <vds/occupancy.h>
#include <vds/sprite.h>

#include "points.h"
#include "solids.h"
#if VDS_PEERS_EMBREE
#include "embree_parity.h"
#endif
#if VDS_PEERS_CGAL
#include "cgal_side.h"
#endif

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

constexpr double kTimeOnceAbove = 1.0;               // seconds: warm-up long enough to be the measurement
constexpr std::size_t kSlabPoints = std::size_t(1) << 24; // grid points held at once

double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

struct Case {
    std::string name;
    vds::TriangleMesh mesh;
};

// The points one call classifies: random points, or x layers [i0, i1) of a
// grid, their centres in the grid's order (C order, k fastest).
struct Slab {
    const glm::vec3* points = nullptr;
    std::size_t count = 0;
};

struct Method {
    std::string name;
    unsigned threads = 1;
    double buildSeconds = 0.0;
    // Per-point methods classify a slab; grid methods (sweeps) label a whole grid.
    std::function<void(const Slab&, std::uint8_t*)> run;
    std::function<void(const vds::Grid&, std::uint8_t*)> runGrid;
    bool gridOnly() const { return bool(runGrid); }
};

struct Row {
    std::string mesh;
    std::size_t triangles = 0;
    std::string method;
    unsigned threads = 0;
    double build = 0.0;
    double query = 0.0;
    std::size_t points = 0;
    std::size_t wrong = 0;
    bool timedOnce = false;
    bool skipped = false;
    std::string why; // when skipped
};

struct PointSet {
    std::string title;
    std::uint32_t grid = 0; // 0: random points
    std::vector<Row> rows;
};

// Warm-up, then the best of three; every run writes the same labels.
template <class Run> double timeBest(const Run& run, bool& timedOnce) {
    auto t0 = Clock::now();
    run();
    double best = since(t0);
    if (best > kTimeOnceAbove) {
        timedOnce = true;
        return best;
    }
    best = 1e300;
    for (int r = 0; r < 3; ++r) {
        t0 = Clock::now();
        run();
        best = std::min(best, since(t0));
    }
    return best;
}

std::string cpuModel() {
    std::ifstream in("/proc/cpuinfo");
    for (std::string line; std::getline(in, line);)
        if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
    return "unknown CPU";
}

std::vector<Case> generatedCases() {
    using namespace vds::solids;
    std::vector<Case> cases;
    // Three disjoint boxes: 36 triangles, the smallest closed mesh worth a BVH.
    vds::TriangleMesh boxes = merge(merge(box({0.0f, 0.0f, 0.0f}, {1.0f, 1.0f, 1.0f}).mesh,
                                          box({1.5f, 0.2f, 0.3f}, {2.5f, 1.4f, 0.9f}).mesh),
                                    box({0.4f, 1.6f, 0.1f}, {2.2f, 2.1f, 1.7f}).mesh);
    cases.push_back({"3 boxes", std::move(boxes)});
    cases.push_back({"torus 32", torus({0, 0, 0}, 1.0f, 0.35f, 32).mesh});
    cases.push_back({"sphere 128", sphere({0, 0, 0}, 1.0f, 128).mesh});
    cases.push_back({"sphere 1002", sphere({0, 0, 0}, 1.0f, 1002).mesh});
    return cases;
}

std::vector<std::string> defaultMeshPaths(const std::string& dir) {
    std::vector<std::string> paths;
    for (const char* name : {"spot.obj", "fandisk.obj", "rocker-arm.obj"}) {
        const fs::path p = fs::path(dir) / name;
        if (fs::exists(p)) paths.push_back(p.string());
    }
    return paths;
}

// The first is always vds exact (the reference); the sprite on T threads is
// kSprite, its sweep kSweep; the peers compiled in follow.
constexpr std::size_t kExact = 0;

// A classifier as a benchmark row: per-point methods classify a slab; the
// sweeps (`grid` true) label a whole grid through `Classifier::occupancy`.
Method row(std::string name, std::shared_ptr<const vds::Classifier> c, unsigned threads, double build,
           bool grid = false) {
    Method m{std::move(name), threads, build, {}, {}};
    if (grid)
        m.runGrid = [c, threads](const vds::Grid& g, std::uint8_t* out) {
            c->occupancy(g, out, {vds::Rule::Parity, threads});
        };
    else
        m.run = [c, threads](const Slab& s, std::uint8_t* out) {
            c->classify(vds::PointsView(s.points, s.count), out, {vds::Rule::Parity, threads});
        };
    return m;
}

// Every method through the library's one contract: vds's own by
// `vds::makeClassifier` and their `MethodInfo` names, the peers as Custom
// classifiers.
std::vector<Method> buildMethods(const vds::TriangleMesh& mesh, unsigned threads, std::uint32_t resolution,
                                 std::string& spriteShape, std::size_t& kSprite, std::size_t& kSweep) {
    std::vector<Method> methods;
    const std::string at = " @" + std::to_string(resolution);
    vds::MethodOptions options;
    options.resolution = resolution;
    options.axis = vds::Axis::Z;
    options.bakeMethod = vds::BakeMethod::Cpu;
    options.threads = threads;
    const auto make = [&](vds::Method method, double& seconds) {
        const auto t0 = Clock::now();
        std::shared_ptr<const vds::Classifier> c = vds::makeClassifier(mesh, method, options);
        seconds = since(t0);
        return c;
    };
    const auto name = [](vds::Method method) { return std::string("vds ") + vds::methodInfo(method).name; };

    double build = 0.0;
    const auto exact = make(vds::Method::Exact, build);
    methods.push_back(row(name(vds::Method::Exact), exact, threads, build));
    const auto certified = make(vds::Method::Certified, build);
    methods.push_back(row(name(vds::Method::Certified) + at, certified, threads, build));
    const auto sprite = make(vds::Method::Sprite, build);
    spriteShape = sprite->summary();
    for (unsigned t : {1u, threads}) {
        if (t == 1 && threads == 1) continue;
        methods.push_back(row(name(vds::Method::Sprite) + at, sprite, t, build));
    }
    kSprite = methods.size() - 1;
    methods.push_back(row(name(vds::Method::Sprite) + " sweep" + at, sprite, threads, build, true));
    kSweep = methods.size() - 1;
    // The exact column sweep from the mesh: its build is part of its query time.
    const vds::TriangleMesh* meshPtr = &mesh;
    Method voxelize{"vds exact sweep (occupancy of the mesh)", threads, 0.0, {}, {}};
    voxelize.runGrid = [meshPtr, threads](const vds::Grid& g, std::uint8_t* out) {
        vds::occupancy(*meshPtr, g, out, {vds::Rule::Parity, threads});
    };
    methods.push_back(voxelize);

#if VDS_PEERS_EMBREE
    const auto embreeStart = Clock::now();
    std::shared_ptr<const vds::Classifier> embree = vds::peers::makeEmbreeParity(mesh, threads);
    methods.push_back(row("Embree parity", embree, threads, since(embreeStart)));
#endif
#if VDS_PEERS_CGAL
    const auto cgalStart = Clock::now();
    std::shared_ptr<const vds::Classifier> cgal = vds::peers::makeCgalSide(mesh);
    methods.push_back(row("CGAL Side_of_triangle_mesh", cgal, 1, since(cgalStart)));
#endif
    return methods;
}

bool isCgal(const Method& m) { return m.name.rfind("CGAL", 0) == 0; }

// Centres of the cells of x layers [i0, i1) of `grid`, in its order.
void cellCentres(const vds::Grid& grid, std::uint32_t i0, std::uint32_t i1, glm::vec3* out, unsigned threads) {
    const std::size_t perLayer = std::size_t(grid.dims.y) * grid.dims.z;
    // Layer i on thread i % threads: the layers cost the same.
    std::vector<std::thread> crew;
    for (unsigned t = 0; t < threads; ++t)
        crew.emplace_back([&, t] {
            for (std::size_t i = t; i < i1 - i0; i += threads)
                for (std::uint32_t j = 0; j < grid.dims.y; ++j)
                    for (std::uint32_t k = 0; k < grid.dims.z; ++k)
                        out[i * perLayer + std::size_t(j) * grid.dims.z + k] =
                            grid.cellCentre(std::uint32_t(i0 + i), j, k);
        });
    for (std::thread& worker : crew) worker.join();
}

// Runs every method on one point set of one mesh and appends one row per
// method to `set`: the sweeps on the whole grid, the others slab by slab.
void measureSet(PointSet& set, const Case& c, const std::vector<Method>& methods, const std::vector<glm::vec3>& random,
                unsigned threads, std::size_t cgalLimit, std::size_t kSprite, std::size_t kSweep) {
    const std::size_t total = set.grid ? std::size_t(set.grid) * set.grid * set.grid : random.size();
    std::vector<Row> rows(methods.size());
    for (std::size_t m = 0; m < methods.size(); ++m) {
        rows[m] = {c.name, c.mesh.triangles.size(), methods[m].name, methods[m].threads, methods[m].buildSeconds};
        rows[m].points = total;
        if (methods[m].gridOnly() && !set.grid) {
            rows[m].skipped = true;
            rows[m].why = "grids only";
        } else if (isCgal(methods[m]) && total > cgalLimit) {
            rows[m].skipped = true;
            rows[m].why = "more points than --cgal-limit";
        }
    }

    vds::Grid grid;
    std::vector<glm::vec3> centres;
    std::uint32_t layers = 0;
    std::vector<std::vector<std::uint8_t>> whole(methods.size()); // the sweeps' labels
    if (set.grid) {
        grid = {vds::meshBounds(c.mesh), glm::uvec3(set.grid)};
        const std::size_t perLayer = std::size_t(set.grid) * set.grid;
        layers = std::uint32_t(std::clamp<std::size_t>(kSlabPoints / perLayer, 1, set.grid));
        centres.resize(std::size_t(layers) * perLayer);
        for (std::size_t m = 0; m < methods.size(); ++m) {
            if (!methods[m].gridOnly() || rows[m].skipped) continue;
            whole[m].resize(total);
            rows[m].query = timeBest([&] { methods[m].runGrid(grid, whole[m].data()); }, rows[m].timedOnce);
        }
    }
    std::vector<std::vector<std::uint8_t>> labels(methods.size());
    std::size_t sweepDiffers = 0;
    const std::uint32_t slabs = set.grid ? (set.grid + layers - 1) / layers : 1;
    for (std::uint32_t slabIndex = 0; slabIndex < slabs; ++slabIndex) {
        Slab slab;
        std::size_t first = 0; // of the slab's cells in the grid
        if (set.grid) {
            const std::uint32_t i0 = slabIndex * layers, i1 = std::min(set.grid, i0 + layers);
            slab.count = std::size_t(i1 - i0) * set.grid * set.grid;
            first = std::size_t(i0) * set.grid * set.grid;
            cellCentres(grid, i0, i1, centres.data(), threads);
            slab.points = centres.data();
        } else {
            slab.points = random.data();
            slab.count = random.size();
        }
        for (std::size_t m = 0; m < methods.size(); ++m) {
            if (rows[m].skipped || methods[m].gridOnly()) continue;
            labels[m].resize(slab.count);
            bool once = false;
            rows[m].query += timeBest([&] { methods[m].run(slab, labels[m].data()); }, once);
            rows[m].timedOnce = rows[m].timedOnce || once;
        }
        for (std::size_t m = 0; m < methods.size(); ++m) {
            if (rows[m].skipped) continue;
            const std::uint8_t* mine = methods[m].gridOnly() ? whole[m].data() + first : labels[m].data();
            for (std::size_t k = 0; k < slab.count; ++k) rows[m].wrong += mine[k] != labels[kExact][k];
        }
        // The sweep must give the sprite's answers exactly.
        if (set.grid)
            for (std::size_t k = 0; k < slab.count; ++k) sweepDiffers += labels[kSprite][k] != whole[kSweep][first + k];
    }
    if (sweepDiffers)
        throw std::logic_error("the sweep differs from the sprite on " + std::to_string(sweepDiffers) + " points of " +
                               c.name + ", " + set.title);
    set.rows.insert(set.rows.end(), rows.begin(), rows.end());
}

void printTable(const PointSet& set) {
    std::printf("\n### %s\n\n", set.title.c_str());
    const bool grid = set.grid != 0;
    std::printf("| mesh | triangles | method | threads | build s | M points/s | × Embree | wrong |%s\n",
                grid ? " query s | build + query s |" : "");
    std::printf("|---|---:|---|---:|---:|---:|---:|---:|%s\n", grid ? "---:|---:|" : "");
    bool anyOnce = false;
    for (const Row& r : set.rows) {
        if (r.skipped && r.why == "grids only") continue;
        std::printf("| %s | %zu | %s | %u | %.3f | ", r.mesh.c_str(), r.triangles, r.method.c_str(), r.threads, r.build);
        if (r.skipped) {
            std::printf("— (%s) | | |%s\n", r.why.c_str(), grid ? " | |" : "");
            continue;
        }
        const double rate = double(r.points) / r.query;
        double embreeRate = 0.0;
        for (const Row& e : set.rows)
            if (e.mesh == r.mesh && e.method == "Embree parity" && !e.skipped) embreeRate = double(e.points) / e.query;
        std::printf("%.3g%s | ", rate / 1e6, r.timedOnce ? "*" : "");
        if (embreeRate > 0.0) std::printf("%.2f | ", rate / embreeRate);
        else std::printf("— | ");
        if (r.wrong) std::printf("%zu (%.3g %%) |", r.wrong, 100.0 * double(r.wrong) / double(r.points));
        else std::printf("0 |");
        if (grid) std::printf(" %.3f | %.3f |", r.query, r.build + r.query);
        std::printf("\n");
        anyOnce = anyOnce || r.timedOnce;
    }
    if (anyOnce) std::printf("\n\\* timed once: its warm-up run took more than %.0f s.\n", kTimeOnceAbove);
}

// Which peers this program was built with, and which it lacks.
void printPeers() {
    std::string compiled, missing;
#if VDS_PEERS_EMBREE
    compiled += vds::peers::embreeVersion() + " ray parity (TBB)";
#else
    missing += "Embree (libembree-dev, libtbb-dev)";
#endif
#if VDS_PEERS_CGAL
    compiled += (compiled.empty() ? "" : ", ") + vds::peers::cgalVersion() + " Side_of_triangle_mesh";
#else
    missing += std::string(missing.empty() ? "" : ", ") + "CGAL (libcgal-dev)";
#endif
    std::printf("peers compiled in: %s\n", compiled.empty() ? "none" : compiled.c_str());
    if (!missing.empty())
        std::printf("peers missing (not found when this program was built): %s; see bench/install-peers.sh\n",
                    missing.c_str());
}

// Every closed case against every point set (the open ones are skipped, said so in the table).
void runCases(const std::vector<Case>& cases, std::vector<PointSet>& sets, std::size_t pointCount, unsigned threads,
              std::uint32_t resolution, std::size_t cgalLimit) {
    std::printf("\n| mesh | triangles | sprite |\n|---|---:|---|\n");
    for (const Case& c : cases) {
        const vds::MeshReport report = vds::validateMesh(c.mesh);
        if (!report.closed()) {
            std::printf("| %s | %zu | skipped: %s |\n", c.name.c_str(), c.mesh.triangles.size(), report.summary().c_str());
            continue;
        }
        std::string shape;
        std::size_t kSprite = 0, kSweep = 0;
        const std::vector<Method> methods = buildMethods(c.mesh, threads, resolution, shape, kSprite, kSweep);
        std::printf("| %s | %zu | %s |\n", c.name.c_str(), c.mesh.triangles.size(), shape.c_str());
        std::fflush(stdout);
        const std::vector<glm::vec3> random = vds::test::randomPoints(vds::meshBounds(c.mesh), pointCount);
        for (PointSet& set : sets) {
            const auto t0 = Clock::now();
            measureSet(set, c, methods, random, threads, cgalLimit, kSprite, kSweep);
            std::fprintf(stderr, "  %s, %s: %.1f s\n", c.name.c_str(), set.title.c_str(), since(t0));
        }
    }
}

} // namespace

int main(int argc, char** argv) {
    CLI::App app{"vds against Embree ray parity and CGAL Side_of_triangle_mesh, on the same points; "
                 "wrong answers counted against vds's exact classifier"};
    std::size_t pointCount = 1000000;
    std::vector<std::uint32_t> grids = {128, 256, 512};
    bool full = false;
    bool generated = true;
    unsigned threads = std::max(1u, std::thread::hardware_concurrency());
    std::uint32_t resolution = 1024;
    std::size_t cgalLimit = 20000000;
    std::string meshDir = VDS_PEERS_MESH_DIR;
    std::vector<std::string> meshPaths;
    app.add_option("--points", pointCount, "uniform random points per mesh, in its box grown by 10 % per side")
        ->capture_default_str()
        ->check(CLI::PositiveNumber);
    app.add_option("--grids", grids, "grid sizes n (n^3 cell centres over the mesh box)")
        ->delimiter(',')
        ->allow_extra_args(false)
        ->capture_default_str()
        ->check(CLI::Range(1u, 4096u));
    app.add_flag("--full", full, "add the 1024^3 grid (an hour and more on two cores)");
    app.add_option("--threads", threads, "query threads for vds and Embree (CGAL runs on one)")
        ->capture_default_str()
        ->check(CLI::Range(1u, 1024u));
    app.add_option("--resolution", resolution, "sprite resolution")->capture_default_str()->check(CLI::Range(1u, 16384u));
    app.add_option("--cgal-limit", cgalLimit, "skip CGAL on point sets larger than this")->capture_default_str();
    app.add_option("--mesh-dir", meshDir, "where spot.obj, fandisk.obj and rocker-arm.obj are read from")
        ->capture_default_str();
    app.add_flag("!--no-generated", generated, "leave out the generated boxes, tori and spheres");
    app.add_option("meshes", meshPaths, "closed meshes to use instead of those of bench/meshes");
    CLI11_PARSE(app, argc, argv);
    if (full)
        for (std::uint32_t n : {1024u})
            if (std::find(grids.begin(), grids.end(), n) == grids.end()) grids.push_back(n);

    try {
        std::printf("vds_peers_bench: %s, %u hardware threads; vds and Embree query on %u threads, CGAL on 1\n",
                    cpuModel().c_str(), std::thread::hardware_concurrency(), threads);
        printPeers();

        std::vector<Case> cases;
        if (meshPaths.empty()) meshPaths = defaultMeshPaths(meshDir);
        if (meshPaths.empty())
            std::printf("no meshes in %s (bench/fetch-meshes.sh downloads them): generated meshes only\n",
                        meshDir.c_str());
        for (const auto& path : meshPaths) cases.push_back({fs::path(path).filename().string(), vds::loadMesh(path)});
        if (generated)
            for (auto& c : generatedCases()) cases.push_back(std::move(c));

        std::vector<PointSet> sets;
        sets.push_back({std::to_string(pointCount) + " uniform random points in the mesh box grown by 10 % per side",
                        0,
                        {}});
        for (std::uint32_t n : grids)
            sets.push_back({"grid " + std::to_string(n) + "³ (" + std::to_string(std::size_t(n) * n * n) +
                                " cell centres over the mesh box)",
                            n,
                            {}});

        runCases(cases, sets, pointCount, threads, resolution, cgalLimit);
        for (const PointSet& set : sets) printTable(set);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "vds_peers_bench: %s\n", e.what());
        return 1;
    }
    return 0;
}
