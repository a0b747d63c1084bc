// vds internal: what the winding engine's grids of bounds (bound_ranges.h)
// ask of the surface a boundary belongs to: which cells it may meet, and
// over which cells the caller's integer term is one integer.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include <glm/vec3.hpp>

#include <vds/detail/projected_mesh.h>

namespace vds::detail {

/// The cells of a grid: cell (i, j, k) spans lo + (i, j, k) * size to
/// lo + (i + 1, j + 1, k + 1) * size.
struct CellLattice {
    glm::dvec3 lo{0.0}, size{0.0};
    glm::uvec3 dims{0};
    std::size_t index(const glm::uvec3& at) const { return (std::size_t(at.z) * dims.y + at.y) * dims.x + at.x; }
};

/// The surface a boundary belongs to, for ranges of its whole generalized
/// winding number: over a cell that no part of the surface meets, the
/// winding number is smooth (its gradient is the boundary's Biot-Savart
/// integral, which EdgeTree::driftWithin bounds in any direction;
/// across a cap or a boundary edge's sweep its integer term and boundary
/// term jump together), so its value at the cell's centre and the drift
/// over the cell give its range, and a query there needs neither term.
class CapsSurface {
public:
    virtual ~CapsSurface() = default;
    /// The integer term at q, as the caller counts it (crossings strictly
    /// in front of q towards -axis, the top-left rule on ties).
    virtual int winding(const glm::vec3& q) const = 0;
    /// Sets met[cells.index(at)] = 1 for every cell the surface may meet:
    /// a cell left 0 must be clear of every triangle, a cell set may be.
    virtual void markCells(const CellLattice& cells, std::vector<std::uint8_t>& met) const = 0;
};

/// What a caller knows of its integer term over whole cells, where the
/// surface itself is not at hand (a sprite has columns, not triangles):
/// over a cell clear of the boundary's sweep B is smooth, so an integer
/// term that is one integer n over the cell, as the queries landing in it
/// ask it, makes n plus B's range the whole winding number's range there,
/// and a query in the cell needs neither term.
class CellWindings {
public:
    static constexpr std::int32_t kUnknown = std::numeric_limits<std::int32_t>::min();
    virtual ~CellWindings() = default;
    /// Sets windings[cells.index(at)] = n for every cell over which the
    /// integer term is known to be n; leaves the rest (kUnknown). And
    /// closed[cells.index(at)] = n for every cell over which the integer
    /// term plus `caps`' crossing count (ProjectedMesh::winding) at the
    /// point B is taken at is known to be n: the crossing count of the
    /// closed surface the caps make of the mesh, one integer where that
    /// surface keeps out of the cell, across the boundary's sweep too: for
    /// the queries that ask inside() (those that ask insideApart are not
    /// held to it).
    virtual void constantWindings(const CellLattice& cells, const ProjectedMesh* caps,
                                  std::vector<std::int32_t>& windings, std::vector<std::int32_t>& closed) const = 0;
};

/// Marks the cells triangle (a, b, c) may meet: those its box overlaps
/// that its plane does not pass clear of, both with a margin of `slack`.
void markTriangleCells(const CellLattice& cells, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                       double slack, std::vector<std::uint8_t>& met);

/// A projected mesh as the surface of its boundary edges: its crossing
/// count, and the cells its triangles (parallel ones too: the winding
/// number jumps across them as well) may meet. Keeps a reference.
class ProjectedSurface final : public CapsSurface {
public:
    explicit ProjectedSurface(const ProjectedMesh& mesh) : mesh_(mesh) {}
    int winding(const glm::vec3& q) const override { return mesh_.winding(q); }
    void markCells(const CellLattice& cells, std::vector<std::uint8_t>& met) const override;

private:
    const ProjectedMesh& mesh_;
};

} // namespace vds::detail
