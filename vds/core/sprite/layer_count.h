// vds internal: the layers and crossings a bake along one axis would make,
// counted without baking (chooseViewAxis, bake.cpp).
#pragma once

#include <cstdint>
#include <memory>

#include <vds/mesh.h>
#include <vds/sprite.h>

namespace vds::detail {

struct LayerCount {
    std::uint32_t most = 0;   ///< the most crossings of one column: d_S
    std::uint64_t total = 0;  ///< crossings in all
};

/// The counts of the CPU baker's sprite of `mesh` along a grid's axis at
/// the grid's texel centres, by its claim rule: equal to counting every
/// texel of every triangle's box (see layer_count.cpp), in time proportional
/// to the rows the triangles span rather than the texels they cover. One
/// counter counts several grids in turn (the three axes of
/// `chooseViewAxis`), reusing its buffers from one count to the next.
class LayerCounter {
public:
    LayerCounter();
    ~LayerCounter();
    LayerCount count(MeshView mesh, const SpriteGrid& grid, unsigned threads);

private:
    struct Buffers;
    std::unique_ptr<Buffers> buffers_;
};

} // namespace vds::detail
