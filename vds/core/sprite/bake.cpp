#include <vds/bake.h>

#include <algorithm>
#include <atomic>
#include <cstdio>

#include <vds/error.h>

#include <vds/detail/bake_common.h>
#include "winding/antipodal.h"
#include "predicates/projected_mesh.h"
#include <vds/detail/parallel.h>

namespace vds {

namespace detail {

BakeSetup prepareBake(MeshView mesh, const BakeOptions& options) {
    const HostPhase phase(options.timings, BakePhase::Validation);
    BakeSetup setup;
    setup.report = validateMesh(mesh);
    requireUsable(setup.report, options.sourceName);
    requireVolume(setup.report, options.sourceName);
    const Axis axis = options.axis ? *options.axis : chooseViewAxis(mesh, options.resolution).axis;
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
    s.status = setup.report.oriented() ? SolidStatus::Closed : SolidStatus::Open;
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
    const MeshReport report = validateMesh(mesh);
    requireUsable(report, "mesh");
    requireVolume(report, "mesh");
    AxisChoice choice;
    choice.resolution = resolution;
    for (Axis axis : {Axis::X, Axis::Y, Axis::Z}) {
        const SpriteGrid grid = makeGrid(report.bounds, axis, resolution);
        const detail::ProjectedMesh projected(mesh, axis);
        // Texel centres along s and t (a baking grid is axis-aligned: s
        // follows i alone, t follows j alone), to bound each triangle's texels.
        std::vector<float> sAt(grid.width), tAt(grid.height);
        float q[3];
        for (std::uint32_t i = 0; i < grid.width; ++i) {
            projected.toViewSpace(grid.texelCentre(i, 0, 0.0f), q);
            sAt[i] = q[0];
        }
        for (std::uint32_t j = 0; j < grid.height; ++j) {
            projected.toViewSpace(grid.texelCentre(0, j, 0.0f), q);
            tAt[j] = q[1];
        }
        std::vector<std::atomic<std::uint32_t>> count(std::size_t(grid.width) * grid.height);
        parallelFor(threads, projected.crossable, 256, [&](std::size_t begin, std::size_t end) {
            float c[3] = {0.0f, 0.0f, 0.0f};
            for (std::size_t k = begin; k < end; ++k) {
                const detail::Triangle& t = projected.tris[k];
                const float slo = std::min({t.v[0][0], t.v[1][0], t.v[2][0]}), shi = std::max({t.v[0][0], t.v[1][0], t.v[2][0]});
                const float tlo = std::min({t.v[0][1], t.v[1][1], t.v[2][1]}), thi = std::max({t.v[0][1], t.v[1][1], t.v[2][1]});
                // Every texel whose centre lies in the triangle's closed box (no
                // other can be claimed); the centre (sAt[i], tAt[j]) is the
                // baker's `texelCentre(i, j)` exactly: s follows i alone, t j alone.
                const std::size_t i0 = std::size_t(std::lower_bound(sAt.begin(), sAt.end(), slo) - sAt.begin());
                const std::size_t i1 = std::size_t(std::upper_bound(sAt.begin(), sAt.end(), shi) - sAt.begin());
                const std::size_t j0 = std::size_t(std::lower_bound(tAt.begin(), tAt.end(), tlo) - tAt.begin());
                const std::size_t j1 = std::size_t(std::upper_bound(tAt.begin(), tAt.end(), thi) - tAt.begin());
                for (std::size_t j = j0; j < j1; ++j)
                    for (std::size_t i = i0; i < i1; ++i) {
                        c[0] = sAt[i];
                        c[1] = tAt[j];
                        if (detail::claims(t, c)) count[j * grid.width + i].fetch_add(1, std::memory_order_relaxed);
                    }
            }
        });
        std::uint32_t most = 0;
        std::uint64_t total = 0;
        for (const auto& n : count) {
            const std::uint32_t v = n.load(std::memory_order_relaxed);
            most = std::max(most, v);
            total += v;
        }
        choice.layers[std::size_t(axis)] = most;
        choice.crossings[std::size_t(axis)] = total;
    }
    std::uint64_t bestKey = ~std::uint64_t(0);
    for (Axis axis : {Axis::Z, Axis::X, Axis::Y}) {
        const std::uint64_t key = (std::uint64_t(choice.layers[std::size_t(axis)]) << 40) | choice.crossings[std::size_t(axis)];
        if (key < bestKey) {
            bestKey = key;
            choice.axis = axis;
        }
    }
    return choice;
}

} // namespace vds
