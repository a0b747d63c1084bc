// vds::gl internal: compute dispatch sizes, for every room of vds::gl and
// for vds::voxel (dispatch.cpp). A grid of more than 65535 workgroups is
// laid out as rows of 65535 (x) and numbered, in the shaders,
// `gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x`
// (vdsWorkGroupIndex in shaders/vds/compute.glsl).
#pragma once

#include <cstddef>
#include <cstdint>

#include <GL/gl.h>

namespace vds::detail {

/// Dispatches `groups` workgroups (at least one) as rows of up to 65535;
/// shaders skip numbers past the real count. Throws `OutOfMemory` past
/// 65535 rows.
void dispatchGroups(std::uint64_t groups);

/// Dispatches one invocation per item of `items` with `local` invocations
/// per workgroup (`dispatchGroups` of enough groups); nothing for no items.
void dispatchItems(std::size_t items, std::uint32_t local);

/// Workgroups for a grid-stride loop over `items` with `local` invocations
/// per group: enough to fill any GPU, at most 65535.
GLuint strideGroups(std::uint64_t items, std::uint32_t local = 256);

} // namespace vds::detail
