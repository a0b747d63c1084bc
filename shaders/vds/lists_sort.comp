// Per-pixel fragment lists, second half: count each pixel's nodes, or copy
// them to the pixel's slot of the output and sort them by (depth, triangle).
layout(local_size_x = 16, local_size_y = 16) in;

layout(binding = 0, r32ui) uniform readonly uimage2D u_heads;
struct VdsNode {
    float depth;
    uint key;
    uint next;
};
layout(std430, binding = 0) readonly buffer Nodes { VdsNode nodes[]; };
layout(std430, binding = 1) buffer Counts { uint counts[]; };   // COUNT: out; SORT: offsets in
layout(std430, binding = 2) buffer Sorted { uvec2 sorted[]; };  // SORT: (depth bits, key)
uniform ivec2 u_size;
uniform int u_rowBegin;

const uint VDS_NO_NODE = 0xffffffffu;
const uint VDS_ENTERING_BIT = 0x80000000u;

bool before(uvec2 a, uvec2 b) {
    float da = uintBitsToFloat(a.x), db = uintBitsToFloat(b.x);
    return da < db || (da == db && (a.y & ~VDS_ENTERING_BIT) < (b.y & ~VDS_ENTERING_BIT));
}

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy) + ivec2(0, u_rowBegin);
    if (p.x >= u_size.x || p.y >= u_size.y) return;
    uint column = uint(p.y - u_rowBegin) * uint(u_size.x) + uint(p.x);
    uint node = imageLoad(u_heads, p).r;
#ifdef VDS_COUNT
    uint n = 0u;
    for (; node != VDS_NO_NODE; node = nodes[node].next) ++n;
    counts[column] = n;
#else
    uint begin = counts[column];
    uint end = begin;
    for (; node != VDS_NO_NODE; node = nodes[node].next) {
        uvec2 item = uvec2(floatBitsToUint(nodes[node].depth), nodes[node].key);
        uint k = end++;
        while (k > begin && before(item, sorted[k - 1u])) {
            sorted[k] = sorted[k - 1u];
            --k;
        }
        sorted[k] = item;
    }
#endif
}
