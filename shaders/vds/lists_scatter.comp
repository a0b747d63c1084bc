// Fragment lists, scatter pass: every crossing of the node pool (the third
// and later of its column) moves to its place in the sprite's column order
// (CSR): the column's offset, the prefix sum of the counts, plus the slot
// the fill pass gave it. The sort pass adds the column's first two and
// orders the column.
layout(local_size_x = 256) in; // before the include: it reads gl_WorkGroupSize
#include "vds/compute.glsl"

layout(std430, binding = 0) readonly restrict buffer Nodes { uvec4 nodes[]; };
layout(std430, binding = 1) readonly restrict buffer Offsets { uint offsets[]; };
layout(std430, binding = 2) writeonly restrict buffer Pairs { uvec2 pairs[]; };
uniform uint u_nodes;
uniform uint u_base; // the band's first offset

void main() {
    for (uint i = gl_GlobalInvocationID.x; i < u_nodes; i = vdsNextIndex(i, u_nodes)) {
        uvec4 node = nodes[i];
        pairs[offsets[node.z] - u_base + node.w] = node.xy;
    }
}
