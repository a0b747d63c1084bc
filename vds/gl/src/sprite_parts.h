// vds internal: building GpuSprites from parts made on the GPU (gpu_bake.cpp).
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include <vds/gl/sprite.h>

namespace vds::detail {

/// An R32F 3D texture for an LDI of `size` texels: nearest filtering, clamp
/// to border, border 1.0, contents undefined. Throws `InvalidArgument` past
/// GL_MAX_3D_TEXTURE_SIZE, `OutOfMemory` if GL cannot hold it.
Texture makeSpriteTexture(glm::uvec3 size);

struct GpuSpriteAccess {
    /// A sprite from its parts (either may be empty), placed as `grid` says,
    /// with the baked mesh's boundary edges (as `Sprite::boundaryEdges`).
    static GpuSprite make(Texture texture, Buffer offsets, Buffer crossings, std::uint64_t crossingCount,
                          glm::uvec3 size, const SpriteGrid& grid, SolidStatus status,
                          const std::vector<glm::vec3>& boundaryEdges);
};

} // namespace vds::detail
