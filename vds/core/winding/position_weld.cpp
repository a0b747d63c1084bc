// vds: positions welded by value (position_weld.h).
#include <vds/detail/position_weld.h>

#include <algorithm>
#include <cstring>

namespace vds::detail {

std::vector<std::uint32_t> weldPositions(const glm::vec3* positions, std::size_t n, std::vector<glm::vec3>& where) {
    // A position's key: its coordinates' bits, -0 made +0 (x + 0 is +0 for
    // x = -0 and x itself otherwise), so that equal keys are equal values.
    struct Key {
        std::uint64_t xy;
        std::uint32_t z, vertex;
    };
    const auto bits = [](float f) {
        f += 0.0f;
        std::uint32_t u;
        std::memcpy(&u, &f, 4);
        return u;
    };
    std::vector<Key> keys(n);
    for (std::size_t v = 0; v < n; ++v) {
        const glm::vec3 p = positions[v];
        keys[v] = {std::uint64_t(bits(p.x)) << 32 | bits(p.y), bits(p.z), std::uint32_t(v)};
    }
    std::sort(keys.begin(), keys.end(), [](const Key& a, const Key& b) {
        return a.xy != b.xy ? a.xy < b.xy : a.z != b.z ? a.z < b.z : a.vertex < b.vertex;
    });
    // Each run of equal keys starts at its smallest vertex (the sort's tie order).
    std::vector<std::uint32_t> first(n), runFirsts;
    for (std::size_t k = 0; k < n; ++k) {
        if (k == 0 || keys[k].xy != keys[k - 1].xy || keys[k].z != keys[k - 1].z) runFirsts.push_back(keys[k].vertex);
        first[keys[k].vertex] = runFirsts.back();
    }
    std::sort(runFirsts.begin(), runFirsts.end()); // ids in the order of first occurrence
    std::vector<std::uint32_t> idOfFirst(n, 0);
    where.resize(runFirsts.size());
    for (std::size_t r = 0; r < runFirsts.size(); ++r) {
        where[r] = positions[runFirsts[r]];
        idOfFirst[runFirsts[r]] = std::uint32_t(r);
    }
    std::vector<std::uint32_t> id(n);
    for (std::size_t v = 0; v < n; ++v) id[v] = idOfFirst[first[v]];
    return id;
}


} // namespace vds::detail
