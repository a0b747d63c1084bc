#include <vds/bake.h>

#include <algorithm>

#include "bake_common.h"
#include "bake_gl.h"
#include <vds/error.h>
#include <vds/exact.h>
#include <vds/gl_context.h>

namespace vds {

BakeMethod parseBakeMethod(const std::string& s) {
    if (s == "peel") return BakeMethod::Peel;
    if (s == "lists") return BakeMethod::Lists;
    if (s == "cpu") return BakeMethod::Cpu;
    throw InvalidArgument("unknown bake method '" + s + "' (expected peel, lists or cpu)");
}

const char* toString(BakeMethod m) {
    return m == BakeMethod::Peel ? "peel" : m == BakeMethod::Lists ? "lists" : "cpu";
}

namespace detail {

BakeSetup prepareBake(MeshView mesh, const BakeOptions& options) {
    BakeSetup setup;
    setup.report = validateMesh(mesh);
    requireUsable(setup.report, options.sourceName);
    setup.grid = makeGrid(setup.report.bounds, options.axis, options.resolution);
    return setup;
}

Sprite assembleSprite(const BakeSetup& setup, const BakeOptions& options, MeshView mesh,
                      std::vector<std::uint32_t> offsets, std::vector<float> crossings) {
    Sprite s;
    s.grid = setup.grid;
    s.offsets = std::move(offsets);
    s.crossings = std::move(crossings);
    std::uint32_t most = 0;
    for (std::size_t c = 0; c + 1 < s.offsets.size(); ++c) most = std::max(most, s.offsets[c + 1] - s.offsets[c]);
    s.depthComplexity = most;
    s.sourceName = options.sourceName;
    s.sourceTriangles = mesh.triangleCount;
    s.status = setup.report.closed() ? SolidStatus::Closed : SolidStatus::Open;
    s.validation = setup.report.summary();
    s.checkConsistent();
    return s;
}

} // namespace detail

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

Sprite bake(MeshView mesh, const BakeOptions& options, GlContext* gl) {
    if (options.method == BakeMethod::Cpu) return bakeCpu(mesh, options);
    const detail::BakeSetup setup = detail::prepareBake(mesh, options);
    std::unique_ptr<GlContext> own;
    if (!gl) {
        own = std::make_unique<GlContext>();
        gl = own.get();
    } else {
        gl->makeCurrent();
    }
    std::vector<std::uint32_t> offsets;
    std::vector<float> crossings;
    if (options.method == BakeMethod::Peel)
        detail::bakePeel(*gl, mesh, setup.grid, options, offsets, crossings);
    else
        detail::bakeLists(*gl, mesh, setup.grid, options, offsets, crossings);
    return detail::assembleSprite(setup, options, mesh, std::move(offsets), std::move(crossings));
}

} // namespace vds
