// The counts of count_layers.frag reduced to the most in a column (d_S) and
// their sum (the crossings): a grid-stride loop per invocation, then one
// atomic of each per invocation. Each axis writes its own pair (u_axis), so
// that the three are read back at once.
layout(local_size_x = 256) in; // before the include: it reads gl_WorkGroupSize
#include "vds/compute.glsl"

layout(std430, binding = 0) readonly restrict buffer Counts { uint counts[]; };
layout(std430, binding = 1) restrict buffer Result { uint result[6]; }; // (most, total) per axis
uniform uint u_columns;
uniform uint u_axis;

void main() {
    uint best = 0u, sum = 0u;
    for (uint c = gl_GlobalInvocationID.x; c < u_columns; c = vdsNextIndex(c, u_columns)) {
        uint n = counts[c];
        best = max(best, n);
        sum += n;
    }
    if (best != 0u) atomicMax(result[2u * u_axis], best);
    if (sum != 0u) atomicAdd(result[2u * u_axis + 1u], sum);
}
