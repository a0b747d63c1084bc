// Per-pixel fragment lists in one pass: an atomic counter hands out nodes, a
// head-pointer image links them per pixel. Fragments beyond the pool are
// counted but not stored; the baker then retries with a larger pool or in
// bands, so no crossing is ever dropped.
#include "vds/bake_common.glsl"

layout(early_fragment_tests) in;
layout(binding = 0, r32ui) uniform coherent uimage2D u_heads;
layout(binding = 0, offset = 0) uniform atomic_uint u_counter;

struct VdsNode {
    float depth;
    uint key;
    uint next;
};
layout(std430, binding = 0) writeonly buffer Nodes { VdsNode nodes[]; };
uniform uint u_capacity;

void main() {
    uint index = atomicCounterIncrement(u_counter);
    if (index >= u_capacity) return;
    uint next = imageAtomicExchange(u_heads, ivec2(gl_FragCoord.xy), index);
    nodes[index] = VdsNode(vdsFragmentDepth(), vdsFragmentKey(), next);
}
