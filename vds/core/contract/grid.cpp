// vds: the one grid of cells (<vds/grid.h>): its cell centres, checks, the
// one sizing of cubic grids and the cubic grid over a box.
#include <vds/grid.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include <vds/error.h>

namespace vds {

float Grid::cellCoordinate(int axis, std::uint32_t index) const {
    const double lo = box.lo[axis], hi = box.hi[axis];
    return float(lo + (double(first[axis] + index) + 0.5) * (hi - lo) / double(wholeCells(axis)));
}

glm::vec3 Grid::cellCentre(std::uint32_t i, std::uint32_t j, std::uint32_t k) const {
    return {cellCoordinate(0, i), cellCoordinate(1, j), cellCoordinate(2, k)};
}

void checkGrid(const Grid& grid) {
    if (grid.dims.x == 0 || grid.dims.y == 0 || grid.dims.z == 0)
        throw InvalidArgument("grid has a zero dimension");
    if (std::uint64_t(grid.dims.x) * grid.dims.y * grid.dims.z > kMaxGridCells)
        throw InvalidArgument("grid of " + std::to_string(grid.dims.x) + "x" + std::to_string(grid.dims.y) +
                              "x" + std::to_string(grid.dims.z) + " cells is too large (at most 2^34 cells)");
    for (int a = 0; a < 3; ++a)
        if (grid.whole[a] && std::uint64_t(grid.first[a]) + grid.dims[a] > grid.whole[a])
            throw InvalidArgument("grid slab reaches past its whole grid");
    for (int a = 0; a < 3; ++a)
        if (!(std::isfinite(grid.box.lo[a]) && std::isfinite(grid.box.hi[a]) && grid.box.lo[a] < grid.box.hi[a]))
            throw InvalidArgument("grid box is empty or not finite");
}

glm::uvec3 cubicCells(const glm::vec3& extent, std::uint32_t n) {
    const double longest = std::max({double(extent.x), double(extent.y), double(extent.z)});
    glm::uvec3 cells(1u);
    if (!(longest > 0.0)) return cells;
    const double cell = longest / n;
    for (int a = 0; a < 3; ++a) {
        const double fit = std::ceil(double(extent[a]) / cell); // NaN for a NaN extent: 1 cell
        cells[a] = double(extent[a]) == longest || fit >= double(n) ? n : fit >= 1.0 ? std::uint32_t(fit) : 1u;
    }
    return cells;
}

Grid cubicGrid(const Box& box, std::uint32_t n) {
    Grid grid;
    grid.box = box;
    const glm::vec3 size = box.hi - box.lo;
    const float longest = std::max({size.x, size.y, size.z});
    grid.dims = cubicCells(size, n);
    // The box grows to whole cells so that cells stay cubic.
    for (int a = 0; a < 3; ++a)
        grid.box.hi[a] = float(double(box.lo[a]) + double(grid.dims[a]) * double(longest) / double(n));
    return grid;
}

} // namespace vds
