// Batch classification on the GPU: one invocation per point, the same VPT as
// every other stage, answers identical to vds::Sprite::contains.
#include "vds/vpt.glsl"

layout(local_size_x = 256) in;
layout(std430, binding = 0) readonly buffer Points { float points[]; }; // x y z, tightly packed
layout(std430, binding = 1) writeonly buffer Labels { uint labels[]; };
uniform sampler3D u_ldi;
uniform VdsPlacement u_placement;
uniform int u_rule;
uniform uint u_count;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= u_count) return;
    vec3 p = vec3(points[3u * i], points[3u * i + 1u], points[3u * i + 2u]);
    labels[i] = vdsContains(u_ldi, u_placement, p, u_rule) ? 1u : 0u;
}
