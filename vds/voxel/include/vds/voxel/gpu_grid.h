// vds: voxel representations uploaded for an application's own shaders —
// the GL side of the GLSL lookups shaders/voxel/solid.glsl and
// shaders/voxel/slicemap.glsl (`#include "voxel/solid.glsl"` resolves with
// no other call, see <vds/gl/shader.h>).
//
// The GL rule of <vds/gl/context.h> holds: the constructors taking a
// `GlContext` make it current for the upload and restore the caller's; the
// others upload to the context current on the calling thread (of any
// origin). An upload belongs to that context and thread: `setUniforms`
// under another, or on another thread, throws a one-line `GlError`.
#pragma once

#include <cstddef>
#include <string>

#include <vds/gl/context.h>
#include <vds/gl/objects.h>
#include <vds/voxel/grid.h>
#include <vds/voxel/slicemap.h>

namespace vds::voxel {

/// A solid voxelization (`BitGrid`) as voxel/solid.glsl reads it: its words
/// in a buffer, seen through a GL_R32UI buffer texture. In GLSL:
///   uniform usamplerBuffer u_voxels; uniform VdsVoxelGrid u_voxelGrid;
///   if (vdsBitGridContains(u_voxels, u_voxelGrid, p)) ...
/// Move-only.
class GpuBitGrid {
public:
    GpuBitGrid() = default;
    GpuBitGrid(const GlContext& gl, const BitGrid& grid);
    explicit GpuBitGrid(const BitGrid& grid);

    const Texture& texture() const { return texture_; } ///< GL_TEXTURE_BUFFER, GL_R32UI
    const Buffer& words() const { return words_; }
    const VoxelGrid& grid() const { return grid_; }
    std::size_t gpuBytes() const { return bytes_; }
    /// Binds the texture to `unit` and sets, in `program` (in use or not),
    /// the usamplerBuffer uniform `sampler` and the VdsVoxelGrid uniform
    /// `grid` (e.g. "u_voxels[1]", "u_voxelGrid[1]"). Unknown names are ignored.
    void setUniforms(GLuint program, const std::string& sampler, const std::string& grid, GLuint unit) const;

private:
    ContextStamp stamp_;
    Buffer words_;
    Texture texture_;
    VoxelGrid grid_;
    std::size_t bytes_ = 0;
};

/// A slicemap pair as voxel/slicemap.glsl reads it: one RGBA32UI 2D array
/// texture (front layers, then back), and for local slicing an RGBA32F 2D
/// texture of per-column ranges. In GLSL:
///   uniform usampler2DArray u_slicemap; uniform VdsSlicemap u_map;
///   uniform sampler2D u_ranges; // local slicing only
///   vdsSlicemapContains(u_slicemap, u_map, p) or vdsSlicemapLocalContains(u_slicemap, u_ranges, u_map, p)
/// Move-only.
class GpuSlicemap {
public:
    GpuSlicemap() = default;
    GpuSlicemap(const GlContext& gl, const Slicemap& map);
    explicit GpuSlicemap(const Slicemap& map);

    bool isLocal() const { return bool(ranges_); }
    const Texture& maps() const { return maps_; }
    const Texture& ranges() const { return ranges_; } ///< empty unless `isLocal()`
    std::size_t gpuBytes() const { return bytes_; }
    /// Binds the maps to `unit` (and, for local slicing, the ranges to
    /// `unit + 1`: samplers of different types need their own units) and
    /// sets, in `program` (in use or not), the sampler uniforms `maps` and
    /// `ranges` and the VdsSlicemap uniform `map`. Returns the first unit
    /// after those used.
    GLuint setUniforms(GLuint program, const std::string& maps, const std::string& ranges, const std::string& map,
                       GLuint unit) const;

private:
    ContextStamp stamp_;
    Texture maps_, ranges_;
    VoxelGrid grid_;
    std::int32_t backLayer_ = 0;
    std::size_t bytes_ = 0;
};

} // namespace vds::voxel
