// vds: the cells a surface or a triangle may meet (caps_surface.h).
#include <vds/detail/caps_surface.h>

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include <vds/detail/caps_math.h>

namespace vds::detail {

void ProjectedSurface::markCells(const CellLattice& cells, std::vector<std::uint8_t>& met) const {
    // Against the rounding of a point's cell index, as the grid's edges.
    const double slack = caps::cellSlack(cells.size * glm::dvec3(cells.dims));
    for (const Triangle& t : mesh_.tris) {
        glm::dvec3 v[3];
        for (int k = 0; k < 3; ++k)
            for (int i = 0; i < 3; ++i) v[k][mesh_.perm[i]] = double(t.v[k][i]);
        markTriangleCells(cells, v[0], v[1], v[2], slack, met);
    }
}

void markTriangleCells(const CellLattice& cells, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                       double slack, std::vector<std::uint8_t>& met) {
    glm::uvec3 first(0), last(0);
    for (int k = 0; k < 3; ++k) {
        const double from = std::min({a[k], b[k], c[k]}) - slack, to = std::max({a[k], b[k], c[k]}) + slack;
        const double end = cells.lo[k] + double(cells.dims[k]) * cells.size[k];
        if (!(to >= cells.lo[k] && from <= end)) return; // NaN too
        const auto index = [&](double x) {
            if (!(cells.size[k] > 0.0)) return 0.0;
            return std::clamp(std::floor((x - cells.lo[k]) / cells.size[k]), 0.0, double(cells.dims[k] - 1));
        };
        first[k] = std::uint32_t(index(from));
        last[k] = std::uint32_t(index(to));
    }
    const glm::dvec3 n = glm::cross(b - a, c - a);
    const glm::dvec3 half = 0.5 * cells.size + slack;
    const double reach = std::fabs(n.x) * half.x + std::fabs(n.y) * half.y + std::fabs(n.z) * half.z;
    // The plane's offset at a cell's centre, against its reach over the
    // cell, with room for the rounding of both (relative 1e-9).
    const double rounding = 1e-9 * (glm::length(n) * (glm::length(a - cells.lo) + glm::length(cells.size * glm::dvec3(cells.dims))) + reach);
    glm::uvec3 at;
    for (at.z = first.z; at.z <= last.z; ++at.z)
        for (at.y = first.y; at.y <= last.y; ++at.y)
            for (at.x = first.x; at.x <= last.x; ++at.x) {
                const glm::dvec3 centre = cells.lo + (glm::dvec3(at) + 0.5) * cells.size;
                if (std::fabs(glm::dot(n, centre - a)) > reach + rounding) continue;
                met[cells.index(at)] = 1;
            }
}

} // namespace vds::detail
