// The auto axis's count in the bake's own raster: every fragment is one
// crossing of its column (as in lists.frag), counted and nothing else.
layout(early_fragment_tests) in;
layout(std430, binding = 0) restrict buffer Counts { uint counts[]; };
uniform uint u_width;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    atomicAdd(counts[uint(p.y) * u_width + uint(p.x)], 1u);
}
