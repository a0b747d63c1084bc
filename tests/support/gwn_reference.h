// Test support: the generalized winding number a sprite stands for, in
// double and independently of the library's boundary code, the yardstick of
// the GPU tests (tests/gl/gwn_gpu_test.cpp, gpu_occupancy_test.cpp).
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <vds/sprite.h>

namespace vds::test {

// The GWN the sprite stands for at `world`, in double, independently of the
// library's boundary code: the signed count of the column's crossings in
// front, plus the solid angles (+axis, a - q, b - q) / 4 pi of the boundary
// edges at the texel-centre point q at the point's depth. In front of or
// behind the box the column's count is that of none or all of its
// crossings; beside the box (no column) there are none and q is the point
// itself. NaN where the point is not finite. (Where q's ray passes exactly
// over a boundary edge this naive sum takes atan2's side of the jump, not
// the library's tie rule, and can differ by 1.)
inline double referenceGwn(const Sprite& s, const glm::vec3& world) {
    const glm::vec3 t = s.grid.toTexture(world);
    if (!(std::isfinite(t.x) && std::isfinite(t.y) && std::isfinite(t.z))) return std::nan("");
    const float fs = std::floor(t.x * float(s.width())), ft = std::floor(t.y * float(s.height()));
    int winding = 0;
    glm::dvec3 q;
    if (fs >= 0.0f && fs < float(s.width()) && ft >= 0.0f && ft < float(s.height())) {
        const auto i = std::uint32_t(fs), j = std::uint32_t(ft);
        const std::size_t c = std::size_t(j) * s.width() + i;
        for (std::uint32_t k = s.offsets[c]; k < s.offsets[c + 1] && crossingDepth(s.crossings[k]) < t.z; ++k)
            winding += crossingEnters(s.crossings[k]) ? 1 : -1;
        q = glm::dvec3(s.grid.texelCentre(i, j, t.z));
    } else {
        const glm::ivec3 p = axisPermutation(s.grid.axis);
        q[p.x] = double(s.grid.box.lo[p.x]) + double(t.x) * double(s.width()) * double(s.grid.texelSize);
        q[p.y] = double(s.grid.box.lo[p.y]) + double(t.y) * double(s.height()) * double(s.grid.texelSize);
        q[p.z] = double(s.grid.box.lo[p.z]) + double(t.z) * (double(s.grid.box.hi[p.z]) - double(s.grid.box.lo[p.z]));
    }
    glm::dvec3 axis(0.0);
    axis[axisPermutation(s.grid.axis).z] = 1.0;
    double sum = 0.0;
    for (std::size_t k = 0; k + 1 < s.boundaryEdges.size(); k += 2) {
        const glm::dvec3 u = glm::dvec3(s.boundaryEdges[k]) - q, v = glm::dvec3(s.boundaryEdges[k + 1]) - q;
        const double lu = glm::length(u), lv = glm::length(v);
        sum += 2.0 * std::atan2(glm::dot(axis, glm::cross(u, v)), lu * lv + glm::dot(axis, u) * lv +
                                                                       glm::dot(axis, v) * lu + glm::dot(u, v));
    }
    return double(winding) + sum / (4.0 * 3.14159265358979323846);
}

} // namespace vds::test
