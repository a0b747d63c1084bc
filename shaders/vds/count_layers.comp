// The counts of count_layers.frag reduced to the most in a column (d_S) and
// their sum (the crossings): a grid-stride loop per invocation, then one
// atomic of each per invocation.
layout(local_size_x = 256) in; // before the include: it reads gl_WorkGroupSize
#include "vds/compute.glsl"

layout(std430, binding = 0) readonly restrict buffer Counts { uint counts[]; };
layout(std430, binding = 1) restrict buffer Result { uint most; uint total; };
uniform uint u_columns;

void main() {
    uint best = 0u, sum = 0u;
    for (uint c = gl_GlobalInvocationID.x; c < u_columns; c = vdsNextIndex(c, u_columns)) {
        uint n = counts[c];
        best = max(best, n);
        sum += n;
    }
    if (best != 0u) atomicMax(most, best);
    if (sum != 0u) atomicAdd(total, sum);
}
