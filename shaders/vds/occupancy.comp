// Occupancy grids on the GPU: the volumetric parity test (Trapp & Doellner
// 2008, section 3.2) for a whole grid column at once, as vds::occupancy does
// on the CPU. One invocation a grid column along the sprite's view axis
// walks that texel column's crossings once, front to back, while it steps
// through the column's cells.
//
// The host computes, with the CPU's arithmetic, each grid column's texel and
// each slice's texture depth, so this shader only compares floats: its
// labels equal the CPU sweep's on every cell. Labels are bytes (1 inside),
// cell index (i * dims.y + j) * dims.z + k, in a buffer of 32-bit words four
// bytes each (low byte first) that the host cleared to 0: each invocation
// ORs in the words its inside cells touch, once per word.
//
// One program per rule (VDS_RULE_ID, vpt.glsl's VDS_RULE_*) and sweep,
// chosen at compile time: no code is kept alive by a uniform. Without the
// boundary term, where the sweep axis is not the labels' fastest (a cell's
// four bytes then lie in four columns, not along one), an invocation takes a
// quad of columns that share their words, so that one atomic writes four
// cells: the four columns follow v (VDS_SWEEP_QUADS_ALONG_V) or u
// (VDS_SWEEP_QUADS_ALONG_U), whichever the labels' fastest axis is; with
// neither, one column an invocation. Rule::GeneralizedWinding on a sprite with boundary edges
// (VDS_BOUNDARY_TERM) adds, per cell, the boundary term at the cell's
// texel-centre point (the point the CPU takes): the one rule whose labels
// are not only compared floats, and O(boundary edges) a cell. There the
// workgroup's columns step through the slices together, so that the term is
// summed by the whole workgroup (boundary_tiles.glsl): the edges staged
// through shared memory, a far chain or loop taken whole when every cell of
// the workgroup's slice may take it.
#define VDS_LOCAL_SIZE 64
layout(local_size_x = VDS_LOCAL_SIZE) in; // before the include: it reads gl_WorkGroupSize
#ifdef VDS_BOUNDARY_TERM
#define VDS_BOUNDARY_BINDING 5 // the boundary edges
#endif
#include "vds/compute.glsl"
#include "vds/vpt.glsl"
#ifdef VDS_BOUNDARY_TERM
#define VDS_TERM_POINTS 1 // one cell a column at a time
#include "vds/boundary_tiles.glsl"
#include "vds/tile_bound.glsl"
#endif

layout(std430, binding = 0) readonly restrict buffer Offsets { uint offsets[]; };
layout(std430, binding = 1) readonly restrict buffer Crossings { float crossings[]; };
layout(std430, binding = 2) readonly restrict buffer Texels { int texels[]; }; // per grid column; -1: outside
layout(std430, binding = 3) readonly restrict buffer Depths { float depths[]; }; // per slice, increasing
layout(std430, binding = 4) restrict buffer Cells { uint cells[]; };
#include "vds/columns.glsl"

uniform uint u_columns;    // grid columns: dims[u] * dims[v]
uniform uint u_dimV;       // column c is (c / dimV, c % dimV) along (u, v)
uniform uint u_strideU;    // label index steps along u, v and the view axis
uniform uint u_strideV;
uniform uint u_step;
uniform uint u_firstSlice; // slices [first, end) lie in the sprite's depth range
uniform uint u_endSlice;
uniform uint u_width;      // the sprite's width in texels: texel = t * width + s
uniform uint u_dimU;       // grid columns along u
#if defined(VDS_SWEEP_QUADS_ALONG_V) || defined(VDS_SWEEP_QUADS_ALONG_U)
#define VDS_SWEEP_QUADS
uniform uint u_quads;      // quads along the quad axis
#endif
#ifdef VDS_BOUNDARY_TERM
uniform VdsBoundary u_boundary;
uniform ivec2 u_size; // the sprite's width and height in texels
// Per grid column: its texture (s, t), for the cells of a column beside the
// texture, whose term is taken at the cell itself (texels[] is then -1).
layout(std430, binding = 6) readonly restrict buffer ColumnPoints { vec2 columnPoints[]; };
#endif

void vdsFlush(uint word, uint bits) {
    if (bits != 0u) atomicOr(cells[word], bits);
}

// Marks cell `index` inside: its bit in the word being gathered, the word
// before flushed when the cell lies in another.
void vdsMark(uint index, inout uint word, inout uint bits) {
    if (index >> 2u != word) {
        vdsFlush(word, bits);
        word = index >> 2u;
        bits = 0u;
    }
    bits |= 1u << (8u * (index & 3u));
}


// Walks grid column `column`'s cells (none where `live` is false, which
// still takes every step for the workgroup's votes and tiles). With the
// boundary term every slice of the grid is walked (u_firstSlice 0), in
// front of and behind the box (none or all of the column's crossings in
// front), and columns beside the texture too (no crossing, the term at the
// cell itself), as the CPU classifies those cells.
void vdsSweepColumn(uint column, bool live) {
    int texel = live ? texels[column] : -1;
#ifdef VDS_BOUNDARY_TERM
    bool valid = live; // a column of the grid: beside the texture too
    vec2 beside = live ? columnPoints[column] : vec2(0.0);
#endif
    live = texel >= 0;
#ifndef VDS_BOUNDARY_TERM
    if (!live) return;
#endif
    uint base = (column / u_dimV) * u_strideU + (column % u_dimV) * u_strideV;
    uint e = live ? offsets[texel] : 0u, last = live ? offsets[texel + 1] : 0u;
    ivec2 st = ivec2(int(uint(max(texel, 0)) % u_width), int(uint(max(texel, 0)) / u_width));
    int parity = 0, winding = 0;
    uint word = 0u, bits = 0u;
#ifdef VDS_BOUNDARY_TERM
    // The column's cells' (s, t) in the bake's frame: the same at every depth.
    vec2 at = live ? vdsColumnPoint(u_boundary, st, 0.0).xy : vdsBesidePoint(u_boundary, u_size, vec3(beside, 0.0)).xy;
    VdsTileBound tile = vdsTileSetup(u_boundary, at, valid);
#endif
    for (uint k = u_firstSlice; k < u_endSlice; ++k) {
        float depth = depths[k];
        vdsWalkColumn(e, last, depth, parity, winding);
#ifdef VDS_BOUNDARY_TERM
        vec3 q[1] = vec3[1](live ? vdsColumnPoint(u_boundary, st, depth)
                                 : vdsBesidePoint(u_boundary, u_size, vec3(beside, depth)));
        bool inside, any;
        bool decided = vdsTileDecides(u_boundary, tile, q[0].z, int(k), valid, winding, inside, any);
        if (any) { // some cell of the workgroup is not decided by the tile's bound: the exact term
            bool alive[1] = bool[1](valid);
            float term[1];
            vdsBoundaryTerms(u_boundary, q, alive, term);
            if (!decided) inside = float(winding) + term[0] > 0.5;
        }
        inside = valid && inside;
#elif VDS_RULE_ID == VDS_RULE_WINDING
        bool inside = winding != 0;
#else
        bool inside = parity != 0;
#endif
        if (inside) vdsMark(base + k * u_step, word, bits); // (no `continue`: the loop stays uniform for the barriers)
    }
    vdsFlush(word, bits);
}

#ifdef VDS_SWEEP_QUADS
// The quad's column j (count 4, some past the grid's edge where its size is
// not a multiple of 4): -1 where none.
int vdsQuadColumn(uint quad, uint j) {
#ifdef VDS_SWEEP_QUADS_ALONG_V
    uint iu = quad / u_quads;
    uint iv = 4u * (quad % u_quads) + j;
#else
    uint iv = quad % u_dimV;
    uint iu = 4u * (quad / u_dimV) + j;
#endif
    return iu < u_dimU && iv < u_dimV ? int(iu * u_dimV + iv) : -1;
}

// Four columns at once, slice by slice: their cells at a slice share a
// word (two where the fastest axis's size is not a multiple of 4), flushed
// once.
void vdsSweepQuad(uint quad) {
    uint base[4], e[4], last[4];
    int parity[4], winding[4];
    bool live[4]; // a column of the grid inside the sprite's texture
    for (uint j = 0u; j < 4u; ++j) {
        int column = vdsQuadColumn(quad, j);
        int texel = column >= 0 ? texels[column] : -1;
        uint c = uint(max(column, 0));
        base[j] = (c / u_dimV) * u_strideU + (c % u_dimV) * u_strideV;
        e[j] = texel >= 0 ? offsets[texel] : 0u;
        last[j] = texel >= 0 ? offsets[texel + 1] : 0u;
        parity[j] = 0;
        winding[j] = 0;
        live[j] = texel >= 0;
    }
    uint word = 0u, bits = 0u;
    for (uint k = u_firstSlice; k < u_endSlice; ++k) {
        float depth = depths[k];
        for (uint j = 0u; j < 4u; ++j) {
            vdsWalkColumn(e[j], last[j], depth, parity[j], winding[j]);
#if VDS_RULE_ID == VDS_RULE_WINDING
            bool inside = live[j] && winding[j] != 0;
#else
            bool inside = live[j] && parity[j] != 0;
#endif
            if (inside) vdsMark(base[j] + k * u_step, word, bits);
        }
    }
    vdsFlush(word, bits);
}
#endif

#ifdef VDS_BOUNDARY_TERM
// The workgroup's columns as a square of 8 x 8 (u, v) (VDS_LOCAL_SIZE 64):
// its cells at a slice lie within a few cells of one another, so a chain
// or loop far from them all is taken whole by the vote more often than
// along a line of 64 columns.
#define VDS_TILE_SIDE 8u
#endif

void main() {
#ifdef VDS_BOUNDARY_TERM
    // Workgroup by workgroup (one tile of columns): `tile` is the same in
    // every invocation.
    uint tilesV = (u_dimV + VDS_TILE_SIDE - 1u) / VDS_TILE_SIDE;
    uint tiles = tilesV * ((u_dimU + VDS_TILE_SIDE - 1u) / VDS_TILE_SIDE);
    uint local = gl_LocalInvocationID.x;
    for (uint tile = vdsWorkGroupIndex(); tile < tiles; tile += gl_NumWorkGroups.x * gl_NumWorkGroups.y) {
        uint iu = (tile / tilesV) * VDS_TILE_SIDE + local / VDS_TILE_SIDE;
        uint iv = (tile % tilesV) * VDS_TILE_SIDE + local % VDS_TILE_SIDE;
        bool live = iu < u_dimU && iv < u_dimV;
        vdsSweepColumn(live ? iu * u_dimV + iv : 0u, live);
    }
#else
#if defined(VDS_SWEEP_QUADS_ALONG_V)
    uint items = u_dimU * u_quads;
#elif defined(VDS_SWEEP_QUADS_ALONG_U)
    uint items = u_dimV * ((u_dimU + 3u) / 4u);
#else
    uint items = u_columns;
#endif
    for (uint item = vdsWorkGroupIndex() * gl_WorkGroupSize.x + gl_LocalInvocationID.x; item < items;
         item = vdsNextIndex(item, items)) {
#ifdef VDS_SWEEP_QUADS
        vdsSweepQuad(item);
#else
        vdsSweepColumn(item, true);
#endif
    }
#endif
}
