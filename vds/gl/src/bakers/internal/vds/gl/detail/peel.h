// vds::gl internal: the depth-peeling bake (peel.cpp), the paper's method.
#pragma once

#include <cstdint>
#include <vector>

#include <vds/bake.h>
#include <vds/gl/context.h>
#include <vds/gl/detail/phase_clock.h>
#include <vds/gl/mesh.h>

namespace vds::detail {

/// The depth-peeling bake behind bakeOnGl(): fills the CSR layers of `grid`
/// on `gl` (current), timing its phases on `clock`. `uploaded`: the mesh
/// already in GL (the axis count's), or null to upload it.
void bakePeel(const GlContext& gl, MeshView mesh, const SpriteGrid& grid, const BakeOptions& options,
              GlPhaseClock& clock, std::vector<std::uint32_t>& offsets, std::vector<float>& crossings,
              const GpuMesh* uploaded = nullptr);

} // namespace vds::detail
