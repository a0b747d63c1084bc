// vds internal: the library's one weld. Positions are the same vertex when
// they are equal as floats (-0 and +0 alike; a NaN or infinite coordinate
// makes a vertex its own). Validation welds a mesh's vertices with it, and
// the generalized winding number's boundary its edges' ends.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include <vds/detail/large_vector.h>

namespace vds::detail {

/// True when every coordinate of `p` is finite.
inline bool finitePosition(const glm::vec3& p) {
    return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
}

/// For each of the `n` positions, the first (lowest) position equal to it,
/// for any number of `threads`; those not finite are their own and counted
/// in `notFinite`. Hashed, in parallel parts past 2^16 positions.
LargeVector<std::uint32_t> weldByPosition(const glm::vec3* positions, std::size_t n, unsigned threads,
                                          std::size_t& notFinite);

/// The same weld as ids: each position's id, ids numbered in the order of
/// their first position, and `where` each id's position (its first's).
std::vector<std::uint32_t> weldPositions(const glm::vec3* positions, std::size_t n, std::vector<glm::vec3>& where);

} // namespace vds::detail
