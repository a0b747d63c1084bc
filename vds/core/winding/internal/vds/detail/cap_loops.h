// vds internal: a boundary's edges walked into closed loops, each closed by
// its cap (the fan from its centroid), and the caps as a projected mesh for
// their crossing count C_caps (boundary_caps.h says why).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include <vds/axis.h>
#include <vds/mesh.h>

#include <vds/detail/edge_tree.h>
#include <vds/detail/projected_mesh.h>

namespace vds::detail {

struct CellLattice;

/// The loops and caps of `edgeCount` boundary edges. Built once, then
/// thread safe to query.
class CapLoops {
public:
    /// `edges`: 2 * `edgeCount` points, edge k from [2k] to [2k+1]
    /// (copied). `axis`: the integer term's ray runs towards -axis.
    CapLoops(const glm::vec3* edges, std::size_t edgeCount, Axis axis);

    /// False when the edges do not close into loops (not a mesh's
    /// boundary): every query then takes the per-edge sum.
    bool closed() const { return closed_; }
    /// True where the caps are a mesh (closed, some edges): C_caps, the
    /// trees and the grids exist.
    bool capped() const { return projected_.has_value(); }
    int axisIndex() const { return axisIndex_; }
    std::size_t edgeCount() const { return edges_.size() / 2; }
    const std::vector<CapLoop>& loops() const { return loops_; }
    /// The edges as given (edge k from [2k] to [2k+1]).
    const std::vector<glm::vec3>& edges() const { return edges_; }
    /// The edges in loop order: loop l's edges are [first, first + count).
    const std::vector<glm::vec3>& loopEdges() const { return loopEdges_; }
    /// The caps as a projected mesh (capped() only), for C_caps.
    const ProjectedMesh& projected() const { return *projected_; }

    /// `winding + B(q)` by the per-edge sum over the edges as given.
    double exact(int winding, const glm::vec3& q) const;
    /// The cap triangles q's ray towards -axis crosses in front of q, as
    /// (loop, +1 or -1): C_caps loop by loop, counted as projected() counts.
    void capCrossings(const glm::vec3& q, std::vector<std::pair<std::uint32_t, int>>& out) const;
    /// Sets met[cells.index(at)] = 1 for every cell a cap triangle may meet
    /// (margin `slack`).
    void markCapCells(const CellLattice& cells, double slack, std::vector<std::uint8_t>& met) const;
    std::size_t memoryBytes() const;

private:
    /// Loop `loop`'s cap: its centroid, radius and area, and its fan among
    /// the caps' triangles.
    void addCap(CapLoop& loop);

    int axisIndex_;
    bool closed_ = true;
    std::vector<glm::vec3> edges_;
    std::vector<glm::vec3> loopEdges_;
    std::vector<CapLoop> loops_;
    std::vector<glm::vec3> capPositions_;
    std::vector<glm::uvec3> capTriangles_;
    std::vector<std::uint32_t> capLoopOf_;   ///< the loop of each cap triangle
    std::optional<ProjectedMesh> projected_; ///< the caps, for C_caps
};

} // namespace vds::detail
