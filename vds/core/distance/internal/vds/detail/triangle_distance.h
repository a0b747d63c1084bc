// vds: the closest point on one triangle, in double (Ericson, "Real-Time
// Collision Detection", 2005, section 5.1.5: the Voronoi regions of the
// corners and edges tested in turn, the face's last).
//
// Every point returned lies on the triangle up to rounding: a corner, a
// clamped interpolation along an edge (t in [0, 1]), or a convex
// combination with non-negative weights summing to one. A degenerate
// triangle (corners on a line or one point), whose face region has no
// area, answers as the nearest of its three edges.
#pragma once

#include <cstdint>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <vds/distance.h>

namespace vds::detail {

struct TriangleHit {
    glm::dvec3 point;
    Feature feature;
    std::uint8_t index; ///< the edge or corner
};

/// The closest point of the segment from corner `index` (at a) to b.
inline TriangleHit closestOnEdge(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b, std::uint8_t index) {
    const glm::dvec3 ab = b - a;
    const double len2 = glm::dot(ab, ab);
    const double t = len2 > 0.0 ? glm::dot(p - a, ab) / len2 : 0.0;
    if (t <= 0.0) return {a, Feature::Vertex, index};
    if (t >= 1.0) return {b, Feature::Vertex, std::uint8_t((index + 1) % 3)};
    return {a + ab * t, Feature::Edge, index};
}

inline double distance2(const glm::dvec3& p, const glm::dvec3& q) {
    const glm::dvec3 d = p - q;
    return glm::dot(d, d);
}

/// The nearest of the three edges: a degenerate triangle's closest point.
inline TriangleHit closestOnEdges(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b,
                                  const glm::dvec3& c) {
    TriangleHit best = closestOnEdge(p, a, b, 0);
    for (const TriangleHit& h : {closestOnEdge(p, b, c, 1), closestOnEdge(p, c, a, 2)})
        if (distance2(p, h.point) < distance2(p, best.point)) best = h;
    return best;
}

inline TriangleHit closestOnTriangle(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b,
                                     const glm::dvec3& c) {
    const glm::dvec3 ab = b - a, ac = c - a, ap = p - a;
    const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
    if (d1 <= 0.0 && d2 <= 0.0) return {a, Feature::Vertex, 0};
    const glm::dvec3 bp = p - b;
    const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
    if (d3 >= 0.0 && d4 <= d3) return {b, Feature::Vertex, 1};
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 && d1 - d3 > 0.0) return {a + ab * (d1 / (d1 - d3)), Feature::Edge, 0};
    const glm::dvec3 cp = p - c;
    const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
    if (d6 >= 0.0 && d5 <= d6) return {c, Feature::Vertex, 2};
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 && d2 - d6 > 0.0) return {a + ac * (d2 / (d2 - d6)), Feature::Edge, 2};
    const double va = d3 * d6 - d5 * d4;
    const double e1 = d4 - d3, e2 = d5 - d6;
    if (va <= 0.0 && e1 >= 0.0 && e2 >= 0.0 && e1 + e2 > 0.0) return {b + (c - b) * (e1 / (e1 + e2)), Feature::Edge, 1};
    const double sum = va + vb + vc;
    if (!(sum > 0.0) || va < 0.0 || vb < 0.0 || vc < 0.0) return closestOnEdges(p, a, b, c);
    return {a + ab * (vb / sum) + ac * (vc / sum), Feature::Face, 0};
}

} // namespace vds::detail
