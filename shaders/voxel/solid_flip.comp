// Solid voxelization in compute, first pass (Schwarz 2012, section 2.5): one
// invocation per triangle flips, in every column whose centre the triangle
// covers under the rasterizer's fill rule (see vdsClaimsEdge), only the first
// voxel behind it; the
// propagation pass (voxel/solid_propagate.comp) then turns each column into
// its prefix XOR. Shared edges and vertices are claimed once, so a column
// through them counts one crossing, as with the rasterizer.
#include "voxel/solid_common.glsl"

layout(local_size_x = 64) in;
layout(std430, binding = 2) coherent buffer VdsVoxels { uint vdsVoxels[]; };
uniform VdsVoxelGrid u_grid;
uniform uint u_triangleCount;

void main() {
    uint t = gl_GlobalInvocationID.y * gl_NumWorkGroups.x * gl_WorkGroupSize.x + gl_GlobalInvocationID.x;
    if (t >= u_triangleCount) return;
    vec3 a, b, c;
    vdsSnappedTriangle(u_grid, t, a, b, c);
    double area = vdsEdge(a, b, dvec2(c.xy));
    if (area == 0.0) return; // parallel to z: no column crosses it (no fragment either)
    vec3 p = a, q = area > 0.0 ? b : c, r = area > 0.0 ? c : b; // counter-clockwise for the coverage test
    vec2 lo = min(a.xy, min(b.xy, c.xy)), hi = max(a.xy, max(b.xy, c.xy));
    ivec2 first = max(ivec2(ceil(lo - 0.5)), ivec2(0));
    ivec2 last = min(ivec2(floor(hi - 0.5)), u_grid.size.xy - 1);
    for (int j = first.y; j <= last.y; ++j) {
        for (int i = first.x; i <= last.x; ++i) {
            dvec2 centre = dvec2(i, j) + 0.5;
            if (!vdsCovers(p, q, r, centre)) continue;
            // The depth from the vertices in their original order: the same
            // rounding as in the rasterizing voxelizer's fragment shader.
            int k = vdsFirstVoxelBehind(vdsPlaneDepth(a, b, c, centre));
            if (k < u_grid.size.z) atomicXor(vdsVoxels[vdsWordIndex(u_grid.size, ivec3(i, j, k))], 1u << uint(k & 31));
        }
    }
}
