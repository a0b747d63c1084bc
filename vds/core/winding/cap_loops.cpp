// vds: a boundary's edges walked into loops and capped (cap_loops.h).
#include <vds/detail/cap_loops.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include <vds/detail/antipodal.h>
#include <vds/detail/caps_surface.h>
#include <vds/detail/position_weld.h>

namespace vds::detail {

namespace {

/// The boundary's edges as a graph on their welded endpoints, walked loop
/// by loop.
class LoopWalker {
public:
    /// Welds endpoints equal by value, as boundaryEdges() does (the same weld).
    LoopWalker(const glm::vec3* edges, std::size_t edgeCount)
        : edges_(edges), tail_(edgeCount), head_(edgeCount), used_(edgeCount, 0) {
        std::vector<glm::vec3> where;
        const std::vector<std::uint32_t> id = weldPositions(edges, 2 * edgeCount, where);
        for (std::size_t k = 0; k < edgeCount; ++k) {
            tail_[k] = id[2 * k];
            head_[k] = id[2 * k + 1];
        }
        out_.resize(where.size());
        for (std::size_t k = 0; k < edgeCount; ++k) out_[tail_[k]].push_back(std::uint32_t(k));
        nextOut_.assign(where.size(), 0);
    }

    bool used(std::size_t edge) const { return used_[edge] != 0; }

    /// Appends the loop from edge `start` along unused outgoing edges until
    /// it returns to its start, edge k as two points of `loopEdges`; false
    /// where it runs into a vertex with no unused edge out (an open chain).
    bool walk(std::size_t start, std::vector<glm::vec3>& loopEdges) {
        std::ptrdiff_t e = std::ptrdiff_t(start);
        while (true) {
            used_[std::size_t(e)] = 1;
            loopEdges.push_back(edges_[2 * std::size_t(e)]);
            loopEdges.push_back(edges_[2 * std::size_t(e) + 1]);
            if (head_[std::size_t(e)] == tail_[start]) return true;
            e = takeOut(std::size_t(e));
            if (e < 0) return false;
        }
    }

private:
    // The next edge out of the head of edge `in`: where several are unused
    // (a vertex the boundary passes more than once, as along a fin on a
    // non-manifold ring of edges), the one turning back most sharply, so
    // that loops stay small and tight (a fin's own triangle) instead of
    // running around the ring: small loops have small caps, which the tree
    // takes by expansion from close by.
    std::ptrdiff_t takeOut(std::size_t in) {
        const std::uint32_t v = head_[in];
        std::vector<std::uint32_t>& out = out_[v];
        std::size_t& n = nextOut_[v];
        while (n < out.size() && used_[out[n]]) ++n;
        if (n == out.size()) return -1;
        std::size_t best = n;
        const glm::dvec3 arrive = glm::dvec3(edges_[2 * in + 1]) - glm::dvec3(edges_[2 * in]);
        double bestTurn = std::numeric_limits<double>::infinity();
        for (std::size_t m = n; m < out.size(); ++m) {
            const std::uint32_t e = out[m];
            if (used_[e]) continue;
            const glm::dvec3 leave = glm::dvec3(edges_[2 * e + 1]) - glm::dvec3(edges_[2 * e]);
            const double scale = glm::length(arrive) * glm::length(leave);
            const double turn = scale > 0.0 ? glm::dot(arrive, leave) / scale : 1.0;
            if (turn < bestTurn) {
                bestTurn = turn;
                best = m;
            }
        }
        std::swap(out[n], out[best]);
        return std::ptrdiff_t(out[n++]);
    }

    const glm::vec3* edges_;
    std::vector<std::uint32_t> tail_, head_; ///< each edge's welded endpoints
    std::vector<std::vector<std::uint32_t>> out_; ///< each vertex's edges out
    std::vector<std::size_t> nextOut_;            ///< each vertex's first edge out that may be unused
    std::vector<std::uint8_t> used_;
};

} // namespace

CapLoops::CapLoops(const glm::vec3* edges, std::size_t edgeCount, Axis axis)
    : axisIndex_(axisPermutation(axis).z), edges_(edges, edges + 2 * edgeCount) {
    LoopWalker walker(edges, edgeCount);
    for (std::size_t start = 0; start < edgeCount && closed_; ++start) {
        if (walker.used(start)) continue;
        CapLoop loop;
        loop.first = std::uint32_t(loopEdges_.size() / 2);
        // an open chain: these are not a mesh's boundary
        if (!walker.walk(start, loopEdges_)) closed_ = false;
        loop.count = std::uint32_t(loopEdges_.size() / 2) - loop.first;
        addCap(loop);
        loops_.push_back(loop);
    }
    if (closed_ && !capTriangles_.empty())
        projected_.emplace(MeshView(capPositions_.data(), capPositions_.size(), capTriangles_.data(), capTriangles_.size()),
                           axis);
}

void CapLoops::addCap(CapLoop& loop) {
    glm::dvec3 sum(0.0);
    for (std::uint32_t k = loop.first; k < loop.first + loop.count; ++k) sum += glm::dvec3(loopEdges_[2 * k]);
    const glm::vec3 c(sum / double(loop.count)); // rounded: the caps' float and double forms agree
    loop.centroid = glm::dvec3(c);
    const std::uint32_t apex = std::uint32_t(capPositions_.size());
    capPositions_.push_back(c);
    for (std::uint32_t k = loop.first; k < loop.first + loop.count; ++k) {
        const glm::vec3 a = loopEdges_[2 * k], b = loopEdges_[2 * k + 1];
        const std::uint32_t ia = std::uint32_t(capPositions_.size());
        capPositions_.push_back(a);
        capPositions_.push_back(b);
        capTriangles_.emplace_back(apex, ia + 1, ia); // (c, b, a): the cap's boundary is the loop reversed
        capLoopOf_.push_back(std::uint32_t(loops_.size()));
        loop.radius = std::max(loop.radius, glm::length(glm::dvec3(a) - loop.centroid));
    }
    for (std::uint32_t k = loop.first; k < loop.first + loop.count; ++k) {
        const glm::dvec3 a(loopEdges_[2 * k]), b(loopEdges_[2 * k + 1]);
        loop.area += 0.5 * glm::length(glm::cross(b - loop.centroid, a - loop.centroid));
    }
}

double CapLoops::exact(int winding, const glm::vec3& q) const {
    return double(winding) + boundaryTermExact(edges_.data(), edges_.size() / 2, axisIndex_, glm::dvec3(q));
}

void CapLoops::capCrossings(const glm::vec3& q, std::vector<std::pair<std::uint32_t, int>>& out) const {
    out.clear();
    float v[3];
    projected_->toViewSpace(q, v);
    projected_->crossings(projected_->grid.find(v), v,
                          [&](const Triangle& t, int crossing) { out.emplace_back(capLoopOf_[t.index], crossing); });
}

void CapLoops::markCapCells(const CellLattice& cells, double slack, std::vector<std::uint8_t>& met) const {
    for (const glm::uvec3& c : capTriangles_)
        markTriangleCells(cells, glm::dvec3(capPositions_[c.x]), glm::dvec3(capPositions_[c.y]),
                          glm::dvec3(capPositions_[c.z]), slack, met);
}

std::size_t CapLoops::memoryBytes() const {
    const auto held = [](const auto& v) { return v.capacity() * sizeof(v[0]); };
    return held(edges_) + held(loopEdges_) + held(loops_) + held(capPositions_) + held(capTriangles_) +
           held(capLoopOf_) + (projected_ ? projected_->memoryBytes() : 0);
}

} // namespace vds::detail
