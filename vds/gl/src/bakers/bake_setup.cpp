// What every GL bake runs before and around its baker (see bake_setup.h).
#include <vds/gl/detail/bake_setup.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include <GL/glext.h>

#include <vds/error.h>
#include <vds/detail/parallel.h>
#include <vds/gl/detail/layer_count.h>
#include <vds/gl/detail/lists.h>
#include <vds/gl/detail/peel.h>

namespace vds::detail {
namespace {

// Triangles a chunk of `drawableBox`.
constexpr std::size_t kBoxChunk = std::size_t(1) << 16;

// The box of every position, where every index is in range and every
// coordinate finite (the mesh can be drawn before validation); nullopt
// otherwise. Validation's bounds (of the used vertices) equal it unless an
// unused vertex lies outside.
std::optional<Box> drawableBox(MeshView mesh) {
    const std::size_t nv = mesh.positionCount, nt = mesh.triangleCount;
    if (nv == 0 || nt == 0) return std::nullopt;
    const std::size_t chunks = (std::max(nv, nt) + kBoxChunk - 1) / kBoxChunk;
    std::vector<Box> boxes(chunks, Box{mesh.positions[0], mesh.positions[0]});
    std::vector<std::uint8_t> bad(chunks, 0);
    detail::parallelFor(0, std::max(nv, nt), kBoxChunk, [&](std::size_t begin, std::size_t end) {
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

// prepareGlBake where the GPU counts the axis: the count is issued first,
// in the box of the positions, and validation runs on the host while the GPU
// draws; the count is read back after (recounted in validation's bounds
// where they differ). False where the mesh cannot be drawn before
// validation (an index out of range or a coordinate not finite): then
// validation goes first, and throws.
bool countBesideValidation(const GlContext& gl, MeshView mesh, const BakeOptions& options, GlPhaseClock& clock,
                           ValidatedMesh& out, Axis& axis) {
    const std::optional<Box> box = drawableBox(mesh);
    if (!box) return false;
    BakeOptions untimed = options;
    untimed.timings = nullptr;
    std::optional<PendingLayerCount> pending;
    {
        const GlPhaseClock::Scope phase(clock, BakePhase::Axis, true, false); // timed on the GPU, not waited for
        const CurrentContext current(gl);
        out.drawn.emplace(mesh);
        pending = PendingLayerCount::start(gl, *out.drawn, *box, options.resolution);
    }
    {
        const GlPhaseClock::Scope phase(clock, BakePhase::Validation, false);
        out.report = validateForBake(mesh, untimed);
    }
    const bool ready = pending && out.report.bounds.lo == box->lo && out.report.bounds.hi == box->hi;
    const GlPhaseClock::Scope phase(clock, BakePhase::Axis, !ready);
    const std::optional<AxisChoice> counted =
        ready ? std::optional<AxisChoice>(pending->finish())
              : countLayersOnGl(gl, *out.drawn, out.report.bounds, options.resolution); // the mesh drawn again
    axis = counted ? counted->axis : chooseViewAxis(mesh, out.report, options.resolution).axis; // too large for GL
    return true;
}

} // namespace

// The one validation of every baker (detail::prepareBake), timed on the GL
// bake's clock: the axis count on the GPU's timer where it runs there, and
// then beside validation.
ValidatedMesh prepareGlBake(const GlContext& gl, MeshView mesh, const BakeOptions& options, GlPhaseClock& clock) {
    ValidatedMesh out;
    Axis axis = options.axis.value_or(Axis::Z);
    const bool gpuCount = !options.axis && countsOnGpu(gl);
    if (!gpuCount || !countBesideValidation(gl, mesh, options, clock, out, axis)) {
        BakeOptions untimed = options;
        untimed.timings = nullptr;
        // Where the CPU counts the axis, validation finds the edges' partners and facings for it.
        MeshFinds finds;
        {
            const GlPhaseClock::Scope phase(clock, BakePhase::Validation, false);
            out.report = validateForBake(mesh, untimed, options.axis || gpuCount ? nullptr : &finds);
        }
        if (!options.axis) {
            const GlPhaseClock::Scope phase(clock, BakePhase::Axis, gpuCount);
            axis = bakeAxis(mesh, out.report, untimed, axisCounter(gl, mesh, options, &out.drawn), finds);
        }
    }
    out.grid = makeGrid(out.report.bounds, axis, options.resolution);
    return out;
}

void report(const BakeOptions& options, const std::string& what) {
    if (options.progress) options.progress(what);
}

} // namespace vds::detail

namespace vds {

Sprite detail::bakePrepared(const GlContext& gl, const BakeSetup& setup, MeshView mesh, const BakeOptions& options,
                        const GlBakeOptions& glOptions, const GpuMesh* uploaded) {
    if (options.method == BakeMethod::Cpu) return bakeCpu(setup, mesh, options);
    std::vector<std::uint32_t> offsets;
    std::vector<float> crossings;
    {
        const CurrentContext restore(gl);
        if (options.timings) options.timings->renderer = gl.info().renderer;
        detail::GlPhaseClock phases(options.timings);
        if (options.method == BakeMethod::Peel)
            detail::bakePeel(gl, mesh, setup.grid, options, phases, offsets, crossings, uploaded);
        else
            detail::bakeLists(gl, mesh, setup.grid, options, glOptions, phases, offsets, crossings, uploaded);
        phases.collect();
    }
    return detail::assembleSprite(setup, options, mesh, std::move(offsets), std::move(crossings));
}

} // namespace vds
