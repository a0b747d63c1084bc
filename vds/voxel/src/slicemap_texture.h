// vds::voxel internal: a slicemap pair as shaders/voxel/slicemap.glsl reads
// it, for classifyOnGpu and the effects: one RGBA32UI array texture, front layers then back layers, word
// w in channel w % 4 of layer w / 4; local slicing adds an RGBA32F texture of
// (near, far, slices per depth) per column.
#pragma once

#include <cstddef>

#include <vds/gl/objects.h>
#include <vds/voxel/slicemap.h>

namespace vds::voxel::detail {

struct SlicemapTextures {
    Texture maps, ranges; ///< ranges only for local slicing
    std::size_t bytes = 0;
};

SlicemapTextures uploadSlicemap(const Slicemap& map);

/// Nearest filtering (integer textures are incomplete without it).
void nearestFiltering(const Texture& t);

} // namespace vds::voxel::detail
