// vds::gl: a signed distance grid as a 3D texture, for `vdsDistance` in
// shaders/vds/vpt.glsl (its error bound is stated there).
#pragma once

#include <vds/gl/objects.h>
#include <vds/grid.h>

namespace vds {

/// Uploads `cells` (grid.cellCount() floats in `Grid::index` order, as
/// `SignedDistance::grid` fills them) into a new GL_TEXTURE_3D of
/// grid.dims texels (texel (i, j, k) = cell (i, j, k): x along i), R32F,
/// linear filtering, clamped to the edge; shaders read it with
/// `vdsDistance(field, grid.box.lo, grid.box.hi, world)`. Needs a current
/// context; the texture belongs to it. Throws like `checkGrid`, and
/// `OutOfMemory` for more texels than GL_MAX_3D_TEXTURE_SIZE allows.
Texture uploadDistanceTexture(const Grid& grid, const float* cells);

} // namespace vds
