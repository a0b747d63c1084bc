// Fragment lists, sort pass: each column's crossings sorted by depth, then
// triangle index (the order of every baker, so that layers are bit for bit
// those of depth peeling), and written as the sprite stores them: the depth
// with the sign bit set where the ray leaves the solid (encodeCrossing in
// <vds/sprite.h>). A column's first two crossings come from their fixed
// place; columns of one or two, most columns of most solids, take no loop;
// longer ones join the scattered rest and are insertion-sorted in place.
// (A local array for short columns was 4x slower on llvmpipe, which lowers
// its indexing to chains of selects; and a loop condition of the form
// `k > 0 && before(item, a[k - 1])` was compiled wrongly by Mesa 22.)
layout(local_size_x = 256) in; // before the include: it reads gl_WorkGroupSize
#include "vds/compute.glsl"

layout(std430, binding = 0) readonly restrict buffer Offsets { uint offsets[]; };
layout(std430, binding = 1) readonly restrict buffer Firsts { uvec4 firsts[]; }; // slots 0 and 1 of a column
layout(std430, binding = 2) restrict buffer Pairs { uvec2 pairs[]; };           // depth bits, key
layout(std430, binding = 3) writeonly restrict buffer Crossings { uint crossings[]; };
uniform uint u_columns;
uniform uint u_base; // the band's first offset

const uint VDS_ENTERING_BIT = 0x80000000u;

bool before(uvec2 a, uvec2 b) {
    float da = uintBitsToFloat(a.x), db = uintBitsToFloat(b.x);
    return da < db || (da == db && (a.y & ~VDS_ENTERING_BIT) < (b.y & ~VDS_ENTERING_BIT));
}

uint encoded(uvec2 item) { return (item.y & VDS_ENTERING_BIT) != 0u ? item.x : item.x ^ 0x80000000u; }

void main() {
    for (uint c = gl_GlobalInvocationID.x; c < u_columns; c = vdsNextIndex(c, u_columns)) {
        uint begin = offsets[c] - u_base;
        uint n = offsets[c + 1u] - u_base - begin;
        if (n == 0u) continue;
        uvec4 first = firsts[c];
        uvec2 a = first.xy, b = first.zw;
        if (n == 1u) {
            crossings[begin] = encoded(a);
            continue;
        }
        if (before(b, a)) {
            uvec2 t = a;
            a = b;
            b = t;
        }
        if (n == 2u) {
            crossings[begin] = encoded(a);
            crossings[begin + 1u] = encoded(b);
            continue;
        }
        pairs[begin] = a;
        pairs[begin + 1u] = b;
        for (uint i = 2u; i < n; ++i) {
            uvec2 item = pairs[begin + i];
            uint k = i;
            while (k > 0u) {
                uvec2 previous = pairs[begin + k - 1u];
                if (!before(item, previous)) break;
                pairs[begin + k] = previous;
                --k;
            }
            pairs[begin + k] = item;
        }
        for (uint i = 0u; i < n; ++i) crossings[begin + i] = encoded(pairs[begin + i]);
    }
}
