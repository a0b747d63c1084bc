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
// Rule::GeneralizedWinding (u_rule 2) adds, per cell, the boundary term at
// the cell's texel-centre point (vpt.glsl's vdsContainsGeneralizedAt, the
// point the CPU takes): the one rule whose labels are not only compared
// floats, and O(boundary edges) a cell.
layout(local_size_x = 64) in; // before the include: it reads gl_WorkGroupSize
#define VDS_BOUNDARY_BINDING 5 // the boundary edges, for Rule::GeneralizedWinding
#include "vds/compute.glsl"
#include "vds/vpt.glsl"

layout(std430, binding = 0) readonly restrict buffer Offsets { uint offsets[]; };
layout(std430, binding = 1) readonly restrict buffer Crossings { float crossings[]; };
layout(std430, binding = 2) readonly restrict buffer Texels { int texels[]; }; // per grid column; -1: outside
layout(std430, binding = 3) readonly restrict buffer Depths { float depths[]; }; // per slice, increasing
layout(std430, binding = 4) restrict buffer Cells { uint cells[]; };

uniform uint u_columns;    // grid columns: dims[u] * dims[v]
uniform uint u_dimV;       // column c is (c / dimV, c % dimV) along (u, v)
uniform uint u_strideU;    // label index steps along u, v and the view axis
uniform uint u_strideV;
uniform uint u_step;
uniform uint u_firstSlice; // slices [first, end) lie in the sprite's depth range
uniform uint u_endSlice;
uniform int u_rule;        // 0 parity, 1 winding, 2 generalized winding
uniform uint u_width;      // the sprite's width in texels: texel = t * width + s
uniform VdsBoundary u_boundary; // read by u_rule 2 only

void vdsFlush(uint word, uint bits) {
    if (bits != 0u) atomicOr(cells[word], bits);
}

void main() {
    for (uint column = vdsWorkGroupIndex() * gl_WorkGroupSize.x + gl_LocalInvocationID.x; column < u_columns;
         column = vdsNextIndex(column, u_columns)) {
        int texel = texels[column];
        if (texel < 0) continue;
        uint base = (column / u_dimV) * u_strideU + (column % u_dimV) * u_strideV;
        uint e = offsets[texel], last = offsets[texel + 1];
        ivec2 st = ivec2(int(uint(texel) % u_width), int(uint(texel) / u_width));
        int parity = 0, winding = 0;
        uint word = 0u, bits = 0u;
        for (uint k = u_firstSlice; k < u_endSlice; ++k) {
            float depth = depths[k];
            // Each crossing counts for the cells whose depth lies strictly behind it.
            for (; e < last && abs(crossings[e]) < depth; ++e) {
                parity ^= 1;
                winding += floatBitsToInt(crossings[e]) < 0 ? -1 : 1;
            }
            bool inside = u_rule == 2   ? vdsContainsGeneralizedAt(u_boundary, winding, st, depth)
                          : u_rule == 1 ? winding != 0
                                        : parity != 0;
            if (!inside) continue;
            uint index = base + k * u_step;
            if (index >> 2u != word) {
                vdsFlush(word, bits);
                word = index >> 2u;
                bits = 0u;
            }
            bits |= 1u << (8u * (index & 3u));
        }
        vdsFlush(word, bits);
    }
}
