// voxel/solid.glsl: point-in-solid against a binary voxelization, in any
// shader stage (see <vds/voxel/solid.h>).
//
// The bit grid is a texture buffer of 32-bit words (GL_R32UI), in the layout
// of voxel/grid.glsl. A point is inside iff the voxel holding it is set;
// points outside the grid are outside. Same answer as vds::voxel::BitGrid::
// contains for the same point:
//   uniform usamplerBuffer u_voxels; uniform VdsVoxelGrid u_voxelGrid;
//   if (vdsBitGridContains(u_voxels, u_voxelGrid, worldPosition)) ...
#ifndef VDS_VOXEL_SOLID_GLSL
#define VDS_VOXEL_SOLID_GLSL

#include "voxel/grid.glsl"

bool vdsBitGridTest(usamplerBuffer words, ivec3 size, ivec3 cell) {
    uint w = texelFetch(words, vdsWordIndex(size, cell)).r;
    return ((w >> uint(cell.z & 31)) & 1u) != 0u;
}

bool vdsBitGridContains(usamplerBuffer words, VdsVoxelGrid grid, vec3 world) {
    vec3 f = floor(vdsToCells(grid, world));
    if (!(f.x >= 0.0 && f.x < float(grid.size.x) && f.y >= 0.0 && f.y < float(grid.size.y) && f.z >= 0.0 &&
          f.z < float(grid.size.z)))
        return false;
    return vdsBitGridTest(words, grid.size, ivec3(f));
}

#endif
