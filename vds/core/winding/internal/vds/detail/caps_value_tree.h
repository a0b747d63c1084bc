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
/// this). Built once (its subtrees on the library's threads), then thread
/// safe.
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
    const CapLoops& loops_;
    std::vector<std::array<glm::dvec3, 3>> leafTris_; ///< cap triangles in tree order
    std::vector<CapsNode> nodes_; ///< [0] is the root; empty where the caps are no mesh
};

} // namespace vds::detail
