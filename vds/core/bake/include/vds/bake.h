// vds: baking a closed triangle mesh into a volumetric depth sprite.
//
// Trapp & Döllner 2008, section 4.1: the mesh box is mapped into the unit
// cube, viewed orthographically along one axis, and every surface crossing of
// every texel's ray is recorded. Three bakers produce the same layers:
//  - Peel:  classic depth peeling, one layer per pass, d_S found with an
//           occlusion query (the paper's method);
//  - Lists: one pass of per-pixel fragment lists; counting, a GPU prefix
//           sum and a per-column sort in compute build the sprite's columns
//           on the GPU, read back once (fastest on GPUs);
//  - Cpu:   exact ray casting on the CPU (<vds/exact.h>), no GL needed.
// Crossings at equal depth are ordered by triangle index in all three. The
// default, `BakeMethod::Auto`, is Lists on a GPU and Cpu on a software
// renderer (`chooseBakeMethod` in <vds/gl/bake.h>).
//
// Which layer bakes: vds::core has the Cpu method, `bakeCpu` below, and no
// GL word. vds::gl has the GL methods, `bakeOnGl(gl, mesh, options)` in
// <vds/gl/bake.h>, on a context the caller passes. `vds::bake(mesh,
// options)` and `vds::bake(gl, mesh, options)`, which pick by
// `options.method` and make a context when none is given, live in the
// umbrella (<vds/all.h>, vds::vds).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <vds/mesh.h>
#include <vds/mesh_check.h>
#include <vds/sprite.h>

namespace vds {

/// How to bake. Auto (the default): the fastest correct baker where it
/// runs: the GL fragment lists on a GPU, the CPU baker on a software
/// renderer (llvmpipe: a one-shot CPU bake is faster there) or without GL
/// (`chooseBakeMethod` in <vds/gl/bake.h> and <vds/all.h>).
enum class BakeMethod : std::uint8_t { Peel, Lists, Cpu, Auto };

template <> struct EnumNames<BakeMethod> {
    static constexpr const char* kind = "bake method";
    static constexpr EnumName<BakeMethod> table[] = {{"auto", BakeMethod::Auto},
                                                     {"lists", BakeMethod::Lists},
                                                     {"peel", BakeMethod::Peel},
                                                     {"cpu", BakeMethod::Cpu}};
};

/// Parses "auto" / "peel" / "lists" / "cpu"; throws `InvalidArgument`.
BakeMethod parseBakeMethod(const std::string& s);
const char* toString(BakeMethod m);

/// The phases of a bake, in the order they run. Not every baker has every
/// phase; a phase that runs more than once (row bands, peeling passes) adds up.
enum class BakePhase : std::uint8_t {
    Validation,  ///< checking the mesh (host)
    Axis,        ///< choosing the view axis where the options name none: the layers counted along each axis
                 ///< (the GL bakers on a GPU: in their own raster, GPU-timed; elsewhere the CPU's count)
    Compile,     ///< building the GL programs: the first bake on a context only
    Upload,      ///< the mesh into GL buffers; the CPU baker: projecting and indexing the triangles
    Raster,      ///< drawing the mesh (fragment lists, or every peeling pass); the CPU baker: casting the rays
    Scan,        ///< crossings per column and their prefix sum, the column offsets (GPU scan for lists)
    Sort,        ///< scattering the crossings into their columns and sorting each column
    TextureFill, ///< filling the 3D texture from the columns (`bakeToGpu`)
    ReadBack,    ///< copying the columns (lists) or the layers (peel) from GL to the host
    Assembly,    ///< the host sprite: d_S, metadata and its consistency check (`bakeToGpu`: the GpuSprite, an
                 ///< open mesh's boundary edges and their chain tree)
};
constexpr std::size_t kBakePhaseCount = 10;

template <> struct EnumNames<BakePhase> {
    static constexpr const char* kind = "bake phase";
    static constexpr EnumName<BakePhase> table[] = {
        {"validation", BakePhase::Validation}, {"axis", BakePhase::Axis}, {"compile", BakePhase::Compile},   {"upload", BakePhase::Upload},
        {"raster", BakePhase::Raster},         {"scan", BakePhase::Scan},         {"sort", BakePhase::Sort},
        {"texture", BakePhase::TextureFill},   {"read-back", BakePhase::ReadBack}, {"assembly", BakePhase::Assembly}};
};
const char* toString(BakePhase p);

/// Where the time of one bake went, phase by phase: filled by `bake()` (and
/// `bakeToGpu()`) when `BakeOptions::timings` points at one.
///
/// Wall times are host clock (std::chrono::steady_clock). To make them mean
/// something per phase, a measured GL bake waits for GL (glFinish) at the
/// end of every phase, which a bake without `timings` does not; GPU times are
/// GL timer queries (GL_TIME_ELAPSED) around the phase's GL commands, so they
/// count the GPU's work alone, not the driver's or the transfers' waiting.
struct BakeTimings {
    struct Phase {
        double wallSeconds = 0.0; ///< host time from the phase's start until its GL work was done
        double gpuSeconds = -1.0; ///< GPU time of the phase's GL commands; < 0 where none was measured
        std::uint32_t runs = 0;   ///< how often the phase ran (0: not at all)
    };
    std::array<Phase, kBakePhaseCount> phases{};
    double wallSeconds = 0.0;        ///< the whole call
    std::string renderer;            ///< GL_RENDERER of the context that baked; empty for the CPU baker
    std::uint32_t bands = 0;         ///< fragment lists: row bands baked (1: the whole image in one pass)
    std::uint64_t listNodes = 0;     ///< fragment lists: the node pool's final capacity (see GlBakeOptions::maxListNodes, <vds/gl/bake.h>)
    std::uint64_t crossings = 0;     ///< crossings in the sprite

    Phase& operator[](BakePhase p) { return phases[std::size_t(p)]; }
    const Phase& operator[](BakePhase p) const { return phases[std::size_t(p)]; }
    /// Sum of the GPU times measured (0 if none).
    double gpuSeconds() const;
    /// A few lines for people: one per phase that ran, with wall and GPU
    /// milliseconds, then the total, e.g. "  raster      3.10 ms   GPU 2.95 ms".
    std::string report() const;
};

struct BakeOptions {
    std::uint32_t resolution = 1024;        ///< texels on the longer side of the view, 1..16384
    /// View direction. Unset (the default): the axis with the fewest layers
    /// at this resolution, `chooseViewAxis(mesh, resolution)`.
    std::optional<Axis> axis;
    BakeMethod method = BakeMethod::Auto;
    std::string sourceName;                 ///< recorded in the sprite (e.g. the mesh file name)
    /// Called now and then with a short description of the work in progress.
    std::function<void(const std::string&)> progress;
    /// If set, reset and filled with the phase times of this bake (see
    /// `BakeTimings`: measuring adds a wait for GL at each phase's end). The
    /// caller owns it; it must outlive the call.
    BakeTimings* timings = nullptr;
};

/// What `chooseViewAxis` measured: for each axis (x, y, z), the sprite's
/// depth complexity d_S (its layers) and crossings at `resolution`.
struct AxisChoice {
    Axis axis = Axis::Z;          ///< the fewest layers; ties: fewer crossings, then z, x, y
    std::uint32_t resolution = 0;
    std::array<std::uint32_t, 3> layers{};  ///< d_S along x, y, z
    std::array<std::uint64_t, 3> crossings{};
    /// One line, e.g. "axis y: 12 layers (x 20, y 12, z 14 at 1024 texels)".
    std::string summary() const;
};

/// The view axis with the fewest layers (the least depth complexity d_S; ties
/// go to fewer crossings in all) at `resolution`: the d_S and crossing counts
/// of the sprites the bakers would make along x, y and z, counted exactly
/// (the CPU baker's texel centres and claim rule, row by row: each triangle
/// claims one run of texels on a row, counted by its two ends, and where two
/// triangles continue a surface across an edge their ends there cancel, so
/// mostly the silhouette's edges are counted; without sorting or storing
/// crossings: a few percent of one CPU bake). Trapp & Doellner 2008,
/// section 6, name this "optimal view direction" as future work: fewer
/// layers mean a smaller texture and fewer lookups per test.
/// Throws like `bakeCpu` (an unusable mesh, a resolution out of range).
AxisChoice chooseViewAxis(MeshView mesh, std::uint32_t resolution = 1024, unsigned threads = 0);
/// The same for a mesh that `validateMesh` gave `report` for and that passed
/// `requireUsable` and `requireVolume` (no second validation).
AxisChoice chooseViewAxis(MeshView mesh, const MeshReport& report, std::uint32_t resolution, unsigned threads = 0);
/// The same, reusing what `validation` (of this `mesh`) found beside its
/// report: the edges are not grouped a second time, nor the facings found.
/// The report must have passed `requireUsable` and `requireVolume`.
AxisChoice chooseViewAxis(MeshView mesh, const MeshValidation& validation, std::uint32_t resolution,
                          unsigned threads = 0);

/// The CPU baker: the sprite the GL bakers make, by exact ray casting at
/// texel centres (what every entry point runs for `BakeMethod::Cpu`). A column holds
/// one crossing per triangle whose projection claims the texel centre (the
/// rule of `ExactClassifier`, <vds/exact.h>), at the depth of the triangle's
/// plane there in LDI texture space, sorted by depth, then triangle index.
/// Validates the mesh first: empty meshes, non-finite coordinates and bad
/// indices throw `InvalidMesh`; an open or inconsistently oriented mesh is
/// baked, its sprite marked `SolidStatus::Open` (the caller should warn: the
/// answers are those of a surface, not a solid); a closed, oriented mesh
/// with non-manifold edges bounds a solid and is marked
/// `SolidStatus::Closed`. Throws `InvalidArgument` for a resolution out of
/// range. Runs on every hardware thread; `options.progress` is called on
/// the calling thread. Fills `options.timings` (validation, upload = indexing
/// the triangles, raster = casting the rays, assembly) if set.
Sprite bakeCpu(MeshView mesh, const BakeOptions& options);

} // namespace vds
