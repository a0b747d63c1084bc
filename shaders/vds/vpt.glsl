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
// get it (GpuBoundary::setUniforms fills both):
//   #define VDS_BOUNDARY_BINDING 5
//   #include "vds/vpt.glsl"
//   uniform VdsBoundary u_boundary;
//   if (vdsContainsGeneralized(u_ldi, u_placement, u_boundary, worldPosition)) ...
// It declares
//   layout(std430, binding = VDS_BOUNDARY_BINDING) readonly buffer VdsBoundaryEdges {
//       vec4 vdsBoundaryEdges[]; };
// with 2 * VdsBoundary.edgeCount entries (then the tree's node records, if
// any): edge k runs from vdsBoundaryEdges[2k]
// to vdsBoundaryEdges[2k+1], xyz the endpoint in the baked mesh's coordinates
// permuted to the sprite's (s, t, r) order (Sprite::boundaryEdges read at
// axisPermutation(axis), loop by loop where they close into loops; a cyclic
// permutation, so solid angles keep their sign), w unused. Placing the sprite elsewhere (GpuSprite::setPlacement)
// changes neither: the term is evaluated in the bake's frame.
//
// The GPU evaluates it in float where the C++ `Sprite::classify` uses double:
// the value errs by about float epsilon times the coordinates' magnitude
// over the distance to the boundary curve (a 32-segment unit sphere with
// three holes, 20,000 points in its box, on llvmpipe: median 1.0e-6, 99.9th
// percentile 1.8e-5, worst 1.6e-4, the same with the tree below as with
// every edge summed; tests/gl/gwn_gpu_test.cpp), and each node the tree
// takes by its expansion adds at most 1e-5 (VDS_NODE_TOLERANCE, a proven
// bound; the true error is far smaller). So labels can differ
// from the CPU's only where the value is within that error of 1/2, or where
// the point's texel-centre point lies, within float error, on the sweep of
// a boundary edge along +r (there the term jumps by 1; the CPU's tie rule
// for exact ties is mirrored, but a near-tie can round to either side).
// The cost is O(boundary edges) a point at most: GpuSprite uploads the
// chain tree of the C++ labels (VdsBoundary.nodeCount records after the
// edges: groups of whole loops, then halves of a loop's edges down to
// chains of at most 4), and a node whose ball the point's ray misses is
// taken by its chord and its fan's expansion where that errs little
// (vdsBoundaryTerm), so a point near a large opening sums the few chains
// near it and takes the rest of the rim by their chords. Each node visited
// costs about as much as an edge on llvmpipe, so where the points need
// most of a small boundary's edges anyway (a teapot's 160, a shell's fins
// of 3 edges) the walk is up to 1.3x slower than the per-edge sum was;
// near larger loops it is 1.5x faster (docs/benchmarks.md).
#ifndef VDS_VPT_GLSL
#define VDS_VPT_GLSL

#define VDS_RULE_PARITY 0
#define VDS_RULE_WINDING 1
#define VDS_RULE_GENERALIZED_WINDING 2

// The full solid angle, 4 pi: a winding number is a sum of solid angles over
// it. The library defines it in every program it builds, from the C++
// constant (vds::detail::kFourPi); this default serves a user's shader that
// includes this file on its own.
#ifndef VDS_FOUR_PI
#define VDS_FOUR_PI 12.566370614359172
#endif

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

// The one step of every column walk (this texture's, the compact columns'
// of vds/columns.glsl, classify.comp's lockstep walks): crossing `e`'s
// step of the winding number where it lies strictly in front of depth r,
// +1 entering and -1 leaving, and 0 where it does not: a column is sorted
// front to back, so its walk ends there. A value, not inout arguments:
// llvmpipe copies array elements in and out of a call, which cost the
// lockstep walks 5% of their rate.
int vdsCrossingStep(float e, float r) {
    if (!(abs(e) < r)) return 0;
    return floatBitsToInt(e) < 0 ? -1 : 1;
}

// vdsCrossingStep counted into `parity` and `winding`; false where the walk ends.
bool vdsCountCrossing(float e, float r, inout int parity, inout int winding) {
    int step = vdsCrossingStep(e, r);
    parity ^= step & 1;
    winding += step;
    return step != 0;
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
        if (e == 1.0 || !vdsCountCrossing(e, r, parity, winding)) break;
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
// number of boundary edges (GpuBoundary::setUniforms):
//   lo    the baked box's low corner, (s, t, r) order, mesh coordinates
//   step  (texel size, texel size, the box's extent along r), mesh units
//   edgeCount  boundary edges in VdsBoundaryEdges; 0: the mesh is closed, or
//         only inconsistently oriented, and the rule reads as Winding.
struct VdsBoundary {
    vec3 lo;
    vec3 step;
    int edgeCount;
    int nodeCount; // chain tree node records after the edges (0: sum every edge)
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
// vdsEdgeSolidAngleOf takes u = a - q, v = b - q and their lengths made
// before: along a chain of edges one edge's v is the next one's u, so a
// caller that sums a chain computes one length an edge, not two.
float vdsEdgeSolidAngleOf(vec3 u, vec3 v, float lu, float lv, vec3 a, vec3 b) {
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

float vdsEdgeSolidAngle(vec3 a, vec3 b, vec3 q) {
    vec3 u = a - q;
    vec3 v = b - q;
    return vdsEdgeSolidAngleOf(u, v, length(u), length(v), a, b);
}

#ifdef VDS_BOUNDARY_BINDING
layout(std430, binding = VDS_BOUNDARY_BINDING) readonly buffer VdsBoundaryEdges { vec4 vdsBoundaryEdges[]; };

// A node is taken by its chord and its fan's expansion where the
// expansion's remainder bound is at most this (winding number units; C++
// kBoundaryNodeTolerance).
#define VDS_NODE_TOLERANCE 1e-5
// A node of this many edges or fewer that is not taken sums its edges
// rather than opening its children (each node visited costs about as much
// as an edge: on llvmpipe 16 beat 8 and 32).
#define VDS_NODE_SUM_EDGES 16
// Nodes taken, and ranges of edges (or chords) to sum, gathered before
// they are evaluated.
#define VDS_NODE_BATCH 16

// The solid angles of `count` edges whose endpoints are the pairs of
// entries from vdsBoundaryEdges[at] on, in steradians.
float vdsEdgePairs(int at, int count, vec3 q) {
    float sum = 0.0;
    for (int k = at; k < at + 2 * count; k += 2)
        sum += vdsEdgeSolidAngle(vdsBoundaryEdges[k].xyz, vdsBoundaryEdges[k + 1].xyz, q);
    return sum;
}

// The integral of n . (x - q) / |x - q|^3 over the fan of the node record
// at `at`, by its expansion to second order about the ball's centre (C++
// BoundaryCaps::expansion), at y = centre - q.
float vdsNodeExpansion(int at, vec3 y) {
    float d2 = dot(y, y);
    vec4 a = vdsBoundaryEdges[at + 2];
    vec4 m1 = vdsBoundaryEdges[at + 3];
    vec4 m2 = vdsBoundaryEdges[at + 4];
    // M_ij, row-major: M_00 = a.w, then m1 (M_01, M_02, M_10, M_11) and
    // m2 (M_12, M_20, M_21, M_22)
    float yMy = y.x * (a.w * y.x + m1.x * y.y + m1.y * y.z) + y.y * (m1.z * y.x + m1.w * y.y + m2.x * y.z) +
                y.z * (m2.y * y.x + m2.z * y.y + m2.w * y.z);
    float first = dot(a.xyz, y) + (a.w + m1.w + m2.w) - 3.0 * yMy / d2;
    // N_ijk: 18 floats in [7] to [11], row i the pairs 00, 11, 22, 01, 02,
    // 12, against y_j y_k (twice for j != k).
    vec4 n0 = vdsBoundaryEdges[at + 7];
    vec4 n1 = vdsBoundaryEdges[at + 8];
    vec4 n2 = vdsBoundaryEdges[at + 9];
    vec4 n3 = vdsBoundaryEdges[at + 10];
    vec4 n4 = vdsBoundaryEdges[at + 11];
    vec4 yyA = vec4(y.x * y.x, y.y * y.y, y.z * y.z, 2.0 * y.x * y.y);
    vec2 yyB = vec2(2.0 * y.x * y.z, 2.0 * y.y * y.z);
    float yNyy = y.x * (dot(n0, yyA) + dot(n1.xy, yyB)) + y.y * (dot(n1.zw, yyA.xy) + dot(n2, vec4(yyA.zw, yyB))) +
                 y.z * (dot(n3, yyA) + dot(n4.xy, yyB));
    vec3 rows = vdsBoundaryEdges[at + 5].xyz;
    vec3 columns = vdsBoundaryEdges[at + 6].xyz;
    float second = 0.5 / d2 * (-3.0 * (2.0 * dot(columns, y) + dot(rows, y)) + 15.0 * yNyy / d2);
    return (first + second) / (d2 * sqrt(d2));
}

// Whether the node whose ball is `ball` (centre, radius) and whose bound's
// scale is `errorScale` may be taken whole at q by its chord and expansion:
// q's ray towards -r misses the ball (the fan's crossing count is 0), q lies
// outside it and the expansion's remainder bound is at most
// VDS_NODE_TOLERANCE.
bool vdsNodeTaken(vec4 ball, float errorScale, vec3 q) {
    vec3 y = ball.xyz - q;
    float r2 = ball.w * ball.w;
    float d2 = dot(y, y);
    float d = sqrt(d2);
    float e = d - ball.w;
    return (y.x * y.x + y.y * y.y > r2 || q.z < ball.z - ball.w) && e > 0.0 &&
           errorScale * ball.w * (d + 3.0 * e) <= VDS_NODE_TOLERANCE * 3.0 * d2 * d2 * e * e;
}

// The boundary term at q (the bake's frame, (s, t, r) order): the sum over
// the edges of their solid angles, over 4 pi. With the chain tree
// (GpuBoundary::setUniforms sets nodeCount; C++ caps_tree.h,
// BoundaryCaps::chains, and vds/gl/src/sprite pack_boundary.h for the records): a node's
// edges run from P to Q, closed by its chord Q -> P into a fan in its
// ball (whole loops have no chord). Where q's ray towards -r misses the
// ball, the ray crosses no fan, so the node's edges' angles sum to the
// chord's angle less the fan's solid angle, taken by the expansion to
// second order about the ball's centre c where its remainder bound
// errorScale R (d + 3e) / (3 d^4 e^2), e = d - R, allows; other nodes are
// opened, and small ones and leaves sum their edges. The nodes come in
// preorder, each with the index of the node after its subtree, so the walk
// needs no stack: opening a node goes on to the next one, taking or
// summing it skips its subtree. Neighbouring invocations run in lockstep
// on SIMD hardware, so the walk only gathers what to evaluate (a few
// loads a node), then the expansions and the edges (chords among them)
// are evaluated in two flat loops.
float vdsBoundaryTerm(VdsBoundary boundary, vec3 q) {
    if (boundary.nodeCount == 0) return vdsEdgePairs(0, boundary.edgeCount, q) / VDS_FOUR_PI;
    int base = 2 * boundary.edgeCount;
    float sum = 0.0;
    int node = 0;
    int taken[VDS_NODE_BATCH];
    int pairsAt[VDS_NODE_BATCH]; // a range of edges, or a chord, to sum:
    int pairs[VDS_NODE_BATCH];   // its first endpoint's entry and its edges
    while (node < boundary.nodeCount) {
        int takenCount = 0;
        int rangeCount = 0;
        while (node < boundary.nodeCount && takenCount < VDS_NODE_BATCH && rangeCount < VDS_NODE_BATCH) {
            int at = base + 14 * node;
            vec4 ball = vdsBoundaryEdges[at];
            vec4 links = vdsBoundaryEdges[at + 1]; // errorScale, skip, first edge, count << 2 | flags
            int skip = floatBitsToInt(links.y);
            int flags = floatBitsToInt(links.w);
            if (vdsNodeTaken(ball, links.x, q)) {
                taken[takenCount] = at;
                takenCount += 1;
                if ((flags & 2) != 0) {
                    pairsAt[rangeCount] = at + 12;
                    pairs[rangeCount] = 1;
                    rangeCount += 1;
                }
                node = skip;
            } else if ((flags & 1) != 0 || (flags >> 2) <= VDS_NODE_SUM_EDGES) {
                pairsAt[rangeCount] = 2 * floatBitsToInt(links.z);
                pairs[rangeCount] = flags >> 2;
                rangeCount += 1;
                node = skip;
            } else {
                node += 1;
            }
        }
        for (int k = 0; k < takenCount; ++k)
            sum -= vdsNodeExpansion(taken[k], vdsBoundaryEdges[taken[k]].xyz - q);
        // the ranges' edges in one flat loop
        int range = 0;
        int edge = 0;
        while (range < rangeCount) {
            int at = pairsAt[range] + 2 * edge;
            sum += vdsEdgeSolidAngle(vdsBoundaryEdges[at].xyz, vdsBoundaryEdges[at + 1].xyz, q);
            edge += 1;
            if (edge == pairs[range]) {
                range += 1;
                edge = 0;
            }
        }
    }
    return sum / VDS_FOUR_PI;
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

// ---- Distance to the border --------------------------------------------------
// A distance texture (<vds/gl/distance.h>, `uploadDistanceTexture`): the
// signed distances of a vds::Grid's cell centres over the box [lo, hi]
// (SignedDistance::grid), one R32F texel a cell, linear filtering, clamped
// to the edge. Cell (i, j, k)'s centre lo + (i + 1/2, j + 1/2, k + 1/2) *
// (hi - lo) / dims is texel (i, j, k)'s centre, so the lookup is the
// trilinear interpolation of the exact distances around `world`: negative
// inside by the grid's rule, and within half a cell's diagonal of the exact
// signed distance (distance is 1-Lipschitz, and the interpolation weights
// average the corners' offsets: sqrt(sum_a t_a (1 - t_a) h_a^2) <= |h| / 2),
// plus the filter's weight rounding (8 bits on many GPUs: 1/256 of a cell's
// change, below |h| sqrt(3) / 256). Exact at the cell centres to float
// rounding. Beyond the outermost cell centres (the cell-centre box), the
// lookup is that at the box's nearest point c, its magnitude grown by
// |world - c|: the far end of what 1-Lipschitz allows, so values keep growing
// away from the grid (a band or a fade does not smear along the clamped
// edge) and the bound grows by 2 |world - c|. Where the sign changes within
// a cell (on the surface) the sign of the lookup can differ from the
// classifier's.
float vdsDistance(sampler3D field, vec3 lo, vec3 hi, vec3 world) {
    vec3 halfCell = 0.5 * (hi - lo) / vec3(textureSize(field, 0));
    vec3 nearest = clamp(world, lo + halfCell, hi - halfCell);
    float d = texture(field, (nearest - lo) / (hi - lo)).r;
    float away = length(world - nearest);
    return d < 0.0 ? d - away : d + away;
}

#endif
