// Benchmark: prints figures, asserts nothing about speed.
//
//   vds_bench [--resolutions 512,1024,2048] [--points N] [--no-cpu-bake] [MESH ...]
//
// 1. Bake time, depth peeling vs fragment lists (and the exact CPU baker), at
//    each resolution, on the meshes given (default: ../shared/meshes/*.obj)
//    and a generated sphere of about 1M triangles; the two GL bakers' layers
//    are compared bit for bit on every bake.
// 2. Classification throughput for N uniform random points (default 10M) in
//    each mesh's padded box, sprites at 1024: CPU with 1 and 2 threads, GL
//    compute (upload, dispatch and read-back included), and the exact
//    classifier on the same points.
// 3. File size of the .vds (OpenEXR deep, ZIPS) vs the dense w*h*d float texture.
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <random>
#include <algorithm>
#include <sstream>
#include <thread>
#include <string>
#include <vector>

#include <vds/bake.h>
#include <vds/exact.h>
#include <vds/gl_context.h>
#include <vds/gpu_sprite.h>
#include <vds/mesh_io.h>
#include "solids.h"
#include <vds/vds_file.h>

namespace {

namespace fs = std::filesystem;

double seconds(const std::function<void()>& f) {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

bool identical(const vds::Sprite& a, const vds::Sprite& b) {
    return a.offsets == b.offsets && a.crossings.size() == b.crossings.size() &&
           std::memcmp(a.crossings.data(), b.crossings.data(), a.crossings.size() * sizeof(float)) == 0;
}

std::vector<std::uint32_t> parseList(const std::string& s) {
    std::vector<std::uint32_t> v;
    std::stringstream in(s);
    std::string item;
    while (std::getline(in, item, ',')) v.push_back(std::uint32_t(std::stoul(item)));
    return v;
}

} // namespace

int main(int argc, char** argv) {
    std::vector<std::uint32_t> resolutions = {512, 1024, 2048};
    std::size_t pointCount = 10000000;
    bool cpuBake = true;
    std::vector<std::string> meshPaths;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--resolutions" && i + 1 < argc) resolutions = parseList(argv[++i]);
        else if (a == "--points" && i + 1 < argc) pointCount = std::stoull(argv[++i]);
        else if (a == "--no-cpu-bake") cpuBake = false;
        else if (a == "--classify-only") resolutions.clear();
        else if (a == "--help") {
            std::puts("usage: vds_bench [--resolutions 512,1024,2048] [--points N] [--no-cpu-bake] [--classify-only] [MESH ...]");
            return 0;
        } else meshPaths.push_back(a);
    }
    if (meshPaths.empty()) {
        for (const char* dir : {"../shared/meshes", "../../shared/meshes", "../../../shared/meshes"})
            if (fs::is_directory(dir)) {
                for (const auto& e : fs::directory_iterator(dir))
                    if (e.path().extension() == ".obj") meshPaths.push_back(e.path().string());
                break;
            }
        std::sort(meshPaths.begin(), meshPaths.end());
    }
    try {
        std::vector<vds::TriangleMesh> meshes;
        for (const auto& p : meshPaths) meshes.push_back(vds::loadMesh(p));
        meshes.push_back(vds::solids::sphere({0, 0, 0}, 1.0f, 1002).mesh); // 1,002,000 triangles
        meshes.back().name = "sphere-1M (generated)";

        vds::GlContext gl;
        const vds::GlInfo& info = gl.info();
        std::printf("GL: %s | %s | platform %s\n", info.renderer.c_str(), info.version.c_str(), info.platform.c_str());
        std::printf("CPU threads available: %u\n\n", std::thread::hardware_concurrency());
        { // warm-up: compile the programs once
            vds::BakeOptions o;
            o.resolution = 16;
            for (auto m : {vds::BakeMethod::Peel, vds::BakeMethod::Lists}) {
                o.method = m;
                vds::bake(vds::solids::box({0, 0, 0}, {1, 1, 1}).mesh, o, &gl);
            }
        }

        if (!resolutions.empty()) {
            std::puts("## Bake time (seconds), one run each\n");
            std::puts("| mesh | triangles | resolution | w x h x d | peel | lists | peel / lists | cpu (exact) | identical |");
            std::puts("|---|---:|---:|---|---:|---:|---:|---:|---|");
        }
        struct SizeRow { std::string mesh; std::uint32_t res; std::size_t file, dense, crossings; };
        std::vector<SizeRow> sizes;
        for (const auto& mesh : meshes)
            for (std::uint32_t res : resolutions) {
                vds::BakeOptions o;
                o.resolution = res;
                o.sourceName = mesh.name;
                vds::Sprite peel, lists, cpu;
                o.method = vds::BakeMethod::Peel;
                const double tPeel = seconds([&] { peel = vds::bake(mesh, o, &gl); });
                o.method = vds::BakeMethod::Lists;
                const double tLists = seconds([&] { lists = vds::bake(mesh, o, &gl); });
                double tCpu = -1;
                if (cpuBake) {
                    o.method = vds::BakeMethod::Cpu;
                    tCpu = seconds([&] { cpu = vds::bake(mesh, o); });
                }
                char cpuText[32] = "-";
                if (tCpu >= 0) std::snprintf(cpuText, sizeof cpuText, "%.2f", tCpu);
                std::printf("| %s | %zu | %u | %ux%ux%u | %.2f | %.2f | %.1fx | %s | %s |\n", mesh.name.c_str(),
                            mesh.triangles.size(), res, lists.width(), lists.height(), lists.depthComplexity, tPeel,
                            tLists, tPeel / tLists, cpuText, identical(peel, lists) ? "yes" : "NO");
                std::fflush(stdout);
                const fs::path file = fs::temp_directory_path() / "vds_bench.vds";
                vds::writeSprite(lists, file.string());
                sizes.push_back({mesh.name, res, std::size_t(fs::file_size(file)), lists.denseBytes(), lists.crossings.size()});
                fs::remove(file);
            }

        if (!sizes.empty()) {
            std::puts("\n## File size: .vds (OpenEXR deep, ZIPS) vs the paper's dense float texture\n");
            std::puts("| mesh | resolution | crossings | .vds bytes | dense bytes | dense / .vds |");
            std::puts("|---|---:|---:|---:|---:|---:|");
        }
        for (const auto& s : sizes)
            std::printf("| %s | %u | %zu | %zu | %zu | %.1fx |\n", s.mesh.c_str(), s.res, s.crossings, s.file, s.dense,
                        double(s.dense) / double(s.file));

        std::printf("\n## Classification: %zu uniform random points in each mesh's box grown by 10%%, sprites at 1024\n\n",
                    pointCount);
        std::puts("Points per second; every classifier answers the same points. VDS CPU answers must equal GL's.\n");
        std::puts("| mesh | w x h x d | VDS CPU 1 thread | VDS CPU 2 threads | VDS GL compute | exact, 2 threads | "
                  "VDS CPU 2 thr / exact | GL / exact | CPU == GL | VDS differs from exact |");
        std::puts("|---|---|---:|---:|---:|---:|---:|---:|---|---:|");
        vds::GpuClassifier classifier(gl);
        std::vector<glm::vec3> points(pointCount);
        std::vector<std::uint8_t> a(pointCount), b(pointCount), c(pointCount), e(pointCount);
        for (const auto& mesh : meshes) {
            vds::BakeOptions o;
            o.resolution = 1024;
            const vds::Sprite sprite = vds::bake(mesh, o, &gl);
            const vds::Box box = sprite.grid.box;
            std::mt19937 rng(42);
            std::uniform_real_distribution<float> u(-0.1f, 1.1f);
            for (auto& p : points) p = box.lo + glm::vec3(u(rng), u(rng), u(rng)) * (box.hi - box.lo);
            vds::ClassifyOptions one, two;
            one.threads = 1;
            two.threads = 2;
            const double t1 = seconds([&] { vds::classify(sprite, points.data(), points.size(), a.data(), one); });
            const double t2 = seconds([&] { vds::classify(sprite, points.data(), points.size(), b.data(), two); });
            const vds::GpuSprite gpu(sprite);
            const double tg = seconds([&] { classifier.classify(gpu, points.data(), points.size(), c.data()); });
            const vds::ExactClassifier exact(mesh);
            const double te = seconds([&] { exact.classify(points.data(), points.size(), e.data(), two); });
            std::size_t differ = 0;
            for (std::size_t k = 0; k < pointCount; ++k) differ += a[k] != e[k];
            const double n = double(pointCount);
            std::printf("| %s | %ux%ux%u | %.3g | %.3g | %.3g | %.3g | %.1fx | %.1fx | %s | %.4f %% |\n", mesh.name.c_str(),
                        sprite.width(), sprite.height(), sprite.depthComplexity, n / t1, n / t2, n / tg, n / te, te / t2,
                        te / tg, (a == b && a == c) ? "yes" : "NO", 100.0 * double(differ) / n);
            std::fflush(stdout);
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "vds_bench: error: %s\n", e.what());
        return 1;
    }
    return 0;
}
