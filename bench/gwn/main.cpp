// vds_gwn_bench: the generalized winding number of open meshes, exact, in
// sprites and over grids, against the brute-force per-edge sum, with the
// points split by how close their value lies to 1/2; all rates in one run.
//
//   vds_gwn_bench [MESH.obj ...] [--points 200000] [--resolution 1024]
//                 [--dims 64] [--threads 1] [--no-generated] [--only NAME]
//                 [--dump DIR]
//
// Meshes: the ones named (default: the bunny, teapot and suzanne beside the
// project, if present), then four hard cases built in code: a shell with one
// large opening, a sphere with 100 punched holes, a soup of 400 loose
// triangles (1,200 boundary edges) and a non-manifold shell (open underside,
// a fin inside sharing a ring of edges).
//
// Yardstick: for each of `--points` uniform points in the mesh's box padded
// by 10%, w = ExactClassifier::generalizedWinding, the exact crossing count
// plus the boundary term summed over every boundary edge in double (the
// Antipodal split); inside where w > 1/2 + 1e-9 (closer to 1/2 is a tie). Each method labels every
// point once (wrong labels counted against the yardstick), again, and then
// each |w - 1/2| band on its own, its points repeated up to 20,000 where
// fewer, timed (wall clock, `--threads` threads). One-time builds are
// timed apart, the same way for both ("build", ms): the exact classifier's
// construction (its triangles' grid, its caps and their range grid), and
// the sprite's caps (by a call on one point; the bake not counted); the
// first call ("all") counts the cells of the range grid the points land in.
// Occupancy: `--dims` cubed cells of the padded box by the mesh sweep, its
// labels checked against the exact classifier at the cell centres.
//
// `--dump DIR` writes, for each mesh, NAME.obj (its positions and triangles
// as measured), NAME.points (the points, little-endian float32 x y z) and
// NAME.w (the yardstick's values, float64), so that a method built outside
// the project can be measured on the same points and checked the same way.
#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include <CLI/CLI.hpp>
#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>

#include <vds/bake.h>
#include <vds/error.h>
#include <vds/exact.h>
#include <vds/mesh_io.h>
#include <vds/occupancy.h>
#include <vds/sprite.h>

#include "solids.h"

namespace {

using Clock = std::chrono::steady_clock;
constexpr double kPi = glm::pi<double>(); // for the generated spheres

double seconds(Clock::time_point since) { return std::chrono::duration<double>(Clock::now() - since).count(); }

// body(k) for every k < count, on all cores (the yardstick's values: not
// timed).
template <class Body>
void forEachOnAllCores(std::size_t count, const Body& body) {
    const std::size_t threads = std::max(1u, std::thread::hardware_concurrency());
    std::vector<std::thread> crew;
    for (std::size_t t = 0; t < threads; ++t)
        crew.emplace_back([&, t] {
            for (std::size_t k = t * count / threads; k < (t + 1) * count / threads; ++k) body(k);
        });
    for (std::thread& thread : crew) thread.join();
}

std::vector<glm::vec3> uniformPoints(const vds::Box& box, std::size_t n, std::mt19937& rng) {
    const glm::vec3 pad = 0.1f * (box.hi - box.lo);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::vector<glm::vec3> points(n);
    for (glm::vec3& p : points)
        for (int a = 0; a < 3; ++a) p[a] = box.lo[a] - pad[a] + u(rng) * (box.hi[a] - box.lo[a] + 2.0f * pad[a]);
    return points;
}

// ---- generated hard cases --------------------------------------------------

vds::TriangleMesh shellWithOpening() {
    return vds::solids::openSphere(96, 192, [](const glm::vec3& c) { return c.z < 0.6f; });
}

vds::TriangleMesh punchedSphere() {
    std::mt19937 rng(7);
    std::normal_distribution<float> g(0.0f, 1.0f);
    std::vector<glm::vec3> holes(100);
    for (glm::vec3& h : holes) h = glm::normalize(glm::vec3(g(rng), g(rng), g(rng)));
    return vds::solids::openSphere(96, 192, [&](const glm::vec3& c) {
        for (const glm::vec3& h : holes)
            if (glm::dot(c, h) > 0.9985f) return false;
        return true;
    });
}

vds::TriangleMesh soup() { return vds::solids::looseTriangles(400, 0.15f, 11); }

// An open-bottomed sphere with a fin inside: triangles on the ring of edges
// at the equator, pointing inward, so that ring's edges have three faces.
vds::TriangleMesh nonManifoldShell() {
    const int rings = 64, segments = 128;
    vds::TriangleMesh m = vds::solids::openSphere(rings, segments, [](const glm::vec3& c) { return c.z > -0.7f; });
    const int i = rings / 2;
    for (int j = 0; j < segments; ++j) {
        const glm::vec3 a = m.positions[std::size_t(i * segments + j)],
                        b = m.positions[std::size_t(i * segments + (j + 1) % segments)];
        m.positions.push_back(0.5f * (a + b) * 0.6f + glm::vec3(0.0f, 0.0f, 0.3f));
        m.triangles.push_back({std::uint32_t(i * segments + j), std::uint32_t(i * segments + (j + 1) % segments),
                               std::uint32_t(m.positions.size() - 1)});
    }
    return m;
}

// ---- the table -------------------------------------------------------------

// The label of a per-edge sum: values within 1e-9 of 1/2 are ties, outside.
bool inside(double w) { return w > 0.5 + 1e-9; }

const double kBands[] = {0.001, 0.02, 0.1};
constexpr int kBandCount = 4; // |w - 1/2| < 0.001, < 0.02, < 0.1, the rest

int bandOf(double w) {
    const double d = std::fabs(w - 0.5);
    for (int b = 0; b < 3; ++b)
        if (d < kBands[b]) return b;
    return 3;
}

struct Row {
    std::string mesh, method;
    std::size_t wrong = 0;
    double build = -1.0; ///< ms: the one-time build before the first call (none: -1)
    double all = 0.0;   ///< the first call: the range grid's cells it fills counted, builds not
    double again = 0.0; ///< the same points again
    double band[kBandCount] = {};
};

/// Fewest points a band is timed on (its points repeated).
constexpr std::size_t kBandTimed = 20000;

template <class Classify>
Row measure(const std::string& mesh, const std::string& method, const std::vector<glm::vec3>& points,
            const std::vector<double>& w, const std::vector<std::vector<glm::vec3>>& bands, Classify&& classify) {
    Row row{mesh, method};
    std::vector<std::uint8_t> labels(points.size());
    auto t0 = Clock::now();
    classify(points, labels);
    row.all = double(points.size()) / seconds(t0) / 1e6;
    for (std::size_t k = 0; k < points.size(); ++k) row.wrong += (labels[k] != 0) != inside(w[k]);
    t0 = Clock::now();
    classify(points, labels);
    row.again = double(points.size()) / seconds(t0) / 1e6;
    for (int b = 0; b < kBandCount; ++b) {
        const std::vector<glm::vec3>& band = bands[std::size_t(b)];
        if (band.empty()) continue;
        // A small band is timed over copies of its points (at least
        // kBandTimed in one call): a dozen points alone time the call.
        std::vector<glm::vec3> timed;
        timed.reserve(std::max(band.size(), kBandTimed));
        while (timed.size() < kBandTimed) timed.insert(timed.end(), band.begin(), band.end());
        std::vector<std::uint8_t> l(timed.size());
        t0 = Clock::now();
        classify(timed, l);
        row.band[b] = double(l.size()) / seconds(t0) / 1e6;
    }
    return row;
}

// A file name for a mesh's name: letters and digits, the rest '-'.
std::string slug(const std::string& name) {
    std::string s;
    for (const char c : name) s += std::isalnum(static_cast<unsigned char>(c)) ? c : '-';
    return s;
}

void dump(const std::string& dir, const std::string& name, const vds::TriangleMesh& mesh,
          const std::vector<glm::vec3>& points, const std::vector<double>& w) {
    const std::string base = dir + "/" + slug(name);
    std::ofstream obj(base + ".obj");
    obj.precision(9);
    for (const glm::vec3& p : mesh.positions) obj << "v " << p.x << ' ' << p.y << ' ' << p.z << '\n';
    for (const auto& t : mesh.triangles) obj << "f " << t[0] + 1 << ' ' << t[1] + 1 << ' ' << t[2] + 1 << '\n';
    std::ofstream(base + ".points", std::ios::binary)
        .write(reinterpret_cast<const char*>(points.data()), std::streamsize(points.size() * sizeof(glm::vec3)));
    std::ofstream(base + ".w", std::ios::binary)
        .write(reinterpret_cast<const char*>(w.data()), std::streamsize(w.size() * sizeof(double)));
    if (!obj) throw vds::Error(base + ".obj: cannot write");
}

struct GwnSettings {
    std::size_t points = 200000;
    std::uint32_t resolution = 1024, dims = 64;
    unsigned threads = 1;
    std::string dumpDir;
};

// The sprite's rows: its caps built by the classifier's first call (one
// point), then the timed calls.
Row spriteRow(const std::string& name, const GwnSettings& set,
              const std::vector<glm::vec3>& points, const std::vector<double>& w,
              const std::vector<std::vector<glm::vec3>>& bands, const vds::SpriteClassifier& sprite) {
    const vds::ClassifyOptions gwn{vds::Rule::GeneralizedWinding, set.threads};
    std::uint8_t one = 0;
    const auto built = Clock::now();
    sprite.classify(vds::PointsView(points.data(), 1), &one, gwn);
    const double spriteBuild = seconds(built) * 1e3;
    Row row = measure(name, "sprite GWN @" + std::to_string(set.resolution), points, w, bands,
                      [&](const auto& p, auto& l) { sprite.classify(vds::PointsView(p.data(), p.size()), l.data(), gwn); });
    row.build = spriteBuild;
    return row;
}

// Occupancy by the mesh sweep, checked against the exact classifier at the
// cell centres: one table row.
void occupancyRow(const std::string& name, const vds::TriangleMesh& mesh, const GwnSettings& set,
                  const vds::ExactClassifier& exact, std::size_t edges) {
    const vds::ClassifyOptions gwn{vds::Rule::GeneralizedWinding, set.threads};
    const vds::Box b = vds::meshBounds(mesh);
    const vds::Grid grid = vds::cubicGrid({b.lo - 0.1f * (b.hi - b.lo), b.hi + 0.1f * (b.hi - b.lo)}, set.dims);
    std::vector<std::uint8_t> cells(grid.cellCount()), expected(grid.cellCount());
    const auto t0 = Clock::now();
    vds::occupancy(vds::MeshView(mesh), grid, cells.data(), gwn);
    const double occupancyRate = double(cells.size()) / seconds(t0) / 1e6;
    std::vector<glm::vec3> centres;
    centres.reserve(cells.size());
    for (std::uint32_t i = 0; i < grid.dims.x; ++i)
        for (std::uint32_t j = 0; j < grid.dims.y; ++j)
            for (std::uint32_t k = 0; k < grid.dims.z; ++k) centres.push_back(grid.cellCentre(i, j, k));
    exact.classify({centres.data(), centres.size()}, expected.data(), {vds::Rule::GeneralizedWinding, 0});
    std::size_t differ = 0;
    for (std::size_t k = 0; k < cells.size(); ++k) differ += cells[k] != expected[k];
    std::printf("| %s | %zu | occupancy GWN %ux%ux%u | %zu (vs exact) | | %.3f | | | | | |\n", name.c_str(), edges,
                grid.dims.x, grid.dims.y, grid.dims.z, differ, occupancyRate);
}

// One mesh: the yardstick's values, the methods' rows, the occupancy row
// and how the sprite's caps answer.
void benchMesh(const std::string& name, const vds::TriangleMesh& mesh, const GwnSettings& set) {
    auto built = Clock::now();
    const vds::ExactClassifier exact(mesh, vds::Axis::Z);
    const double exactBuild = seconds(built) * 1e3;
    const std::size_t edges = vds::meshBoundaryEdges(mesh).size() / 2;
    std::mt19937 rng(1);
    const std::vector<glm::vec3> points = uniformPoints(vds::meshBounds(mesh), set.points, rng);
    std::vector<double> w(points.size());
    forEachOnAllCores(points.size(), [&](std::size_t k) { w[k] = exact.generalizedWinding(points[k]); });
    if (!set.dumpDir.empty()) dump(set.dumpDir, name, mesh, points, w);
    std::vector<std::vector<glm::vec3>> bands(kBandCount);
    std::size_t counts[kBandCount] = {};
    for (std::size_t k = 0; k < points.size(); ++k) {
        bands[std::size_t(bandOf(w[k]))].push_back(points[k]);
        ++counts[bandOf(w[k])];
    }
    const vds::ClassifyOptions gwn{vds::Rule::GeneralizedWinding, set.threads};
    std::vector<Row> rows;
    rows.push_back(measure(name, "brute-force per-edge sum", points, w, bands, [&](const auto& p, auto& l) {
        for (std::size_t k = 0; k < p.size(); ++k) l[k] = inside(exact.generalizedWinding(p[k])) ? 1 : 0;
    }));
    rows.push_back(measure(name, "exact GWN", points, w, bands,
                           [&](const auto& p, auto& l) { exact.classify({p.data(), p.size()}, l.data(), gwn); }));
    rows.back().build = exactBuild;
    vds::BakeOptions o;
    o.resolution = set.resolution;
    const vds::SpriteClassifier sprite(vds::bakeCpu(mesh, o));
    rows.push_back(spriteRow(name, set, points, w, bands, sprite));
    // (A sprite's labels may differ from the yardstick's within a texel of
    // the surface: its points sit at texel centres.)
    for (const Row& r : rows) {
        char build[32] = "";
        if (r.build >= 0.0) std::snprintf(build, sizeof build, "%.1f", r.build);
        std::printf("| %s | %zu | %s | %zu | %s | %.3f | %.3f | %.3f | %.3f | %.3f | %.3f |\n", r.mesh.c_str(), edges,
                    r.method.c_str(), r.wrong, build, r.all, r.again, r.band[0], r.band[1], r.band[2], r.band[3]);
    }
    occupancyRow(name, mesh, set, exact, edges);
    std::printf("| %s | | points per band | | | %zu | | %zu | %zu | %zu | %zu |\n", name.c_str(), points.size(),
                counts[0], counts[1], counts[2], counts[3]);
    std::fflush(stdout);
}

} // namespace

int main(int argc, char** argv) {
    CLI::App app("vds_gwn_bench: generalized winding numbers on open meshes");
    std::vector<std::string> meshes;
    GwnSettings set;
    bool noGenerated = false;
    std::string only;
    app.add_option("meshes", meshes, "meshes (default: the bunny, teapot and suzanne of bench/meshes, from bench/fetch-meshes.sh)");
    app.add_option("--points", set.points, "uniform points in the padded box");
    app.add_option("--resolution", set.resolution, "sprite resolution");
    app.add_option("--dims", set.dims, "occupancy grid cells along each side");
    app.add_option("--threads", set.threads, "threads (0: all)");
    app.add_flag("--no-generated", noGenerated, "leave out the hard cases built in code");
    app.add_option("--only", only, "measure only the meshes whose name contains this");
    app.add_option("--dump", set.dumpDir, "write each mesh, its points and the yardstick's values into this folder");
    CLI11_PARSE(app, argc, argv);
    if (meshes.empty())
        for (const char* name : {"stanford-bunny", "teapot", "suzanne"})
            meshes.push_back(std::string(VDS_BENCH_MESHES) + "/" + name + ".obj");
    try {
        std::vector<std::pair<std::string, vds::TriangleMesh>> inputs;
        for (const std::string& path : meshes) {
            std::string name = path.substr(path.find_last_of('/') + 1);
            inputs.emplace_back(name.substr(0, name.find_last_of('.')), vds::loadMesh(path));
        }
        if (!noGenerated) {
            inputs.emplace_back("shell, one large opening", shellWithOpening());
            inputs.emplace_back("sphere, 100 punched holes", punchedSphere());
            inputs.emplace_back("soup, 400 loose triangles", soup());
            inputs.emplace_back("non-manifold shell", nonManifoldShell());
        }
        std::printf("%zu uniform points in the padded box, %u thread(s); rates in million points (cells) per "
                    "second; bands by the yardstick's |w - 1/2|\n\n",
                    set.points, set.threads);
        std::printf("| mesh | boundary edges | method | wrong | build ms | all | again | < 0.001 | < 0.02 | < 0.1 | >= 0.1 |\n"
                    "|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|\n");
        for (const auto& [name, mesh] : inputs)
            if (name.find(only) != std::string::npos) benchMesh(name, mesh, set);
    } catch (const vds::Error& e) {
        std::fprintf(stderr, "vds_gwn_bench: %s\n", e.what());
        return 1;
    }
    return 0;
}
