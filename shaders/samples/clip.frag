// Sample: a fragment inside any clip sprite is discarded (Trapp & Doellner
// 2008, Figure 1). Back faces seen through the cut are drawn in the cut colour.
#include "vds/vpt.glsl"

#define VDS_MAX_CLIP 8
uniform sampler3D u_ldi[VDS_MAX_CLIP];
uniform VdsPlacement u_placement[VDS_MAX_CLIP];
uniform int u_clipCount;
uniform int u_rule;
uniform vec3 u_lightDirection;
uniform vec3 u_frontColour;
uniform vec3 u_cutColour;

in vec3 v_world;
layout(location = 0) out vec4 o_colour;

void main() {
    vec3 n = normalize(cross(dFdx(v_world), dFdy(v_world))); // before any discard: derivatives need the quad
    for (int i = 0; i < u_clipCount; ++i)
        if (vdsContains(u_ldi[i], u_placement[i], v_world, u_rule)) discard;
    float light = 0.25 + 0.75 * abs(dot(n, u_lightDirection));
    o_colour = vec4((gl_FrontFacing ? u_frontColour : u_cutColour) * light, 1.0);
}
