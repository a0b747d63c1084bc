// vds/vpt.glsl: the volumetric parity test in any shader stage.
//
// Trapp & Doellner 2008, section 3.2 and Figure 5. A sprite's layered depth
// image is a float 3D texture (R32F, nearest filtering, border value 1,
// clamp to border): texel (i, j, k) is the k-th crossing of column (i, j),
// sorted front to back, padded with 1.0. A crossing's sign bit is set where
// the ray leaves the solid (see <vds/sprite.h>).
//
// Usable on its own (no includes, guarded), with GLSL 4.30 or later:
//   uniform sampler3D u_ldi;            // GpuSprite::bind / setUniforms
//   uniform VdsPlacement u_placement;   // P_S and M_S
//   if (vdsContains(u_ldi, u_placement, worldPosition, VDS_RULE_PARITY)) ...
// The arithmetic is written out in the same order as the C++ classifier and
// marked precise, so the two give identical answers for identical inputs.
#ifndef VDS_VPT_GLSL
#define VDS_VPT_GLSL

#define VDS_RULE_PARITY 0
#define VDS_RULE_WINDING 1

// P_S (world position of the LDI texture-space origin) and M_S (world ->
// LDI texture space, linear part).
struct VdsPlacement {
    mat3 matrix;
    vec3 position;
};

// World point -> LDI texture space: T = M_S * (P - P_S).
vec3 vdsToTexture(VdsPlacement placement, vec3 world) {
    precise vec3 d = world - placement.position;
    mat3 m = placement.matrix;
    precise float s = (m[0][0] * d.x + m[1][0] * d.y) + m[2][0] * d.z;
    precise float t = (m[0][1] * d.x + m[1][1] * d.y) + m[2][1] * d.z;
    precise float r = (m[0][2] * d.x + m[1][2] * d.y) + m[2][2] * d.z;
    return vec3(s, t, r);
}

// The column (texel) of an LDI of size.x by size.y texels that texture-space
// point T falls in; false when T lies outside the box [0,1]^3.
bool vdsColumnOf(vec3 T, ivec2 size, out ivec2 column) {
    column = ivec2(0);
    if (!(T.z >= 0.0 && T.z <= 1.0)) return false;
    precise float fs = floor(T.x * float(size.x));
    precise float ft = floor(T.y * float(size.y));
    if (!(fs >= 0.0 && fs < float(size.x) && ft >= 0.0 && ft < float(size.y))) return false;
    column = ivec2(fs, ft);
    return true;
}

// Winding number of the crossings strictly in front of texture-space point T
// (entering +1, leaving -1); `parity` receives their count modulo 2. Points
// outside [0,1]^3 have no crossings in front.
int vdsWinding(sampler3D ldi, vec3 T, out int parity) {
    parity = 0;
    ivec3 size = textureSize(ldi, 0);
    ivec2 column;
    if (!vdsColumnOf(T, size.xy, column)) return 0;
    int winding = 0;
    for (int k = 0; k < size.z; ++k) {
        float e = texelFetch(ldi, ivec3(column, k), 0).r;
        if (!(abs(e) < T.z)) break; // sorted: nothing further is in front (padding is 1.0)
        parity ^= 1;
        winding += floatBitsToInt(e) < 0 ? -1 : 1;
    }
    return winding;
}

// Inside test of a world point against one sprite.
bool vdsContains(sampler3D ldi, VdsPlacement placement, vec3 world, int rule) {
    int parity;
    int winding = vdsWinding(ldi, vdsToTexture(placement, world), parity);
    return rule == VDS_RULE_WINDING ? winding != 0 : parity != 0;
}

// The paper's Figure 5 form: filtered lookups with texture(), relying on the
// texture's nearest filtering and border value 1 outside [0,1]^2 (every
// stored depth, and the border, that lies behind T.r flips the parity; a
// closed solid has an even number of crossings per column, so counting those
// behind equals counting those in front). Kept for reference; vdsContains is
// exact to the texel and also offers the winding rule.
bool vdsParityTestPaper(sampler3D ldi, vec3 T, int depth, bool initParity) {
    bool parity = initParity;
    float offset = 1.0 / float(depth);
    for (int i = 0; i < depth; ++i) {
        if (T.z < abs(texture(ldi, vec3(T.xy, offset * (float(i) + 0.5))).r)) parity = !parity;
    }
    return parity;
}

#endif
