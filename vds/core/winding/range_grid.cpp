// vds: a grid of bounds' cells (range_grid.h).
#include <vds/detail/range_grid.h>

#include <algorithm>

#include <glm/geometric.hpp>

#include <vds/detail/caps_math.h>

namespace vds::detail {

CellsBall RangeGrid::ballOf(const glm::uvec3& first, const glm::uvec3& last) const {
    const glm::dvec3 from(box.lo), to(box.hi);
    const double slack = caps::cellSlack(to - from);
    const glm::dvec3 centre = from + 0.5 * (glm::dvec3(first) + glm::dvec3(last + 1u)) * size;
    const glm::vec3 c(centre);
    // Every point of the widened cells lies within this of c.
    return {c, 0.5 * glm::length(glm::dvec3(last + 1u - first) * size) + glm::length(glm::dvec3(c) - centre) +
                   2.0 * slack};
}

void RangeGrid::allocate() const {
    const RangeGrid& g = *this;
    const std::size_t cells = std::size_t(g.dims.x) * g.dims.y * g.dims.z;
    g.state.reset(new std::atomic<CellState>[cells]);
    g.near.reset(new std::unique_ptr<std::uint32_t[]>[cells]);
    g.nearCount.reset(new std::uint32_t[cells]());
    g.nearLoops.reset(new std::uint32_t[cells]());
    g.farCrossed.reset(new std::uint8_t[cells]());
    g.planMisses.reset(new std::atomic<std::uint8_t>[cells]);
    for (std::size_t c = 0; c < cells; ++c) g.planMisses[c].store(0, std::memory_order_relaxed);
    for (std::size_t c = 0; c < cells; ++c) g.state[c].store(CellState::Unvisited, std::memory_order_relaxed);
    g.alone.reset(new CellVerdict[cells]);
    g.lo.reset(new double[cells]);
    g.hi.reset(new double[cells]);
    g.visits.reset(new std::atomic<std::uint16_t>[cells]);
    for (std::size_t c = 0; c < cells; ++c) g.visits[c].store(0, std::memory_order_relaxed);
    g.fields.reset(new std::unique_ptr<CellField>[cells]);
    g.spent.reset(new std::atomic<std::uint32_t>[cells]);
    for (std::size_t c = 0; c < cells; ++c) g.spent[c].store(0, std::memory_order_relaxed);
    g.fieldState.reset(new std::atomic<std::uint8_t>[cells]);
    for (std::size_t c = 0; c < cells; ++c) g.fieldState[c].store(0, std::memory_order_relaxed);
}

} // namespace vds::detail
