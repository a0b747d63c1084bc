// vds: the texel grid of a sprite (SpriteGrid, <vds/sprite.h>): how a mesh
// box becomes an LDI, and world points its texture space.
#include <vds/sprite.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

#include <vds/error.h>
#include <vds/grid.h>

#include <vds/detail/aligned_axes.h>
#include <vds/detail/vpt.h>

namespace vds {

glm::vec3 SpriteGrid::toTexture(const glm::vec3& world) const { return detail::textureOf(*this, world); }

SpriteGrid makeGrid(const Box& box, Axis axis, std::uint32_t resolution) {
    if (resolution == 0 || resolution > kMaxResolution)
        throw InvalidArgument("resolution " + std::to_string(resolution) + " is out of range (1 to " +
                              std::to_string(kMaxResolution) + ")");
    const glm::ivec3 p = axisPermutation(axis);
    const glm::vec3 ext = box.hi - box.lo;
    const double es = ext[p.x], et = ext[p.y], er = ext[p.z];
    if (!(std::isfinite(es) && std::isfinite(et) && std::isfinite(er)))
        throw InvalidArgument("box is not finite");
    const double across = std::max(es, et);
    if (!(across > 0.0)) throw InvalidArgument(std::string("box has no extent across the view axis ") + toString(axis));
    if (!(er > 0.0)) throw InvalidArgument(std::string("box has no extent along the view axis ") + toString(axis));

    SpriteGrid g;
    g.box = box;
    g.axis = axis;
    const double texel = across / resolution;
    const glm::uvec3 texels = cubicCells(glm::vec3(ext[p.x], ext[p.y], 0.0f), resolution);
    g.width = texels.x;
    g.height = texels.y;
    g.texelSize = float(texel);
    g.position = box.lo;
    g.matrix = glm::mat3(0.0f);
    g.matrix[p.x][0] = float(1.0 / (g.width * texel));
    g.matrix[p.y][1] = float(1.0 / (g.height * texel));
    g.matrix[p.z][2] = float(1.0 / er);
    return g;
}

bool sweepsByColumns(const SpriteGrid& grid) {
    const std::optional<glm::ivec3> axes = detail::alignedAxes(grid);
    return axes && grid.matrix[(*axes)[2]][2] > 0.0f;
}

} // namespace vds
