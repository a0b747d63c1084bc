// vds internal: what every baker shares (validation, grid, assembly).
#pragma once

#include <cstdint>
#include <vector>

#include <vds/bake.h>

namespace vds::detail {

struct BakeSetup {
    MeshReport report;
    SpriteGrid grid;
};

/// Validates the mesh (throws `InvalidMesh` if unusable) and builds the grid.
BakeSetup prepareBake(MeshView mesh, const BakeOptions& options);

/// Assembles a sprite from per-column crossings in CSR form (already sorted);
/// fills d_S and the metadata, then checks consistency.
Sprite assembleSprite(const BakeSetup& setup, const BakeOptions& options, MeshView mesh,
                      std::vector<std::uint32_t> offsets, std::vector<float> crossings);

} // namespace vds::detail
