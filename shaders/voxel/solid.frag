// Solid voxelization by rasterization (Schwarz 2012, section 2.3): every
// fragment flips, with atomic XOR, every voxel of its column whose centre
// lies behind the fragment's triangle. A voxel ends up set iff the ray from
// its centre towards -z crosses the surface an odd number of times. The
// depth is recomputed from the triangle (fetched by gl_PrimitiveID) exactly as
// the compute voxelizer does, instead of being interpolated by the rasterizer.
#include "voxel/solid_common.glsl"

layout(std430, binding = 2) coherent buffer VdsVoxels { uint vdsVoxels[]; };
uniform VdsVoxelGrid u_grid;

void main() {
    ivec2 column = ivec2(gl_FragCoord.xy);
    vec3 a, b, c;
    vdsSnappedTriangle(u_grid, uint(gl_PrimitiveID), a, b, c);
    int first = vdsFirstVoxelBehind(vdsPlaneDepth(a, b, c, dvec2(column) + 0.5));
    if (first >= u_grid.size.z) return;
    int base = vdsWordIndex(u_grid.size, ivec3(column, 0));
    int words = vdsZWords(u_grid.size);
    for (int w = first >> 5; w < words; ++w) {
        uint mask = vdsValidBits(u_grid.size, w);
        if (w == (first >> 5)) mask &= 0xffffffffu << uint(first & 31);
        atomicXor(vdsVoxels[base + w], mask);
    }
}
