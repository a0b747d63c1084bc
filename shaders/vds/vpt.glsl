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
//
// The generalized winding number of open meshes (Rule::GeneralizedWinding),
// by the Antipodal split (Martens, Trettner & Bessmeltsev 2026): the column's
// signed crossing count plus a boundary term summed over the baked mesh's
// boundary edges, which live in a shader storage buffer. Define
// VDS_BOUNDARY_BINDING to the buffer's binding point before the include to
// get it (GpuSprite::setBoundaryUniforms fills both):
//   #define VDS_BOUNDARY_BINDING 5
//   #include "vds/vpt.glsl"
//   uniform VdsBoundary u_boundary;
//   if (vdsContainsGeneralized(u_ldi, u_placement, u_boundary, worldPosition)) ...
// It declares
//   layout(std430, binding = VDS_BOUNDARY_BINDING) readonly buffer VdsBoundaryEdges {
//       vec4 vdsBoundaryEdges[]; };
// with 2 * VdsBoundary.edgeCount entries (then the loop records, if any):
// edge k runs from vdsBoundaryEdges[2k]
// to vdsBoundaryEdges[2k+1], xyz the endpoint in the baked mesh's coordinates
// permuted to the sprite's (s, t, r) order (Sprite::boundaryEdges read at
// axisPermutation(axis), loop by loop where they close into loops; a cyclic
// permutation, so solid angles keep their sign), w unused. Placing the sprite elsewhere (GpuSprite::setPlacement)
// changes neither: the term is evaluated in the bake's frame.
//
// The GPU evaluates it in float where the C++ `Sprite::classify` uses double:
// the value errs by about float epsilon times the coordinates' magnitude
// over the distance to the boundary curve (a 32-segment unit sphere with
// three holes, 20,000 points in its box: median 5e-7, 99.9th percentile
// 1.2e-5, worst 1.6e-4; tests/gl/gwn_gpu_test.cpp). So labels can differ
// from the CPU's only where the value is within that error of 1/2, or where
// the point's texel-centre point lies, within float error, on the sweep of
// a boundary edge along +r (there the term jumps by 1; the CPU's tie rule
// for exact ties is mirrored, but a near-tie can round to either side).
// The cost is O(boundary edges) a point at most: with the loop records
// GpuSprite uploads after the edges (VdsBoundary.loopCount), a loop of 4 or
// more edges whose ball the point's ray misses is taken by its cap's
// expansion where that errs by at most 1e-5 (vdsBoundaryTerm).
#ifndef VDS_VPT_GLSL
#define VDS_VPT_GLSL

#define VDS_RULE_PARITY 0
#define VDS_RULE_WINDING 1
#define VDS_RULE_GENERALIZED_WINDING 2

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
// Whether T is finite (points that are not are outside, as on the CPU).
bool vdsFinite(vec3 T) {
    return abs(T.x) < 3.0e38 && abs(T.y) < 3.0e38 && abs(T.z) < 3.0e38;
}

// The column that texture-space point T lies in front of, in or behind,
// whatever its depth; false beside the box (or where T is not finite).
bool vdsColumnAcross(vec3 T, ivec2 size, out ivec2 column) {
    column = ivec2(0);
    precise float fs = floor(T.x * float(size.x));
    precise float ft = floor(T.y * float(size.y));
    if (!(fs >= 0.0 && fs < float(size.x) && ft >= 0.0 && ft < float(size.y))) return false;
    column = ivec2(fs, ft);
    return true;
}

bool vdsColumnOf(vec3 T, ivec2 size, out ivec2 column) {
    column = ivec2(0);
    if (!(T.z >= 0.0 && T.z <= 1.0)) return false;
    return vdsColumnAcross(T, size, column);
}

// Winding number of the crossings strictly in front of texture-space point T
// (entering +1, leaving -1); `parity` receives their count modulo 2. Points
// outside [0,1]^3 have no crossings in front.
// The same for column `column` at any texture depth r: none in front of
// r <= 0, all of them behind the box (r > 1). The padding (+1.0) ends the
// column there; so does an entering crossing at exactly depth 1, which it
// cannot be told from (a leaving one, -1.0, as a closed mesh's face on the
// box's far side gives, is counted).
int vdsColumnWinding(sampler3D ldi, ivec2 column, float r, out int parity) {
    parity = 0;
    int winding = 0;
    int layers = textureSize(ldi, 0).z;
    for (int k = 0; k < layers; ++k) {
        float e = texelFetch(ldi, ivec3(column, k), 0).r;
        if (!(abs(e) < r) || e == 1.0) break; // sorted: nothing further is in front
        parity ^= 1;
        winding += floatBitsToInt(e) < 0 ? -1 : 1;
    }
    return winding;
}

int vdsWinding(sampler3D ldi, vec3 T, out int parity) {
    parity = 0;
    ivec2 column;
    if (!vdsColumnOf(T, textureSize(ldi, 0).xy, column)) return 0;
    return vdsColumnWinding(ldi, column, T.z, parity);
}

// Inside test of a world point against one sprite.
bool vdsContains(sampler3D ldi, VdsPlacement placement, vec3 world, int rule) {
    int parity;
    int winding = vdsWinding(ldi, vdsToTexture(placement, world), parity);
    return rule == VDS_RULE_WINDING ? winding != 0 : parity != 0;
}

// The frame of the bake that the boundary term is evaluated in, and the
// number of boundary edges (GpuSprite::setBoundaryUniforms):
//   lo    the baked box's low corner, (s, t, r) order, mesh coordinates
//   step  (texel size, texel size, the box's extent along r), mesh units
//   edgeCount  boundary edges in VdsBoundaryEdges; 0: the mesh is closed, or
//         only inconsistently oriented, and the rule reads as Winding.
struct VdsBoundary {
    vec3 lo;
    vec3 step;
    int edgeCount;
    int loopCount; // loop records after the edges (0: sum every edge)
};

// The point the column's count belongs to: the centre of texel `column` at
// texture depth r, in the bake's frame, (s, t, r) order, as the C++
// `SpriteGrid::texelCentre` rounds it.
vec3 vdsColumnPoint(VdsBoundary boundary, ivec2 column, float r) {
    precise float s = boundary.lo.x + (float(column.x) + 0.5) * boundary.step.x;
    precise float t = boundary.lo.y + (float(column.y) + 0.5) * boundary.step.y;
    precise float d = boundary.lo.z + r * boundary.step.z;
    return vec3(s, t, d);
}

// Signed solid angle of the spherical triangle (+r, a - q, b - q), in
// steradians, by Van Oosterom & Strackee with the first vertex the unit
// axis (C++ `edgeSolidAngle`). On the edge's sweep (det exactly 0 with the
// triangle flipped), where it jumps by 4 pi, it takes the side of the point
// moved by (eps, -eps^2) in (s, t), as the crossing count's tie rule does; an
// edge along the axis adds 0.
float vdsEdgeSolidAngle(vec3 a, vec3 b, vec3 q) {
    vec3 u = a - q;
    vec3 v = b - q;
    float lu = length(u);
    float lv = length(v);
    float det = u.x * v.y - u.y * v.x;
    float den = ((lu * lv + dot(u, v)) + u.z * lv) + v.z * lu;
    if (det == 0.0) {
        if (!(den < 0.0)) return 0.0; // atan(0, x >= 0) is 0 (and atan(0, 0) undefined in GLSL)
        vec3 d = a - b;
        det = d.y != 0.0 ? d.y : d.x;
        if (det == 0.0) return 0.0;
    }
    return 2.0 * atan(det, den);
}

#ifdef VDS_BOUNDARY_BINDING
layout(std430, binding = VDS_BOUNDARY_BINDING) readonly buffer VdsBoundaryEdges { vec4 vdsBoundaryEdges[]; };

// The solid angles of edges [first, first + count), in steradians.
float vdsEdgeRange(int first, int count, vec3 q) {
    float sum = 0.0;
    for (int k = first; k < first + count; ++k)
        sum += vdsEdgeSolidAngle(vdsBoundaryEdges[2 * k].xyz, vdsBoundaryEdges[2 * k + 1].xyz, q);
    return sum;
}

// A far loop's edges are summed by its cap's expansion where that errs by
// at most this (in winding number units; the float sum errs by some 1e-6).
#define VDS_LOOP_TOLERANCE 1e-5

// The boundary term at q (the bake's frame, (s, t, r) order): the sum over
// the edges of their solid angles, over 4 pi. With loop records
// (GpuSprite::setBoundaryUniforms sets loopCount), loop by loop: a loop
// whose ball (it holds the loop and its cap, the fan from its centroid)
// q's ray along the axis misses has no crossing with its cap, so its
// edges' sum is minus its cap's solid angle, taken by the expansion to
// second order about the centroid (C++ caps_tree.h gives the terms and the
// remainder bound R S (D + 3e) / (4 pi D^4 e^2)) where that bound allows;
// other loops sum their edges, and so do the loops of fewer than 4 edges,
// which have no record (their edges come after the recorded loops').
float vdsBoundaryTerm(VdsBoundary boundary, vec3 q) {
    if (boundary.loopCount == 0) return vdsEdgeRange(0, boundary.edgeCount, q) / 12.566370614359172;
    float sum = 0.0;
    int tail = 0; // past the last recorded loop's edges
    for (int l = 0; l < boundary.loopCount; ++l) {
        int at = 2 * boundary.edgeCount + 12 * l;
        vec4 m2 = vdsBoundaryEdges[at + 4];
        int first = floatBitsToInt(m2.y);
        int count = floatBitsToInt(m2.z);
        tail = first + count;
        vec4 ball = vdsBoundaryEdges[at];
        vec3 y = ball.xyz - q;
        if (y.x * y.x + y.y * y.y > ball.w * ball.w) {
            vec4 area = vdsBoundaryEdges[at + 1];
            float d2 = dot(y, y);
            float d = sqrt(d2);
            float e = d - ball.w;
            float bound = area.w * ball.w * (d + 3.0 * e) / (3.0 * d2 * d2 * e * e);
            if (bound <= VDS_LOOP_TOLERANCE) {
                vec4 m0 = vdsBoundaryEdges[at + 2];
                vec4 m1 = vdsBoundaryEdges[at + 3];
                float yMy = y.x * (m0.x * y.x + m0.y * y.y + m0.z * y.z) +
                            y.y * (m0.w * y.x + m1.x * y.y + m1.y * y.z) +
                            y.z * (m1.z * y.x + m1.w * y.y + m2.x * y.z);
                float first = dot(area.xyz, y) + (m0.x + m1.x + m2.x) - 3.0 * yMy / d2;
                // N_ijk: 18 floats from [7], row i the pairs 00, 11, 22, 01, 02, 12.
                float n[20];
                for (int v = 0; v < 5; ++v) {
                    vec4 w = vdsBoundaryEdges[at + 7 + v];
                    n[4 * v] = w.x;
                    n[4 * v + 1] = w.y;
                    n[4 * v + 2] = w.z;
                    n[4 * v + 3] = w.w;
                }
                float yy0 = y.x * y.x, yy1 = y.y * y.y, yy2 = y.z * y.z;
                float yy3 = 2.0 * y.x * y.y, yy4 = 2.0 * y.x * y.z, yy5 = 2.0 * y.y * y.z;
                float yNyy = 0.0;
                for (int i = 0; i < 3; ++i)
                    yNyy += y[i] * (n[6 * i] * yy0 + n[6 * i + 1] * yy1 + n[6 * i + 2] * yy2 + n[6 * i + 3] * yy3 +
                                    n[6 * i + 4] * yy4 + n[6 * i + 5] * yy5);
                vec3 rows = vdsBoundaryEdges[at + 5].xyz;
                vec3 columns = vdsBoundaryEdges[at + 6].xyz;
                float second = 0.5 / d2 * (-3.0 * (2.0 * dot(columns, y) + dot(rows, y)) + 15.0 * yNyy / d2);
                sum -= (first + second) / (d2 * d);
                continue;
            }
        }
        sum += vdsEdgeRange(first, count, q);
    }
    // The edges of loops too small for a record come after the loops'.
    sum += vdsEdgeRange(tail, boundary.edgeCount - tail, q);
    return sum / 12.566370614359172;
}

// The column's signed count `winding` at depth r plus the boundary term at
// the column's texel-centre point at that depth.
float vdsGeneralizedWindingAt(VdsBoundary boundary, int winding, ivec2 column, float r) {
    if (boundary.edgeCount == 0) return float(winding);
    return float(winding) + vdsBoundaryTerm(boundary, vdsColumnPoint(boundary, column, r));
}

// The rule's test from the column's count: the value above 1/2; with no
// boundary edges the winding rule (winding != 0), as on the CPU.
bool vdsContainsGeneralizedAt(VdsBoundary boundary, int winding, ivec2 column, float r) {
    if (boundary.edgeCount == 0) return winding != 0;
    return vdsGeneralizedWindingAt(boundary, winding, column, r) > 0.5;
}

// Beside the box (T's (s, t) outside [0,1]^2, where no ray meets the mesh):
// the point itself in the bake's frame, (s, t, r) order, as the C++
// classifier places it.
vec3 vdsBesidePoint(VdsBoundary boundary, ivec2 size, vec3 T) {
    precise float s = boundary.lo.x + T.x * float(size.x) * boundary.step.x;
    precise float t = boundary.lo.y + T.y * float(size.y) * boundary.step.y;
    precise float d = boundary.lo.z + T.z * boundary.step.z;
    return vec3(s, t, d);
}

// The rule's test beside the box: no crossing, the boundary term at the
// point itself.
bool vdsContainsGeneralizedBeside(VdsBoundary boundary, ivec2 size, vec3 T) {
    if (boundary.edgeCount == 0) return false;
    return vdsBoundaryTerm(boundary, vdsBesidePoint(boundary, size, T)) > 0.5;
}

// The generalized winding number at a world point, in float (C++
// `Sprite::generalizedWinding`), everywhere: the GWN of an open mesh need
// not vanish outside the sprite's box (just beyond a large opening it
// exceeds 1/2). In front of or behind the box, the column's count with
// none or all of its crossings in front, at its texel centre as inside the
// box; beside the box, no crossing and the term at the point itself. 0 where
// the point is not finite.
float vdsGeneralizedWinding(sampler3D ldi, VdsPlacement placement, VdsBoundary boundary, vec3 world) {
    vec3 T = vdsToTexture(placement, world);
    if (!vdsFinite(T)) return 0.0;
    ivec3 size = textureSize(ldi, 0);
    ivec2 column;
    if (!vdsColumnAcross(T, size.xy, column))
        return boundary.edgeCount == 0 ? 0.0 : vdsBoundaryTerm(boundary, vdsBesidePoint(boundary, size.xy, T));
    int parity;
    int winding = vdsColumnWinding(ldi, column, T.z, parity);
    return vdsGeneralizedWindingAt(boundary, winding, column, T.z);
}

// Inside test of a world point by Rule::GeneralizedWinding, everywhere (as
// vdsGeneralizedWinding places it).
bool vdsContainsGeneralized(sampler3D ldi, VdsPlacement placement, VdsBoundary boundary, vec3 world) {
    vec3 T = vdsToTexture(placement, world);
    if (!vdsFinite(T)) return false;
    ivec3 size = textureSize(ldi, 0);
    ivec2 column;
    if (!vdsColumnAcross(T, size.xy, column)) return vdsContainsGeneralizedBeside(boundary, size.xy, T);
    int parity;
    int winding = vdsColumnWinding(ldi, column, T.z, parity);
    return vdsContainsGeneralizedAt(boundary, winding, column, T.z);
}
#endif

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
