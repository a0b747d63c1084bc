// vds_io_bench: how fast meshes are read from files and validated.
//
//   vds_io_bench [MESH ...] [--triangles 1000000] [--runs 5] [--dir DIR]
//
// Generates a closed torus of about `--triangles` triangles (a grid of
// quads, two triangles each), writes it as OBJ text ("%.6f" coordinates, as
// most exporters write them), binary little-endian PLY and binary STL into
// a temporary folder (temp file + rename), then reads each with
// vds::loadMesh and prints MB/s (file bytes over the best of `--runs` wall
// times), beside the rate of reading the bytes alone (the disk, or the page
// cache, speed), and the same for each MESH file given. Then validateMesh
// on the generated mesh, on one thread and on all: the best of `--runs`
// times in ms and the report. Each figure is given by wall time and by the
// process's CPU time (steadier on a shared machine). One process, one run:
// the figures compare with each other, not with other machines.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <functional>
#include <string>
#include <vector>

#include <time.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <glm/gtc/constants.hpp>

#include <vds/mesh.h>
#include <vds/mesh_check.h>
#include <vds/mesh_io.h>

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

/// A torus of `rings` x `sides` quads, two triangles each, facing out.
vds::TriangleMesh torus(std::uint32_t rings, std::uint32_t sides) {
    vds::TriangleMesh m;
    const double pi = glm::pi<double>();
    for (std::uint32_t i = 0; i < rings; ++i)
        for (std::uint32_t j = 0; j < sides; ++j) {
            const double u = 2 * pi * i / rings, v = 2 * pi * j / sides;
            const double r = 1.0 + 0.35 * std::cos(v);
            m.positions.emplace_back(float(r * std::cos(u)), float(r * std::sin(u)), float(0.35 * std::sin(v)));
        }
    const auto at = [&](std::uint32_t i, std::uint32_t j) { return (i % rings) * sides + j % sides; };
    for (std::uint32_t i = 0; i < rings; ++i)
        for (std::uint32_t j = 0; j < sides; ++j) {
            m.triangles.emplace_back(at(i, j), at(i + 1, j), at(i + 1, j + 1));
            m.triangles.emplace_back(at(i, j), at(i + 1, j + 1), at(i, j + 1));
        }
    return m;
}

void writeAtomically(const fs::path& path, const std::string& bytes) {
    const fs::path partial = path.string() + ".partial";
    std::ofstream(partial, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
    fs::rename(partial, path);
}

std::string objText(const vds::TriangleMesh& m) {
    std::string s;
    char line[128];
    for (const auto& p : m.positions) {
        std::snprintf(line, sizeof line, "v %.6f %.6f %.6f\n", double(p.x), double(p.y), double(p.z));
        s += line;
    }
    for (const auto& t : m.triangles) {
        std::snprintf(line, sizeof line, "f %u %u %u\n", t.x + 1, t.y + 1, t.z + 1);
        s += line;
    }
    return s;
}

template <class T> void put(std::string& out, T v) { out.append(reinterpret_cast<const char*>(&v), sizeof v); }

std::string plyBinary(const vds::TriangleMesh& m) {
    std::string s = "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(m.positions.size()) +
                    "\nproperty float x\nproperty float y\nproperty float z\nelement face " +
                    std::to_string(m.triangles.size()) + "\nproperty list uchar int vertex_indices\nend_header\n";
    for (const auto& p : m.positions) {
        put(s, p.x);
        put(s, p.y);
        put(s, p.z);
    }
    for (const auto& t : m.triangles) {
        put(s, std::uint8_t(3));
        for (int k = 0; k < 3; ++k) put(s, std::int32_t(t[k]));
    }
    return s;
}

std::string stlBinary(const vds::TriangleMesh& m) {
    std::string s(80, ' ');
    put(s, std::uint32_t(m.triangles.size()));
    for (const auto& t : m.triangles) {
        for (int k = 0; k < 3; ++k) put(s, 0.0f);
        for (int k = 0; k < 3; ++k)
            for (int c = 0; c < 3; ++c) put(s, m.positions[t[k]][c]);
        put(s, std::uint16_t(0));
    }
    return s;
}

/// Seconds of CPU time this process has used, all its threads together.
double cpuSeconds() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

struct Times {
    double wall = 1e30, cpu = 1e30; ///< the best of the runs, seconds
};

/// The best wall and CPU times of `runs` runs of `work`. On a shared
/// machine the CPU time is the steadier figure of work done on one thread.
Times best(int runs, const std::function<void()>& work) {
    Times t;
    for (int r = 0; r < runs; ++r) {
        const auto start = Clock::now();
        const double cpu = cpuSeconds();
        work();
        t.cpu = std::min(t.cpu, cpuSeconds() - cpu);
        t.wall = std::min(t.wall, std::chrono::duration<double>(Clock::now() - start).count());
    }
    return t;
}

} // namespace

int main(int argc, char** argv) {
    CLI::App app{"vds_io_bench: mesh file reading (MB/s) and validation (ms) on a generated torus"};
    std::size_t triangles = 1000000;
    int runs = 5;
    std::string dir;
    std::vector<std::string> meshes;
    app.add_option("meshes", meshes, "mesh files to read too (.obj, .ply, .stl, .off)");
    app.add_option("--triangles", triangles, "about how many triangles the torus has")->check(CLI::Range(8, 100000000));
    app.add_option("--runs", runs, "runs of each measurement, the best one counts")->check(CLI::Range(1, 100));
    app.add_option("--dir", dir, "folder for the generated files (default: a new one in the system's temp folder)");
    CLI11_PARSE(app, argc, argv);

    try {
        const auto sides = std::uint32_t(std::max(4.0, std::sqrt(double(triangles) / 4.0)));
        const auto rings = std::uint32_t(std::max<std::size_t>(4, triangles / (2 * sides)));
        const vds::TriangleMesh mesh = torus(rings, sides);
        const fs::path folder = dir.empty() ? fs::temp_directory_path() / ("vds_io_bench_" + std::to_string(::getpid()))
                                            : fs::path(dir);
        fs::create_directories(folder);
        std::printf("torus: %zu triangles, %zu vertices; files in %s\n", mesh.triangles.size(), mesh.positions.size(),
                    folder.string().c_str());

        struct File {
            const char* label;
            fs::path path;
            std::string bytes;
        };
        std::vector<File> files = {{"OBJ text", folder / "torus.obj", objText(mesh)},
                                   {"PLY binary", folder / "torus.ply", plyBinary(mesh)},
                                   {"STL binary", folder / "torus.stl", stlBinary(mesh)}};
        for (File& f : files) writeAtomically(f.path, f.bytes);
        for (const std::string& m : meshes) {
            std::ifstream in(m, std::ios::binary);
            std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
            files.push_back({nullptr, m, std::move(bytes)});
        }

        std::printf("%-18s %7s %11s %11s %11s\n", "format", "MB", "load MB/s", "(CPU time)", "bytes MB/s");
        for (const File& f : files) {
            const double mb = double(f.bytes.size()) / 1e6;
            const std::string label = f.label ? f.label : f.path.filename().string();
            std::size_t loaded = 0;
            const Times load = best(runs, [&] { loaded = vds::loadMesh(f.path.string()).triangles.size(); });
            const Times raw = best(runs, [&] {
                std::ifstream in(f.path, std::ios::binary);
                std::vector<char> buffer(f.bytes.size());
                in.read(buffer.data(), std::streamsize(buffer.size()));
            });
            if (f.label && loaded != mesh.triangles.size()) throw std::runtime_error(label + " lost triangles");
            std::printf("%-18s %7.1f %11.0f %11.0f %11.0f\n", label.c_str(), mb, mb / load.wall, mb / load.cpu,
                        mb / raw.wall);
        }
        for (unsigned threads : {1u, 0u}) {
            vds::MeshReport report;
            const Times validate = best(runs, [&] { report = vds::validateMesh(mesh, threads); });
            std::printf("validateMesh, %s: %.1f ms (CPU time %.1f ms): %s\n",
                        threads == 1 ? "1 thread" : "all threads", validate.wall * 1e3, validate.cpu * 1e3,
                        report.summary().c_str());
        }
        if (dir.empty()) fs::remove_all(folder);
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "vds_io_bench: %s\n", e.what());
        return 1;
    }
}
