// vds: what every baker shares (<vds/detail/bake_common.h>): its
// preparation (validation, the view axis, the grid; a count beside
// validation where a baker's raster counts), the sprite's assembly, and the
// axis choice and timings of <vds/bake.h>.
#include <vds/bake.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <optional>
#include <vector>

#include <vds/error.h>
#include <vds/mesh_check.h>

#include <vds/detail/bake_common.h>
#include <vds/detail/edge_partners.h>
#include <vds/detail/antipodal.h>
#include <vds/detail/layer_count.h>
#include <vds/detail/parallel.h>

namespace vds {

namespace detail {

namespace {

// Triangles a chunk of `drawableBox`.
constexpr std::size_t kBoxChunk = std::size_t(1) << 16;

// The box of every position, where every index is in range and every
// coordinate finite (the mesh can be drawn before validation: a count beside
// it starts there); nullopt otherwise. Validation's bounds (of the used
// vertices) equal it unless an unused vertex lies outside.
std::optional<Box> drawableBox(MeshView mesh) {
    const std::size_t nv = mesh.positionCount, nt = mesh.triangleCount;
    if (nv == 0 || nt == 0) return std::nullopt;
    const std::size_t chunks = (std::max(nv, nt) + kBoxChunk - 1) / kBoxChunk;
    std::vector<Box> boxes(chunks, Box{mesh.positions[0], mesh.positions[0]});
    std::vector<std::uint8_t> bad(chunks, 0);
    parallelFor(0, std::max(nv, nt), kBoxChunk, [&](std::size_t begin, std::size_t end) {
        Box& box = boxes[begin / kBoxChunk];
        bool wrong = false;
        for (std::size_t i = begin; i < std::min(end, nv); ++i) {
            const glm::vec3 p = mesh.positions[i];
            wrong |= !(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
            box.lo = glm::min(box.lo, p);
            box.hi = glm::max(box.hi, p);
        }
        for (std::size_t t = begin; t < std::min(end, nt); ++t) {
            const glm::uvec3 tri = mesh.triangles[t];
            wrong |= tri.x >= nv || tri.y >= nv || tri.z >= nv;
        }
        bad[begin / kBoxChunk] = wrong;
    });
    if (std::find(bad.begin(), bad.end(), 1) != bad.end()) return std::nullopt;
    Box all = boxes[0];
    for (const Box& b : boxes) all.lo = glm::min(all.lo, b.lo), all.hi = glm::max(all.hi, b.hi);
    return all;
}

} // namespace

MeshReport validateForBake(MeshView mesh, const BakeOptions& options, MeshFinds* finds) {
    const HostPhase phase(options.timings, BakePhase::Validation);
    MeshReport report = finds ? validateMesh(mesh, 0, *finds) : validateMesh(mesh);
    requireUsable(report, options.sourceName);
    requireVolume(report, options.sourceName);
    return report;
}

Axis bakeAxis(MeshView mesh, const MeshReport& report, const BakeOptions& options, const MeshFinds& finds) {
    if (options.axis) return *options.axis;
    const HostPhase phase(options.timings, BakePhase::Axis);
    return chooseViewAxis(mesh, report, options.resolution, 0, finds).axis;
}

BakeSetup prepareBake(MeshView mesh, const BakeOptions& options, AxisCountBeside* beside) {
    BakeSetup setup;
    // A count beside validation starts first. Where the mesh cannot be drawn
    // before validation (an index out of range, a coordinate not finite,
    // nothing to draw), validation throws before it would be needed.
    const std::optional<Box> drawn = beside && !options.axis ? drawableBox(mesh) : std::nullopt;
    if (drawn) beside->start(*drawn);
    // Validation finds the edges' partners and the facings where the CPU will count the axis.
    MeshFinds finds;
    setup.report = validateForBake(mesh, options, options.axis || drawn ? nullptr : &finds);
    const std::optional<AxisChoice> counted = drawn ? beside->finish(setup.report) : std::nullopt;
    const Axis axis = counted ? counted->axis : bakeAxis(mesh, setup.report, options, finds);
    setup.grid = makeGrid(setup.report.bounds, axis, options.resolution);
    return setup;
}

Sprite assembleSprite(const BakeSetup& setup, const BakeOptions& options, MeshView mesh,
                      std::vector<std::uint32_t> offsets, std::vector<float> crossings) {
    const HostPhase phase(options.timings, BakePhase::Assembly);
    std::vector<glm::vec3> edges = setup.report.oriented() ? std::vector<glm::vec3>() : boundaryEdges(mesh);
    if (options.method != BakeMethod::Cpu) recastBoundaryColumns(mesh, setup.grid, edges, offsets, crossings);
    Sprite s;
    s.grid = setup.grid;
    s.offsets = std::move(offsets);
    s.crossings = std::move(crossings);
    std::uint32_t most = 0;
    for (std::size_t c = 0; c + 1 < s.offsets.size(); ++c) most = std::max(most, s.offsets[c + 1] - s.offsets[c]);
    s.depthComplexity = most;
    s.sourceName = options.sourceName;
    s.sourceTriangles = mesh.triangleCount;
    s.status = solidStatus(setup.report);
    s.validation = setup.report.summary();
    s.boundaryEdges = std::move(edges);
    s.checkConsistent();
    if (options.timings) options.timings->crossings = s.crossings.size();
    return s;
}

} // namespace detail

const char* toString(BakePhase p) { return enumName(p); }

double BakeTimings::gpuSeconds() const {
    double total = 0.0;
    for (const Phase& p : phases)
        if (p.gpuSeconds > 0.0) total += p.gpuSeconds;
    return total;
}

std::string BakeTimings::report() const {
    std::string out;
    char line[160];
    for (std::size_t k = 0; k < kBakePhaseCount; ++k) {
        const Phase& p = phases[k];
        if (p.runs == 0) continue;
        int n = std::snprintf(line, sizeof line, "  %-10s %9.2f ms", toString(BakePhase(k)), 1e3 * p.wallSeconds);
        if (p.gpuSeconds >= 0.0)
            n += std::snprintf(line + n, sizeof line - std::size_t(n), "   GPU %8.2f ms", 1e3 * p.gpuSeconds);
        if (p.runs > 1) std::snprintf(line + n, sizeof line - std::size_t(n), "   (%u runs)", p.runs);
        out += line;
        out += '\n';
    }
    std::snprintf(line, sizeof line, "  %-10s %9.2f ms   GPU %8.2f ms", "total", 1e3 * wallSeconds, 1e3 * gpuSeconds());
    out += line;
    out += '\n';
    return out;
}

std::string AxisChoice::summary() const {
    std::string s = std::string("axis ") + toString(axis) + ": " + std::to_string(layers[std::size_t(axis)]) +
                    " layers (";
    for (int a = 0; a < 3; ++a)
        s += std::string(a ? ", " : "") + toString(Axis(a)) + " " + std::to_string(layers[std::size_t(a)]);
    return s + " at " + std::to_string(resolution) + " texels)";
}

AxisChoice chooseViewAxis(MeshView mesh, std::uint32_t resolution, unsigned threads) {
    detail::MeshFinds finds; // found by validation, used by the count
    const MeshReport report = detail::validateMesh(mesh, threads, finds);
    requireUsable(report, "mesh");
    requireVolume(report, "mesh");
    return detail::chooseViewAxis(mesh, report, resolution, threads, finds);
}

AxisChoice chooseViewAxis(MeshView mesh, const MeshReport& report, std::uint32_t resolution, unsigned threads) {
    return detail::chooseViewAxis(mesh, report, resolution, threads, detail::MeshFinds());
}

AxisChoice chooseViewAxis(MeshView mesh, const MeshValidation& validation, std::uint32_t resolution,
                          unsigned threads) {
    return detail::chooseViewAxis(mesh, validation.report(), resolution, threads, validation.finds());
}

AxisChoice detail::chooseViewAxis(MeshView mesh, const MeshReport& report, std::uint32_t resolution, unsigned threads,
                                  const MeshFinds& finds) {
    AxisChoice choice;
    choice.resolution = resolution;
    const std::array<SpriteGrid, 3> grids = {makeGrid(report.bounds, Axis::X, resolution),
                                             makeGrid(report.bounds, Axis::Y, resolution),
                                             makeGrid(report.bounds, Axis::Z, resolution)};
    const std::array<detail::LayerCount, 3> counts = detail::countLayers(mesh, grids, threads, finds);
    for (Axis axis : {Axis::X, Axis::Y, Axis::Z}) {
        choice.layers[std::size_t(axis)] = counts[std::size_t(axis)].most;
        choice.crossings[std::size_t(axis)] = counts[std::size_t(axis)].total;
    }
    detail::pickFewestLayers(choice);
    return choice;
}

void detail::pickFewestLayers(AxisChoice& choice) {
    std::uint64_t bestKey = ~std::uint64_t(0);
    for (Axis axis : {Axis::Z, Axis::X, Axis::Y}) {
        const std::uint64_t key = (std::uint64_t(choice.layers[std::size_t(axis)]) << 40) | choice.crossings[std::size_t(axis)];
        if (key < bestKey) {
            bestKey = key;
            choice.axis = axis;
        }
    }
}

BakeMethod parseBakeMethod(const std::string& s) { return parseEnum<BakeMethod>(s); }
const char* toString(BakeMethod m) { return enumName(m); }

} // namespace vds
