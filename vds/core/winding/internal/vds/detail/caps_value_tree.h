// vds internal: the value tree of the caps: a tree over the cap triangles
// (cut to about the loops' edge length), each node's moments about its
// centre, for B = C_caps - w_caps with a proven error bound
// (boundary_caps.h derives the bound).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include <vds/detail/cap_loops.h>
#include <vds/detail/caps_math.h>
#include <vds/detail/chain_tree.h>

namespace vds::detail {

/// Error bound a tree node may add when taken by its expansion, per unit of
/// the solid angle it subtends, for values (then exactly where the bound
/// exceeds the value's tolerance).
constexpr double kCapValueTolerance = 1e-3;

/// The value tree of `loops`' caps (kept by reference: it must outlive
/// this). Built once, then thread safe.
class CapsValueTree {
public:
    explicit CapsValueTree(const CapLoops& loops);
    /// B(q) and its error bound, taking nodes whose bound is at most
    /// `nodeTolerance` by the expansion to second order. Points are float
    /// so that the crossing count and the solid angles are taken at the
    /// same point.
    CapsEstimate estimate(const glm::vec3& q, double nodeTolerance) const;
    std::size_t memoryBytes() const;

private:
    using Triangles = std::vector<std::array<glm::dvec3, 3>>;
    /// `unsignedMoments[node]`: the integral of |n| (x - centre) dA, for the
    /// parent's moments from its children's.
    std::uint32_t build(std::uint32_t first, std::uint32_t last, std::vector<std::uint32_t>& order,
                        const Triangles& tris, std::vector<glm::dvec3>& unsignedMoments);
    /// build()'s leaf `node` (its ball set) at `index`: its triangles'
    /// moments, and the triangles themselves into leafTris_.
    void buildLeaf(CapsNode& node, std::uint32_t index, std::uint32_t first, std::uint32_t last,
                   const std::vector<std::uint32_t>& order, const Triangles& tris,
                   std::vector<glm::dvec3>& unsignedMoments);
    /// build()'s inner `node` at `index`: its children's moments moved to
    /// its centre and summed.
    void gatherChildren(CapsNode& node, std::uint32_t index, std::vector<glm::dvec3>& unsignedMoments);

    const CapLoops& loops_;
    Triangles leafTris_;         ///< cap triangles in tree order
    std::vector<CapsNode> nodes_; ///< [0] is the root; empty where the caps are no mesh
};

} // namespace vds::detail
