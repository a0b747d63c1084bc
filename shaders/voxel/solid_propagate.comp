// Solid voxelization in compute, propagation pass (Schwarz 2012, section
// 2.5): each column becomes the prefix XOR of its flips, front to back, so a
// voxel is set iff an odd number of flips lie at or in front of it. One
// invocation per column; within a word the prefix XOR is five shifts.
#include "voxel/grid.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, binding = 2) coherent buffer VdsVoxels { uint vdsVoxels[]; };
uniform ivec3 u_size;

void main() {
    ivec2 column = ivec2(gl_GlobalInvocationID.xy);
    if (column.x >= u_size.x || column.y >= u_size.y) return;
    int base = vdsWordIndex(u_size, ivec3(column, 0));
    int words = vdsZWords(u_size);
    uint carry = 0u;
    for (int w = 0; w < words; ++w) {
        uint x = vdsVoxels[base + w];
        x ^= x << 1u;
        x ^= x << 2u;
        x ^= x << 4u;
        x ^= x << 8u;
        x ^= x << 16u;
        x ^= carry;
        carry = (x & 0x80000000u) != 0u ? 0xffffffffu : 0u;
        int valid = u_size.z - 32 * w;
        vdsVoxels[base + w] = valid >= 32 ? x : (x & ((1u << uint(valid)) - 1u));
    }
}
