// The host's exact answers written into GPU labels (GpuCertifiedClassifier,
// GL buffers to GL buffers): certified.comp left each unsure point's label
// byte at 2; answer k is (index << 1) | label, and the byte becomes the label
// by an atomic XOR with 2 ^ label, so answers sharing a word do not race.
#define VDS_LOCAL_SIZE 256
layout(local_size_x = VDS_LOCAL_SIZE) in;
#include "vds/compute.glsl"

layout(std430, binding = 0) restrict buffer Labels { uint labels[]; };
layout(std430, binding = 1) readonly restrict buffer Answers { uint answers[]; };
uniform uint u_count;

void main() {
    for (uint i = gl_GlobalInvocationID.x; i < u_count; i = vdsNextIndex(i, u_count)) {
        uint index = answers[i] >> 1u;
        atomicXor(labels[index >> 2u], (2u ^ (answers[i] & 1u)) << (8u * (index & 3u)));
    }
}
