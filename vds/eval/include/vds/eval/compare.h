// vds::eval: the VDS against slicemaps and solid voxels as point-in-solid
// tests, on one mesh: error, build time, query throughput and memory, at
// equal resolution and at equal memory budgets (the table of docs/voxel.md,
// `vds compare MESH`).
//
// Ground truth is the exact classifier (Method::Exact, Axis::Z) on the mesh
// itself: each row is held to the rule it answers by (parity, or winding
// for the sprite's winding row); with `rule` Rule::GeneralizedWinding, the
// exact generalized winding number for every row (open meshes accepted).
// Points: `uniformPoints` uniform in the mesh box grown by `padding` of its
// size on each side, and `surfacePoints` near the surface (a uniformly random
// point of the surface, by area, moved along its face normal by a uniform
// offset in [-band, band], band = `surfaceBand` times the longest box side).
// For each wrong answer the distance of the point to the surface (exact, to
// the nearest triangle) is taken; the worst is reported in mesh units and in
// cells of the row's representation.
//
// Rows: a method of the method table (<vds/classify.h>) and a rule, every
// one made by `vds::makeClassifier` and queried through `Classifier::classify`:
//  - sprite, sprite/winding (and sprite/generalized-winding with that rule):
//    Method::Sprite baked with BakeMethod::Lists along z, its texels the size
//    of the voxel grid's cells;
//  - every voxel representation's CPU lookup (slicemap, slicemap-local,
//    solid, solid-compute). They answer parity and need a closed mesh: with
//    Rule::GeneralizedWinding they are held to the exact generalized winding
//    number as they are, and left out for an open mesh (`CompareResult::note`
//    says so).
// Series "resolution": every method at each of `resolutions` (cells along the
// box's longest side; the VDS at the same texel size). Series "memory": every
// method at the largest resolution whose `memoryBytes` fits each budget.
// Builds are timed after one untimed warm-up build per method (shader
// compilation is not counted), as the fastest of up to three builds while
// they take under 0.3 s together; throughput is whole passes over all points
// for at least 0.1 s on `threads` CPU threads.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include <vds/classify.h>
#include <vds/gl/context.h>
#include <vds/mesh.h>
#include <vds/mesh_check.h>
#include <vds/sprite.h>

namespace vds::eval {

/// The largest resolution a comparison builds, at equal resolution or within a budget.
constexpr std::uint32_t kMaxCompareResolution = 4096;

struct CompareOptions {
    std::vector<std::uint32_t> resolutions = {32, 64, 128}; ///< each 1..kMaxCompareResolution
    /// Memory budgets in bytes; empty: the solid voxel grid's size at each resolution.
    std::vector<std::size_t> memoryBudgets;
    std::size_t uniformPoints = 100000;
    std::size_t surfacePoints = 50000;
    float padding = 0.1f;             ///< of the box size, on each side, for the uniform points
    float surfaceBand = 1.0f / 64.0f; ///< of the longest box side, for the near-surface points
    std::uint32_t seed = 1;
    /// Rule::GeneralizedWinding: every row against the exact generalized
    /// winding number, open meshes accepted, and a vds-gwn row. Otherwise
    /// (the default) each VDS row against its own rule, the others against parity.
    Rule rule = Rule::Parity;
    unsigned threads = 0;                             ///< CPU threads for queries, 0: one per hardware thread
    std::string meshName;                             ///< recorded in the result
    std::function<void(const std::string&)> progress; ///< called with what is being done
    MeshFlags meshFlags; ///< the caller's flags, named by the refusal of a mesh (<vds/mesh_check.h>)
};

struct CompareRow {
    Method method = Method::Sprite; ///< the method that answered
    Rule rule = Rule::Parity;       ///< the rule it answered by
    /// The method's name, and "/" and the rule's for any rule but parity:
    /// "sprite", "sprite/winding", "slicemap-local", ...
    std::string name() const;
    std::string series;           ///< "resolution" or "memory"
    std::uint64_t target = 0;     ///< the series' value: resolution, or budget in bytes
    std::uint32_t resolution = 0; ///< the builder's resolution (the VDS: its bake resolution)
    glm::uvec3 cells{0u};         ///< columns x, y; and slices, voxels or d_S along z
    double cellSize = 0.0;        ///< column (texel) edge, mesh units
    std::size_t memoryBytes = 0;  ///< what the CPU query reads (the VDS: its CSR layers; by the GWN: and boundary edges)
    std::size_t gpuBytes = 0;     ///< what the GLSL lookup reads (the VDS: its dense 3D texture)
    double buildSeconds = 0.0;
    double pointsPerSecond = 0.0; ///< query throughput on the CPU
    std::size_t uniformWrong = 0;
    std::size_t surfaceWrong = 0;
    double uniformErrorRate = 0.0;   ///< uniformWrong / uniformPoints
    double surfaceErrorRate = 0.0;   ///< surfaceWrong / surfacePoints
    double errorRate = 0.0;          ///< over all points
    double worstErrorDistance = 0.0; ///< mesh units; 0 when nothing is wrong
    double worstErrorCells = 0.0;    ///< worstErrorDistance / cellSize
};

struct CompareResult {
    std::string meshName;
    std::size_t triangles = 0;
    std::string validation; ///< `MeshReport::summary()` of the mesh (non-manifold edges are named there)
    Box bounds;
    std::size_t uniformPoints = 0, surfacePoints = 0;
    std::size_t uniformInside = 0;     ///< the truth answers "inside" among the uniform points
    /// "parity" (sprite/winding: winding), or "generalized-winding" for every row.
    std::string truth = "parity";
    /// One line for the reader when some rows are left out or answer
    /// another rule than the truth; empty otherwise. `table()` ends with it.
    double exactBuildSeconds = 0.0;    ///< the exact classifier's construction
    double exactPointsPerSecond = 0.0; ///< and its throughput, for scale
    std::string note;
    std::vector<CompareRow> rows;

    /// A text table, one row per line, with a header.
    std::string table() const;
    /// The whole result as a JSON object.
    std::string json() const;
};

/// Runs the comparison on a mesh for which both rules define inside (closed
/// and consistently oriented, non-manifold edges allowed: see
/// `requireInsideDefined`), or on any usable mesh with `options.rule`
/// Rule::GeneralizedWinding. Uses `gl` if given (made current), else makes a
/// context. Throws `InvalidMesh` for an open, inconsistently oriented or
/// unusable mesh (with Rule::GeneralizedWinding: an unusable one),
/// `InvalidArgument` for an empty or out-of-range resolution list, and what
/// the builders throw.
CompareResult compare(MeshView mesh, const CompareOptions& options = {}, GlContext* gl = nullptr);

/// A chart of error rate (all points, %) against memory (bytes, log scale)
/// as a standalone SVG document of `width` x `height` pixels (at least
/// 400 x 300): one colour per method, resolution series as lines with dots
/// (one `<polyline>` each), memory series as rings, axis ticks with values,
/// a legend naming every method, and a tooltip (`<title>`) on each dot.
std::string errorChart(const CompareResult& result, std::uint32_t width = 900, std::uint32_t height = 560);

} // namespace vds::eval
