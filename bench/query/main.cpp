// Query benchmark: how fast each of vds's CPU paths answers, in one run, on
// the same points and threads, with wrong answers counted against the exact
// classifier. Random points: the sprite with its two column layouts, the
// exact classifier, the certified classifier. Grids: the exact column sweep
// and the sprite's sweep against classifying the cell centres one by one.
// Prints Markdown tables (docs/benchmarks.md).
//
//   vds_query_bench [--points N] [--grids 128,256,512] [--resolution 1024] [--threads T] [MESH ...]
#include <chrono>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include <vds/all.h>
#include <vds/bake.h>
#include <vds/certified.h>
#include <vds/exact.h>
#include <vds/mesh_io.h>
#include <vds/occupancy.h>

#include "solids.h"

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// Best of `repeats` timings of `work` (after it ran once untimed).
template <class Work> double best(int repeats, const Work& work) {
    work();
    double fastest = 1e30;
    for (int r = 0; r < repeats; ++r) {
        const auto start = Clock::now();
        work();
        fastest = std::min(fastest, secondsSince(start));
    }
    return fastest;
}

std::size_t differing(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b) {
    std::size_t n = 0;
    for (std::size_t k = 0; k < a.size(); ++k) n += a[k] != b[k];
    return n;
}

struct Input {
    std::string name;
    vds::TriangleMesh mesh;
};

void randomPoints(const Input& in, std::size_t count, std::uint32_t resolution, unsigned threads) {
    const vds::Box b = vds::meshBounds(in.mesh);
    std::mt19937 rng(1);
    std::uniform_real_distribution<float> u(-0.1f, 1.1f);
    std::vector<glm::vec3> points(count);
    for (auto& p : points) p = b.lo + glm::vec3(u(rng), u(rng), u(rng)) * (b.hi - b.lo);
    vds::BakeOptions o;
    o.resolution = resolution;
    o.method = vds::BakeMethod::Cpu;
    auto start = Clock::now();
    const vds::Sprite sprite = vds::bake(in.mesh, o);
    const double bakeSeconds = secondsSince(start);
    start = Clock::now();
    const vds::ExactClassifier exact(in.mesh);
    const double exactBuild = secondsSince(start);
    start = Clock::now();
    const vds::CertifiedClassifier certified(in.mesh, {resolution, vds::Axis::Z, threads});
    const double certifiedBuild = secondsSince(start);

    std::vector<std::uint8_t> truth(count), labels(count);
    const double exactSeconds = best(1, [&] { exact.classify(vds::PointsView(points.data(), count), truth.data(), {vds::Rule::Parity, threads}); });
    struct Row {
        const char* method;
        unsigned threads;
        double build, seconds;
        std::size_t wrong;
        std::string note;
    };
    std::vector<Row> rows;
    for (unsigned t : {1u, threads}) {
        for (vds::QueryLayout layout : {vds::QueryLayout::Offsets, vds::QueryLayout::Packed}) {
            const vds::ClassifyOptions co{vds::Rule::Parity, t};
            const double s = best(2, [&] {
                vds::classify(sprite, vds::PointsView(points.data(), count), labels.data(), co, {layout});
            });
            rows.push_back({layout == vds::QueryLayout::Packed ? "sprite, packed columns" : "sprite, offsets", t,
                            bakeSeconds, s, differing(labels, truth), ""});
        }
        if (t == threads && threads == 1) break;
    }
    vds::ClassifyStats stats;
    const double certifiedSeconds = best(2, [&] {
        vds::ClassifyOptions options{vds::Rule::Parity, threads};
        options.stats = &stats;
        certified.classify(vds::PointsView(points.data(), count), labels.data(), options);
    });
    char note[64];
    std::snprintf(note, sizeof note, "%.3f%% to the exact path", 100.0 * double(stats.exact) / double(count));
    rows.push_back({"certified", threads, certifiedBuild, certifiedSeconds, differing(labels, truth), note});
    rows.push_back({"exact", threads, exactBuild, exactSeconds, 0, ""});

    std::printf("\n### %s: %zu triangles, %zu uniform points in the box grown by 10%%, sprite and bands at %u\n\n",
                in.name.c_str(), in.mesh.triangles.size(), count, resolution);
    std::printf("| method | threads | build s | M points/s | vs exact | wrong | |\n|---|---|---|---|---|---|---|\n");
    for (const Row& r : rows)
        std::printf("| %s | %u | %.2f | %.1f | %.1fx | %zu | %s |\n", r.method, r.threads, r.build,
                    double(count) / r.seconds * 1e-6, exactSeconds / r.seconds, r.wrong, r.note.c_str());
}

void grids(const Input& in, const std::vector<std::uint32_t>& sizes, std::uint32_t resolution, unsigned threads) {
    std::printf("\n### %s: occupancy grids (cubic cells over the bounding box)\n\n", in.name.c_str());
    std::printf("| cells | exact sweep G cells/s | sprite sweep G cells/s | sprite per point G cells/s | exact per point "
                "G cells/s | sweep vs exact per point | wrong (exact sweep, sprite sweep) |\n"
                "|---|---|---|---|---|---|---|\n");
    vds::BakeOptions o;
    o.resolution = resolution;
    o.method = vds::BakeMethod::Cpu;
    const vds::Sprite sprite = vds::bake(in.mesh, o);
    const vds::ExactClassifier exact(in.mesh);
    for (std::uint32_t n : sizes) {
        const vds::Grid grid = vds::cubicGrid(vds::meshBounds(in.mesh), n);
        const std::size_t cells = grid.cellCount();
        std::vector<std::uint8_t> swept(cells), spriteSwept(cells), perPoint(cells), truth(cells);
        const vds::ClassifyOptions opt{vds::Rule::Parity, threads};
        const double sweep = best(2, [&] { vds::occupancy(in.mesh, grid, swept.data(), opt); });
        const double spriteSweep = best(2, [&] { vds::occupancy(sprite, grid, spriteSwept.data(), opt); });
        std::vector<glm::vec3> centres;
        centres.reserve(cells);
        for (std::uint32_t i = 0; i < grid.dims.x; ++i)
            for (std::uint32_t j = 0; j < grid.dims.y; ++j)
                for (std::uint32_t k = 0; k < grid.dims.z; ++k) centres.push_back(grid.cellCentre(i, j, k));
        const double spritePoints =
            best(1, [&] { vds::classify(sprite, vds::PointsView(centres.data(), cells), perPoint.data(), {vds::Rule::Parity, threads}); });
        const auto start = Clock::now();
        exact.classify(vds::PointsView(centres.data(), cells), truth.data(), {vds::Rule::Parity, threads});
        const double exactPoints = secondsSince(start);
        std::printf("| %ux%ux%u | %.2f | %.2f | %.3f | %.4f | %.0fx | %zu, %zu |\n", grid.dims.x, grid.dims.y,
                    grid.dims.z, cells / sweep * 1e-9, cells / spriteSweep * 1e-9, cells / spritePoints * 1e-9,
                    cells / exactPoints * 1e-9, exactPoints / sweep, differing(swept, truth),
                    differing(spriteSwept, truth));
    }
}

} // namespace

int main(int argc, char** argv) {
    CLI::App app("vds query benchmark: sprite layouts, certified and exact classification, occupancy sweeps");
    std::size_t points = 4000000;
    std::vector<std::uint32_t> sizes{128, 256};
    std::uint32_t resolution = 1024;
    unsigned threads = 2;
    std::vector<std::string> meshes;
    app.add_option("--points", points, "uniform random points per mesh")->capture_default_str();
    app.add_option("--grids", sizes, "cubic grid sizes (cells on the longest side)")->allow_extra_args(false)->delimiter(',')->capture_default_str();
    app.add_option("--resolution", resolution, "sprite and band resolution")->capture_default_str()->check(CLI::Range(1u, 16384u));
    app.add_option("--threads", threads, "threads for the multi-threaded rows")->capture_default_str()->check(CLI::Range(1u, 256u));
    app.add_option("MESH", meshes, "meshes (default: a generated torus and sphere)");
    CLI11_PARSE(app, argc, argv);
    try {
        std::vector<Input> inputs;
        for (const std::string& path : meshes) inputs.push_back({path.substr(path.find_last_of('/') + 1), vds::loadMesh(path)});
        if (inputs.empty()) {
            inputs.push_back({"torus (generated)", vds::solids::torus({0, 0, 0}, 1.0f, 0.35f, 256).mesh});
            inputs.push_back({"sphere (generated)", vds::solids::sphere({0, 0, 0}, 1.0f, 512).mesh});
        }
        std::printf("# vds query benchmark: %zu points, sprite/bands at %u, %u threads\n", points, resolution, threads);
        for (const Input& in : inputs) {
            randomPoints(in, points, resolution, threads);
            grids(in, sizes, resolution, threads);
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "vds_query_bench: %s\n", e.what());
        return 1;
    }
    return 0;
}
