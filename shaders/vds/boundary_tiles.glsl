// vds/boundary_tiles.glsl: the generalized winding number's boundary term
// (vpt.glsl's vdsBoundaryTerm) summed by a whole workgroup together, the
// way a GPU is fast: the edges are staged through shared memory a tile at a
// time (one edge loaded per invocation, then every invocation sums the whole
// tile for its points, all in lockstep with no divergence), and the chain
// tree's nodes are walked by the workgroup as one: a node is taken whole by
// its chord and its fan's expansion only when every point of the workgroup
// may take it (a vote through shared memory), so the walk, its loads and its
// branches are the same in every invocation.
//
// The floor is the brute-force sum (every edge for every point, tiled): the
// walk costs one vote a node visited more, and a node of at most one tile of
// edges is summed rather than opened, so it stays within a few votes of
// that floor where no node is ever taken, and skips whole chains or loops
// where the workgroup's points (coherent queries, an occupancy column's
// cells) all lie far from them.
//
// Float error: the same as vdsBoundaryTerm's (vpt.glsl): the edges' solid
// angles in float, summed in another order, and at most VDS_NODE_TOLERANCE
// (1e-5) for each node taken (a proven bound on the expansion's remainder).
//
// Include after vpt.glsl with VDS_BOUNDARY_BINDING defined, and define
// VDS_LOCAL_SIZE (the one-dimensional local size: the tile's edges) and
// VDS_TERM_POINTS (points per invocation) first. Call vdsBoundaryTerms in
// uniform control flow from every invocation of the workgroup.
#ifndef VDS_BOUNDARY_TILES_GLSL
#define VDS_BOUNDARY_TILES_GLSL

// A node of at most this many edges is summed, not opened: its edges fill
// at most one tile, which costs about what the votes on its children would.
#define VDS_NODE_TILE_EDGES VDS_LOCAL_SIZE

shared vec3 vdsTileFrom[VDS_LOCAL_SIZE];
shared vec3 vdsTileTo[VDS_LOCAL_SIZE];
// The last vote round each slot was refused in (rounds alternate slots, so
// a round's writers never overwrite what the round before is still reading).
shared int vdsRefused[2];

// Adds the solid angles of edges [first, first + count) at each point to
// `sum`, a tile of VDS_LOCAL_SIZE edges at a time.
void vdsSumEdgeTiles(int first, int count, vec3 q[VDS_TERM_POINTS], inout float sum[VDS_TERM_POINTS]) {
    int local = int(gl_LocalInvocationID.x);
    for (int tile = 0; tile < count; tile += VDS_LOCAL_SIZE) {
        barrier(); // the tile before is read by every invocation
        if (local < count - tile) {
            int at = 2 * (first + tile + local);
            vdsTileFrom[local] = vdsBoundaryEdges[at].xyz;
            vdsTileTo[local] = vdsBoundaryEdges[at + 1].xyz;
        }
        memoryBarrierShared(); // the tile's stores visible to the workgroup (as scan.comp does)
        barrier();
        int n = min(VDS_LOCAL_SIZE, count - tile);
        // The edges come in chains (the chain tree's leaves, in loop order):
        // where an edge starts at the last one's end, its u and |u| are the
        // last one's v and |v|. The test reads shared memory only, so the
        // branch is the same in every invocation.
        vec3 u[VDS_TERM_POINTS];
        float lu[VDS_TERM_POINTS];
        for (int e = 0; e < n; ++e) {
            vec3 a = vdsTileFrom[e];
            vec3 b = vdsTileTo[e];
            if (e == 0 || a != vdsTileTo[e - 1]) {
                for (int k = 0; k < VDS_TERM_POINTS; ++k) {
                    u[k] = a - q[k];
                    lu[k] = length(u[k]);
                }
            }
            for (int k = 0; k < VDS_TERM_POINTS; ++k) {
                vec3 v = b - q[k];
                float lv = length(v);
                sum[k] += vdsEdgeSolidAngleOf(u[k], v, lu[k], lv, a, b);
                u[k] = v;
                lu[k] = lv;
            }
        }
    }
}

// Whether every invocation's live points may take the node whose ball and
// error scale are given: one vote of the workgroup, in round `round`.
bool vdsAllTake(vec4 ball, float errorScale, vec3 q[VDS_TERM_POINTS], bool live[VDS_TERM_POINTS], int round) {
    bool take = true;
    for (int k = 0; k < VDS_TERM_POINTS; ++k) take = take && (!live[k] || vdsNodeTaken(ball, errorScale, q[k]));
    if (!take) vdsRefused[round & 1] = round; // every refusing invocation writes the same value
    memoryBarrierShared();
    barrier();
    return vdsRefused[round & 1] != round;
}

// The boundary term (winding number units) at each point q[k]; where
// live[k] is false the point takes part in the loads and votes but its term
// is meaningless.
void vdsBoundaryTerms(VdsBoundary boundary, vec3 q[VDS_TERM_POINTS], bool live[VDS_TERM_POINTS],
                      out float term[VDS_TERM_POINTS]) {
    float sum[VDS_TERM_POINTS];
    for (int k = 0; k < VDS_TERM_POINTS; ++k) sum[k] = 0.0;
    if (boundary.nodeCount == 0) {
        vdsSumEdgeTiles(0, boundary.edgeCount, q, sum);
    } else {
        barrier(); // a previous call's last vote is read
        if (gl_LocalInvocationID.x == 0u) {
            vdsRefused[0] = -1;
            vdsRefused[1] = -1;
        }
        memoryBarrierShared();
        barrier();
        int base = 2 * boundary.edgeCount;
        int node = 0;
        for (int round = 0; node < boundary.nodeCount; ++round) {
            int at = base + 14 * node;
            vec4 ball = vdsBoundaryEdges[at];
            vec4 links = vdsBoundaryEdges[at + 1]; // errorScale, skip, first edge, count << 2 | flags
            int flags = floatBitsToInt(links.w);
            if (vdsAllTake(ball, links.x, q, live, round)) {
                for (int k = 0; k < VDS_TERM_POINTS; ++k) sum[k] -= vdsNodeExpansion(at, ball.xyz - q[k]);
                if ((flags & 2) != 0) { // its chord
                    vec3 a = vdsBoundaryEdges[at + 12].xyz, b = vdsBoundaryEdges[at + 13].xyz;
                    for (int k = 0; k < VDS_TERM_POINTS; ++k) sum[k] += vdsEdgeSolidAngle(a, b, q[k]);
                }
                node = floatBitsToInt(links.y);
            } else if ((flags & 1) != 0 || (flags >> 2) <= VDS_NODE_TILE_EDGES) {
                vdsSumEdgeTiles(floatBitsToInt(links.z), flags >> 2, q, sum);
                node = floatBitsToInt(links.y);
            } else {
                node += 1;
            }
        }
    }
    for (int k = 0; k < VDS_TERM_POINTS; ++k) term[k] = sum[k] / VDS_FOUR_PI;
}

#endif
