// vds_sparse_band_bench: a narrow band computed sparsely (vds::sparseBand)
// against OpenVDB's meshToLevelSet, the peer users reach for, at the same
// voxels (voxel (i, j, k) centred on vds's cell (i, j, k)) and half-width.
//
//   vds_sparse_band_bench MESH [--subdivide K] --dims N [--band 3] [--threads 2]
//                         --method vds|openvdb|compare
//
// MESH is subdivided K times (each triangle into four at its edges'
// midpoints: the same surface, 4^K times the triangles), so a million
// triangles come from a public mesh. The grid has N cubic cells along the
// longest side of the mesh's box grown by band + 2 cells. One method a run,
// so that the peak memory (the maximum resident size, VmHWM) is that
// method's: time (mesh in memory to band in memory, vds's distance index
// included), peak (the process's, the mesh's own counted, its subdivision's
// not), voxels stored, bytes. `compare` runs both and reads every
// OpenVDB active voxel against vds's exact band: the largest and mean
// difference (in voxels) where both hold a distance, and the voxels whose
// sign differs from vds's (whose signs equal the exact classifier's), the
// first hundred of them settled by the classifier's brute force.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>
#include <openvdb/openvdb.h>
#include <openvdb/tools/MeshToVolume.h>
#include <tbb/global_control.h>

#include <vds/distance.h>
#include <vds/error.h>
#include <vds/exact.h>
#include <vds/mesh_io.h>
#include <vds/sparse_band.h>

namespace {

using Clock = std::chrono::steady_clock;

double seconds(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

/// A line of /proc/self/status ("VmHWM:", "VmRSS:") in GiB.
double statusGiB(const char* field) {
    std::FILE* f = std::fopen("/proc/self/status", "r");
    if (!f) return 0.0;
    char line[256];
    double kib = 0.0;
    while (std::fgets(line, sizeof line, f))
        if (std::strncmp(line, field, std::strlen(field)) == 0) kib = std::atof(line + std::strlen(field));
    std::fclose(f);
    return kib / (1024.0 * 1024.0);
}

/// Starts the peak resident size afresh (Linux: clear_refs 5), so that the
/// peak a method reports is its own, not the mesh's subdivision's.
void resetPeak() {
    if (std::FILE* f = std::fopen("/proc/self/clear_refs", "w")) {
        std::fputs("5", f);
        std::fclose(f);
    }
}

double peakGiB() { return statusGiB("VmHWM:"); }

/// Each triangle into four at its edges' midpoints (shared edges share them).
vds::TriangleMesh subdivide(const vds::TriangleMesh& in) {
    vds::TriangleMesh out;
    out.positions = in.positions;
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> midpoints;
    const auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
        const auto key = std::minmax(a, b);
        const auto [at, added] = midpoints.emplace(key, std::uint32_t(out.positions.size()));
        if (added) out.positions.push_back(0.5f * (in.positions[a] + in.positions[b]));
        return at->second;
    };
    out.triangles.reserve(in.triangles.size() * 4);
    for (const glm::uvec3& t : in.triangles) {
        const std::uint32_t ab = midpoint(t.x, t.y), bc = midpoint(t.y, t.z), ca = midpoint(t.z, t.x);
        out.triangles.insert(out.triangles.end(), {{t.x, ab, ca}, {ab, t.y, bc}, {ca, bc, t.z}, {ab, bc, ca}});
    }
    return out;
}

openvdb::math::Transform::Ptr transformOf(const vds::Grid& grid) {
    const double cell = double(grid.box.hi.x - grid.box.lo.x) / grid.dims.x;
    openvdb::math::Transform::Ptr t = openvdb::math::Transform::createLinearTransform(cell);
    t->postTranslate(openvdb::Vec3d(grid.box.lo.x + 0.5 * cell, grid.box.lo.y + 0.5 * cell, grid.box.lo.z + 0.5 * cell));
    return t;
}

openvdb::FloatGrid::Ptr openvdbBand(const vds::TriangleMesh& mesh, const vds::Grid& grid, float bandCells) {
    std::vector<openvdb::Vec3s> points(mesh.positions.size());
    for (std::size_t k = 0; k < points.size(); ++k)
        points[k] = openvdb::Vec3s(mesh.positions[k].x, mesh.positions[k].y, mesh.positions[k].z);
    std::vector<openvdb::Vec3I> triangles(mesh.triangles.size());
    for (std::size_t k = 0; k < triangles.size(); ++k)
        triangles[k] = openvdb::Vec3I(mesh.triangles[k].x, mesh.triangles[k].y, mesh.triangles[k].z);
    return openvdb::tools::meshToLevelSet<openvdb::FloatGrid>(*transformOf(grid), points, triangles, bandCells);
}

/// Voxels whose sign differs that a brute force settles (`settleSigns`).
constexpr std::size_t kSettled = 100;

struct Comparison {
    std::size_t both = 0, signs = 0, openvdbOnly = 0;
    double maxError = 0.0, sumError = 0.0;
    std::vector<glm::uvec3> disputed; ///< the first kSettled voxels whose sign differs
};

/// Every active voxel of `level` against the vds band's value of its cell.
Comparison compare(const openvdb::FloatGrid& level, const vds::SparseBand& band) {
    Comparison c;
    const float w = float(band.halfWidth);
    const double cell = double(band.grid.box.hi.x - band.grid.box.lo.x) / band.grid.dims.x;
    for (auto leaf = level.tree().cbeginLeaf(); leaf; ++leaf)
        for (auto v = leaf->cbeginValueOn(); v; ++v) {
            const openvdb::Coord at = v.getCoord();
            if (at.x() < 0 || at.y() < 0 || at.z() < 0 || std::uint32_t(at.x()) >= band.grid.dims.x ||
                std::uint32_t(at.y()) >= band.grid.dims.y || std::uint32_t(at.z()) >= band.grid.dims.z) {
                ++c.openvdbOnly;
                continue;
            }
            const float exact = band.value(std::uint32_t(at.x()), std::uint32_t(at.y()), std::uint32_t(at.z()));
            const float theirs = *v;
            if (std::signbit(exact) != std::signbit(theirs) && c.signs++ < kSettled)
                c.disputed.emplace_back(at.x(), at.y(), at.z());
            if (std::abs(exact) < w) {
                ++c.both;
                const double e = std::abs(double(theirs) - double(exact)) / cell;
                c.maxError = std::max(c.maxError, e);
                c.sumError += e;
            } else {
                ++c.openvdbOnly;
            }
        }
    return c;
}

/// How many of the disputed voxels the exact classifier's brute force
/// (every triangle, no acceleration) labels as vds's sign does.
std::size_t settleSigns(const vds::TriangleMesh& mesh, const vds::SparseBand& band, const Comparison& c) {
    const vds::ExactClassifier exact(mesh, vds::Axis::Z);
    std::size_t agree = 0;
    for (const glm::uvec3& at : c.disputed)
        agree += exact.containsByEveryTriangle(band.grid.cellCentre(at.x, at.y, at.z), band.rule) ==
                 std::signbit(band.value(at.x, at.y, at.z));
    return agree;
}

} // namespace

int main(int argc, char** argv) {
    CLI::App app("vds_sparse_band_bench: vds's sparse band against OpenVDB's meshToLevelSet");
    std::string path, method = "vds";
    unsigned subdivisions = 0, threads = 2;
    std::uint32_t dims = 512;
    float bandCells = 3.0f;
    app.add_option("MESH", path, "a closed mesh file")->required();
    app.add_option("--subdivide", subdivisions, "split each triangle into four this many times");
    app.add_option("--dims", dims, "cubic cells along the box's longest side");
    app.add_option("--band", bandCells, "half-width in cells");
    app.add_option("--threads", threads, "threads for both");
    app.add_option("--method", method, "vds, openvdb or compare")->check(CLI::IsMember({"vds", "openvdb", "compare"}));
    CLI11_PARSE(app, argc, argv);
    try {
        vds::TriangleMesh mesh = vds::loadMesh(path);
        for (unsigned k = 0; k < subdivisions; ++k) mesh = subdivide(mesh);
        vds::Box box = vds::meshBounds(mesh);
        const float longest = std::max({box.hi.x - box.lo.x, box.hi.y - box.lo.y, box.hi.z - box.lo.z});
        const float pad = (bandCells + 2.0f) * longest / float(dims - 2.0f * (bandCells + 2.0f));
        box.lo -= glm::vec3(pad);
        box.hi += glm::vec3(pad);
        const vds::Grid grid = vds::cubicGrid(box, dims);
        const double cell = double(grid.box.hi.x - grid.box.lo.x) / grid.dims.x;
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
        openvdb::initialize();
        std::printf("mesh %s x%u subdivided: %zu triangles; grid %ux%ux%u, band +-%g cells, %u threads\n", path.c_str(),
                    subdivisions, mesh.triangles.size(), grid.dims.x, grid.dims.y, grid.dims.z, double(bandCells), threads);
        std::printf("mesh and grid in memory: %.2f GiB resident (the peaks below count it)\n", statusGiB("VmRSS:"));
        resetPeak();
        vds::SparseBand band;
        if (method != "openvdb") {
            const auto start = Clock::now();
            const vds::SignedDistance distance(mesh, vds::Rule::Parity);
            band = vds::sparseBand(distance, mesh, grid, vds::SparseBandOptions{threads, bandCells * cell});
            std::printf("vds sparseBand:         %8.2f s  peak %6.2f GiB  %12zu voxels  %8.1f MB held\n", seconds(start),
                        peakGiB(), band.values.size(), double(band.memoryBytes()) * 1e-6);
        }
        if (method != "vds") {
            const auto start = Clock::now();
            const openvdb::FloatGrid::Ptr level = openvdbBand(mesh, grid, bandCells);
            std::printf("OpenVDB meshToLevelSet: %8.2f s  peak %6.2f GiB  %12zu voxels  %8.1f MB held\n", seconds(start),
                        peakGiB(), std::size_t(level->activeVoxelCount()), double(level->memUsage()) * 1e-6);
            if (method == "compare") {
                const Comparison c = compare(*level, band);
                std::printf("OpenVDB against vds: %zu voxels in both bands, error max %.3f mean %.4f voxels; %zu wrong "
                            "signs; %zu active voxels outside vds's band\n",
                            c.both, c.maxError, c.sumError / double(std::max<std::size_t>(c.both, 1)), c.signs,
                            c.openvdbOnly);
                std::printf("the brute-force classifier (every triangle) gives vds's sign on %zu of the first %zu of "
                            "those wrong signs\n",
                            settleSigns(mesh, band, c), c.disputed.size());
            }
        }
    } catch (const vds::Error& e) {
        std::fprintf(stderr, "vds_sparse_band_bench: %s\n", e.what());
        return 1;
    }
    return 0;
}
