// vds::gl internal: the sprite's 3D texture as every maker of a GpuSprite
// allocates it (sprite.cpp).
#pragma once

#include <glm/vec3.hpp>

#include <vds/gl/objects.h>

namespace vds::detail {

/// An R32F 3D texture for an LDI of `size` texels: nearest filtering, clamp
/// to border, border 1.0, contents undefined. Throws `InvalidArgument` past
/// GL_MAX_3D_TEXTURE_SIZE, `OutOfMemory` if GL cannot hold it.
Texture makeSpriteTexture(glm::uvec3 size);

} // namespace vds::detail
