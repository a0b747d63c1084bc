// Certified classification on the GPU (GpuCertifiedClassifier,
// classify/certified.cpp): every point whose certified band gap is known is
// answered here (vdsContainsCertain, vds/certified.glsl), the others are
// marked 2 in the labels and appended, with their bits and index, to a list
// the host answers with the exact classifier: compaction on the GPU, so the
// host reads back only what it must answer.
//
// One program per rule (VDS_RULE_ID, 0 parity or 1 winding: a mesh whose
// bands certify the winding rules has a winding number that is an integer
// everywhere, so the generalized winding number reads as the winding
// number). Each invocation takes four consecutive points (vds/points.glsl)
// and writes their labels as one 32-bit word, byte k for point k, as
// classify.comp; one atomicAdd per invocation with unsure points reserves
// their places in the list.
#define VDS_LOCAL_SIZE 256
layout(local_size_x = VDS_LOCAL_SIZE) in;
#define VDS_CERTIFIED_OFFSETS_BINDING 3
#define VDS_CERTIFIED_BANDS_BINDING 4
#include "vds/compute.glsl"
#include "vds/points.glsl"
#include "vds/certified.glsl"

layout(std430, binding = 2) writeonly restrict buffer Labels { uint labels[]; };
// The unsure points: their count, then per point its x, y, z as bits (the
// host classifies the very floats read here) and its index in the batch.
// Holds a record for every point of the batch.
layout(std430, binding = 5) restrict buffer Unsure {
    uint unsureCount;
    uint unsurePad[3];
    uvec4 unsure[];
};
uniform VdsCertified u_certified;

void main() {
    uint quads = vdsPointQuads();
    for (uint q = gl_GlobalInvocationID.x; q < quads; q = vdsNextIndex(q, quads)) {
        vec3 p[4];
        uint valid = vdsLoadPoints(q, p);
        uint word = 0u, marked = 0u, count = 0u;
        for (uint k = 0u; k < valid; ++k) {
            int answer = vdsContainsCertain(u_certified, p[k], VDS_RULE_ID);
            if (answer == VDS_UNSURE) {
                marked |= 1u << k;
                ++count;
            }
            word |= uint(answer == VDS_UNSURE ? 2 : answer) << (8u * k);
        }
        labels[q] = word;
        if (count == 0u) continue;
        uint at = atomicAdd(unsureCount, count);
        for (uint k = 0u; k < 4u; ++k)
            if ((marked & (1u << k)) != 0u) unsure[at++] = uvec4(floatBitsToUint(p[k]), 4u * q + k);
    }
}
