// Benchmark: prints figures, asserts nothing about speed. It does check that
// the answers agree (fragment lists and peeling bit for bit; every GPU
// classification point for point with the CPU's) and says so in the tables.
//
//   vds_bench [--quick | --full] [options] [MESH ...]      (vds_bench --help)
//
// 1. Bake time: the exact CPU baker, fragment lists (to the host, and
//    straight into a GpuSprite) and depth peeling, in one run, with their
//    ratios; then the fragment-list bake phase by phase (wall and GPU time).
//    Meshes: bench/meshes (bench/fetch-meshes.sh), samples/data, a generated
//    torus knot of 230,400 triangles and a UV sphere of 1,002,000.
// 2. Classification throughput in G points/s: the CPU on 1 and on all
//    threads; the GPU from host arrays to host arrays (upload, dispatch and
//    read-back included); the GPU on points already in a GL buffer (random,
//    and column-coherent: 32 points a column, columns in raster order).
// 3. File size of the .vds (OpenEXR deep) against the dense float texture.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include <sys/resource.h>

#include <GL/gl.h>
#include <GL/glext.h>

#include <CLI/CLI.hpp>

#include <vds/all.h>
#include <vds/bake.h>
#include <vds/error.h>
#include <vds/exact.h>
#include <vds/gl/occupancy.h>
#include <vds/gl/context.h>
#include <vds/gl/bake.h>
#include <vds/gl/sprite.h>
#include <vds/mesh_io.h>
#include <vds/vds_file.h>
#include "plain_kernels.h"
#include "solids.h"

namespace {

namespace fs = std::filesystem;

double seconds(const std::function<void()>& f) {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// User + system time of every thread of this process (llvmpipe's included).
double processSeconds() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

// Best (least) wall time of `runs` runs; `cpu`, if given, receives the least
// process CPU time of them, which other programs on a shared machine disturb less.
double best(unsigned runs, const std::function<void()>& f, double* cpu = nullptr) {
    double t = 1e300, c = 1e300;
    for (unsigned k = 0; k < std::max(1u, runs); ++k) {
        const double c0 = processSeconds();
        t = std::min(t, seconds(f));
        c = std::min(c, processSeconds() - c0);
    }
    if (cpu) *cpu = c;
    return t;
}

bool identical(const vds::Sprite& a, const vds::Sprite& b) {
    return a.offsets == b.offsets && a.crossings.size() == b.crossings.size() &&
           std::memcmp(a.crossings.data(), b.crossings.data(), a.crossings.size() * sizeof(float)) == 0;
}

struct BenchMesh {
    vds::TriangleMesh mesh;
    bool bundled = false;                   ///< a file, not generated
    std::vector<std::uint32_t> resolutions; ///< of the bake table
};

struct Settings {
    std::string mode = "default";
    std::vector<std::uint32_t> resolutions{1024};
    std::vector<std::uint32_t> knotResolutions{1024};
    std::vector<std::uint32_t> sphereResolutions{2048};
    std::size_t points = 10000000;
    std::size_t exactPoints = 1000000;
    std::uint32_t classifyResolution = 2048;
    double warmUp = 0.5;              // seconds of GPU work before each timed GPU figure
    std::size_t gwnPoints = 1000000;  // points a mesh for the generalized winding table
    std::uint32_t gwnResolution = 1024;
    std::uint32_t gwnDims = 256;      // cells a side of the occupancy grids
    unsigned bakeRuns = 2;
    unsigned classifyRuns = 2;
    bool cpuBake = true, peel = true, bakeTable = true, classifyTable = true, sizes = true;
    std::string meshDir;
    std::vector<std::string> meshFiles;
};

std::string sizeText(std::uint32_t w, std::uint32_t h, std::uint32_t d) {
    return std::to_string(w) + "x" + std::to_string(h) + "x" + std::to_string(d);
}

std::string ms(double s) {
    char b[32];
    std::snprintf(b, sizeof b, s >= 10.0 ? "%.0f" : s >= 0.1 ? "%.1f" : "%.2f", 1e3 * s);
    return b;
}

std::string ratio(double a, double b) {
    char t[32];
    std::snprintf(t, sizeof t, "%.2fx", a / b);
    return t;
}

std::string rate(double points, double s) { // G points/s
    char b[32];
    std::snprintf(b, sizeof b, "%.3g", points / s * 1e-9);
    return b;
}

// A phase cell: "wall" or "wall / GPU" in ms, "-" when the phase did not run.
std::string phaseCell(const vds::BakeTimings& t, vds::BakePhase p) {
    const vds::BakeTimings::Phase& ph = t[p];
    if (ph.runs == 0) return "-";
    std::string s = ms(ph.wallSeconds);
    if (ph.gpuSeconds >= 0.0) s += " / " + ms(ph.gpuSeconds);
    if (ph.runs > 1) s += " (x" + std::to_string(ph.runs) + ")";
    return s;
}

// GPU time of the GL commands `f` sends (GL_TIME_ELAPSED); < 0 where the
// driver's timer gives more than the wall time or less than a thousandth of
// it (llvmpipe: about 0 for compute).
double gpuSeconds(const std::function<void()>& f, double* wall) {
    const vds::Query query = vds::Query::create(GL_TIME_ELAPSED);
    glFinish();
    const auto t0 = std::chrono::steady_clock::now();
    glBeginQuery(GL_TIME_ELAPSED, query.id());
    f();
    glEndQuery(GL_TIME_ELAPSED);
    glFinish();
    *wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    GLuint64 ns = 0;
    glGetQueryObjectui64v(query.id(), GL_QUERY_RESULT, &ns);
    vds::checkGl("timing a dispatch");
    const double s = 1e-9 * double(ns);
    return s < 1e-3 * *wall || s > *wall ? -1.0 : s;
}

// A GPU figure: the best wall time (glFinish) and GL timer (1e300: none).
struct Timed {
    double wall = 1e300, gpu = 1e300;
    double best() const { return gpu < 1e300 ? gpu : wall; } ///< the GL timer where the driver has one
};

// Warms the GPU up with `dispatch`, then times it, best of the runs.
Timed timeGpu(const Settings& set, const std::function<void()>& dispatch) {
    vds::bench::warmUp(dispatch, set.warmUp);
    Timed t;
    for (unsigned k = 0; k < std::max(1u, set.classifyRuns); ++k) {
        double w = 0;
        const double g = gpuSeconds(dispatch, &w);
        t.wall = std::min(t.wall, w);
        if (g > 0) t.gpu = std::min(t.gpu, g);
    }
    return t;
}

void readLabels(GLuint labels, std::size_t n, std::vector<std::uint8_t>& out) {
    std::vector<std::uint8_t> bytes((n + 3) / 4 * 4);
    glGetNamedBufferSubData(labels, 0, GLsizeiptr(bytes.size()), bytes.data());
    out.assign(bytes.begin(), bytes.begin() + std::ptrdiff_t(n));
}

std::vector<BenchMesh> loadMeshes(const Settings& set) {
    std::vector<BenchMesh> meshes;
    std::vector<std::string> files = set.meshFiles;
    if (files.empty()) {
        std::vector<std::string> dirs;
        if (!set.meshDir.empty()) dirs.push_back(set.meshDir);
        for (const char* d : {VDS_BENCH_MESHES})
            dirs.emplace_back(d);
        for (const auto& dir : dirs)
            if (fs::is_directory(dir)) {
                for (const auto& e : fs::directory_iterator(dir))
                    if (e.path().extension() == ".obj") files.push_back(e.path().string());
                break;
            }
        std::sort(files.begin(), files.end());
        // The sample's mesh, unless the same file (name and size) is there already.
        const fs::path sample = fs::path(VDS_SOURCE_DIR) / "samples" / "data" / "spot.obj";
        if (fs::exists(sample)) {
            bool seen = false;
            for (const auto& f : files)
                seen |= fs::path(f).filename() == sample.filename() && fs::file_size(f) == fs::file_size(sample);
            if (!seen) files.push_back(sample.string());
        }
    }
    for (const auto& f : files) {
        BenchMesh m;
        m.mesh = vds::loadMesh(f);
        m.bundled = true;
        m.resolutions = set.resolutions;
        meshes.push_back(std::move(m));
    }
    if (set.meshFiles.empty()) {
        BenchMesh knot;
        knot.mesh = vds::solids::torusKnot({0, 0, 0}, 1.0f, 2, 3, 0.15f, 1800, 64).mesh; // 230,400 triangles
        knot.mesh.name = "trefoil knot (generated)";
        knot.resolutions = set.knotResolutions;
        meshes.push_back(std::move(knot));
        BenchMesh sphere;
        sphere.mesh = vds::solids::sphere({0, 0, 0}, 1.0f, 1002).mesh; // 1,002,000 triangles
        sphere.mesh.name = "UV sphere (generated)";
        sphere.resolutions = set.sphereResolutions;
        meshes.push_back(std::move(sphere));
    }
    return meshes;
}

struct SizeRow {
    std::string mesh;
    std::uint32_t res;
    std::size_t file, dense, crossings;
};

struct PhaseRow {
    std::string mesh;
    std::uint32_t res;
    vds::BakeTimings host, gpu;
};

// Wall-time ratios of the CPU baker over the lists on the mesh files.
struct BakeRatios {
    std::vector<double> wall, cpu;
};

// One mesh at one resolution: every baker timed (an untimed bake first),
// the row printed, the phases measured once, the file size kept.
PhaseRow bakeRow(const Settings& set, vds::GlContext& gl, const BenchMesh& m, std::uint32_t res,
                 std::vector<SizeRow>& sizes, BakeRatios& ratios) {
    vds::BakeOptions o;
    o.resolution = res;
    o.sourceName = m.mesh.name;
    vds::Sprite lists, peel, cpu;
    // Untimed first bakes: the GL bakers' scratch space grows to this
    // size once, and the allocator warms up for the CPU baker.
    o.method = vds::BakeMethod::Lists;
    vds::bake(gl, m.mesh, o);
    if (set.cpuBake) {
        o.method = vds::BakeMethod::Cpu;
        vds::bake(m.mesh, o);
        o.method = vds::BakeMethod::Lists;
    }
    double cLists = 0, cCpu = 0;
    const double tLists = best(set.bakeRuns, [&] { lists = vds::bake(gl, m.mesh, o); }, &cLists);
    const double tGpu = best(set.bakeRuns, [&] {
        const vds::GpuBake b = vds::bakeToGpu(gl, m.mesh, o);
        glFinish();
    });
    double tPeel = -1, tCpu = -1;
    if (set.peel) {
        o.method = vds::BakeMethod::Peel;
        tPeel = seconds([&] { peel = vds::bake(gl, m.mesh, o); });
    }
    if (set.cpuBake) {
        o.method = vds::BakeMethod::Cpu;
        tCpu = best(set.bakeRuns, [&] { cpu = vds::bake(m.mesh, o); }, &cCpu);
        if (m.bundled) {
            ratios.wall.push_back(tCpu / tLists);
            ratios.cpu.push_back(cCpu / cLists);
        }
    }
    PhaseRow row{m.mesh.name, res, {}, {}};
    o.method = vds::BakeMethod::Lists;
    o.timings = &row.host;
    vds::bake(gl, m.mesh, o);
    o.timings = &row.gpu;
    vds::bakeToGpu(gl, m.mesh, o);
    std::printf("| %s | %zu | %u | %s | %s | %s | %s | %s | %s | %s | %s | %s |\n", m.mesh.name.c_str(),
                m.mesh.triangles.size(), res, sizeText(lists.width(), lists.height(), lists.depthComplexity).c_str(),
                tCpu < 0 ? "-" : ms(tCpu).c_str(), ms(tLists).c_str(), ms(tGpu).c_str(),
                tPeel < 0 ? "-" : ms(tPeel).c_str(), tCpu < 0 ? "-" : ratio(tCpu, tLists).c_str(),
                tCpu < 0 ? "-" : ratio(cCpu, cLists).c_str(), tPeel < 0 ? "-" : ratio(tPeel, tLists).c_str(),
                tPeel < 0 ? "-" : identical(peel, lists) ? "yes" : "NO");
    std::fflush(stdout);
    if (set.sizes && m.bundled) {
        const fs::path file = fs::temp_directory_path() / "vds_bench.vds";
        vds::writeSprite(lists, file.string());
        sizes.push_back({m.mesh.name, res, std::size_t(fs::file_size(file)), lists.denseBytes(), lists.crossings.size()});
        fs::remove(file);
    }
    return row;
}

void printRatioSummary(const char* what, const std::vector<double>& ratios) {
    double logSum = 0;
    std::size_t faster = 0;
    for (double r : ratios) {
        logSum += std::log(r);
        faster += r >= 1.0;
    }
    const auto [lo, hi] = std::minmax_element(ratios.begin(), ratios.end());
    std::printf("- %s: lists as fast or faster on %zu of %zu; cpu / lists from %.2fx to %.2fx, geometric mean "
                "%.2fx.\n",
                what, faster, ratios.size(), *lo, *hi, std::exp(logSum / double(ratios.size())));
}

void printPhaseTable(const std::vector<PhaseRow>& phases) {
    std::puts("\n## Fragment-list bake, phase by phase (ms: wall / GPU timer; one measured run)\n");
    std::puts("Measured runs wait for GL at the end of each phase, so the phases add up to about the total; GPU");
    std::puts("times are GL timer queries (none where the driver's timer reports nothing usable, as llvmpipe's).");
    std::puts("`host`: read back into a Sprite; `GPU`: bakeToGpu, the 3D texture filled in compute.\n");
    std::puts("| mesh | res | to | validation | axis | compile | upload | raster | scan | sort | texture | read-back | "
              "assembly | total | GPU total | wall / GPU | crossings | nodes | bands |");
    std::puts("|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    using P = vds::BakePhase;
    for (const auto& r : phases)
        for (const auto* t : {&r.host, &r.gpu})
            std::printf("| %s | %u | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %llu | %llu | %u |\n",
                        r.mesh.c_str(), r.res, t == &r.host ? "host" : "GPU", phaseCell(*t, P::Validation).c_str(),
                        phaseCell(*t, P::Axis).c_str(), phaseCell(*t, P::Compile).c_str(), phaseCell(*t, P::Upload).c_str(),
                        phaseCell(*t, P::Raster).c_str(), phaseCell(*t, P::Scan).c_str(), phaseCell(*t, P::Sort).c_str(),
                        phaseCell(*t, P::TextureFill).c_str(), phaseCell(*t, P::ReadBack).c_str(),
                        phaseCell(*t, P::Assembly).c_str(), ms(t->wallSeconds).c_str(),
                        t->gpuSeconds() > 0 ? ms(t->gpuSeconds()).c_str() : "-",
                        t->gpuSeconds() > 0 ? ratio(t->wallSeconds, t->gpuSeconds()).c_str() : "-",
                        (unsigned long long)t->crossings, (unsigned long long)t->listNodes, t->bands);
}

void bakeTable(const Settings& set, vds::GlContext& gl, const std::vector<BenchMesh>& meshes,
               std::vector<SizeRow>& sizes) {
    std::printf("## Bake time: CPU vs fragment lists vs depth peeling (ms, best of %u after an untimed bake; "
                "peeling: one run)\n\n",
                set.bakeRuns);
    std::puts("`cpu`: exact ray casting on every core. `lists`: fragment lists, the sprite read back to the host.");
    std::puts("`to GPU`: fragment lists into a GpuSprite (3D texture + columns), nothing read back (`bakeToGpu`).");
    std::puts("Ratios above 1 mean lists are faster. `CPU time`: the same ratio in process CPU time (every thread,");
    std::puts("llvmpipe's too), which other programs on a shared machine disturb less than wall time.");
    std::puts("`lists == peel`: the two GL bakers' layers, bit for bit.\n");
    std::puts("| mesh | triangles | res | w x h x d | cpu | lists | to GPU | peel | cpu / lists | (CPU time) | "
              "peel / lists | lists == peel |");
    std::puts("|---|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|---|");
    std::vector<PhaseRow> phases;
    BakeRatios ratios;
    for (const auto& m : meshes)
        for (std::uint32_t res : m.resolutions) phases.push_back(bakeRow(set, gl, m, res, sizes, ratios));
    if (!ratios.wall.empty()) {
        std::puts("\nFragment lists vs the CPU baker on the mesh files, this run:");
        printRatioSummary("wall time", ratios.wall);
        printRatioSummary("process CPU time", ratios.cpu);
    }
    printPhaseTable(phases);
}

// `n` points, 32 to a column: columns spread evenly over the image, in
// raster order, each point at a random place in its texel and a random
// depth in the box grown by 5% (the sprite as baked, not moved).
void coherentPoints(const vds::SpriteGrid& grid, std::vector<glm::vec3>& points) {
    constexpr std::size_t kPerColumn = 32;
    const std::size_t columns = std::size_t(grid.width) * grid.height;
    const std::size_t used = std::max<std::size_t>(1, (points.size() + kPerColumn - 1) / kPerColumn);
    const double stride = double(columns) / double(used);
    const glm::ivec3 axes = vds::axisPermutation(grid.axis);
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> jitter(-0.49f, 0.49f), depth(-0.05f, 1.05f);
    for (std::size_t k = 0; k < points.size(); ++k) {
        const std::size_t c = std::min(columns - 1, std::size_t(double(k / kPerColumn) * stride));
        glm::vec3 p = grid.texelCentre(std::uint32_t(c % grid.width), std::uint32_t(c / grid.width), depth(rng));
        p[axes.x] += jitter(rng) * grid.texelSize;
        p[axes.y] += jitter(rng) * grid.texelSize;
        points[k] = p;
    }
}

// One set of resident points: vds's classifier and the plain kernel on the
// same buffers, timed after the warm-up, their labels read back.
struct ResidentCase {
    const std::vector<glm::vec3>& points;
    Timed& vds;
    Timed& plain;
    std::vector<std::uint8_t>& vdsLabels;
    std::vector<std::uint8_t>& plainLabels;
};

void measureResident(const Settings& set, vds::GpuClassifier& classifier, const vds::bench::PlainKernels& plain,
                     const vds::GpuSprite& gpu, const ResidentCase& c) {
    const std::size_t n = c.points.size();
    vds::Buffer points = vds::Buffer::create(), labels = vds::Buffer::create();
    glNamedBufferStorage(points.id(), GLsizeiptr(n * 12), c.points.data(), 0);
    glNamedBufferStorage(labels.id(), GLsizeiptr((n + 3) / 4 * 4), nullptr, 0);
    vds::checkGl("allocating the benchmark's buffers");
    c.vds = timeGpu(set, [&] { classifier.classify(gpu, points.id(), n, labels.id()); });
    readLabels(labels.id(), n, c.vdsLabels);
    c.plain = timeGpu(set, [&] { plain.parity(gpu, points.id(), n, labels.id()); });
    readLabels(labels.id(), n, c.plainLabels);
}

void classifyTable(const Settings& set, vds::GlContext& gl, const std::vector<BenchMesh>& meshes) {
    const unsigned threads = std::max(1u, std::thread::hardware_concurrency());
    const std::size_t n = set.points;
    std::printf("\n## Classification: %zu points a mesh, sprites at %u (G points/s)\n\n", n, set.classifyResolution);
    std::puts("`random`: uniform in the mesh box grown by 10%. `coherent`: 32 points a column, columns in raster order.");
    std::printf("CPU: vds::classify on 1 and %u threads. GPU host -> host: GpuClassifier from and to host arrays, the\n"
                "transfers included (HostTransfer::Auto; `mapped`: HostTransfer::Mapped). GPU resident: points and labels in GL buffers (wall time with glFinish, and the\n"
                "GL timer), best of %u, each after %.1f s of warm-up. `plain`: the plainest GL kernel over the same\n"
                "buffers in the same run (bench/vds/plain_kernels.h; GL timer where there is one), and vds / plain.\n"
                "`exact`: the exact classifier on the first %zu random points, %u threads;\n"
                "`VDS vs exact`: share of those points where the sprite answers otherwise (all near the surface).\n\n",
                threads, set.classifyRuns, set.warmUp, std::min(n, set.exactPoints), threads);
    std::printf("| mesh | w x h x d | CPU 1 thr | CPU %u thr | GPU host -> host | (mapped) | GPU resident random | "
                "(GPU timer) | plain random | vds / plain | GPU resident coherent | (GPU timer) | plain coherent | "
                "vds / plain | exact | GPU == CPU | VDS vs exact |\n",
                threads);
    std::puts("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|---:|");
    vds::GpuClassifier classifier(gl);
    vds::GpuClassifier mapped(gl, std::size_t(1) << 22, vds::HostTransfer::Mapped);
    const vds::bench::PlainKernels plain(gl);
    std::vector<glm::vec3> unit(n), random(n), coherent(n);
    {
        std::mt19937 rng(42);
        std::uniform_real_distribution<float> u(-0.1f, 1.1f);
        for (auto& p : unit) p = glm::vec3(u(rng), u(rng), u(rng));
    }
    std::vector<std::uint8_t> cpu1(n), cpuN(n), hostToHost(n), hostMapped(n), resident(n), coherentCpu(n), coherentGpu(n);
    for (const auto& m : meshes) {
        vds::BakeOptions o;
        o.resolution = set.classifyResolution;
        const vds::Sprite sprite = vds::bake(gl, m.mesh, o);
        const vds::GpuSprite gpu(sprite, vds::GpuSpriteParts::ColumnsOnly);
        const vds::Box box = sprite.grid.box;
        for (std::size_t k = 0; k < n; ++k) random[k] = box.lo + unit[k] * (box.hi - box.lo);
        coherentPoints(sprite.grid, coherent);

        vds::ClassifyOptions one, all;
        one.threads = 1;
        all.threads = threads;
        const double t1 = best(1, [&] { vds::classify(sprite, vds::PointsView(random.data(), n), cpu1.data(), one); });
        const double tN = best(set.classifyRuns, [&] { vds::classify(sprite, vds::PointsView(random.data(), n), cpuN.data(), all); });
        vds::bench::warmUp([&] { classifier.classify(gpu, vds::PointsView(random.data(), std::min<std::size_t>(n, 1 << 20)),
                                                     hostToHost.data()); }, set.warmUp);
        const double tHost = best(set.classifyRuns, [&] { classifier.classify(gpu, vds::PointsView(random.data(), n), hostToHost.data()); });
        const double tMapped = best(set.classifyRuns, [&] { mapped.classify(gpu, vds::PointsView(random.data(), n), hostMapped.data()); });

        // Resident: the points uploaded once, the labels left in GL.
        Timed vdsRandom, vdsCoherent, plainRandom, plainCoherent;
        std::vector<std::uint8_t> plainLabels(n), plainCoherentLabels(n);
        const ResidentCase randomCase{random, vdsRandom, plainRandom, resident, plainLabels};
        const ResidentCase coherentCase{coherent, vdsCoherent, plainCoherent, coherentGpu, plainCoherentLabels};
        for (const ResidentCase& c : {randomCase, coherentCase}) measureResident(set, classifier, plain, gpu, c);
        vds::classify(sprite, vds::PointsView(coherent.data(), n), coherentCpu.data(), all);

        const std::size_t ne = std::min(n, set.exactPoints);
        std::vector<std::uint8_t> exactLabels(ne);
        const vds::ExactClassifier exact(m.mesh);
        const double tExact = seconds([&] { exact.classify(vds::PointsView(random.data(), ne), exactLabels.data(), all); });
        std::size_t differ = 0;
        for (std::size_t k = 0; k < ne; ++k) differ += cpuN[k] != exactLabels[k];
        const bool equal = cpu1 == cpuN && cpuN == hostToHost && cpuN == hostMapped && cpuN == resident && coherentCpu == coherentGpu &&
                           plainLabels == cpuN && plainCoherentLabels == coherentCpu;
        const double points = double(n);
        std::printf("| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %.4f %% |\n",
                    m.mesh.name.c_str(), sizeText(sprite.width(), sprite.height(), sprite.depthComplexity).c_str(),
                    rate(points, t1).c_str(), rate(points, tN).c_str(), rate(points, tHost).c_str(),
                    rate(points, tMapped).c_str(),
                    rate(points, vdsRandom.wall).c_str(), vdsRandom.gpu < 1e300 ? rate(points, vdsRandom.gpu).c_str() : "-",
                    rate(points, plainRandom.best()).c_str(), ratio(plainRandom.best(), vdsRandom.best()).c_str(),
                    rate(points, vdsCoherent.wall).c_str(),
                    vdsCoherent.gpu < 1e300 ? rate(points, vdsCoherent.gpu).c_str() : "-",
                    rate(points, plainCoherent.best()).c_str(), ratio(plainCoherent.best(), vdsCoherent.best()).c_str(),
                    rate(double(ne), tExact).c_str(), equal ? "yes" : "NO",
                    100.0 * double(differ) / double(std::max<std::size_t>(ne, 1)));
        std::fflush(stdout);
    }
}

// Labels of the plain parity kernel in `form` (4 bytes a point in the
// one-point form), as one byte a point.
std::vector<std::uint8_t> readFormLabels(GLuint labels, std::size_t n, vds::bench::PlainForm form) {
    if (!form.onePoint) {
        std::vector<std::uint8_t> out;
        readLabels(labels, n, out);
        return out;
    }
    std::vector<std::uint32_t> wide(n);
    glGetNamedBufferSubData(labels, 0, GLsizeiptr(n * 4), wide.data());
    return std::vector<std::uint8_t>(wide.begin(), wide.end());
}

// The plain parity kernel in each form (bench/vds/plain_kernels.h), random and
// coherent points resident in GL, GL timer, best of the runs after the
// warm-up: which of the columns' reads and points an invocation holds GL
// below a plain CUDA kernel on random points. Each form's labels against
// the CPU's.
void plainFormsTable(const Settings& set, vds::GlContext& gl, const std::vector<BenchMesh>& meshes) {
    using vds::bench::PlainForm;
    const std::size_t n = set.points;
    const PlainForm forms[4] = {{false, false}, {true, false}, {false, true}, {true, true}};
    std::printf("\n## The plain parity kernel's forms: %zu points a mesh, sprites at %u (G points/s)\n\n", n,
                set.classifyResolution);
    std::puts("`ssbo`: the columns read from storage buffers; `texel`: from buffer textures (the texture cache). `x4`:");
    std::puts("four points an invocation, one label word; `x1`: one point an invocation, a 32-bit label.\n");
    std::puts("| mesh | random ssbo x4 | texel x4 | ssbo x1 | texel x1 | coherent ssbo x4 | texel x4 | ssbo x1 | texel x1 | "
              "labels == CPU |");
    std::puts("|---|---:|---:|---:|---:|---:|---:|---:|---:|---|");
    const vds::bench::PlainKernels plain(gl);
    std::vector<glm::vec3> unit(n), random(n), coherent(n);
    std::mt19937 rng(42);
    std::uniform_real_distribution<float> u(-0.1f, 1.1f);
    for (auto& p : unit) p = glm::vec3(u(rng), u(rng), u(rng));
    for (const auto& m : meshes) {
        vds::BakeOptions o;
        o.resolution = set.classifyResolution;
        const vds::Sprite sprite = vds::bake(gl, m.mesh, o);
        const vds::GpuSprite gpu(sprite, vds::GpuSpriteParts::ColumnsOnly);
        for (std::size_t k = 0; k < n; ++k) random[k] = sprite.grid.box.lo + unit[k] * (sprite.grid.box.hi - sprite.grid.box.lo);
        coherentPoints(sprite.grid, coherent);
        std::string row = "| " + m.mesh.name;
        bool equal = true;
        for (const std::vector<glm::vec3>* set_ : {&random, &coherent}) {
            std::vector<std::uint8_t> cpu(n);
            vds::classify(sprite, vds::PointsView(set_->data(), n), cpu.data());
            vds::Buffer points = vds::Buffer::create(), labels = vds::Buffer::create();
            glNamedBufferStorage(points.id(), GLsizeiptr(n * 12), set_->data(), 0);
            glNamedBufferStorage(labels.id(), GLsizeiptr(n * 4 + 4), nullptr, 0);
            for (const PlainForm& form : forms) {
                const Timed t = timeGpu(set, [&] { plain.parity(gpu, points.id(), n, labels.id(), form); });
                equal = equal && readFormLabels(labels.id(), n, form) == cpu;
                row += " | " + rate(double(n), t.best());
            }
        }
        std::printf("%s | %s |\n", row.c_str(), equal ? "yes" : "NO");
        std::fflush(stdout);
    }
}

// The generalized winding number on the GPU, open meshes only: vds's
// program against the brute-force plain kernel, and the occupancy sweeps.
void gwnTable(const Settings& set, vds::GlContext& gl, const std::vector<BenchMesh>& meshes) {
    const std::size_t n = set.gwnPoints;
    std::printf("\n## Generalized winding number on the GPU: %zu points a mesh, sprites at %u (G points/s)\n\n", n,
                set.gwnResolution);
    std::puts("Open meshes only. Points uniform in the box grown by 10%, resident in GL; best of the runs after the");
    std::puts("warm-up. `brute force`: the plain kernel summing every boundary edge for every point (bench/vds/plain_kernels.h),");
    std::puts("and its edge terms/s. `differ`: labels unlike the CPU's (float against double, near 1/2). Occupancy:");
    std::printf("%u^3 cells over the box, G cells/s, generalized winding against parity.\n\n", set.gwnDims);
    std::puts("| mesh | w x h x d (axis; CPU count's axis) | boundary edges | vds | brute force | vds / brute | "
              "G edge terms/s (brute) | differ | occupancy GWN | occupancy parity | GWN / parity |");
    std::puts("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    vds::GpuClassifier classifier(gl);
    vds::GpuOccupancy occupancy(gl);
    const vds::bench::PlainKernels plain(gl);
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(-0.1f, 1.1f);
    std::vector<glm::vec3> points(n);
    for (const auto& m : meshes) {
        vds::BakeOptions o;
        o.resolution = set.gwnResolution;
        const vds::Sprite sprite = vds::bake(gl, m.mesh, o);
        if (sprite.boundaryEdges.empty()) continue;
        const vds::GpuSprite gpu(sprite, vds::GpuSpriteParts::ColumnsOnly);
        for (auto& p : points) p = sprite.grid.box.lo + glm::vec3(u(rng), u(rng), u(rng)) * (sprite.grid.box.hi - sprite.grid.box.lo);
        vds::Buffer pointBuffer = vds::Buffer::create(), labels = vds::Buffer::create();
        glNamedBufferStorage(pointBuffer.id(), GLsizeiptr(n * 12), points.data(), 0);
        glNamedBufferStorage(labels.id(), GLsizeiptr((n + 3) / 4 * 4), nullptr, 0);
        std::vector<std::uint8_t> cpu(n), mine(n), brute(n);
        vds::ClassifyOptions gwn;
        gwn.rule = vds::Rule::GeneralizedWinding;
        vds::classify(sprite, vds::PointsView(points.data(), n), cpu.data(), gwn);
        const Timed tv = timeGpu(set, [&] { classifier.classify(gpu, pointBuffer.id(), n, labels.id(), gwn); });
        readLabels(labels.id(), n, mine);
        const Timed tb = timeGpu(set, [&] { plain.generalizedWinding(gpu, pointBuffer.id(), n, labels.id()); });
        readLabels(labels.id(), n, brute);
        std::size_t differ = 0;
        for (std::size_t k = 0; k < n; ++k) differ += (cpu[k] != mine[k]) + (cpu[k] != brute[k]);
        vds::Grid grid;
        grid.box = sprite.grid.box;
        grid.dims = glm::uvec3(set.gwnDims);
        const std::uint64_t cells = grid.cellCount();
        vds::Buffer cellBuffer = vds::Buffer::create();
        glNamedBufferStorage(cellBuffer.id(), GLsizeiptr((cells + 3) / 4 * 4), nullptr, 0);
        vds::ClassifyOptions parity;
        const Timed og = timeGpu(set, [&] { occupancy.occupancy(gpu, grid, cellBuffer.id(), gwn); });
        const Timed op = timeGpu(set, [&] { occupancy.occupancy(gpu, grid, cellBuffer.id(), parity); });
        const double edges = double(sprite.boundaryEdges.size() / 2);
        const vds::Axis cpuAxis = vds::chooseViewAxis(m.mesh, set.gwnResolution).axis;
        std::printf("| %s | %s (%s; %s) | %.0f | %s | %s | %s | %s | %zu | %s | %s | %s |\n", m.mesh.name.c_str(),
                    sizeText(sprite.width(), sprite.height(), sprite.depthComplexity).c_str(),
                    vds::toString(sprite.grid.axis), vds::toString(cpuAxis), edges,
                    rate(double(n), tv.best()).c_str(), rate(double(n), tb.best()).c_str(),
                    ratio(tb.best(), tv.best()).c_str(), rate(double(n) * edges, tb.best()).c_str(), differ,
                    rate(double(cells), og.best()).c_str(), rate(double(cells), op.best()).c_str(),
                    ratio(op.best(), og.best()).c_str());
        std::fflush(stdout);
    }
}

// --quick and --full: the settings they stand for.
void applyMode(Settings& set, bool quick, bool full) {
    if (quick) {
        set.mode = "quick";
        set.resolutions = {512};
        set.knotResolutions = {512};
        set.sphereResolutions = {1024};
        set.points = 1000000;
        set.classifyResolution = 1024;
        set.gwnPoints = 100000;
        set.gwnDims = 64;
        set.bakeRuns = 1;
        set.classifyRuns = 1;
        set.sizes = false;
    } else if (full) {
        set.mode = "full";
        set.resolutions = {512, 1024, 2048};
        set.knotResolutions = {1024, 2048};
        set.sphereResolutions = {1024, 2048};
        set.points = 100000000;
        set.bakeRuns = 3;
        set.classifyRuns = 5;
    }
}

// Every program compiled once, outside the figures.
void compileOnce(vds::GlContext& gl) {
    vds::BakeOptions o;
    o.resolution = 16;
    const auto box = vds::solids::box({0, 0, 0}, {1, 1, 1}).mesh;
    for (auto method : {vds::BakeMethod::Peel, vds::BakeMethod::Lists}) {
        o.method = method;
        vds::bake(gl, box, o);
    }
    vds::bakeToGpu(gl, box, o);
}

void printSizes(const std::vector<SizeRow>& sizes) {
    if (sizes.empty()) return;
    std::puts("\n## File size: .vds (OpenEXR deep, ZIPS) vs the paper's dense float texture\n");
    std::puts("| mesh | resolution | crossings | .vds bytes | dense bytes | dense / .vds |");
    std::puts("|---|---:|---:|---:|---:|---:|");
    for (const auto& s : sizes)
        std::printf("| %s | %u | %zu | %zu | %zu | %.1fx |\n", s.mesh.c_str(), s.res, s.crossings, s.file, s.dense,
                    double(s.dense) / double(s.file));
}

} // namespace

int main(int argc, char** argv) {
    Settings set;
    CLI::App app{"vds_bench: bake time, bake phases, classification throughput and file size, printed as tables"};
    bool quick = false, full = false, bakeOnly = false, classifyOnly = false, noCpuBake = false, noPeel = false,
         plainForms = false;
    std::vector<std::uint32_t> resolutions;
    std::size_t points = 0;
    std::uint32_t classifyResolution = 0;
    unsigned runs = 0;
    auto* quickFlag = app.add_flag("--quick", quick,
                                   "mesh files at 512, knot at 512, sphere at 1024, 1M points, one run each (about a "
                                   "minute on llvmpipe)");
    app.add_flag("--full", full,
                 "mesh files at 512, 1024 and 2048, knot and sphere at 1024 and 2048, 100M points, best of 3 "
                 "(for GPUs)")
        ->excludes(quickFlag);
    app.add_option("--resolutions", resolutions, "bake resolutions of the mesh files (default 1024)")->delimiter(',');
    app.add_option("--points", points, "points classified per mesh (default 10M)");
    app.add_option("--classify-resolution", classifyResolution, "resolution of the sprites classified against (default 2048)");
    app.add_option("--runs", runs, "runs of each timed step; the best is reported (default 2)");
    app.add_option("--warm-up", set.warmUp, "seconds of GPU work before each timed GPU figure (default 0.5)");
    app.add_option("--gwn-points", set.gwnPoints,
                   "points a mesh for the generalized winding table, open meshes only (default 1M; 0: no table)");
    app.add_option("--gwn-dims", set.gwnDims, "cells a side of its occupancy grids (default 256)");
    app.add_option("--meshes", set.meshDir, "folder of .obj meshes (default bench/meshes: bench/fetch-meshes.sh fills it)");
    app.add_flag("--no-cpu-bake", noCpuBake, "skip the exact CPU baker");
    app.add_flag("--no-peel", noPeel, "skip depth peeling");
    auto* bakeFlag = app.add_flag("--bake-only", bakeOnly, "bake tables only");
    app.add_flag("--classify-only", classifyOnly, "classification table only")->excludes(bakeFlag);
    app.add_flag("--plain-forms", plainForms,
                 "the plain parity kernel's forms only (columns from storage buffers or buffer textures; one or four "
                 "points an invocation), at --points and --classify-resolution");
    app.add_option("meshes", set.meshFiles, "mesh files instead of those of bench/meshes and the generated meshes");
    CLI11_PARSE(app, argc, argv);

    applyMode(set, quick, full);
    if (!resolutions.empty()) set.resolutions = resolutions;
    if (points) set.points = points;
    if (classifyResolution) set.classifyResolution = classifyResolution;
    if (runs) set.bakeRuns = set.classifyRuns = runs;
    set.cpuBake = !noCpuBake;
    set.peel = !noPeel;
    set.bakeTable = !classifyOnly;
    set.classifyTable = !bakeOnly;
    set.sizes = set.sizes && set.bakeTable;
    try {
        const std::vector<BenchMesh> meshes = loadMeshes(set);
        vds::GlContext gl;
        const vds::GlInfo& info = gl.info();
        std::printf("# vds_bench (%s)\n\nGL: %s | %s | %s | platform %s\n", set.mode.c_str(), info.vendor.c_str(),
                    info.renderer.c_str(), info.version.c_str(), info.platform.c_str());
        std::printf("CPU threads: %u\n\n", std::max(1u, std::thread::hardware_concurrency()));
        compileOnce(gl);
        if (plainForms) {
            plainFormsTable(set, gl, meshes);
            return 0;
        }
        std::vector<SizeRow> sizes;
        if (set.bakeTable) bakeTable(set, gl, meshes, sizes);
        if (set.classifyTable) classifyTable(set, gl, meshes);
        if (set.classifyTable && set.gwnPoints) gwnTable(set, gl, meshes);
        printSizes(sizes);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "vds_bench: error: %s\n", e.what());
        return 1;
    }
    return 0;
}
