// vds::voxel: what the two casters of this module (refraction,
// <vds/voxel/refraction.h>; transmittance, <vds/voxel/transmittance.h>)
// share: a solid uploaded as the one representation their fragment shader
// reads — a slicemap pair, a sprite's LDI texture or a 3D texture of cells —
// and the uniforms that bind it: a public base, made only by them.
#pragma once

#include <cstddef>

#include <vds/gl/context.h>
#include <vds/gl/objects.h>
#include <vds/gl/sprite.h>
#include <vds/sprite.h>
#include <vds/voxel/gpu_grid.h>
#include <vds/voxel/grid.h>
#include <vds/voxel/slicemap.h>

namespace vds::voxel {

/// The base of `GpuRefractionCaster` and `GpuTransmittanceCaster`: it
/// belongs to the context current when it was made. Move-only.
class GpuCaster {
public:
    /// Throws a one-line `GlError` naming `what` unless the caster's context is current on its thread.
    void requireContext(const char* what) const { stamp_.check(what); }
    /// Bytes of the GL textures.
    std::size_t gpuBytes() const { return gpuBytes_; }

protected:
    /// Stamps the current context; `who` names the caster in errors.
    explicit GpuCaster(const char* who);

    /// Uploads a slicemap pair as `GpuSlicemap` does.
    void upload(const Slicemap& map);
    /// Uploads a sprite's LDI texture (`GpuSpriteParts::TextureOnly`).
    void upload(const Sprite& sprite);
    /// Uploads `texels` (one `format` texel a cell of `grid`, `bytes` in all)
    /// into a nearest-filtered 3D texture of `internalFormat`.
    void upload(const VoxelGrid& grid, GLenum internalFormat, GLenum format, const float* texels, std::size_t bytes,
                const char* what);

    /// Binds what was uploaded from unit 0 on and sets, in `program` (in
    /// use), the uniforms the casters' shaders declare for it: the slicemap
    /// (u_slicemap, u_ranges, u_map), the sprite (u_ldi, u_placement) or the
    /// 3D texture (`sampler`, u_grid).
    void setSlicemapUniforms(GLuint program) const;
    void setSpriteUniforms(GLuint program) const;
    void setVolumeUniforms(GLuint program, const char* sampler) const;

private:
    ContextStamp stamp_;
    GpuSlicemap slicemap_;
    GpuSprite sprite_;
    Texture volume_;
    VoxelGrid grid_;
    std::size_t gpuBytes_ = 0;
};

} // namespace vds::voxel
