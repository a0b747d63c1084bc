// Exclusive prefix sum of 32-bit counts, work-efficient and multi-level
// (Blelloch 1990, "Prefix sums and their applications", section 1.3: scan in
// chunks, scan the chunk totals, add them back). An invocation owns a chunk
// of VDS_SCAN_CHUNK consecutive values (16 uvec4) and walks it serially, so
// that no pass needs shared memory or barriers (cheap on GPUs, and on
// llvmpipe, where a barrier switches between coroutines):
//  - VDS_SCAN_REDUCE writes each chunk's total to `sums`, the next level up
//    (and with VDS_SCAN_MAX keeps the largest value, d_S, in `maxCount`);
//  - the host reduces level by level until one chunk is left, then the
//    default pass, top level first, rewrites each chunk as its exclusive
//    prefix sums starting at the chunk's scanned total from the level above
//    (u_base for the top level: a row band's offsets start after the
//    crossings of the bands above it).
layout(local_size_x = 256) in; // before the include: it reads gl_WorkGroupSize
#include "vds/compute.glsl"

const uint VDS_SCAN_CHUNK = 16u; // uvec4 per chunk: 64 values

layout(std430, binding = 0) restrict buffer Data { uvec4 data[]; };
layout(std430, binding = 1) restrict buffer Sums { uint sums[]; };
layout(std430, binding = 2) restrict buffer Stats { uint maxCount; };
uniform uint u_chunks; // chunks at this level
uniform uint u_base;
uniform bool u_top;    // the top level: one chunk, starting at u_base

#ifdef VDS_SCAN_REDUCE

#ifdef VDS_SCAN_MAX
shared uint s_max;
#endif

void main() {
    uint chunk = vdsWorkGroupIndex() * gl_WorkGroupSize.x + gl_LocalInvocationID.x;
#ifdef VDS_SCAN_MAX
    if (gl_LocalInvocationID.x == 0u) s_max = 0u;
    memoryBarrierShared();
    barrier();
    uvec4 most = uvec4(0u);
#endif
    if (chunk < u_chunks) {
        uvec4 total = uvec4(0u);
        for (uint i = 0u; i < VDS_SCAN_CHUNK; ++i) {
            uvec4 v = data[chunk * VDS_SCAN_CHUNK + i];
            total += v;
#ifdef VDS_SCAN_MAX
            most = max(most, v);
#endif
        }
        sums[chunk] = total.x + total.y + total.z + total.w;
    }
#ifdef VDS_SCAN_MAX
    atomicMax(s_max, max(max(most.x, most.y), max(most.z, most.w)));
    memoryBarrierShared();
    barrier();
    if (gl_LocalInvocationID.x == 0u && s_max > 0u) atomicMax(maxCount, s_max);
#endif
}

#else

void main() {
    uint chunk = vdsWorkGroupIndex() * gl_WorkGroupSize.x + gl_LocalInvocationID.x;
    if (chunk >= u_chunks) return;
    uint first = u_top ? u_base : sums[chunk];
    for (uint i = 0u; i < VDS_SCAN_CHUNK; ++i) {
        uvec4 v = data[chunk * VDS_SCAN_CHUNK + i];
        data[chunk * VDS_SCAN_CHUNK + i] = uvec4(first, first + v.x, first + v.x + v.y, first + v.x + v.y + v.z);
        first += v.x + v.y + v.z + v.w;
    }
}

#endif
