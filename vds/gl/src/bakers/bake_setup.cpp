// What every GL bake runs before and around its baker (see bake_setup.h).
#include <vds/gl/detail/bake_setup.h>

#include <optional>

#include <GL/glext.h>

#include <vds/error.h>
#include <vds/gl/detail/layer_count.h>
#include <vds/gl/detail/lists.h>
#include <vds/gl/detail/peel.h>

namespace vds::detail {
namespace {

// The GL bakers' axis count beside validation: issued in the box of the
// positions while the host validates, read back after (recounted in
// validation's bounds where they differ: an unused vertex lay outside).
// The mesh it uploads stays in `drawn` for the bake to draw.
class GpuAxisCount final : public AxisCountBeside {
public:
    GpuAxisCount(const GlContext& gl, MeshView mesh, std::uint32_t resolution, GlPhaseClock& clock,
                 std::optional<GpuMesh>& drawn)
        : gl_(gl), mesh_(mesh), resolution_(resolution), clock_(clock), drawn_(drawn) {}

    void start(const Box& positions) override {
        const GlPhaseClock::Scope phase(clock_, BakePhase::Axis, true, false); // timed on the GPU, not waited for
        const CurrentContext current(gl_);
        drawn_.emplace(mesh_);
        box_ = positions;
        pending_ = PendingLayerCount::start(gl_, *drawn_, positions, resolution_);
    }

    // nullopt where the grid is too large for GL: the CPU counts.
    std::optional<AxisChoice> finish(const MeshReport& report) override {
        const bool ready = pending_ && report.bounds.lo == box_.lo && report.bounds.hi == box_.hi;
        const GlPhaseClock::Scope phase(clock_, BakePhase::Axis, !ready);
        if (ready) return pending_->finish();
        return countLayersOnGl(gl_, *drawn_, report.bounds, resolution_); // the mesh drawn again
    }

private:
    const GlContext& gl_;
    MeshView mesh_;
    std::uint32_t resolution_;
    GlPhaseClock& clock_;
    std::optional<GpuMesh>& drawn_;
    Box box_;
    std::optional<PendingLayerCount> pending_;
};

} // namespace

// Every baker's preparation (prepareBake), with the axis counted on the GPU
// beside validation where it counts there.
ValidatedMesh prepareGlBake(const GlContext& gl, MeshView mesh, const BakeOptions& options, GlPhaseClock& clock) {
    ValidatedMesh out;
    std::optional<GpuAxisCount> count;
    if (countsOnGpu(gl)) count.emplace(gl, mesh, options.resolution, clock, out.drawn);
    out.setup = prepareBake(mesh, options, count ? &*count : nullptr);
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
