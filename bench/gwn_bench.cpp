// vds_gwn_bench: parity, winding and the generalized winding number (exact,
// and in sprites) on open meshes, against a brute-force double-precision
// solid-angle sum; and their throughput side by side in one run.
//
//   vds_gwn_bench [MESH.obj ...] [--points 20000] [--resolutions 512,1024,2048]
//                 [--throughput 200000] [--threads 0] [--slices DIR]
//
// Accuracy: `--points` uniform points in the mesh's box padded by 10% on
// every side; the yardstick is inside where the brute-force GWN w > 1/2,
// points with |w - 1/2| <= 0.02 left out. Throughput: `--throughput` other
// uniform points in the same box, each method classifying all of them in
// one batch on `--threads` threads (wall clock, the sprite's bake not
// counted, the capped loops' build counted).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <glm/geometric.hpp>

#include <vds/all.h>
#include <vds/bake.h>
#include <vds/error.h>
#include <vds/eval/image.h>
#include <vds/exact.h>
#include <vds/mesh_io.h>
#include <vds/detail/parallel.h>
#include <vds/sprite.h>

namespace {

using Clock = std::chrono::steady_clock;

double seconds(Clock::time_point since) { return std::chrono::duration<double>(Clock::now() - since).count(); }

std::vector<double> bruteForceGwn(const vds::TriangleMesh& mesh, const std::vector<glm::vec3>& points,
                                  unsigned threads) {
    std::vector<double> w(points.size());
    vds::parallelFor(threads, points.size(), 64, [&](std::size_t begin, std::size_t end) {
        for (std::size_t k = begin; k < end; ++k) {
            const glm::dvec3 p(points[k]);
            double sum = 0.0;
            for (const glm::uvec3& t : mesh.triangles) {
                const glm::dvec3 a = glm::dvec3(mesh.positions[t[0]]) - p, b = glm::dvec3(mesh.positions[t[1]]) - p,
                                 c = glm::dvec3(mesh.positions[t[2]]) - p;
                const double la = glm::length(a), lb = glm::length(b), lc = glm::length(c);
                sum += 2.0 * std::atan2(glm::dot(a, glm::cross(b, c)),
                                        la * lb * lc + glm::dot(a, b) * lc + glm::dot(a, c) * lb + glm::dot(b, c) * la);
            }
            w[k] = sum / (4.0 * 3.14159265358979323846);
        }
    });
    return w;
}

std::vector<glm::vec3> uniformPoints(const vds::Box& box, std::size_t n, std::mt19937& rng) {
    const glm::vec3 pad = 0.1f * (box.hi - box.lo);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::vector<glm::vec3> points(n);
    for (glm::vec3& p : points)
        for (int a = 0; a < 3; ++a) p[a] = box.lo[a] - pad[a] + u(rng) * (box.hi[a] - box.lo[a] + 2.0f * pad[a]);
    return points;
}

struct Tally {
    std::size_t compared = 0, wrong = 0;
};

Tally tally(const std::vector<double>& w, const std::vector<std::uint8_t>& labels) {
    Tally t;
    for (std::size_t k = 0; k < w.size(); ++k) {
        if (std::fabs(w[k] - 0.5) <= 0.02) continue;
        ++t.compared;
        t.wrong += (labels[k] != 0) != (w[k] > 0.5);
    }
    return t;
}

void printRow(const std::string& mesh, const std::string& method, const Tally& t) {
    std::printf("| %s | %s | %zu | %.3f%% |\n", mesh.c_str(), method.c_str(), t.wrong,
                100.0 * double(t.wrong) / double(std::max<std::size_t>(1, t.compared)));
}

// A slice through the mesh's box at depth z, x across and y up: `exact`'s
// parity on the left, the sprite's GWN on the right; inside is dark.
void writeSlices(const vds::TriangleMesh& mesh, const vds::ExactClassifier& exact, const vds::Sprite& sprite,
                 const std::string& path, unsigned threads, float z) {
    const vds::Box box = vds::meshBounds(mesh);
    const glm::vec3 pad = 0.05f * (box.hi - box.lo);
    const std::uint32_t w = 360, h = std::uint32_t(std::lround(360.0 * double(box.hi.y - box.lo.y + 2 * pad.y) /
                                                               double(box.hi.x - box.lo.x + 2 * pad.x)));
    std::vector<glm::vec3> points(std::size_t(w) * h);
    for (std::uint32_t y = 0; y < h; ++y)
        for (std::uint32_t x = 0; x < w; ++x)
            points[std::size_t(y) * w + x] = {box.lo.x - pad.x + (float(x) + 0.5f) / float(w) * (box.hi.x - box.lo.x + 2 * pad.x),
                                              box.hi.y + pad.y - (float(y) + 0.5f) / float(h) * (box.hi.y - box.lo.y + 2 * pad.y), z};
    std::vector<std::uint8_t> parity(points.size()), gwn(points.size());
    exact.classify({points.data(), points.size()}, parity.data(), {vds::Rule::Parity, threads});
    vds::classify(sprite, {points.data(), points.size()}, gwn.data(), {vds::Rule::GeneralizedWinding, threads});
    vds::eval::Image image(2 * w + 8, h);
    for (std::size_t k = 0; k < image.rgba.size(); ++k) image.rgba[k] = 255;
    for (std::uint32_t y = 0; y < h; ++y)
        for (std::uint32_t x = 0; x < w; ++x) {
            const std::size_t k = std::size_t(y) * w + x;
            for (int panel = 0; panel < 2; ++panel) {
                std::uint8_t* px = image.at(x + std::uint32_t(panel) * (w + 8), y);
                const bool inside = (panel == 0 ? parity[k] : gwn[k]) != 0;
                px[0] = inside ? 40 : 235;
                px[1] = inside ? 60 : 235;
                px[2] = inside ? 110 : 230;
            }
        }
    vds::eval::writePng(image, path);
}

} // namespace

int main(int argc, char** argv) {
    CLI::App app("vds_gwn_bench: generalized winding numbers on open meshes");
    std::vector<std::string> meshes;
    std::vector<std::uint32_t> resolutions = {512, 1024, 2048};
    std::size_t pointCount = 20000, throughput = 200000;
    unsigned threads = 0;
    std::string slices;
    app.add_option("meshes", meshes, "meshes (default: the bunny, teapot and suzanne of ../shared/meshes)");
    app.add_option("--points", pointCount, "uniform points for accuracy");
    app.add_option("--resolutions", resolutions, "sprite resolutions")->delimiter(',');
    app.add_option("--throughput", throughput, "uniform points for throughput");
    app.add_option("--threads", threads, "threads (0: all)");
    app.add_option("--slices", slices, "write parity-vs-GWN slice PNGs of each mesh into this directory: at mid z, and through the boundary's median z with parity along y");
    CLI11_PARSE(app, argc, argv);
    if (meshes.empty())
        for (const char* name : {"stanford-bunny", "teapot", "suzanne"})
            meshes.push_back(std::string(VDS_SHARED_MESHES) + "/" + name + ".obj");
    try {
        std::printf("| mesh | method | wrong | wrong share |\n|---|---|---|---|\n");
        std::vector<std::string> speed;
        for (const std::string& path : meshes) {
            const vds::TriangleMesh mesh = vds::loadMesh(path);
            std::string name = path.substr(path.find_last_of('/') + 1);
            name = name.substr(0, name.find_last_of('.'));
            const vds::Box box = vds::meshBounds(mesh);
            std::mt19937 rng(1);
            const std::vector<glm::vec3> points = uniformPoints(box, pointCount, rng);
            const std::vector<double> w = bruteForceGwn(mesh, points, threads);
            const vds::ExactClassifier exact(mesh, vds::Axis::Z);
            std::vector<std::uint8_t> labels(points.size());
            for (vds::Rule rule : {vds::Rule::Parity, vds::Rule::Winding, vds::Rule::GeneralizedWinding}) {
                exact.classify({points.data(), points.size()}, labels.data(), {rule, threads});
                printRow(name, std::string("exact ") + vds::toString(rule), tally(w, labels));
            }
            // Throughput points, and the exact classifier's rates.
            const std::vector<glm::vec3> many = uniformPoints(box, throughput, rng);
            std::vector<std::uint8_t> manyLabels(many.size());
            const auto rate = [&](auto&& run) {
                const auto t0 = Clock::now();
                run();
                return double(many.size()) / seconds(t0) / 1e6;
            };
            const double exactParity = rate([&] {
                exact.classify({many.data(), many.size()}, manyLabels.data(), {vds::Rule::Parity, threads});
            });
            const double exactGwn = rate([&] {
                exact.classify({many.data(), many.size()}, manyLabels.data(), {vds::Rule::GeneralizedWinding, threads});
            });
            for (std::uint32_t resolution : resolutions) {
                vds::BakeOptions o;
                o.resolution = resolution;
                o.method = vds::BakeMethod::Cpu;
                const vds::Sprite sprite = vds::bake(mesh, o);
                const std::string tag = "sprite " + std::to_string(resolution) + " ";
                for (vds::Rule rule : {vds::Rule::Parity, vds::Rule::Winding}) {
                    vds::classify(sprite, {points.data(), points.size()}, labels.data(), {rule, threads});
                    printRow(name, tag + vds::toString(rule), tally(w, labels));
                }
                vds::ClassifyOptions gwn{vds::Rule::GeneralizedWinding, threads, vds::QueryLayout::Auto,
                                         vds::BoundaryEvaluation::Exact};
                vds::classify(sprite, {points.data(), points.size()}, labels.data(), gwn);
                printRow(name, tag + "GWN (exact boundary term)", tally(w, labels));
                gwn.boundary = vds::BoundaryEvaluation::Caps;
                vds::classify(sprite, {points.data(), points.size()}, labels.data(), gwn);
                printRow(name, tag + "GWN (capped loops)", tally(w, labels));

                const double spriteParity = rate([&] {
                    vds::classify(sprite, {many.data(), many.size()}, manyLabels.data(), {vds::Rule::Parity, threads});
                });
                gwn.boundary = vds::BoundaryEvaluation::Exact;
                const double spriteExact = rate([&] { vds::classify(sprite, {many.data(), many.size()}, manyLabels.data(), gwn); });
                // A copy starts without the caps: their build is counted.
                const vds::Sprite fresh = sprite;
                gwn.boundary = vds::BoundaryEvaluation::Caps;
                const double spriteCaps = rate([&] { vds::classify(fresh, vds::PointsView(many.data(), many.size()), manyLabels.data(), gwn); });
                const double spriteWinding = rate([&] {
                    vds::classify(sprite, {many.data(), many.size()}, manyLabels.data(), {vds::Rule::Winding, threads});
                });
                char line[256];
                std::snprintf(line, sizeof line, "| %s | %zu | %zu | %u | %.3f | %.3f | %.2f | %.2f | %.2f | %.2f |",
                              name.c_str(), mesh.triangles.size(), sprite.boundaryEdges.size() / 2, resolution,
                              exactParity, exactGwn, spriteParity, spriteWinding, spriteExact, spriteCaps);
                speed.push_back(line);
                if (!slices.empty() && resolution == 1024) {
                    writeSlices(mesh, exact, sprite, slices + "/gwn-slice-" + name + ".png", threads,
                                0.5f * (box.lo.z + box.hi.z));
                    // Through the holes: at the median depth of the boundary's
                    // vertices, parity by rays along -y (the bunny's base holes
                    // face -y, so columns over them miss a crossing).
                    const std::vector<glm::vec3> edges = vds::meshBoundaryEdges(mesh);
                    if (!edges.empty()) {
                        std::vector<float> zs;
                        for (const glm::vec3& e : edges) zs.push_back(e.z);
                        std::nth_element(zs.begin(), zs.begin() + std::ptrdiff_t(zs.size() / 2), zs.end());
                        const vds::ExactClassifier alongY(mesh, vds::Axis::Y);
                        writeSlices(mesh, alongY, sprite, slices + "/gwn-holes-slice-" + name + ".png", threads,
                                    zs[zs.size() / 2]);
                        std::printf("(slice through the holes at z = %.5f)\n", double(zs[zs.size() / 2]));
                    }
                }
            }
            std::fflush(stdout);
        }
        std::printf("\nThroughput, million points/s (%zu uniform points in the padded box):\n\n", throughput);
        std::printf("| mesh | triangles | boundary edges | sprite resolution | exact parity | exact GWN | sprite parity | "
                    "sprite winding | sprite GWN, exact term | sprite GWN, capped loops |\n"
                    "|---|---|---|---|---|---|---|---|---|---|\n");
        for (const std::string& line : speed) std::printf("%s\n", line.c_str());
    } catch (const vds::Error& e) {
        std::fprintf(stderr, "vds_gwn_bench: %s\n", e.what());
        return 1;
    }
    return 0;
}
