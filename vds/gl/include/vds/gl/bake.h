// vds: the GL bakers (fragment lists, depth peeling; <vds/bake.h>) on a
// context the caller passes, into a host sprite (`bakeOnGl`) or straight
// into a GpuSprite (`bakeToGpu`), for programs that bake at run time and
// only use the sprite on the GPU (renderers, GPU classification).
//
// With the fragment-list method nothing crosses the bus but the mesh: the
// columns built on the GPU (see <vds/bake.h>) become the sprite's columns
// and fill its 3D texture in a compute pass. The other methods bake on the
// host and upload, as `GpuSprite(bake(...))` would.
#pragma once

#include <cstdint>
#include <string>

#include <vds/bake.h>
#include <vds/gl/context.h>
#include <vds/gl/sprite.h>

namespace vds {

/// The GL bakers' own knobs, beside the `BakeOptions` every baker takes
/// (the CPU baker has no use for them).
struct GlBakeOptions {
    /// Fragment lists: limit of the node pool, which holds the crossings past
    /// the first two of each column; 0 = as many as one GL buffer may hold.
    /// When a pass needs more, the image is baked in row bands.
    std::uint64_t maxListNodes = 0;
};

/// The baker `BakeMethod::Auto` means on `gl`: Lists on a GPU, Cpu on a
/// software renderer (llvmpipe, softpipe, SwiftShader), where a one-shot
/// CPU bake is faster. `why`, if given, gets one line saying which and why.
BakeMethod chooseBakeMethod(const GlContext& gl, std::string* why = nullptr);

/// `chooseViewAxis` counted in the GL bakers' own raster on `gl` (made
/// current for the call): the mesh drawn along each axis, each fragment
/// counted in its column, the counts reduced on the GPU. Its layers and
/// crossings are those of the GL bakers' sprites, which differ from the CPU
/// baker's only where the rasterizer's snapping moves an edge across a
/// texel centre. `bakeOnGl` and `bakeToGpu` with no axis set count so on a
/// GPU (a few milliseconds; the bakes issue the count before validating and
/// validate on the host while the GPU draws), and on the CPU
/// (`chooseViewAxis`) on a software renderer, where that is faster; the
/// environment variable VDS_AXIS_COUNT=gpu or =cpu chooses either, to
/// compare them. Validates the mesh and throws like
/// `chooseViewAxis`; falls back to it where one axis's counts exceed GL's
/// largest storage block.
AxisChoice chooseViewAxisOnGl(const GlContext& gl, MeshView mesh, std::uint32_t resolution = 1024);

/// Bakes `mesh` with `options.method` on `gl` (Auto: `chooseBakeMethod(gl)`), which is made current for the
/// call (the caller's current context is current again on return); the
/// Cpu method runs `bakeCpu`. Validates the mesh and throws like `bakeCpu`;
/// `GlError`/`OutOfMemory` from GL.
Sprite bakeOnGl(const GlContext& gl, MeshView mesh, const BakeOptions& options, const GlBakeOptions& glOptions = {});

/// A sprite baked into GL, with what a host `Sprite` would say about it.
struct GpuBake {
    GpuSprite sprite;                  ///< placed as `grid` says
    SpriteGrid grid;                   ///< the texel grid and placement (P_S, M_S) of the bake
    std::uint32_t depthComplexity = 0; ///< d_S: the most crossings in any column
    std::uint64_t crossings = 0;       ///< crossings in all columns
    SolidStatus status = SolidStatus::Closed;
    std::string validation;            ///< `MeshReport::summary()` of the mesh
};

/// Bakes `mesh` into a GpuSprite on `gl`, which is made current for the call
/// (the caller's current context is current again on return); the sprite
/// belongs to `gl`. Validates the mesh and throws like `bake()`; also throws
/// `InvalidArgument` when the texture is asked for and d_S or the size
/// exceed GL_MAX_3D_TEXTURE_SIZE. Equal, texel for texel and offset for
/// offset, to `GpuSprite(bake(mesh, options), parts)`. Fills
/// `options.timings` if set; `BakePhase::TextureFill` is the compute pass that
/// fills the 3D texture (for Peel and Cpu: the upload).
GpuBake bakeToGpu(const GlContext& gl, MeshView mesh, const BakeOptions& options,
                  GpuSpriteParts parts = GpuSpriteParts::Both, const GlBakeOptions& glOptions = {});

} // namespace vds
