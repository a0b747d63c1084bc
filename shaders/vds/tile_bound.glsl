// vds/tile_bound.glsl: most cells of a generalized winding occupancy sweep
// decided without their boundary term, by a bound a workgroup computes
// together for its tile of cells.
//
// A sweep's workgroup takes one slice of a tile of columns at a time: cells
// at one depth, within `radius` (in the bake's frame) of the tile's centre
// c. Their label is winding + term(q) > 1/2, where the term (the boundary
// edges' strips, each swept from its edge towards +r) is, summed over the
// boundary's closed loops, the solid angle of one surface bounded by the
// loops. Away from that surface the term is harmonic, and its gradient is
// the Biot-Savart integral over the loops:
//     |grad term(p)| <= 1/(4 pi) * sum over edges of length / distance(p, edge)^2,
// so every cell of the slice has
//     |term(q) - term(c)| <= delta = radius/(4 pi) * sum length / (distance(c, edge) - radius)^2
// as long as no strip passes through the slice within the tile (the tile's
// `crossDepth`: the least depth of an edge whose (s, t) projection meets the
// tile) and every edge lies farther than `radius` from c. A cell with
// |winding + term(c) - 1/2| > delta + margin is decided: its label is the
// exact term's. `margin` covers term(c)'s float error (each edge's angle in
// float, VDS_TERM_ERROR an edge, as the CPU's double would not differ by
// more) and the tolerance the exact path is held to (1e-4). The rest, if any
// cell of the workgroup is left, take the exact path (boundary_tiles.glsl).
//
// Work: the tile's setup once (each invocation a share of the edges), then a
// slice costs each invocation edges / VDS_LOCAL_SIZE edge terms and
// distances, two barriers and a read of every invocation's share: far less
// than the exact term's every edge a cell, wherever the tile is decided.
//
// Include after vpt.glsl with VDS_BOUNDARY_BINDING and VDS_LOCAL_SIZE
// defined; call every function in uniform control flow from every
// invocation of the workgroup.
#ifndef VDS_TILE_BOUND_GLSL
#define VDS_TILE_BOUND_GLSL

// Float error of one edge's solid angle at c, in winding-number units: an
// atan's and two lengths' rounding on angles up to pi, over 4 pi, with room.
#define VDS_TERM_ERROR 2.0e-7
// The exact path's tolerance against the CPU's double (boundary_tiles.glsl).
#define VDS_EXACT_TOLERANCE 1.0e-4
#define VDS_INFINITY uintBitsToFloat(0x7f800000u)

shared vec4 vdsTileColumn[VDS_LOCAL_SIZE]; // each column's (s, t), and 1 where live
shared vec2 vdsTileShare[2][VDS_LOCAL_SIZE]; // each invocation's (term, bound) share, by round parity
shared int vdsTileLeft[2];                  // the last round a cell was left undecided in

struct VdsTileBound {
    vec2 centre;      // (s, t) of the tile's centre
    float radius;     // every live cell's (s, t) lies within this of the centre
    float crossDepth; // no strip passes through a slice before this depth (bake frame)
};

// The least depth of edge ab's points whose (s, t) lies in box [lo, hi]
// (conservatively: the edge's least depth where its projection meets the
// box at all), or +inf where it does not.
float vdsStripDepth(vec3 a, vec3 b, vec2 lo, vec2 hi) {
    vec2 d = b.xy - a.xy;
    float t0 = 0.0, t1 = 1.0;
    for (int i = 0; i < 2; ++i) {
        if (d[i] == 0.0) {
            if (a[i] < lo[i] || a[i] > hi[i]) return VDS_INFINITY;
        } else {
            float u = (lo[i] - a[i]) / d[i], v = (hi[i] - a[i]) / d[i];
            t0 = max(t0, min(u, v));
            t1 = min(t1, max(u, v));
        }
    }
    return t0 <= t1 ? min(a.z, b.z) : VDS_INFINITY;
}

// The tile's bound from the workgroup's columns: (s, t) of each column's
// cells (any depth) and whether it is live.
VdsTileBound vdsTileSetup(VdsBoundary boundary, vec2 st, bool live) {
    uint local = gl_LocalInvocationID.x;
    barrier(); // the tile before is read by every invocation
    vdsTileColumn[local] = vec4(st, live ? 1.0 : 0.0, 0.0);
    memoryBarrierShared();
    barrier();
    vec2 lo = vec2(VDS_INFINITY), hi = vec2(-VDS_INFINITY);
    for (int k = 0; k < VDS_LOCAL_SIZE; ++k) {
        vec4 c = vdsTileColumn[k];
        if (c.z != 0.0) {
            lo = min(lo, c.xy);
            hi = max(hi, c.xy);
        }
    }
    VdsTileBound tile;
    tile.centre = 0.5 * (lo + hi);
    // Rounding room: the centre and the cells' coordinates are rounded floats.
    vec2 pad = 1.0e-5 * (abs(lo) + abs(hi) + (hi - lo)) + 1.0e-30;
    tile.radius = length(0.5 * (hi - lo) + pad);
    float depth = VDS_INFINITY;
    for (int e = int(local); e < boundary.edgeCount; e += VDS_LOCAL_SIZE)
        depth = min(depth, vdsStripDepth(vdsBoundaryEdges[2 * e].xyz, vdsBoundaryEdges[2 * e + 1].xyz, lo - pad, hi + pad));
    vdsTileShare[0][local] = vec2(depth, 0.0);
    memoryBarrierShared();
    barrier();
    tile.crossDepth = VDS_INFINITY;
    for (int k = 0; k < VDS_LOCAL_SIZE; ++k) tile.crossDepth = min(tile.crossDepth, vdsTileShare[0][k].x);
    barrier(); // every invocation has read the shares before round 0 writes them
    if (local == 0u) {
        vdsTileLeft[0] = -1;
        vdsTileLeft[1] = -1;
    }
    memoryBarrierShared();
    barrier();
    return tile;
}

// Whether this invocation's cell (live, with its column's `winding`) is
// decided at depth `r` (bake frame) of round `round` (rounds count up within
// a tile), and its label if so; `any` is whether some live cell of the
// workgroup is not, so that the workgroup takes the exact path.
bool vdsTileDecides(VdsBoundary boundary, VdsTileBound tile, float r, int round, bool live, int winding,
                    out bool inside, out bool any) {
    uint local = gl_LocalInvocationID.x;
    int slot = round & 1;
    vec3 c = vec3(tile.centre, r);
    vec2 share = vec2(0.0);
    for (int e = int(local); e < boundary.edgeCount; e += VDS_LOCAL_SIZE) {
        vec3 a = vdsBoundaryEdges[2 * e].xyz, b = vdsBoundaryEdges[2 * e + 1].xyz;
        share.x += vdsEdgeSolidAngle(a, b, c);
        vec3 ab = b - a;
        float l2 = dot(ab, ab);
        float t = l2 > 0.0 ? clamp(dot(c - a, ab) / l2, 0.0, 1.0) : 0.0;
        float gap = length(c - (a + t * ab)) * (1.0 - 1.0e-5) - tile.radius;
        share.y += gap > 0.0 ? sqrt(l2) / (gap * gap) : VDS_INFINITY;
    }
    vdsTileShare[slot][local] = share;
    memoryBarrierShared();
    barrier();
    vec2 sum = vec2(0.0);
    for (int k = 0; k < VDS_LOCAL_SIZE; ++k) sum += vdsTileShare[slot][k];
    float term = sum.x / VDS_FOUR_PI;
    float delta = 1.01 * tile.radius * sum.y / VDS_FOUR_PI + VDS_EXACT_TOLERANCE +
                  VDS_TERM_ERROR * float(boundary.edgeCount);
    float w = float(winding) + term;
    bool decided = r < tile.crossDepth && abs(w - 0.5) > delta; // false where delta is not finite
    inside = w > 0.5;
    if (live && !decided) vdsTileLeft[slot] = round;
    memoryBarrierShared();
    barrier();
    any = vdsTileLeft[slot] == round;
    return decided;
}

#endif
