// vds internal: what validation finds of a mesh that the axis count
// (bake/layer_count.cpp) would otherwise find again: the partners of its
// edges (validation's grouping of edges) and its triangles' facings along
// x, y and z (validation's pass over the triangles' corners).
#pragma once

#include <cstdint>
#include <vector>

#include <vds/detail/large_vector.h>

#include <vds/mesh_check.h>

namespace vds::detail {

/// Edge e of triangle t runs from its corner e to corner e + 1: half-edge
/// 3t + e. Its partner is the one other triangle with an edge between the
/// same two vertices, with kSameWay where that edge runs the same way;
/// kNoPartner where none or several do.
constexpr std::uint32_t kNoPartner = ~std::uint32_t(0);
constexpr std::uint32_t kSameWay = std::uint32_t(1) << 31;

/// A triangle's facing along axis a (bits 2a and 2a + 1): the sign of
/// component a of its normal (b - a) x (c - a), which is the orientation of
/// its corners projected along a (<vds/axis.h>'s permutations are cyclic);
/// 0 where it is parallel to a.
constexpr std::uint8_t kFacesPlus = 1;      ///< > 0: counter-clockwise
constexpr std::uint8_t kFacesMinus = 2;     ///< < 0: clockwise
constexpr std::uint8_t kFacesUndecided = 3; ///< too near 0 for double: the exact predicate decides

struct MeshFinds {
    /// Three a triangle: each edge's partner (above), the vertices welded by
    /// position as validation welds them; empty where the mesh is too large
    /// (2^31 / 3 triangles or 2^31 vertices and more).
    LargeVector<std::uint32_t> partners;
    /// One a triangle: its facings (above) along x, y and z, decided in
    /// double where Shewchuk's bound allows; 0 for a triangle with an index
    /// out of range.
    LargeVector<std::uint8_t> facings;
};

/// `validateMesh`, also filling `finds`.
MeshReport validateMesh(MeshView mesh, unsigned threads, MeshFinds& finds);

} // namespace vds::detail

/// The public `MeshValidation`'s finds are the internal ones.
struct vds::MeshValidation::Finds : detail::MeshFinds {};
