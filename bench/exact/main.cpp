// Benchmark of the exact classifier (<vds/exact.h>): points per second of
// ExactClassifier::classify on 1 and 2 threads against the brute-force loop
// over every triangle, on generated spheres and on meshes given as arguments.
// The brute force (written here, in double precision: a ray towards -z against
// every triangle) runs on a sample of the points only; its rate is
// extrapolated, and its answers are compared with the accelerated ones.
//
// usage: vds_exact_bench [--points N] [--sample N] [mesh.obj ...]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <vds/error.h>
#include <vds/exact.h>
#include <vds/mesh.h>
#include <vds/mesh_io.h>
#include "solids.h"

namespace {

double seconds(std::chrono::steady_clock::time_point since) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

// Whether (x, y) lies left of the edge a -> b, or on it and the edge is a
// top or left one (the half-open rule, so that a point on an edge shared by
// two triangles is counted once).
bool leftOf(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& p) {
    const double cross = (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
    return cross > 0.0 || (cross == 0.0 && (b.y < a.y || (b.y == a.y && b.x > a.x)));
}

// Parity of the crossings in front of `p` (smaller z) over every triangle:
// the plain loop that the exact classifier's grid accelerates. Double
// precision, not exact: on random points it disagrees only where a point
// lies within rounding of a triangle, which the `agree` column would show.
bool insideBruteForce(const vds::TriangleMesh& mesh, const glm::vec3& point) {
    const glm::dvec3 p(point);
    bool inside = false;
    for (const auto& t : mesh.triangles) {
        glm::dvec3 v[3] = {glm::dvec3(mesh.positions[t[0]]), glm::dvec3(mesh.positions[t[1]]),
                           glm::dvec3(mesh.positions[t[2]])};
        const double area = (v[1].x - v[0].x) * (v[2].y - v[0].y) - (v[1].y - v[0].y) * (v[2].x - v[0].x);
        if (area == 0.0) continue; // parallel to the ray: never crossed
        if (area < 0.0) std::swap(v[1], v[2]);
        const glm::dvec2 q(p.x, p.y), a(v[0].x, v[0].y), b(v[1].x, v[1].y), c(v[2].x, v[2].y);
        if (!leftOf(a, b, q) || !leftOf(b, c, q) || !leftOf(c, a, q)) continue;
        // The plane's depth at (x, y), by the barycentric weights.
        const double wa = ((b.x - q.x) * (c.y - q.y) - (b.y - q.y) * (c.x - q.x)) / std::abs(area);
        const double wb = ((c.x - q.x) * (a.y - q.y) - (c.y - q.y) * (a.x - q.x)) / std::abs(area);
        if (wa * v[0].z + wb * v[1].z + (1.0 - wa - wb) * v[2].z < p.z) inside = !inside;
    }
    return inside;
}

std::vector<glm::vec3> randomPoints(const vds::Box& box, std::size_t count) {
    const glm::vec3 margin = 0.1f * (box.hi - box.lo);
    std::mt19937 rng(2008);
    std::vector<glm::vec3> points(count);
    for (auto& p : points)
        for (int a = 0; a < 3; ++a)
            p[a] = std::uniform_real_distribution<float>(box.lo[a] - margin[a], box.hi[a] + margin[a])(rng);
    return points;
}

void run(const std::string& name, const vds::TriangleMesh& mesh, std::size_t pointCount, std::size_t sampleCount) {
    auto start = std::chrono::steady_clock::now();
    const vds::ExactClassifier exact(mesh, vds::Axis::Z);
    const double build = seconds(start);
    const auto points = randomPoints(vds::meshBounds(mesh), pointCount);
    std::vector<std::uint8_t> labels(points.size());

    // Best of three runs per thread count.
    double rate[2] = {0.0, 0.0};
    for (int run = 0; run < 3; ++run)
        for (unsigned threads : {1u, 2u}) {
            vds::ClassifyOptions options;
            options.threads = threads;
            start = std::chrono::steady_clock::now();
            exact.classify({points.data(), points.size()}, labels.data(), options);
            rate[threads - 1] = std::max(rate[threads - 1], double(points.size()) / seconds(start));
        }

    const std::size_t sample = std::min(sampleCount, points.size());
    std::vector<std::uint8_t> brute(sample);
    start = std::chrono::steady_clock::now();
    for (std::size_t k = 0; k < sample; ++k) brute[k] = insideBruteForce(mesh, points[k]) ? 1 : 0;
    const double bruteRate = double(sample) / seconds(start);
    std::size_t agree = 0, inside = 0;
    for (std::size_t k = 0; k < sample; ++k) {
        agree += brute[k] == labels[k];
        inside += labels[k];
    }

    std::printf("%-22s %10zu %8.2f %12.3g %12.3g %12.3g %9.0fx %7zu/%zu\n", name.c_str(), mesh.triangles.size(),
                build, rate[0], rate[1], bruteRate, rate[0] / bruteRate, agree, sample);
    std::fflush(stdout);
}

} // namespace

int main(int argc, char** argv) {
    std::size_t pointCount = 1000000, sampleCount = 2000;
    std::vector<std::string> paths;
    CLI::App app("Points per second of the exact classifier on 1 and 2 threads against brute force, on\n"
                 "generated spheres and on the meshes given.",
                 "vds_exact_bench");
    app.get_formatter()->label("Usage", "usage");
    app.option_defaults()->always_capture_default();
    const CLI::Range count(std::size_t(1), std::size_t(1000000000));
    app.add_option("--points", pointCount, "random points in the mesh box + 10%")->check(count);
    app.add_option("--sample", sampleCount, "points classified by brute force too")->check(count);
    app.add_option("MESH", paths, "more meshes to measure")->type_name("");
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0) return app.exit(e); // --help
        std::fprintf(stderr, "vds_exact_bench: %s (try 'vds_exact_bench --help')\n", e.what());
        return 2;
    }
    try {
        std::printf("exact classifier along z, %zu random points in the mesh box + 10%%; "
                    "brute force on the first %zu\n",
                    pointCount, sampleCount);
        std::printf("%-22s %10s %8s %12s %12s %12s %10s %9s\n", "mesh", "triangles", "build s", "1 thr pt/s",
                    "2 thr pt/s", "brute pt/s", "speed-up", "agree");
        for (std::uint32_t segments : {316u, 1000u})
            run("sphere " + std::to_string(segments), vds::solids::sphere({0, 0, 0}, 1.0f, segments).mesh, pointCount,
                sampleCount);
        for (const auto& path : paths) {
            const vds::TriangleMesh mesh = vds::loadMesh(path);
            run(path.substr(path.find_last_of('/') + 1), mesh, pointCount, sampleCount);
        }
    } catch (const vds::Error& e) {
        std::fprintf(stderr, "vds_exact_bench: %s\n", e.what());
        return 1;
    }
    return 0;
}
