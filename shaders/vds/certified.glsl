// vds/certified.glsl: exact answers in any shader stage, where the certified
// bands can give them.
//
// A `CertifiedClassifier` (<vds/certified.h>) proves, per texel column of a
// grid over the mesh's box, where the surface cannot be: between its
// "uncertain bands" every depth has one known winding number. This include
// answers a point from those bands: 1 inside, 0 outside (the exact
// classifier's answer, on every point), or VDS_UNSURE (-1) where the bands
// cannot tell (the point lies in a band, on the box's boundary, is not
// finite, or the rule is not certified for the mesh); those points need the
// exact classifier (a renderer can draw them from the sprite, or mark them).
//
//   #define VDS_CERTIFIED_OFFSETS_BINDING 3
//   #define VDS_CERTIFIED_BANDS_BINDING 4
//   #include "vds/certified.glsl"
//   uniform VdsCertified u_certified;     // GpuCertifiedBands::setUniforms
//   int answer = vdsContainsCertain(u_certified, meshPoint, VDS_RULE_PARITY);
//
// Points are in the mesh's coordinates. The bands are read from two shader
// storage buffers at the caller's bindings (<vds/gl/certified.h> binds them):
//   offsets  uint[columns + 1]: column c = j * width + i has bands
//            [offsets[c], offsets[c+1]), sorted by depth, disjoint;
//   bands    VdsBand[]: {lo, hi, windingAbove}, 12 bytes each.
//
// Why a texel found here in float may be trusted: the point's column comes
// from vpt.glsl's vdsToTexture and vdsColumnOf, the sprite's lookup,
// computed `precise` (no fused multiply-add) in the same order as the C++
// `SpriteGrid::toTexture`; any rounding difference against the C++ lookup
// is a few ulps of the texture coordinate, at most a few thousandths of a
// texel at 16384 texels. Each band's footprint is widened by 1/64 texel for
// exactly that (certified.cpp), so the column found here contains the point
// in its widened footprint even when it is the neighbour of the C++ one,
// and its gaps certify the point. The box and band comparisons are exact
// float comparisons; a GPU that flushes denormals moves values
// monotonically, which can turn a strict comparison into an equality, and
// every equality here answers VDS_UNSURE: never a wrong certain answer.
#ifndef VDS_CERTIFIED_GLSL
#define VDS_CERTIFIED_GLSL

#include "vds/vpt.glsl"

#if !defined(VDS_CERTIFIED_OFFSETS_BINDING) || !defined(VDS_CERTIFIED_BANDS_BINDING)
#error "define VDS_CERTIFIED_OFFSETS_BINDING and VDS_CERTIFIED_BANDS_BINDING before including vds/certified.glsl"
#endif

#define VDS_UNSURE (-1)

struct VdsBand {
    float lo;
    float hi;
    int windingAbove;
};

layout(std430, binding = VDS_CERTIFIED_OFFSETS_BINDING) readonly restrict buffer VdsCertifiedOffsets {
    uint vdsCertifiedOffsets[];
};
layout(std430, binding = VDS_CERTIFIED_BANDS_BINDING) readonly restrict buffer VdsCertifiedBands {
    VdsBand vdsCertifiedBands[];
};

// The bands' frame (GpuCertifiedBands::setUniforms):
//   placement  the grid's P_S and M_S (mesh -> texture space)
//   size       the grid's width and height in texels
//   lo, hi     the mesh's box; depthAxis 0, 1, 2 for x, y, z
//   rules      bit (1 << VDS_RULE_*) for each rule the bands certify
struct VdsCertified {
    VdsPlacement placement;
    ivec2 size;
    vec3 lo;
    vec3 hi;
    int depthAxis;
    int rules;
};

// Whether x is an infinity or a NaN, by its bits: comparisons with NaN are
// not to be trusted on every GPU compiler.
bool vdsNotFinite(float x) { return (floatBitsToUint(x) & 0x7f800000u) == 0x7f800000u; }

// 1 inside, 0 outside, VDS_UNSURE where only the exact classifier can tell.
int vdsContainsCertain(VdsCertified c, vec3 p, int rule) {
    if (((c.rules >> rule) & 1) == 0) return VDS_UNSURE;
    if (vdsNotFinite(p.x) || vdsNotFinite(p.y) || vdsNotFinite(p.z)) return VDS_UNSURE;
    bool outside = false, onBoundary = false;
    for (int a = 0; a < 3; ++a) {
        if (p[a] < c.lo[a] || p[a] > c.hi[a]) outside = true;
        else if (p[a] == c.lo[a] || p[a] == c.hi[a]) onBoundary = true;
    }
    if (outside) return 0; // no surface out there
    if (onBoundary) return VDS_UNSURE;
    ivec2 column;
    if (!vdsColumnOf(vdsToTexture(c.placement, p), c.size, column)) return VDS_UNSURE;
    uint at = uint(column.y) * uint(c.size.x) + uint(column.x);
    uint end = vdsCertifiedOffsets[at + 1u];
    float z = p[c.depthAxis];
    int winding = 0;
    for (uint b = vdsCertifiedOffsets[at]; b < end; ++b) {
        VdsBand band = vdsCertifiedBands[b];
        if (z < band.lo) break;
        if (z <= band.hi) return VDS_UNSURE;
        winding = band.windingAbove;
    }
    bool inside = rule == VDS_RULE_PARITY ? (winding & 1) != 0 : winding != 0;
    return inside ? 1 : 0;
}

#endif
