// vds: the distance grid a sprite carries (`SpriteDistance`, <vds/sprite.h>),
// the exact signed distances of `SignedDistance::grid` over the baked box.
#include <vds/distance.h>

#include <algorithm>
#include <string>

#include <vds/error.h>

namespace vds {

namespace {
/// Cells added on every side of the baked box: a band or a fade of up to
/// two cells past the surface, where it touches the box, reads real
/// distances instead of the clamped edge.
constexpr float kPadCells = 2.0f;
} // namespace

Grid spriteDistanceGrid(const Box& box, std::uint32_t resolution) {
    if (resolution < 4 || resolution > kMaxDistanceResolution)
        throw InvalidArgument("distance resolution " + std::to_string(resolution) + " is out of range (4 to " +
                              std::to_string(kMaxDistanceResolution) + ")");
    const glm::vec3 extent = box.hi - box.lo;
    const float longest = std::max(extent.x, std::max(extent.y, extent.z));
    if (!(longest > 0.0f)) throw InvalidArgument("a distance grid needs a box with an extent");
    // `resolution` cells along the grown longest side, cubic as near as the
    // other sides allow (`cubicGrid`).
    const float cell = longest / (float(resolution) - 2.0f * kPadCells);
    return cubicGrid({box.lo - kPadCells * cell, box.hi + kPadCells * cell}, resolution);
}

SpriteDistance bakeDistance(const TriangleMesh& mesh, const Box& box, std::uint32_t resolution, Rule rule,
                            unsigned threads) {
    SpriteDistance out;
    out.grid = spriteDistanceGrid(box, resolution);
    const SignedDistance exact(mesh, rule);
    out.cells.resize(out.grid.cellCount());
    DistanceGridOptions options;
    options.threads = threads;
    exact.grid(out.grid, out.cells.data(), options);
    return out;
}

} // namespace vds
