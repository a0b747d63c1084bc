#include <vds/voxel/gpu_grid.h>

#include <GL/glext.h>

#include <vds/error.h>

#include <vds/gl/detail/buffers.h>

#include "raster.h"
#include "slicemap_texture.h"

namespace vds::voxel {

namespace {
void setGrid(GLuint program, const std::string& name, const VoxelGrid& grid) {
    detail::setGridUniform(program, name, grid); // glProgramUniform: no program need be in use
}
} // namespace

GpuBitGrid::GpuBitGrid(const GlContext& gl, const BitGrid& grid) : GpuBitGrid((CurrentContext(gl), grid)) {}

GpuBitGrid::GpuBitGrid(const BitGrid& grid)
    : stamp_(ContextStamp::current("GpuBitGrid")), grid_(grid.grid),
      bytes_(grid.words.size() * sizeof(std::uint32_t)) {
    vds::detail::requireStorageSize(bytes_, GlLimits::query().maxStorageBlockBytes, "the voxel words");
    GLint maxTexels = 0; // the usamplerBuffer's limit, one word a texel
    glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &maxTexels);
    if (grid.words.size() > std::size_t(maxTexels))
        throw OutOfMemory("the voxel grid exceeds GL's texture buffer size; lower the resolution");
    words_ = Buffer::create();
    glNamedBufferStorage(words_.id(), GLsizeiptr(std::max<std::size_t>(bytes_, 4)), grid.words.empty() ? nullptr : grid.words.data(), 0);
    checkGl("uploading the voxel words");
    texture_ = Texture::create(GL_TEXTURE_BUFFER);
    glTextureBuffer(texture_.id(), GL_R32UI, words_.id());
    checkGl("making the voxel buffer texture");
}

void GpuBitGrid::setUniforms(GLuint program, const std::string& sampler, const std::string& grid, GLuint unit) const {
    stamp_.check("GpuBitGrid::setUniforms");
    glBindTextureUnit(unit, texture_.id());
    glProgramUniform1i(program, glGetUniformLocation(program, sampler.c_str()), GLint(unit));
    setGrid(program, grid, grid_);
    checkGl("GpuBitGrid::setUniforms");
}

GpuSlicemap::GpuSlicemap(const GlContext& gl, const Slicemap& map) : GpuSlicemap((CurrentContext(gl), map)) {}

GpuSlicemap::GpuSlicemap(const Slicemap& map)
    : stamp_(ContextStamp::current("GpuSlicemap")), grid_(map.grid),
      backLayer_(std::int32_t(map.renderTargets)) {
    detail::SlicemapTextures t = detail::uploadSlicemap(map);
    maps_ = std::move(t.maps);
    ranges_ = std::move(t.ranges);
    bytes_ = t.bytes;
}

GLuint GpuSlicemap::setUniforms(GLuint program, const std::string& maps, const std::string& ranges,
                                const std::string& map, GLuint unit) const {
    stamp_.check("GpuSlicemap::setUniforms");
    glBindTextureUnit(unit, maps_.id());
    glProgramUniform1i(program, glGetUniformLocation(program, maps.c_str()), GLint(unit));
    GLuint next = unit + 1;
    if (ranges_) {
        glBindTextureUnit(next, ranges_.id());
        glProgramUniform1i(program, glGetUniformLocation(program, ranges.c_str()), GLint(next));
        ++next;
    }
    setGrid(program, map + ".grid", grid_);
    glProgramUniform1i(program, glGetUniformLocation(program, (map + ".backLayer").c_str()), backLayer_);
    checkGl("GpuSlicemap::setUniforms");
    return next;
}

} // namespace vds::voxel
