// vds internal: the partners of a mesh's edges, found by validation's
// grouping of edges and handed to the axis count (sprite/layer_count.cpp),
// which would otherwise group them again.
#pragma once

#include <cstdint>
#include <vector>

#include <vds/mesh.h>

namespace vds::detail {

/// Edge e of triangle t runs from its corner e to corner e + 1: half-edge
/// 3t + e. Its partner is the one other triangle with an edge between the
/// same two vertices, with kSameWay where that edge runs the same way;
/// kNoPartner where none or several do.
constexpr std::uint32_t kNoPartner = ~std::uint32_t(0);
constexpr std::uint32_t kSameWay = std::uint32_t(1) << 31;

/// `validateMesh`, also filling `partners` (three a triangle), the vertices
/// welded by position as validation welds them, where the mesh allows
/// (fewer than 2^31 / 3 triangles and 2^31 vertices); otherwise `partners`
/// is left empty.
MeshReport validateMesh(MeshView mesh, unsigned threads, std::vector<std::uint32_t>& partners);

} // namespace vds::detail
