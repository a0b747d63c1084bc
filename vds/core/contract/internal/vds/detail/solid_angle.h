// vds: the signed solid angle of a triangle, the one copy for the contract's
// validation (which parts of a mesh are inside out) and the winding room's
// generalized winding number.
#pragma once

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace vds::detail {

/// Van Oosterom & Strackee's parts of the solid angle of the triangle
/// (u, v, w) seen from the origin: the angle is 2 atan2(det, den); `scale`
/// (|u| |v| |w|) says how small det and den are for the point to lie in
/// the triangle's plane and within it (where the angle jumps by 4 pi).
struct SolidAngleParts {
    double det, den, scale;
};

inline SolidAngleParts solidAngleParts(const glm::dvec3& u, const glm::dvec3& v, const glm::dvec3& w) {
    const double lu = glm::length(u), lv = glm::length(v), lw = glm::length(w);
    const double det = glm::dot(u, glm::cross(v, w));
    const double den = lu * lv * lw + glm::dot(u, v) * lw + glm::dot(u, w) * lv + glm::dot(v, w) * lu;
    return {det, den, lu * lv * lw};
}

/// Signed solid angle of the triangle (u, v, w) seen from the origin (Van
/// Oosterom & Strackee), in double.
inline double solidAngle(const glm::dvec3& u, const glm::dvec3& v, const glm::dvec3& w) {
    const SolidAngleParts s = solidAngleParts(u, v, w);
    return 2.0 * std::atan2(s.det, s.den);
}

} // namespace vds::detail
