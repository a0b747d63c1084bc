// vds internal: what the two GL bakers (bake_peel.cpp, bake_lists.cpp) share.
// Both fill a CSR LDI (offsets, encoded crossings) on the current context.
#pragma once

#include <chrono>
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <GL/gl.h>

#include <vds/bake.h>
#include <vds/detail/bake_common.h>
#include <vds/gl/context.h>
#include <vds/gl/mesh.h>
#include <vds/gl/objects.h>

namespace vds::detail {

/// Times the phases of a GL bake into `timings`, if set (see `BakeTimings`):
/// host wall time from a phase's start until GL has finished its commands
/// (glFinish at the phase's end), and GL_TIME_ELAPSED queries around them.
/// Without timings every call does nothing, so a plain bake never waits.
/// One phase runs at a time (GL allows one active timer query): `begin`
/// ends the running one. A query's time is dropped when it is longer than
/// its phase's wall time or below a thousandth of it, which a working timer
/// never reports (llvmpipe: about 0 for compute passes).
class GlPhaseClock {
public:
    explicit GlPhaseClock(BakeTimings* timings) noexcept : timings_(timings) {}
    ~GlPhaseClock() { end(); }
    GlPhaseClock(const GlPhaseClock&) = delete;
    GlPhaseClock& operator=(const GlPhaseClock&) = delete;

    /// Starts `phase`; `gpu` = false for host work (no timer query). Its
    /// end waits for the GPU, unless `wait` is false (work issued to run
    /// beside the host's next phase: its wall is the issuing, its GPU time
    /// the timer's).
    void begin(BakePhase phase, bool gpu = true, bool wait = true);
    /// Ends the running phase, if any.
    void end() noexcept;
    /// Adds the GPU times of the finished phases (waits for their queries).
    void collect();

    /// One phase for the scope.
    class Scope {
    public:
        Scope(GlPhaseClock& clock, BakePhase phase, bool gpu = true, bool wait = true) : clock_(clock) {
            clock.begin(phase, gpu, wait);
        }
        ~Scope() { clock_.end(); }
        Scope(const Scope&) = delete;
        Scope& operator=(const Scope&) = delete;

    private:
        GlPhaseClock& clock_;
    };

private:
    BakeTimings* timings_;
    bool running_ = false;
    bool gpu_ = false;
    bool wait_ = true;
    BakePhase phase_ = BakePhase::Validation;
    std::chrono::steady_clock::time_point start_;
    struct Measured {
        BakePhase phase;
        Query query;
        double wallSeconds;
    };
    std::vector<Measured> queries_;
};

/// Runs `BakePhase::Validation`: validates the mesh (throws `InvalidMesh`)
/// and makes the grid, as every baker does; `BakePhase::Axis` where the
/// options name no axis. A count on the GPU uploads the mesh, which the bake
/// then draws (`drawn`).
struct ValidatedMesh {
    MeshReport report;
    SpriteGrid grid;
    std::optional<GpuMesh> drawn;
};
ValidatedMesh validateForBake(const GlContext& gl, MeshView mesh, const BakeOptions& options, GlPhaseClock& clock);

/// An immutable buffer holding `bytes` of `data` (at least 4 bytes: GL
/// refuses empty storage; `data` may be null for contents left undefined).
/// Throws `GlError` naming `what`.
Buffer uploadBuffer(const void* data, std::size_t bytes, const char* what);

/// The layers and crossings of the GL bake of `mesh` along each axis at
/// `resolution` in `bounds`, counted in the bake's own raster on `gl` (made
/// current), and the axis of the fewest (`pickFewestLayers`); nullopt where
/// one axis's counts exceed a storage block. These are the GL bake's
/// counts, which differ from the CPU baker's only where the rasterizer's
/// snapping moves an edge across a texel centre.
std::optional<AxisChoice> countLayersOnGl(const GlContext& gl, MeshView mesh, const Box& bounds,
                                          std::uint32_t resolution);
/// The same with the mesh in GL already.
std::optional<AxisChoice> countLayersOnGl(const GlContext& gl, const GpuMesh& drawn, const Box& bounds,
                                          std::uint32_t resolution);
/// `countLayersOnGl` in two halves: `start` issues the three axes' draws
/// and reductions and returns without waiting (nullopt where
/// `countLayersOnGl` gives none); `finish` reads the counts back, waiting
/// for the GPU. The host is free in between (the GL bakes validate the mesh
/// there). Holds `gl` by reference; its scratch buffers hold the counts.
class PendingLayerCount {
public:
    static std::optional<PendingLayerCount> start(const GlContext& gl, const GpuMesh& drawn, const Box& bounds,
                                                  std::uint32_t resolution);
    AxisChoice finish();

private:
    PendingLayerCount(const GlContext& gl, std::uint32_t resolution) : gl_(&gl), resolution_(resolution) {}
    void read(std::size_t axis); ///< axis's counts into choice_, waiting for them
    const GlContext* gl_;
    std::uint32_t resolution_;
    GLuint results_[3] = {0, 0, 0};
    bool read_[3] = {false, false, false};
    AxisChoice choice_;
};
/// True on llvmpipe, softpipe, SwiftShader and software platforms.
bool softwareRenderer(const GlContext& gl);
/// Whether the GL bakes count the auto axis on the GPU: yes but on a
/// software renderer, where the CPU's count is the faster. The environment
/// variable VDS_AXIS_COUNT (`gpu` or `cpu`) overrides it, to compare the two
/// (the tests count on llvmpipe's GPU path so).
bool countsOnGpu(const GlContext& gl);
/// The GL bakers' axis count for `prepareBake`: `countLayersOnGl` where
/// `countsOnGpu`; none (the CPU's) otherwise.
/// Holds `gl` and `mesh` by reference; where `keep` is given, the mesh the
/// count uploads stays there for the bake to draw.
AxisCounter axisCounter(const GlContext& gl, MeshView mesh, const BakeOptions& options,
                        std::optional<GpuMesh>* keep = nullptr);

/// `bakeOnGl` on a mesh validated before (`setup`), with a method chosen
/// (not Auto). Phases timed on `options.timings`; the caller holds the clock.
Sprite bakeOnGl(const GlContext& gl, const BakeSetup& setup, MeshView mesh, const BakeOptions& options,
                const GpuMesh* uploaded = nullptr);

/// `groups` workgroups as a glDispatchCompute grid: x up to 65535, then rows
/// of y. Shaders number a group `gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x`
/// and skip numbers past the real count.
void dispatchGroups(std::uint64_t groups);
/// Workgroups for a grid-stride loop over `items` with `local` invocations
/// per group: enough to fill any GPU, at most 65535.
GLuint strideGroups(std::uint64_t items, std::uint32_t local = 256);

/// The GL bakers behind bakeOnGl(): fill the CSR layers of `grid` on `gl`
/// (current), timing their phases on `clock`.
/// `uploaded`: the mesh already in GL (the axis count's), or null to upload it.
void bakePeel(const GlContext& gl, MeshView mesh, const SpriteGrid& grid, const BakeOptions& options,
              GlPhaseClock& clock, std::vector<std::uint32_t>& offsets, std::vector<float>& crossings,
              const GpuMesh* uploaded = nullptr);

void bakeLists(const GlContext& gl, MeshView mesh, const SpriteGrid& grid, const BakeOptions& options,
               GlPhaseClock& clock, std::vector<std::uint32_t>& offsets, std::vector<float>& crossings,
               const GpuMesh* uploaded = nullptr);

constexpr std::uint32_t kEnteringBit = 0x80000000u;
constexpr std::uint32_t kNoNode = 0xffffffffu;

/// A crossing as the bake shaders key it: the entering bit beside the triangle index.
inline float encodeKeyed(float depth, std::uint32_t key) { return encodeCrossing(depth, (key & kEnteringBit) != 0); }

/// "#define VDS_CLIP_CONTROL" where the context has glClipControl (GL 4.5).
std::string bakeDefines(const GlContext& gl);

/// The raster state of a bake pass, set for the scope and put back to GL's
/// defaults when it ends, also when the pass throws: clip control [0,1] depth,
/// viewport = the grid, no culling, blending or multisampling, depth clamping
/// (crossings on the box's near and far faces must not be clipped), front
/// faces clockwise (the view keeps handedness: clockwise = normal towards the
/// viewer = entering), `program` in use with the grid's placement uniform.
class BakeRasterState {
public:
    BakeRasterState(const GlContext& gl, const SpriteGrid& grid, GLuint program);
    ~BakeRasterState();
    BakeRasterState(const BakeRasterState&) = delete;
    BakeRasterState& operator=(const BakeRasterState&) = delete;

private:
    bool clipControl_;
};

/// A width x height single-level 2D texture of `format`, nearest filtering.
Texture makeTexture2D(GLenum format, const SpriteGrid& grid);

/// Calls options.progress, if set.
void report(const BakeOptions& options, const std::string& what);

} // namespace vds::detail
