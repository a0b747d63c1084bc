// Batch point classification against a voxel representation, with the
// lookup includes every other stage would use (one invocation per point).
// Exactly one of VDS_CLASSIFY_SOLID, VDS_CLASSIFY_SLICEMAP,
// VDS_CLASSIFY_SLICEMAP_LOCAL is defined.
#include "voxel/solid.glsl"
#include "voxel/slicemap.glsl"

layout(local_size_x = 256) in;
layout(std430, binding = 0) readonly buffer Points { float points[]; }; // x y z, tightly packed
layout(std430, binding = 1) writeonly buffer Labels { uint labels[]; };
uniform uint u_count;

#if defined(VDS_CLASSIFY_SOLID)
uniform usamplerBuffer u_voxels;
uniform VdsVoxelGrid u_voxelGrid;
bool inside(vec3 p) { return vdsBitGridContains(u_voxels, u_voxelGrid, p); }
#elif defined(VDS_CLASSIFY_SLICEMAP)
uniform usampler2DArray u_slicemap;
uniform VdsSlicemap u_map;
bool inside(vec3 p) { return vdsSlicemapContains(u_slicemap, u_map, p); }
#else
uniform usampler2DArray u_slicemap;
uniform sampler2D u_ranges;
uniform VdsSlicemap u_map;
bool inside(vec3 p) { return vdsSlicemapLocalContains(u_slicemap, u_ranges, u_map, p); }
#endif

void main() {
    uint i = gl_GlobalInvocationID.y * gl_NumWorkGroups.x * gl_WorkGroupSize.x + gl_GlobalInvocationID.x;
    if (i >= u_count) return;
    vec3 p = vec3(points[3u * i], points[3u * i + 1u], points[3u * i + 2u]);
    labels[i] = inside(p) ? 1u : 0u;
}
