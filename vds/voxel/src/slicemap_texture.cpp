// vds::voxel internal: the slicemap pair uploaded as shaders/voxel/slicemap.glsl reads it.
#include "slicemap_texture.h"

#include <cstdint>
#include <vector>

#include <GL/gl.h>
#include <GL/glext.h>

#include <vds/gl/context.h>

namespace vds::voxel::detail {

void nearestFiltering(const Texture& t) {
    glTextureParameteri(t.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(t.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
}

SlicemapTextures uploadSlicemap(const Slicemap& map) {
    SlicemapTextures out;
    const VoxelGrid& g = map.grid;
    const std::size_t columns = std::size_t(g.dims.x) * g.dims.y;
    const std::uint32_t targets = map.renderTargets;
    std::vector<std::uint32_t> texels(columns * 4 * 2 * targets, 0u);
    for (std::size_t c = 0; c < columns; ++c)
        for (std::uint32_t w = 0; w < map.words; ++w) {
            texels[((w / 4) * columns + c) * 4 + w % 4] = map.front[c * map.words + w];
            texels[((targets + w / 4) * columns + c) * 4 + w % 4] = map.back[c * map.words + w];
        }
    out.maps = Texture::create(GL_TEXTURE_2D_ARRAY);
    glTextureStorage3D(out.maps.id(), 1, GL_RGBA32UI, GLsizei(g.dims.x), GLsizei(g.dims.y), GLsizei(2 * targets));
    nearestFiltering(out.maps);
    glTextureSubImage3D(out.maps.id(), 0, 0, 0, 0, GLsizei(g.dims.x), GLsizei(g.dims.y), GLsizei(2 * targets),
                        GL_RGBA_INTEGER, GL_UNSIGNED_INT, texels.data());
    out.bytes = texels.size() * sizeof(std::uint32_t);
    if (map.slicing == Slicing::Local) {
        std::vector<float> range(columns * 4, 0.0f);
        for (std::size_t c = 0; c < columns; ++c) {
            range[4 * c] = map.nearDepth[c];
            range[4 * c + 1] = map.farDepth[c];
            range[4 * c + 2] = map.slicesPerDepth[c];
        }
        out.ranges = Texture::create(GL_TEXTURE_2D);
        glTextureStorage2D(out.ranges.id(), 1, GL_RGBA32F, GLsizei(g.dims.x), GLsizei(g.dims.y));
        nearestFiltering(out.ranges);
        glTextureSubImage2D(out.ranges.id(), 0, 0, 0, GLsizei(g.dims.x), GLsizei(g.dims.y), GL_RGBA, GL_FLOAT,
                            range.data());
        out.bytes += range.size() * sizeof(float);
    }
    checkGl("uploading a slicemap");
    return out;
}

} // namespace vds::voxel::detail
