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
// with 2 * VdsBoundary.edgeCount entries: edge k runs from vdsBoundaryEdges[2k]
// to vdsBoundaryEdges[2k+1], xyz the endpoint in the baked mesh's coordinates
// permuted to the sprite's (s, t, r) order (Sprite::boundaryEdges[i] read at
// axisPermutation(axis); a cyclic permutation, so solid angles keep their
// sign), w unused. Placing the sprite elsewhere (GpuSprite::setPlacement)
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
// The cost is O(boundary edges) a point.
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

// The boundary term at q (the bake's frame, (s, t, r) order): the sum over
// the edges of their solid angles, over 4 pi. O(edgeCount).
float vdsBoundaryTerm(VdsBoundary boundary, vec3 q) {
    float sum = 0.0;
    for (int k = 0; k < boundary.edgeCount; ++k)
        sum += vdsEdgeSolidAngle(vdsBoundaryEdges[2 * k].xyz, vdsBoundaryEdges[2 * k + 1].xyz, q);
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
