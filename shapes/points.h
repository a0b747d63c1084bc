// vds: reproducible random points, for the tests and the benchmarks.
#pragma once

#include <cstdint>
#include <random>
#include <vector>

#include <glm/vec3.hpp>

#include <vds/mesh.h>

namespace vds::test {

/// `n` uniform points in `box` grown by `pad` times its size on each side.
inline std::vector<glm::vec3> randomPoints(const Box& box, std::size_t n, float pad = 0.1f, std::uint32_t seed = 1) {
    std::mt19937 rng(seed);
    const glm::vec3 size = box.hi - box.lo;
    std::uniform_real_distribution<float> u(-pad, 1.0f + pad);
    std::vector<glm::vec3> p(n);
    for (auto& q : p) q = box.lo + glm::vec3(u(rng), u(rng), u(rng)) * size;
    return p;
}

} // namespace vds::test
