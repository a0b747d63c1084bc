// Test support for vds::voxel: exact expectations computed on the CPU from
// the snapped triangles the voxelizers see.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <vds/mesh.h>
#include <vds/voxel/grid.h>

namespace vds::voxel::test {

/// Triangle `t` of `mesh` in cell coordinates, x and y snapped (as the solid
/// and slicing voxelizers see it).
inline void snappedTriangle(const TriangleMesh& mesh, const VoxelGrid& grid, std::size_t t, glm::vec3 v[3]) {
    for (int k = 0; k < 3; ++k) {
        const glm::vec3 c = grid.toCells(mesh.positions[mesh.triangles[t][k]]);
        v[k] = glm::vec3(snapToSubcells(c.x), snapToSubcells(c.y), c.z);
    }
}

/// Distance in xy from q to the segment a-b.
inline double segmentDistance(glm::dvec2 q, glm::dvec2 a, glm::dvec2 b) {
    const glm::dvec2 ab = b - a, aq = q - a;
    const double len2 = ab.x * ab.x + ab.y * ab.y;
    const double t = len2 > 0.0 ? std::clamp((aq.x * ab.x + aq.y * ab.y) / len2, 0.0, 1.0) : 0.0;
    const glm::dvec2 d = aq - t * ab;
    return std::sqrt(d.x * d.x + d.y * d.y);
}

/// Whether the column centre (i + 0.5, j + 0.5) lies within `tolerance` cells
/// of an edge of a triangle of the mesh projected onto xy (unsnapped).
inline bool nearProjectedEdge(const TriangleMesh& mesh, const VoxelGrid& grid, std::uint32_t i, std::uint32_t j,
                              double tolerance) {
    const glm::dvec2 q(i + 0.5, j + 0.5);
    for (const auto& tri : mesh.triangles) {
        glm::dvec2 p[3];
        for (int k = 0; k < 3; ++k) {
            const glm::vec3 c = grid.toCells(mesh.positions[tri[k]]);
            p[k] = glm::dvec2(c.x, c.y);
        }
        for (int k = 0; k < 3; ++k)
            if (segmentDistance(q, p[k], p[(k + 1) % 3]) <= tolerance) return true;
    }
    return false;
}

/// A triangle's plane at a column centre: its depth (cell z) and the
/// magnitude of its depth gradient across x and y (cells per cell).
struct PlaneSample {
    double depth;
    double slope;
};

/// The planes of the mesh's triangles at the column centre (i + 0.5, j + 0.5),
/// for those whose unsnapped projection contains it (closed).
inline std::vector<PlaneSample> depthsAtColumn(const TriangleMesh& mesh, const VoxelGrid& grid, std::uint32_t i,
                                               std::uint32_t j) {
    const glm::dvec2 q(i + 0.5, j + 0.5);
    std::vector<PlaneSample> depths;
    for (const auto& tri : mesh.triangles) {
        glm::dvec3 p[3];
        for (int k = 0; k < 3; ++k) p[k] = glm::dvec3(grid.toCells(mesh.positions[tri[k]]));
        double w[3], sum = 0.0;
        for (int k = 0; k < 3; ++k) {
            const glm::dvec3& a = p[(k + 1) % 3];
            const glm::dvec3& b = p[(k + 2) % 3];
            w[k] = (b.x - a.x) * (q.y - a.y) - (b.y - a.y) * (q.x - a.x);
            sum += w[k];
        }
        if (sum == 0.0) continue;
        bool inside = true;
        for (double x : w) inside = inside && x * sum >= 0.0;
        if (!inside) continue;
        const glm::dvec3 n = glm::cross(p[1] - p[0], p[2] - p[0]);
        depths.push_back(
            {(w[0] * p[0].z + w[1] * p[1].z + w[2] * p[2].z) / sum, std::hypot(n.x, n.y) / std::fabs(n.z)});
    }
    return depths;
}

/// Whether the snapping of x and y (up to 1/512 cell per axis) may move a
/// triangle's plane across depth `z` at the column centre (i + 0.5, j + 0.5):
/// the plane lies within its slope times the largest snapping shift of `z`.
inline bool nearInDepth(const TriangleMesh& mesh, const VoxelGrid& grid, std::uint32_t i, std::uint32_t j, double z) {
    for (const PlaneSample& s : depthsAtColumn(mesh, grid, i, j))
        if (std::fabs(s.depth - z) <= s.slope * std::sqrt(2.0) / 512.0 + 1e-4) return true;
    return false;
}

} // namespace vds::voxel::test
