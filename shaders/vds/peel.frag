// Depth peeling (Trapp & Doellner 2008, section 4.1; Everitt 2001): keep only
// crossings strictly behind the previous layer's (depth, triangle) pair; the
// depth test then keeps the nearest of them, the lowest triangle on ties.
#include "vds/bake_common.glsl"

layout(binding = 0) uniform sampler2D u_previousDepth; // cleared to 2.0 where empty
layout(binding = 1) uniform usampler2D u_previousKey;
uniform bool u_firstLayer;

layout(location = 0) out float o_depth;
layout(location = 1) out uint o_key;

void main() {
    float z = vdsFragmentDepth();
    uint key = vdsFragmentKey();
    if (!u_firstLayer) {
        ivec2 p = ivec2(gl_FragCoord.xy);
        float pz = texelFetch(u_previousDepth, p, 0).r;
        uint pk = texelFetch(u_previousKey, p, 0).r & ~VDS_ENTERING_BIT;
        uint prim = key & ~VDS_ENTERING_BIT;
        if (z < pz || (z == pz && prim <= pk)) discard;
    }
    gl_FragDepth = gl_FragCoord.z;
    o_depth = z;
    o_key = key;
}
