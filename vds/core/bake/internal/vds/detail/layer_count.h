// vds internal: the layers and crossings a bake along one axis would make,
// counted without baking (chooseViewAxis, bake.cpp).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <vds/detail/edge_partners.h>
#include <vds/mesh.h>
#include <vds/sprite.h>

namespace vds::detail {

struct LayerCount {
    std::uint32_t most = 0;   ///< the most crossings of one column: d_S
    std::uint64_t total = 0;  ///< crossings in all
};

/// The counts of the CPU baker's sprites of `mesh` along the three grids'
/// axes at their texel centres, by its claim rule: equal to counting every
/// texel of every triangle's box (see layer_count.cpp), in time
/// proportional to the rows the triangles span rather than the texels they
/// cover. `grids` are those of x, y and z (`chooseViewAxis`); `finds`,
/// what validation found of the mesh (<vds/detail/edge_partners.h>), or
/// empty: the count then pairs the edges by vertex index and finds the
/// facings itself.
std::array<LayerCount, 3> countLayers(MeshView mesh, const std::array<SpriteGrid, 3>& grids, unsigned threads,
                                      const MeshFinds& finds = MeshFinds());

} // namespace vds::detail
