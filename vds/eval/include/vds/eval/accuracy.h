// vds: how wrong is a sprite, where, and at what resolution it stops mattering.
//
// `evaluate` bakes a mesh at several resolutions and classifies the same
// points with the sprite (VPT) and with the exact classifier: uniform random
// points in the padded box, and points near the surface (where the paper
// says the errors live: Trapp & Doellner 2008, section 5.2). For every wrong
// point it measures the distance to the surface in texels. It also renders
// slice images through the box's centre showing the solid and, in colour,
// where the sprite disagrees with the exact answer.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <vds/bake.h>
#include <vds/mesh.h>
#include <vds/sprite.h>

namespace vds {
class GlContext;
}

namespace vds::eval {

struct EvalOptions {
    std::vector<std::uint32_t> resolutions{256, 512, 1024, 2048};
    std::size_t uniformPoints = 1000000; ///< in the box grown by 10% on each side
    std::size_t surfacePoints = 1000000; ///< within +-4 texels of the surface, at each resolution
    Axis axis = Axis::Z;
    BakeMethod method = BakeMethod::Lists;
    Rule rule = Rule::Parity;
    std::uint32_t seed = 1;
    unsigned threads = 0;
    /// Most wrong points whose distance to the surface is measured (a sample
    /// when there are more; the count of wrong points is always complete).
    std::size_t distanceSample = 5000;
    /// If not empty, slice PNGs are written as `<imagePrefix>-<res>-<axis>.png`.
    std::string imagePrefix;
    std::uint32_t imageSize = 512;
};

struct EvalRow {
    std::uint32_t resolution = 0;
    std::uint32_t width = 0, height = 0, depthComplexity = 0;
    float texelSize = 0.0f;
    double bakeSeconds = 0.0;
    std::size_t fileBytes = 0;   ///< the .vds file
    std::size_t memoryBytes = 0; ///< the CSR sprite in memory
    std::size_t denseBytes = 0;  ///< the paper's dense texture
    std::size_t uniformPoints = 0, uniformWrong = 0;
    std::size_t surfacePoints = 0, surfaceWrong = 0;
    std::size_t distancesMeasured = 0;       ///< wrong points whose distance was measured
    double maxWrongDistanceTexels = 0.0;     ///< farthest wrong point from the surface
    double meanWrongDistanceTexels = 0.0;
    std::size_t wrongBeyondTexelDiagonal = 0; ///< wrong points farther than sqrt(2) texels (of those measured)
    double vdsPointsPerSecond = 0.0;
    double exactPointsPerSecond = 0.0;
    std::vector<std::string> images;
};

struct EvalReport {
    std::string mesh;
    std::size_t triangles = 0;
    std::string validation;
    Rule rule = Rule::Parity;
    Axis axis = Axis::Z;
    std::vector<EvalRow> rows;
};

/// Runs the evaluation. `progress` (may be empty) gets short status lines.
/// GL methods use `gl` if given, else make a context. Throws `InvalidMesh`
/// unless `options.rule` defines inside for the mesh (`requireInsideDefined`:
/// there is no exact answer to compare with otherwise), and like `bake`.
EvalReport evaluate(const TriangleMesh& mesh, const EvalOptions& options, GlContext* gl = nullptr,
                    const std::function<void(const std::string&)>& progress = {});

/// The report as JSON (one object; rows as an array).
std::string toJson(const EvalReport& report);

/// The report as text, what `vds eval` prints: a line naming the mesh, rule
/// and axis, a blank line, then a Markdown table with a header and one row
/// per resolution.
std::string toTable(const EvalReport& report);

} // namespace vds::eval
