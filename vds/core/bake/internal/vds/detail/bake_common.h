// vds internal: what every baker shares (validation, grid, assembly).
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include <vds/bake.h>
#include <vds/detail/edge_partners.h>

namespace vds::detail {

struct BakeSetup {
    MeshReport report;
    SpriteGrid grid;
};

/// Adds the host time of a scope to one phase of `timings`, if set.
class HostPhase {
public:
    HostPhase(BakeTimings* timings, BakePhase phase) noexcept
        : timings_(timings), phase_(phase), start_(std::chrono::steady_clock::now()) {}
    ~HostPhase() {
        if (!timings_) return;
        BakeTimings::Phase& p = (*timings_)[phase_];
        p.wallSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
        ++p.runs;
    }
    HostPhase(const HostPhase&) = delete;
    HostPhase& operator=(const HostPhase&) = delete;

private:
    BakeTimings* timings_;
    BakePhase phase_;
    std::chrono::steady_clock::time_point start_;
};

/// Resets `timings` (if set) and, when the scope ends, records the whole call's time.
class BakeClock {
public:
    explicit BakeClock(BakeTimings* timings) : timings_(timings), start_(std::chrono::steady_clock::now()) {
        if (timings_) *timings_ = BakeTimings{};
    }
    ~BakeClock() {
        if (timings_)
            timings_->wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    }
    BakeClock(const BakeClock&) = delete;
    BakeClock& operator=(const BakeClock&) = delete;

private:
    BakeTimings* timings_;
    std::chrono::steady_clock::time_point start_;
};

/// Validates the mesh (throws `InvalidMesh` if unusable); timed as
/// `BakePhase::Validation`. With `finds`, also what the CPU's axis count
/// would find again (<vds/detail/edge_partners.h>).
MeshReport validateForBake(MeshView mesh, const BakeOptions& options, MeshFinds* finds = nullptr);
/// `options.axis`, or the axis of the fewest layers by the CPU's
/// `chooseViewAxis`, given what validation found for it, timed as
/// `BakePhase::Axis`.
Axis bakeAxis(MeshView mesh, const MeshReport& report, const BakeOptions& options, const MeshFinds& finds);
/// `chooseViewAxis(mesh, report, ...)` given what validation found for it
/// (empty: the count pairs the edges and finds the facings itself).
AxisChoice chooseViewAxis(MeshView mesh, const MeshReport& report, std::uint32_t resolution, unsigned threads,
                          const MeshFinds& finds);
/// An axis count that runs beside validation, in a baker's own raster (the
/// GL bakers' on a GPU: <vds/gl/detail/bake_setup.h>). `start` is called
/// before validation with the box of the positions, where the mesh can be
/// drawn before it is validated; `finish` after it, with the report: the
/// choice, or nullopt to count on the CPU after all.
class AxisCountBeside {
public:
    virtual ~AxisCountBeside() = default;
    virtual void start(const Box& positions) = 0;
    virtual std::optional<AxisChoice> finish(const MeshReport& report) = 0;
};

/// Every baker's preparation: validation, the axis (`options.axis`, else
/// `beside`'s count where given, else the CPU's), and the grid along it.
BakeSetup prepareBake(MeshView mesh, const BakeOptions& options, AxisCountBeside* beside = nullptr);

/// Sets `choice.axis` to the axis of the fewest layers, ties to fewer
/// crossings, then z, x, y (the rule of `chooseViewAxis`).
void pickFewestLayers(AxisChoice& choice);

/// The CPU baker (`bakeCpu`) on a mesh validated before: `setup` holds its
/// report and grid. Its phases are timed on `options.timings`; the caller
/// holds the `BakeClock`.
Sprite bakeCpu(const BakeSetup& setup, MeshView mesh, const BakeOptions& options);

/// Assembles a sprite from per-column crossings in CSR form (already sorted);
/// fills d_S and the metadata, then checks consistency; timed as
/// `BakePhase::Assembly`.
Sprite assembleSprite(const BakeSetup& setup, const BakeOptions& options, MeshView mesh,
                      std::vector<std::uint32_t> offsets, std::vector<float> crossings);

/// Replaces the crossings of every column whose texel centre lies within
/// about a texel of a boundary edge's projection (`edges`: 2 points an edge,
/// as `Sprite::boundaryEdges`) by the CPU baker's exact ones. The GL
/// rasterizer snaps vertices to its subpixel grid, so next to the boundary
/// its crossing count jumps where the snapped edge lies, not where the
/// exact boundary term jumps; there the generalized winding number would be
/// off by one. Away from the boundary the snapped surface still closes up,
/// and counts differ only within the snap of the surface.
void recastBoundaryColumns(MeshView mesh, const SpriteGrid& grid, const std::vector<glm::vec3>& edges,
                           std::vector<std::uint32_t>& offsets, std::vector<float>& crossings);

} // namespace vds::detail
