// Batch classification on the GPU: the volumetric parity test (Trapp &
// Doellner 2008, section 3.2) over a buffer of points, answers identical to
// vds::classify on the CPU (the same arithmetic, vpt.glsl).
//
// Each invocation takes four consecutive points (48 bytes, three aligned
// vec4 loads) and writes their four labels as one 32-bit word, byte k for
// point k: one byte a point, as the host's uint8 arrays hold them, written
// in whole words. The four points go through each step together, so that
// their memory reads overlap. A grid-stride loop covers any count.
//
// VDS_COLUMNS reads the sprite's compact columns (offsets + crossings,
// contiguous per column: one or two cache lines a point); otherwise the
// paper's 3D texture with texelFetch, a column's layers one texel apart.
layout(local_size_x = 256) in; // before the include: it reads gl_WorkGroupSize
#define VDS_BOUNDARY_BINDING 5 // the boundary edges, for Rule::GeneralizedWinding
#include "vds/compute.glsl"
#include "vds/vpt.glsl"

// The same points twice: as vec4 for whole groups of four, as floats for the tail.
layout(std430, binding = 0) readonly buffer Points4 { vec4 points4[]; };
layout(std430, binding = 1) readonly buffer Points { float points[]; };
layout(std430, binding = 2) writeonly restrict buffer Labels { uint labels[]; };
#ifdef VDS_COLUMNS
layout(std430, binding = 3) readonly restrict buffer Offsets { uint offsets[]; };
layout(std430, binding = 4) readonly restrict buffer Crossings { float crossings[]; };
uniform ivec2 u_size; // the sprite's width and height in texels
#else
uniform sampler3D u_ldi;
#endif
#ifdef VDS_COLUMNS
#define VDS_SIZE u_size
#else
#define VDS_SIZE textureSize(u_ldi, 0).xy
#endif
uniform VdsPlacement u_placement;
uniform VdsBoundary u_boundary; // read by VDS_RULE_GENERALIZED_WINDING only
uniform int u_rule;
uniform uint u_count;

bool vdsAnswer(int winding, int parity, ivec2 column, float r) {
    if (u_rule == VDS_RULE_GENERALIZED_WINDING) return vdsContainsGeneralizedAt(u_boundary, winding, column, r);
    return u_rule == VDS_RULE_WINDING ? winding != 0 : parity != 0;
}

// The labels of four points, as one word (0 or 1 in byte k for point k);
// `valid` points past the count are left 0.
uint vdsClassify4(vec3 p[4], uint valid) {
    vec3 T[4];
    bool inBox[4];   // a column to count along: in the box (the generalized winding rule: in front or behind too)
    bool beside[4];  // the generalized winding rule, beside the box: the boundary term alone
    ivec2 column[4];
    bool everywhere = u_rule == VDS_RULE_GENERALIZED_WINDING;
    for (uint k = 0u; k < 4u; ++k) {
        T[k] = vdsToTexture(u_placement, p[k]);
        column[k] = ivec2(0);
        bool finite = k < valid && vdsFinite(T[k]);
        inBox[k] = k < valid && (everywhere ? finite && vdsColumnAcross(T[k], VDS_SIZE, column[k])
                                            : vdsColumnOf(T[k], VDS_SIZE, column[k]));
        beside[k] = everywhere && finite && !inBox[k];
    }
    uint word = 0u;
#ifdef VDS_COLUMNS
    uint begin[4], end[4];
    for (uint k = 0u; k < 4u; ++k) {
        uint c = uint(column[k].y) * uint(u_size.x) + uint(column[k].x);
        begin[k] = inBox[k] ? offsets[c] : 0u;
        end[k] = inBox[k] ? offsets[c + 1u] : 0u;
    }
    for (uint k = 0u; k < 4u; ++k) {
        int parity = 0, winding = 0;
        for (uint i = begin[k]; i < end[k]; ++i) {
            float e = crossings[i];
            if (!(abs(e) < T[k].z)) break; // sorted: nothing further is in front
            parity ^= 1;
            winding += floatBitsToInt(e) < 0 ? -1 : 1;
        }
        if (inBox[k] ? vdsAnswer(winding, parity, column[k], T[k].z)
                     : beside[k] && vdsContainsGeneralizedBeside(u_boundary, VDS_SIZE, T[k]))
            word |= 1u << (8u * k);
    }
#else
    for (uint k = 0u; k < 4u; ++k) {
        bool inside = false;
        if (inBox[k]) {
            int parity;
            int winding = vdsColumnWinding(u_ldi, column[k], T[k].z, parity);
            inside = vdsAnswer(winding, parity, column[k], T[k].z);
        } else if (beside[k]) {
            inside = vdsContainsGeneralizedBeside(u_boundary, VDS_SIZE, T[k]);
        }
        if (inside) word |= 1u << (8u * k);
    }
#endif
    return word;
}

void main() {
    uint quads = u_count / 4u + (u_count % 4u != 0u ? 1u : 0u);
    for (uint q = gl_GlobalInvocationID.x; q < quads; q = vdsNextIndex(q, quads)) {
        vec3 p[4];
        uint first = 4u * q;
        uint valid = min(u_count - first, 4u);
        if (valid == 4u) {
            vec4 a = points4[3u * q], b = points4[3u * q + 1u], c = points4[3u * q + 2u];
            p[0] = a.xyz;
            p[1] = vec3(a.w, b.xy);
            p[2] = vec3(b.zw, c.x);
            p[3] = c.yzw;
        } else {
            for (uint k = 0u; k < 4u; ++k) {
                uint i = 3u * (first + min(k, valid - 1u));
                p[k] = vec3(points[i], points[i + 1u], points[i + 2u]);
            }
        }
        labels[q] = vdsClassify4(p, valid);
    }
}
