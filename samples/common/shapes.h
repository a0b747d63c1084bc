// Samples: closed meshes built in code for the scenes of the samples that
// need no model file (shadows, refraction).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <glm/gtc/constants.hpp>
#include <glm/vec3.hpp>

#include <vds/mesh.h>

namespace vds::samples {

/// Appends a closed UV sphere to `m`, outward facing (inward with
/// `inward`): `segments` around (>= 3) and `segments / 2` rings.
inline void addSphere(TriangleMesh& m, const glm::vec3& centre, float radius, std::uint32_t segments,
                      bool inward = false) {
    const std::uint32_t rings = std::max(2u, segments / 2), base = std::uint32_t(m.positions.size());
    const float pi = glm::pi<float>();
    m.positions.push_back(centre + glm::vec3(0, radius, 0));
    for (std::uint32_t r = 1; r < rings; ++r)
        for (std::uint32_t s = 0; s < segments; ++s) {
            const float theta = pi * float(r) / float(rings), phi = 2.0f * pi * float(s) / float(segments);
            m.positions.push_back(centre + radius * glm::vec3(std::sin(theta) * std::cos(phi), std::cos(theta),
                                                              std::sin(theta) * std::sin(phi)));
        }
    m.positions.push_back(centre - glm::vec3(0, radius, 0));
    const std::uint32_t south = std::uint32_t(m.positions.size()) - 1;
    const auto ring = [&](std::uint32_t r, std::uint32_t s) { return base + 1 + (r - 1) * segments + s % segments; };
    const auto tri = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
        m.triangles.push_back(inward ? glm::uvec3(a, c, b) : glm::uvec3(a, b, c));
    };
    for (std::uint32_t s = 0; s < segments; ++s) {
        tri(base, ring(1, s + 1), ring(1, s));
        tri(south, ring(rings - 1, s), ring(rings - 1, s + 1));
        for (std::uint32_t r = 1; r + 1 < rings; ++r) {
            tri(ring(r, s), ring(r, s + 1), ring(r + 1, s));
            tri(ring(r, s + 1), ring(r + 1, s + 1), ring(r + 1, s));
        }
    }
}

} // namespace vds::samples
