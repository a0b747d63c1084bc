// vds::voxel: the uploads and bindings both casters share (<vds/voxel/caster.h>).
#include <vds/voxel/caster.h>

#include <GL/gl.h>
#include <GL/glext.h>

#include "raster.h"
#include "slicemap_texture.h"

namespace vds::voxel {

GpuCaster::GpuCaster(const char* who) : stamp_(ContextStamp::current(who)) {}

void GpuCaster::upload(const Slicemap& map) {
    slicemap_ = GpuSlicemap(map);
    gpuBytes_ = slicemap_.gpuBytes();
}

void GpuCaster::upload(const Sprite& sprite) {
    sprite_ = GpuSprite(sprite, GpuSpriteParts::TextureOnly);
    gpuBytes_ = sprite.denseBytes();
}

void GpuCaster::upload(const VoxelGrid& grid, GLenum internalFormat, GLenum format, const float* texels,
                       std::size_t bytes, const char* what) {
    grid_ = grid;
    volume_ = Texture::create(GL_TEXTURE_3D);
    glTextureStorage3D(volume_.id(), 1, internalFormat, GLsizei(grid.dims.x), GLsizei(grid.dims.y),
                       GLsizei(grid.dims.z));
    detail::nearestFiltering(volume_);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTextureSubImage3D(volume_.id(), 0, 0, 0, 0, GLsizei(grid.dims.x), GLsizei(grid.dims.y), GLsizei(grid.dims.z),
                        format, GL_FLOAT, texels);
    gpuBytes_ = bytes;
    checkGl(what);
}

void GpuCaster::setSlicemapUniforms(GLuint program) const {
    slicemap_.setUniforms(program, "u_slicemap", "u_ranges", "u_map", 0);
}

void GpuCaster::setSpriteUniforms(GLuint program) const { sprite_.setUniforms(program, "u_ldi", "u_placement", 0); }

void GpuCaster::setVolumeUniforms(GLuint program, const char* sampler) const {
    glBindTextureUnit(0, volume_.id());
    glUniform1i(glGetUniformLocation(program, sampler), 0);
    detail::setGridUniform(program, "u_grid", grid_);
}

} // namespace vds::voxel
