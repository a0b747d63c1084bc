// vds::gl internal: what every GL bake runs before and around its baker
// (bake_setup.cpp): the one validation, timed on the bake's clock, with the
// axis count beside it; the bake of a validated mesh by the method chosen.
#pragma once

#include <optional>
#include <string>

#include <vds/bake.h>
#include <vds/detail/bake_common.h>
#include <vds/gl/bake.h>
#include <vds/gl/context.h>
#include <vds/gl/detail/phase_clock.h>
#include <vds/gl/mesh.h>

namespace vds::detail {

/// A mesh prepared for a GL bake: `prepareBake`'s report and grid (runs
/// `BakePhase::Validation`, and `BakePhase::Axis` where the options name no
/// axis; throws `InvalidMesh`). Where the GPU counts the axis it counts
/// beside validation, and the mesh it uploaded is kept for the bake to draw
/// (`drawn`).
struct ValidatedMesh {
    BakeSetup setup;
    std::optional<GpuMesh> drawn;
};
ValidatedMesh prepareGlBake(const GlContext& gl, MeshView mesh, const BakeOptions& options, GlPhaseClock& clock);

/// `bakeOnGl` on a mesh prepared before (`setup`), with a method chosen
/// (not Auto). Phases timed on `options.timings`; the caller holds the clock.
/// `uploaded`: the mesh already in GL (the axis count's), or null.
Sprite bakePrepared(const GlContext& gl, const BakeSetup& setup, MeshView mesh, const BakeOptions& options,
                const GlBakeOptions& glOptions, const GpuMesh* uploaded = nullptr);

/// Calls options.progress, if set.
void report(const BakeOptions& options, const std::string& what);

} // namespace vds::detail
