// vds_bench's plain kernels (bench/vds/plain_kernels.h): the plainest compute
// kernel over the very buffers vds's classifier reads, its yardstick.
//
// One invocation, four points (point 4q + k, k < u_count - 4q), one label
// word; VDS_PLAIN_GWN adds the boundary term summed over every edge. The
// parity kernel's forms: VDS_PLAIN_TEXEL reads the columns through buffer
// textures (the texture cache) instead of storage buffers; VDS_PLAIN_ONE
// takes one point an invocation and writes a 32-bit label, as a CUDA kernel
// of one thread a point would.
layout(local_size_x = 256) in;
#ifdef VDS_PLAIN_GWN
#define VDS_BOUNDARY_BINDING 5
#endif
#include "vds/vpt.glsl"
layout(std430, binding = 0) readonly buffer Points { float points[]; };
layout(std430, binding = 2) writeonly buffer Labels { uint labels[]; };
#ifdef VDS_PLAIN_TEXEL
layout(binding = 0) uniform usamplerBuffer u_offsets;
layout(binding = 1) uniform samplerBuffer u_crossings;
#define VDS_OFFSET(i) texelFetch(u_offsets, int(i)).x
#define VDS_CROSSING(i) texelFetch(u_crossings, int(i)).x
#else
layout(std430, binding = 3) readonly buffer Offsets { uint offsets[]; };
layout(std430, binding = 4) readonly buffer Crossings { float crossings[]; };
#define VDS_OFFSET(i) offsets[i]
#define VDS_CROSSING(i) crossings[i]
#endif
uniform ivec2 u_size;
uniform VdsPlacement u_placement;
uniform uint u_count;
#ifdef VDS_PLAIN_GWN
uniform VdsBoundary u_boundary;
#endif

bool inside(uint i) {
    vec3 T = vdsToTexture(u_placement, vec3(points[3u * i], points[3u * i + 1u], points[3u * i + 2u]));
    ivec2 column;
#ifdef VDS_PLAIN_GWN
    if (!vdsFinite(T)) return false;
    if (!vdsColumnAcross(T, u_size, column))
        return vdsEdgePairs(0, u_boundary.edgeCount, vdsBesidePoint(u_boundary, u_size, T)) / 12.566370614359172 > 0.5;
#else
    if (!vdsColumnOf(T, u_size, column)) return false;
#endif
    uint c = uint(column.y) * uint(u_size.x) + uint(column.x);
    int winding = 0, parity = 0;
    for (uint k = VDS_OFFSET(c), end = VDS_OFFSET(c + 1u); k < end; ++k) {
        float e = VDS_CROSSING(k);
        if (!(abs(e) < T.z)) break;
        parity ^= 1;
        winding += floatBitsToInt(e) < 0 ? -1 : 1;
    }
#ifdef VDS_PLAIN_GWN
    vec3 q = vdsColumnPoint(u_boundary, column, T.z);
    return float(winding) + vdsEdgePairs(0, u_boundary.edgeCount, q) / 12.566370614359172 > 0.5;
#else
    return parity != 0;
#endif
}

void main() {
    uint q = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * 256u + gl_LocalInvocationID.x;
#ifdef VDS_PLAIN_ONE
    if (q < u_count) labels[q] = inside(q) ? 1u : 0u;
#else
    if (q >= (u_count + 3u) / 4u) return;
    uint word = 0u;
    for (uint k = 0u; k < 4u; ++k)
        if (4u * q + k < u_count && inside(4u * q + k)) word |= 1u << (8u * k);
    labels[q] = word;
#endif
}
