// Fragment lists, fill pass (Trapp & Doellner 2008, section 4.1, in one
// pass instead of peeling): every fragment is one crossing. An atomic add on
// the pixel's count gives the crossing its slot among the pixel's. The first
// two slots of every pixel have a fixed place (`firsts`): most columns of
// most solids hold no more, and their crossings need no pool, no global
// counter and no scatter. Later slots take a place in the node pool from an
// atomic counter; the scatter pass moves them to their column once the
// counts are prefix-summed (lists_scatter.comp). Crossings beyond the pool
// are counted but not stored; the baker then bakes again with a larger pool
// or in row bands, so no crossing is ever dropped.
#include "vds/bake_common.glsl"

layout(early_fragment_tests) in;
layout(binding = 0, offset = 0) uniform atomic_uint u_counter;
// A node: depth bits, key (triangle | entering bit), column in the band, slot in the column.
layout(std430, binding = 0) writeonly restrict buffer Nodes { uvec4 nodes[]; };
layout(std430, binding = 1) restrict buffer Counts { uint counts[]; };
// Slots 0 and 1 of column c: (depth bits, key) at 2c and 2c + 1.
layout(std430, binding = 2) writeonly restrict buffer Firsts { uvec2 firsts[]; };
uniform uint u_capacity;
uniform int u_rowBegin;
uniform uint u_width;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    uint column = uint(p.y - u_rowBegin) * u_width + uint(p.x);
    uint slot = atomicAdd(counts[column], 1u);
    uvec2 crossing = uvec2(floatBitsToUint(vdsFragmentDepth()), vdsFragmentKey());
    if (slot < 2u) {
        firsts[2u * column + slot] = crossing;
    } else {
        uint index = atomicCounterIncrement(u_counter);
        if (index < u_capacity) nodes[index] = uvec4(crossing, column, slot);
    }
}
