// Layout benchmark: vds::classify on uniform random points with the sprite's
// own arrays (QueryLayout::Offsets) against the packed table
// (QueryLayout::Packed, built inside each call and timed with it), and, on
// one thread, the packed layout the library had before (16-byte records with
// two crossings, tested with branches; re-implemented below exactly as it
// was, on the public Sprite arrays): before this change QueryLayout::Auto
// chose it for batches of at least four points a column, the offsets layout
// for smaller ones. In one process, rounds interleaved so all see the same
// load. Checks that all give the same label on every point. Prints a
// Markdown table (docs/benchmarks.md).
//
// Each row gives two rates: per second of the process's CPU time
// (CLOCK_PROCESS_CPUTIME_ID: on a shared machine that leaves out the time a
// thread waited for a core; on two threads it is the rate of one busy
// thread, so it drops when the threads slow each other down, in memory) and
// per second of wall time (what a caller waits, load included).
//
//   vds_layout_bench [--points N] [--resolution R] [--rounds K] [MESH ...]
#include <algorithm>
#include <cmath>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include <vds/all.h>
#include <vds/bake.h>
#include <vds/mesh_io.h>
#include <vds/sprite.h>

#include "points.h"
#include "solids.h"

namespace {

double cpuSeconds() {
    timespec ts{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

double wallSeconds() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// The previous packed layout, as vds::classify ran it (one thread).
struct PreviousRecord {
    float first[2];
    std::uint32_t begin, count;
};

void classifyPrevious(const vds::Sprite& sprite, const glm::vec3* points, std::size_t count, std::uint8_t* labels) {
    constexpr float kPadding = 2.0f;
    const std::size_t columns = sprite.offsets.size() - 1;
    std::vector<PreviousRecord> table(columns);
    for (std::size_t c = 0; c < columns; ++c) {
        const std::uint32_t first = sprite.offsets[c], n = sprite.offsets[c + 1] - first;
        table[c] = {{n > 0 ? sprite.crossings[first] : kPadding, n > 1 ? sprite.crossings[first + 1] : kPadding}, first, n};
    }
    const vds::SpriteGrid& grid = sprite.grid;
    const auto columnOf = [&](const glm::vec3& t) -> std::ptrdiff_t {
        if (!(t.z >= 0.0f && t.z <= 1.0f)) return -1;
        const float fs = std::floor(t.x * float(grid.width)), ft = std::floor(t.y * float(grid.height));
        if (!(fs >= 0.0f && fs < float(grid.width) && ft >= 0.0f && ft < float(grid.height))) return -1;
        return std::ptrdiff_t(ft) * std::ptrdiff_t(grid.width) + std::ptrdiff_t(fs);
    };
    const auto test = [&](const PreviousRecord& c, float r) { // Rule::Parity
        if (!(std::fabs(c.first[0]) < r)) return false;
        if (!(std::fabs(c.first[1]) < r)) return true;
        int parity = 0;
        for (const float *e = sprite.crossings.data() + c.begin + 2, *end = sprite.crossings.data() + c.begin + c.count;
             e < end; ++e) {
            if (!(std::fabs(*e) < r)) break;
            parity ^= 1;
        }
        return parity != 0;
    };
    constexpr std::size_t kBatch = 32;
    std::ptrdiff_t column[kBatch];
    float depth[kBatch];
    for (std::size_t base = 0; base < count; base += kBatch) {
        const std::size_t n = std::min(kBatch, count - base);
        for (std::size_t i = 0; i < n; ++i) {
            const glm::vec3 t = grid.toTexture(points[base + i]);
            column[i] = columnOf(t);
            depth[i] = t.z;
            if (column[i] >= 0) __builtin_prefetch(table.data() + column[i]);
        }
        for (std::size_t i = 0; i < n; ++i)
            labels[base + i] = column[i] >= 0 && test(table[std::size_t(column[i])], depth[i]) ? 1 : 0;
    }
}

struct Input {
    std::string name;
    vds::TriangleMesh mesh;
};

void measure(const Input& in, std::size_t count, std::uint32_t resolution, int rounds) {
    vds::BakeOptions o;
    o.resolution = resolution;
    o.method = vds::BakeMethod::Cpu;
    const vds::Sprite sprite = vds::bake(in.mesh, o);
    const std::vector<glm::vec3> points = vds::test::randomPoints(vds::meshBounds(in.mesh), count);

    struct Variant {
        vds::QueryLayout layout; // Auto here: the previous packed layout
        unsigned threads;
        double best = 1e300, bestWall = 1e300;
        std::vector<std::uint8_t> labels;
    };
    std::vector<Variant> variants;
    variants.push_back({vds::QueryLayout::Auto, 1, 1e300, 1e300, std::vector<std::uint8_t>(count)});
    for (unsigned t : {1u, 2u})
        for (vds::QueryLayout layout : {vds::QueryLayout::Offsets, vds::QueryLayout::Packed})
            variants.push_back({layout, t, 1e300, 1e300, std::vector<std::uint8_t>(count)});
    for (int round = 0; round <= rounds; ++round) // round 0 warms up, untimed
        for (Variant& v : variants) {
            const double cpu = cpuSeconds(), wall = wallSeconds();
            if (v.layout == vds::QueryLayout::Auto)
                classifyPrevious(sprite, points.data(), count, v.labels.data());
            else
                vds::classify(sprite, vds::PointsView(points.data(), count), v.labels.data(), {vds::Rule::Parity, v.threads},
                              {v.layout});
            if (round == 0) continue;
            v.best = std::min(v.best, cpuSeconds() - cpu); // all threads: the time of one busy thread
            v.bestWall = std::min(v.bestWall, wallSeconds() - wall);
        }
    std::size_t differ = 0;
    for (const Variant& v : variants)
        for (std::size_t k = 0; k < count; ++k) differ += v.labels[k] != variants[0].labels[k];
    std::size_t deep = 0; // columns with more than four crossings
    for (std::size_t c = 0; c + 1 < sprite.offsets.size(); ++c) deep += sprite.offsets[c + 1] - sprite.offsets[c] > 4;
    const double offsets1 = variants[1].best;
    const auto name = [](vds::QueryLayout l) {
        return l == vds::QueryLayout::Packed ? "packed" : l == vds::QueryLayout::Offsets ? "offsets" : "packed, previous";
    };
    for (const Variant& v : variants)
        std::printf("| %s | %zu | %ux%ux%u | %.2f%% | %s | %u | %.1f | %.2fx | %.2fx | %.1f |%s\n", in.name.c_str(),
                    in.mesh.triangles.size(), sprite.width(), sprite.height(), sprite.depthComplexity,
                    100.0 * double(deep) / double(sprite.offsets.size() - 1),
                    name(v.layout), v.threads,
                    double(count) / v.best * 1e-6, offsets1 / v.best, variants[0].best / v.best,
                    double(count) / v.bestWall * 1e-6,
                    differ ? " LABELS DIFFER" : "");
    std::fflush(stdout);
    if (differ) throw std::runtime_error("the layouts disagree on " + std::to_string(differ) + " labels");
}

} // namespace

int main(int argc, char** argv) {
    CLI::App app("vds layout benchmark: the sprite's offsets layout against the packed column table");
    std::size_t points = 4000000;
    std::uint32_t resolution = 1024;
    int rounds = 5;
    std::vector<std::string> meshes;
    app.add_option("--points", points, "uniform random points per mesh")->capture_default_str()->check(CLI::PositiveNumber);
    app.add_option("--resolution", resolution, "sprite resolution")->capture_default_str()->check(CLI::Range(1u, 16384u));
    app.add_option("--rounds", rounds, "timed rounds (best of)")->capture_default_str()->check(CLI::Range(1, 100));
    app.add_option("MESH", meshes, "meshes (default: generated ones only)");
    CLI11_PARSE(app, argc, argv);
    try {
        std::vector<Input> inputs;
        for (const std::string& path : meshes)
            inputs.push_back({path.substr(path.find_last_of('/') + 1), vds::loadMesh(path)});
        using namespace vds::solids;
        inputs.push_back({"3 boxes", merge(merge(box({0.0f, 0.0f, 0.0f}, {1.0f, 1.0f, 1.0f}).mesh,
                                                 box({1.5f, 0.2f, 0.3f}, {2.5f, 1.4f, 0.9f}).mesh),
                                           box({0.4f, 1.6f, 0.1f}, {2.2f, 2.1f, 1.7f}).mesh)});
        inputs.push_back({"torus 256", torus({0, 0, 0}, 1.0f, 0.35f, 256).mesh});
        inputs.push_back({"sphere 512", sphere({0, 0, 0}, 1.0f, 512).mesh});
        std::printf("%zu uniform points in the box grown by 10%% per side, sprite at %u, best of %d interleaved rounds; "
                    "packed includes building its table\n\n",
                    points, resolution, rounds);
        std::printf("| mesh | triangles | sprite | columns > 4 crossings | layout | threads | M points/s per thread (CPU "
                    "time) | × offsets, 1 thread | × previous packed, 1 thread | M points/s (wall) |\n"
                    "|---|---:|---|---:|---|---:|---:|---:|---:|---:|\n");
        for (const Input& in : inputs) measure(in, points, resolution, rounds);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "vds_layout_bench: %s\n", e.what());
        return 1;
    }
    return 0;
}
