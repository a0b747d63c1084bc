// A shader of the outside project's own, embedded with vds_embed_shaders,
// that includes the library's public VPT include.
#include "vds/vpt.glsl"
uniform sampler3D u_ldi;
uniform VdsPlacement u_placement;
in vec3 v_world;
out vec4 consumer_tint;
void main() {
    consumer_tint = vdsContains(u_ldi, u_placement, v_world, VDS_RULE_PARITY) ? vec4(1, 0, 0, 1) : vec4(0);
}
