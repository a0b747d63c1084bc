#include <vds/bake.h>

#include <algorithm>
#include <cstdio>

#include <vds/error.h>

#include <vds/detail/bake_common.h>
#include "antipodal.h"

namespace vds {

namespace detail {

BakeSetup prepareBake(MeshView mesh, const BakeOptions& options) {
    const HostPhase phase(options.timings, BakePhase::Validation);
    BakeSetup setup;
    setup.report = validateMesh(mesh);
    requireUsable(setup.report, options.sourceName);
    setup.grid = makeGrid(setup.report.bounds, options.axis, options.resolution);
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

Axis chooseViewAxis(MeshView mesh, std::uint32_t probeResolution) {
    Axis best = Axis::Z;
    std::uint64_t bestKey = ~std::uint64_t(0);
    for (Axis axis : {Axis::Z, Axis::X, Axis::Y}) {
        BakeOptions o;
        o.axis = axis;
        o.resolution = probeResolution;
        const Sprite probe = bakeCpu(mesh, o);
        const std::uint64_t key = (std::uint64_t(probe.depthComplexity) << 40) | probe.crossings.size();
        if (key < bestKey) {
            bestKey = key;
            best = axis;
        }
    }
    return best;
}

} // namespace vds
