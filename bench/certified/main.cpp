// Exact answers on the GPU: certified-gpu against sprite-gpu (the GPU's
// approximate rate, the ceiling) and CPU certified (the exact rate it
// replaces), on the same uniform random points in each mesh's box grown
// by 10%, every classifier at the same resolution. Host arrays in and out
// for all three, then GL buffers in and out for the two GPU methods. The
// runs alternate the methods (A B C, A B C, ...) so that a loaded machine
// disturbs them alike; the best of the runs is reported. certified-gpu's
// labels are checked against CPU certified's (the exact classifier's).
//
//   vds_certified_bench [--points N] [--resolution R] [--runs K] [--threads T] MESH...
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include <vds/all.h>
#include <vds/error.h>
#include <vds/gl/certified.h>

#include "points.h"

namespace {

double seconds(const std::function<void()>& f) {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Best wall time of each function over `runs` rounds, the functions taken in turn each round.
std::vector<double> alternate(unsigned runs, const std::vector<std::function<void()>>& fs) {
    std::vector<double> best(fs.size(), 1e300);
    for (unsigned r = 0; r < std::max(1u, runs); ++r)
        for (std::size_t k = 0; k < fs.size(); ++k) best[k] = std::min(best[k], seconds(fs[k]));
    return best;
}

struct Settings {
    std::size_t points = std::size_t(2) << 20;
    std::uint32_t resolution = 1024;
    unsigned runs = 3, threads = 0;
};

void benchMesh(const Settings& set, const vds::GlContext& gl, const std::string& path) {
    const vds::TriangleMesh mesh = vds::loadMesh(path);
    vds::MethodOptions mo;
    mo.resolution = set.resolution;
    mo.axis = vds::Axis::Z; // one grid for all three
    mo.threads = set.threads;
    const auto certified = vds::makeClassifier(mesh, vds::Method::Certified, mo);
    const auto spriteGpu = vds::makeClassifier(gl, mesh, vds::Method::SpriteGpu, mo);
    vds::CertifiedOptions co;
    co.resolution = set.resolution;
    co.threads = set.threads;
    const vds::GpuCertifiedClassifier certifiedGpu(gl, mesh, co);
    const std::vector<glm::vec3> points = vds::test::randomPoints(vds::meshBounds(mesh), set.points, 0.1f, 7);
    const std::size_t n = points.size();
    std::vector<std::uint8_t> a(n), b(n), c(n);
    vds::ClassifyOptions o;
    o.threads = set.threads;
    vds::ClassifyStats stats;
    vds::ClassifyOptions withStats = o;
    withStats.stats = &stats;
    certifiedGpu.classify(points, c.data(), withStats); // warm: programs built, buffers grown
    const std::vector<double> host = alternate(set.runs, {
        [&] { certified->classify(points, a.data(), o); },
        [&] { spriteGpu->classify(points, b.data(), o); },
        [&] { certifiedGpu.classify(points, c.data(), o); },
    });
    std::size_t wrong = 0;
    for (std::size_t k = 0; k < n; ++k) wrong += a[k] != c[k];
    // Resident: points and labels in GL buffers.
    const vds::CurrentContext current(gl);
    const vds::Buffer pointBuffer = vds::Buffer::create(), labels = vds::Buffer::create();
    glNamedBufferStorage(pointBuffer.id(), GLsizeiptr(n * 12), points.data(), 0);
    glNamedBufferStorage(labels.id(), GLsizeiptr((n + 3) / 4 * 4), nullptr, 0);
    vds::GpuClassifier sprites(gl);
    const auto& gpuSprite = dynamic_cast<const vds::GpuSpriteClassifier&>(*spriteGpu).gpuSprite();
    const std::vector<double> resident = alternate(set.runs, {
        [&] {
            sprites.classify(gpuSprite, pointBuffer.id(), n, labels.id(), o);
            glFinish();
        },
        [&] { certifiedGpu.classify(pointBuffer.id(), n, labels.id(), o); },
    });
    const auto rate = [&](double s) { return double(n) / s * 1e-6; };
    std::printf("| %s | %zu | %.3f%% | %.1f | %.1f | %.1f | %.1f | %.1f | %.2f | %.2f | %zu |\n", mesh.name.c_str(),
                mesh.triangles.size(), 100.0 * double(stats.exact) / double(n), rate(host[0]), rate(host[1]),
                rate(host[2]), rate(resident[0]), rate(resident[1]), resident[0] / resident[1], host[0] / host[2],
                wrong);
}

} // namespace

int main(int argc, char** argv) {
    CLI::App app("certified-gpu against sprite-gpu and CPU certified, M points/s");
    Settings set;
    std::vector<std::string> meshes;
    app.add_option("--points", set.points, "uniform points a mesh (default 2M)");
    app.add_option("--resolution", set.resolution, "texels on the longest side, every method (default 1024)");
    app.add_option("--runs", set.runs, "rounds; the best of each is reported (default 3)");
    app.add_option("--threads", set.threads, "CPU threads, 0: all");
    app.add_option("MESH", meshes, "mesh files")->required();
    CLI11_PARSE(app, argc, argv);
    try {
        const vds::GlContext gl;
        std::printf("%zu uniform points a mesh (box + 10%%), resolution %u along z, best of %u alternating "
                    "rounds; %s\n\n",
                    set.points, set.resolution, set.runs, gl.info().renderer.c_str());
        std::puts("| mesh | triangles | exact path | certified CPU | sprite-gpu host | certified-gpu host | "
                  "sprite-gpu resident | certified-gpu resident | resident: certified-gpu / sprite-gpu | "
                  "host: certified-gpu / certified CPU | wrong |");
        std::puts("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
        for (const std::string& path : meshes) benchMesh(set, gl, path);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "vds_certified_bench: %s\n", e.what());
        return 1;
    }
    return 0;
}
