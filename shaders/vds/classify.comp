// Batch classification on the GPU: the volumetric parity test (Trapp &
// Doellner 2008, section 3.2) over a buffer of points, answers identical to
// vds::classify on the CPU (the same arithmetic, vpt.glsl).
//
// One program per rule and form, chosen at compile time (GpuClassifier
// defines them): no code is kept alive by a uniform.
//   VDS_RULE_ID   0 parity, 1 winding, 2 generalized winding (vpt.glsl's
//                 VDS_RULE_*); the host defines VDS_BOUNDARY_TERM with 2,
//                 which alone carries the boundary term's code.
//   VDS_COLUMNS   reads the sprite's compact columns (offsets + crossings,
//                 contiguous per column: one or two cache lines a point);
//                 otherwise the paper's 3D texture with texelFetch, a
//                 column's layers one texel apart.
//
// Each invocation takes VDS_POINTS_PER_INVOCATION consecutive points (48
// bytes, three aligned vec4 loads) and writes their labels as one 32-bit
// word, byte k for point k: one byte a point, as the host's uint8 arrays hold
// them, written in whole words. The points go through each step together, so
// that their memory reads overlap. (Measured on an H200 in the parity
// program against this form: one point an invocation with the labels
// gathered in shared memory, and the four column walks in lockstep, were
// each slower; docs/benchmarks.md.)
//
// Parity and winding: a grid-stride loop per invocation covers any count.
// Generalized winding: the loop runs per workgroup (every invocation takes
// each step, live or not), because the boundary term is summed by the whole
// workgroup together (boundary_tiles.glsl: edges staged through shared
// memory, far nodes taken by a vote of the workgroup).
#define VDS_LOCAL_SIZE 256
layout(local_size_x = VDS_LOCAL_SIZE) in; // before the include: it reads gl_WorkGroupSize
#ifdef VDS_BOUNDARY_TERM
#define VDS_BOUNDARY_BINDING 5 // the boundary edges
#endif
#include "vds/compute.glsl"
#include "vds/vpt.glsl"

// Four labels of one byte fill the 32-bit word an invocation writes, and
// three vec4 loads hold the four points exactly: the unit of work.
#define VDS_POINTS_PER_INVOCATION 4
#ifdef VDS_BOUNDARY_TERM
#define VDS_TERM_POINTS VDS_POINTS_PER_INVOCATION
#include "vds/boundary_tiles.glsl"
#endif

// The points at bindings 0 and 1, four at a time, and u_count.
#include "vds/points.glsl"
layout(std430, binding = 2) writeonly restrict buffer Labels { uint labels[]; };
#ifdef VDS_COLUMNS
layout(std430, binding = 3) readonly restrict buffer Offsets { uint offsets[]; };
layout(std430, binding = 4) readonly restrict buffer Crossings { float crossings[]; };
uniform ivec2 u_size; // the sprite's width and height in texels
#define VDS_SIZE u_size
#include "vds/columns.glsl"
#else
uniform sampler3D u_ldi;
#define VDS_SIZE textureSize(u_ldi, 0).xy
#endif
uniform VdsPlacement u_placement;
#ifdef VDS_BOUNDARY_TERM
uniform VdsBoundary u_boundary;
#endif

#define VDS_N VDS_POINTS_PER_INVOCATION

// The column's signed count and parity in front of texture depth r.
int vdsCount(ivec2 column, bool inBox, float r, out int parity) {
    parity = 0;
    if (!inBox) return 0;
#ifdef VDS_COLUMNS
    uint c = uint(column.y) * uint(u_size.x) + uint(column.x);
    uint e = offsets[c];
    int winding = 0;
    vdsWalkColumn(e, offsets[c + 1u], r, parity, winding);
    return winding;
#else
    return vdsColumnWinding(u_ldi, column, r, parity);
#endif
}

#if defined(VDS_COLUMNS) && defined(VDS_BOUNDARY_TERM)
// The generalized winding number's program: each point's signed count and
// parity of the crossings in front of its texture depth, the points'
// columns walked in lockstep (every step loads the next crossing of each
// column still in walk). As measured fastest on an H200 (lockstep walks,
// a vote a node, each node's edges summed on their own): merging the ranges
// of adjacent nodes not taken into fuller tile passes cost 0.62 of the rate
// on the teapot, suzanne and the bunny alike (a bisection on the H200:
// docs/benchmarks.md); in the parity and winding programs the lockstep
// walks were the slower on random points.
void vdsCountColumns(ivec2 column[VDS_N], bool inBox[VDS_N], vec3 T[VDS_N], out int winding[VDS_N],
                     out int parity[VDS_N]) {
    uint next[VDS_N], end[VDS_N];
    for (uint k = 0u; k < uint(VDS_N); ++k) {
        uint c = uint(column[k].y) * uint(u_size.x) + uint(column[k].x);
        next[k] = inBox[k] ? offsets[c] : 0u;
        end[k] = inBox[k] ? offsets[c + 1u] : 0u;
        winding[k] = 0;
        parity[k] = 0;
    }
    bool walking = true;
    while (walking) {
        walking = false;
        for (uint k = 0u; k < uint(VDS_N); ++k) {
            if (next[k] >= end[k]) continue;
            int step = vdsCrossingStep(crossings[next[k]], T[k].z);
            if (step == 0) { // the column's walk ends
                end[k] = next[k];
                continue;
            }
            parity[k] ^= 1;
            winding[k] += step;
            ++next[k];
            walking = walking || next[k] < end[k];
        }
    }
}
#endif

// The labels of the points, as one word (0 or 1 in byte k for point k);
// points past `valid` are left 0. For the generalized winding rule every
// invocation of the workgroup must call it (it sums the boundary term
// together), `valid` 0 for those with no points.
uint vdsClassifyPoints(vec3 p[VDS_N], uint valid) {
    vec3 T[VDS_N];
    bool inBox[VDS_N]; // a column to count along
    ivec2 column[VDS_N];
    int winding[VDS_N], parity[VDS_N];
#ifdef VDS_BOUNDARY_TERM
    bool live[VDS_N]; // finite points: in front, behind or beside the box, the term counts
#endif
    for (uint k = 0u; k < uint(VDS_N); ++k) {
        T[k] = vdsToTexture(u_placement, p[k]);
        column[k] = ivec2(0);
#ifdef VDS_BOUNDARY_TERM
        live[k] = k < valid && vdsFinite(T[k]);
        inBox[k] = live[k] && vdsColumnAcross(T[k], VDS_SIZE, column[k]);
#else
        inBox[k] = k < valid && vdsColumnOf(T[k], VDS_SIZE, column[k]);
#endif
    }
#if defined(VDS_COLUMNS) && defined(VDS_BOUNDARY_TERM)
    vdsCountColumns(column, inBox, T, winding, parity);
#else
    for (uint k = 0u; k < uint(VDS_N); ++k) winding[k] = vdsCount(column[k], inBox[k], T[k].z, parity[k]);
#endif
    uint word = 0u;
#ifdef VDS_BOUNDARY_TERM
    vec3 q[VDS_N]; // where the CPU evaluates the term: the texel-centre point, or the point itself beside the box
    for (uint k = 0u; k < uint(VDS_N); ++k)
        q[k] = inBox[k] ? vdsColumnPoint(u_boundary, column[k], T[k].z) : vdsBesidePoint(u_boundary, VDS_SIZE, T[k]);
    float term[VDS_N];
    vdsBoundaryTerms(u_boundary, q, live, term);
    for (uint k = 0u; k < uint(VDS_N); ++k)
        if (live[k] && float(winding[k]) + term[k] > 0.5) word |= 1u << (8u * k);
#else
    for (uint k = 0u; k < uint(VDS_N); ++k) {
#if VDS_RULE_ID == VDS_RULE_WINDING
        bool inside = winding[k] != 0;
#else
        bool inside = parity[k] != 0;
#endif
        if (inBox[k] && inside) word |= 1u << (8u * k);
    }
#endif
    return word;
}

void main() {
    uint quads = vdsPointQuads();
#ifdef VDS_BOUNDARY_TERM
    // Workgroup by workgroup: `first` is the same in every invocation.
    uint step = vdsInvocationCount();
    for (uint first = gl_WorkGroupID.x * gl_WorkGroupSize.x; first < quads;
         first = quads - first > step ? first + step : quads) {
        uint q = first + gl_LocalInvocationID.x;
        vec3 p[VDS_N];
        for (uint k = 0u; k < uint(VDS_N); ++k) p[k] = vec3(0.0);
        uint valid = 0u;
        if (q < quads) valid = vdsLoadPoints(q, p);
        uint word = vdsClassifyPoints(p, valid);
        if (q < quads) labels[q] = word;
    }
#else
    for (uint q = gl_GlobalInvocationID.x; q < quads; q = vdsNextIndex(q, quads)) {
        vec3 p[VDS_N];
        uint valid = vdsLoadPoints(q, p);
        labels[q] = vdsClassifyPoints(p, valid);
    }
#endif
}
