// voxel/transmittance.glsl: light left at a receiver behind semi-transparent
// casters, from a slicemap (Eisemann & Decoret 2006, section 3.1), per-voxel
// absorption (Chang et al. 2014, section 4, equation 1) or a volumetric depth
// sprite's exact entry and exit depths (see <vds/voxel/transmittance.h>).
//
// Every representation is built in light space, where a directional light
// travels along +z: vdsToLight maps a world point there. Same arithmetic, in
// the same order, as the C++ references (slicemapSurfacesInFront,
// absorptionInFront, spriteThicknessInFront), so both give the same counts.
#ifndef VDS_VOXEL_TRANSMITTANCE_GLSL
#define VDS_VOXEL_TRANSMITTANCE_GLSL

#include "voxel/slicemap.glsl"
#include "vds/vpt.glsl"

// light = toLight * world (toLight a rotation; column-major like glm).
vec3 vdsToLight(mat3 m, vec3 w) {
    precise float x = (m[0][0] * w.x + m[1][0] * w.y) + m[2][0] * w.z;
    precise float y = (m[0][1] * w.x + m[1][1] * w.y) + m[2][1] * w.z;
    precise float z = (m[0][2] * w.x + m[1][2] * w.y) + m[2][2] * w.z;
    return vec3(x, y, z);
}

// Set bits of slices [0, slice) of one map of `column` (the summask).
int vdsSlicemapBitsBefore(usampler2DArray maps, ivec2 column, int firstLayer, int words, int slice) {
    int n = 0;
    for (int w = 0; w < words && w * 32 < slice; ++w) {
        uint word = vdsSlicemapWord(maps, column, firstLayer, w);
        int keep = slice - w * 32;
        if (keep < 32) word &= (1u << uint(keep)) - 1u;
        n += bitCount(word);
    }
    return n;
}

// Occupied front and back slices in front of the slice of light-space point
// p. `near`, `far`, `perDepth`: the column's range (uniform slicing: 0, S, 1).
int vdsSlicemapSurfacesInRange(usampler2DArray maps, VdsSlicemap map, ivec2 column, float vz, float near, float far,
                               float perDepth) {
    int slices = map.grid.size.z;
    if (!(near <= far) || !(vz >= near)) return 0; // empty column, or in front of everything
    int slice = slices;                             // beyond the far end: every slice
    if (vz <= far) {
        precise float s = floor((vz - near) * perDepth);
        slice = min(int(s), slices - 1);
    }
    int words = slices >> 5;
    return vdsSlicemapBitsBefore(maps, column, 0, words, slice) +
           vdsSlicemapBitsBefore(maps, column, map.backLayer, words, slice);
}

int vdsSlicemapSurfacesInFront(usampler2DArray maps, VdsSlicemap map, vec3 p) {
    vec3 v = vdsToCells(map.grid, p);
    ivec2 column;
    if (!vdsSlicemapColumn(map, v, column)) return 0;
    return vdsSlicemapSurfacesInRange(maps, map, column, v.z, 0.0, float(map.grid.size.z), 1.0);
}

int vdsSlicemapLocalSurfacesInFront(usampler2DArray maps, sampler2D ranges, VdsSlicemap map, vec3 p) {
    vec3 v = vdsToCells(map.grid, p);
    ivec2 column;
    if (!vdsSlicemapColumn(map, v, column)) return 0;
    vec3 range = texelFetch(ranges, column, 0).xyz;
    return vdsSlicemapSurfacesInRange(maps, map, column, v.z, range.x, range.y, range.z);
}

// Summed absorption of the voxels in front of the voxel of light-space point
// p; `absorption` is an R32F 3D texture over `grid` (x, y, z texel = cell).
float vdsAbsorptionInFront(sampler3D absorption, VdsVoxelGrid grid, vec3 p) {
    vec3 v = vdsToCells(grid, p);
    vec2 f = floor(v.xy);
    if (!(f.x >= 0.0 && f.x < float(grid.size.x) && f.y >= 0.0 && f.y < float(grid.size.y))) return 0.0;
    if (!(v.z > 0.0)) return 0.0;
    int end = v.z >= float(grid.size.z) ? grid.size.z : int(floor(v.z));
    ivec2 column = ivec2(f);
    precise float sum = 0.0;
    for (int k = 0; k < end; ++k) sum += texelFetch(absorption, ivec3(column, k), 0).r;
    return sum;
}

// Length, in the sprite's texture depth units r, of the ray through the
// centre of p's texel column from r = 0 to p (at most r = 1) inside the
// solid (non-zero winding). Multiply by the box's extent along the sprite's
// axis for mesh units.
float vdsSpriteThicknessInFront(sampler3D ldi, VdsPlacement placement, vec3 p) {
    vec3 T = vdsToTexture(placement, p);
    ivec3 size = textureSize(ldi, 0);
    if (!(T.z > 0.0)) return 0.0;
    precise float fs = floor(T.x * float(size.x));
    precise float ft = floor(T.y * float(size.y));
    if (!(fs >= 0.0 && fs < float(size.x) && ft >= 0.0 && ft < float(size.y))) return 0.0;
    ivec2 column = ivec2(fs, ft);
    float r = min(T.z, 1.0);
    int winding = 0, parity = 0;
    float entry = 0.0;
    precise float t = 0.0;
    for (int k = 0; k < size.z; ++k) {
        float e = texelFetch(ldi, ivec3(column, k), 0).r;
        int before = winding;
        if (!vdsCountCrossing(e, r, parity, winding)) break; // sorted; the padding 1.0 stops too
        float d = abs(e);
        if (before == 0 && winding != 0) entry = d;
        else if (before != 0 && winding == 0) t += d - entry;
    }
    if (winding != 0) t += r - entry;
    return t;
}

#endif
