// vds::gl internal: the auto axis's layer count in the GL bakers' own
// raster (layer_count.cpp; `chooseViewAxisOnGl` in <vds/gl/bake.h>).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>

#include <GL/gl.h>

#include <vds/bake.h>
#include <vds/detail/bake_common.h>
#include <vds/gl/context.h>
#include <vds/gl/mesh.h>

namespace vds::detail {

/// The layers and crossings of the GL bake of `mesh` along each axis at
/// `resolution` in `bounds`, counted in the bake's own raster on `gl` (made
/// current), and the axis of the fewest (`pickFewestLayers`); nullopt where
/// one axis's counts exceed a storage block. These are the GL bake's
/// counts, which differ from the CPU baker's only where the rasterizer's
/// snapping moves an edge across a texel centre.
std::optional<AxisChoice> countLayersOnGl(const GlContext& gl, MeshView mesh, const Box& bounds,
                                          std::uint32_t resolution);
/// The same with the mesh in GL already.
std::optional<AxisChoice> countLayersOnGl(const GlContext& gl, const GpuMesh& drawn, const Box& bounds,
                                          std::uint32_t resolution);
/// `countLayersOnGl` in two halves: `start` issues the three axes' draws
/// and reductions and returns without waiting (nullopt where
/// `countLayersOnGl` gives none); `finish` reads the counts back, waiting
/// for the GPU. The host is free in between (the GL bakes validate the mesh
/// there). Holds `gl` by reference; its scratch buffers hold the counts.
class PendingLayerCount {
public:
    static std::optional<PendingLayerCount> start(const GlContext& gl, const GpuMesh& drawn, const Box& bounds,
                                                  std::uint32_t resolution);
    AxisChoice finish();

private:
    PendingLayerCount(const GlContext& gl, std::uint32_t resolution) : gl_(&gl), resolution_(resolution) {}
    void read(std::size_t axis); ///< axis's counts into choice_, waiting for them
    const GlContext* gl_;
    std::uint32_t resolution_;
    GLuint results_[3] = {0, 0, 0};
    bool read_[3] = {false, false, false};
    AxisChoice choice_;
};
/// Whether the GL bakes count the auto axis on the GPU: yes but on a
/// software renderer, where the CPU's count is the faster. The environment
/// variable VDS_AXIS_COUNT (`gpu` or `cpu`) overrides it, to compare the two
/// (the tests count on llvmpipe's GPU path so).
bool countsOnGpu(const GlContext& gl);

} // namespace vds::detail
