// vds_exact_embree_bench: the plain exact classifier against Embree ray
// parity on the same random points (the mesh box grown by 10 %), the two
// timed in alternation in one process so that both see the same machine
// load; prints the best of R rounds of each, their ratio, and how many
// answers differ. By default the two meshes where the ratio is lowest: the
// rocker arm and the generated 1M-triangle UV sphere ("sphere 1002").
//
//   vds_exact_embree_bench [--points N] [--threads T] [--rounds R] [MESH ...]
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include <vds/exact.h>
#include <vds/mesh.h>
#include <vds/mesh_io.h>

#include "embree_parity.h"
#include "points.h"
#include "solids.h"

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

struct Case {
    std::string name;
    vds::TriangleMesh mesh;
};

} // namespace

int main(int argc, char** argv) {
    std::size_t pointCount = 1000000;
    unsigned threads = 2;
    int rounds = 5;
    std::vector<std::string> paths;
    CLI::App app{"vds exact classifier against Embree ray parity"};
    app.add_option("--points", pointCount, "random points per mesh");
    app.add_option("--threads", threads, "threads of both");
    app.add_option("--rounds", rounds, "alternating timed rounds (best of each)");
    app.add_option("meshes", paths, "OBJ/PLY/STL meshes (default: rocker arm and sphere 1002)");
    CLI11_PARSE(app, argc, argv);

    std::vector<Case> cases;
    const bool defaults = paths.empty();
    if (defaults) {
        const std::filesystem::path rocker = std::filesystem::path(VDS_PEERS_MESH_DIR) / "rocker-arm.obj";
        if (std::filesystem::exists(rocker)) paths.push_back(rocker.string());
    }
    for (const std::string& p : paths) cases.push_back({std::filesystem::path(p).stem().string(), vds::loadMesh(p)});
    if (defaults) cases.push_back({"sphere 1002", vds::solids::sphere({0, 0, 0}, 1.0f, 1002).mesh});

    std::printf("| mesh | triangles | exact build s | exact Mpts/s | Embree Mpts/s | exact/Embree | differ |\n");
    std::printf("|---|---:|---:|---:|---:|---:|---:|\n");
    for (const Case& c : cases) {
        const std::vector<glm::vec3> points = vds::test::randomPoints(vds::meshBounds(c.mesh), pointCount);
        auto t0 = Clock::now();
        const vds::ExactClassifier exact(c.mesh, vds::Axis::Z);
        const double build = since(t0);
        const auto embree = vds::peers::makeEmbreeParity(c.mesh, threads);
        std::vector<std::uint8_t> a(points.size()), b(points.size());
        exact.classify({points.data(), points.size()}, a.data(), {vds::Rule::Parity, threads});
        embree->classify(vds::PointsView(points), b.data());
        double te = 1e300, tb = 1e300;
        for (int r = 0; r < rounds; ++r) {
            t0 = Clock::now();
            exact.classify({points.data(), points.size()}, a.data(), {vds::Rule::Parity, threads});
            te = std::min(te, since(t0));
            t0 = Clock::now();
            embree->classify(vds::PointsView(points), b.data());
            tb = std::min(tb, since(t0));
        }
        std::size_t differ = 0;
        for (std::size_t k = 0; k < points.size(); ++k) differ += a[k] != b[k];
        std::printf("| %s | %zu | %.3f | %.2f | %.2f | %.2fx | %zu |\n", c.name.c_str(), c.mesh.triangles.size(), build,
                    points.size() / te * 1e-6, points.size() / tb * 1e-6, tb / te, differ);
        std::fflush(stdout);
    }
}
