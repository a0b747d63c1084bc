// vds internal: the two GL bakers. Both fill a CSR LDI (offsets, encoded crossings).
#pragma once

#include <cstdint>
#include <vector>

#include <vds/bake.h>
#include <vds/gl_context.h>

namespace vds::detail {

void bakePeel(const GlContext& gl, MeshView mesh, const SpriteGrid& grid, const BakeOptions& options,
              std::vector<std::uint32_t>& offsets, std::vector<float>& crossings);

void bakeLists(const GlContext& gl, MeshView mesh, const SpriteGrid& grid, const BakeOptions& options,
               std::vector<std::uint32_t>& offsets, std::vector<float>& crossings);

} // namespace vds::detail
