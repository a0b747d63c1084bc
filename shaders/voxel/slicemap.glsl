// voxel/slicemap.glsl: point-in-solid against a front/back slicemap pair, in
// any shader stage (Eisemann & Decoret 2006, section 3.3; see
// <vds/voxel/slicemap.h> for the layout and the inner-voxel rule).
//
// The pair is one RGBA32UI 2D array texture: layers [0, T) hold the front
// map, layers [T, 2T) the back map (T = VdsSlicemap.backLayer); word w of a
// column is channel w % 4 of layer w / 4 of its map, slice s is bit s % 32 of
// word s / 32. Depth is the slice coordinate v.z of voxel/grid.glsl (uniform
// slicing: slice floor(v.z)). Local slicing adds an RGBA32F 2D texture of
// (near, far, slices per unit of v.z) per column: slice floor((v.z - near) *
// perDepth) for v.z in [near, far]. Same answers as vds::voxel::Slicemap::contains:
//   uniform usampler2DArray u_slicemap; uniform VdsSlicemap u_map;
//   if (vdsSlicemapContains(u_slicemap, u_map, worldPosition)) ...             // uniform slicing
//   if (vdsSlicemapLocalContains(u_slicemap, u_ranges, u_map, worldPosition)) // local slicing
// (Samplers of different types must use different texture units.)
#ifndef VDS_VOXEL_SLICEMAP_GLSL
#define VDS_VOXEL_SLICEMAP_GLSL

#include "voxel/grid.glsl"

struct VdsSlicemap {
    VdsVoxelGrid grid; // columns across x, y; size.z = slices; the cell z coordinate is the slice coordinate
    int backLayer;     // first layer of the back map = layers per map
};

uint vdsSlicemapWord(usampler2DArray maps, ivec2 column, int firstLayer, int word) {
    uvec4 t = texelFetch(maps, ivec3(column, firstLayer + (word >> 2)), 0);
    return t[word & 3];
}

// The inner-voxel rule at `slice` of `column`.
bool vdsSlicemapInside(usampler2DArray maps, VdsSlicemap map, ivec2 column, int slice) {
    int words = map.grid.size.z >> 5;
    int w0 = slice >> 5;
    uint bit = 1u << uint(slice & 31);
    uint f0 = vdsSlicemapWord(maps, column, 0, w0);
    uint b0 = vdsSlicemapWord(maps, column, map.backLayer, w0);
    if (((f0 | b0) & bit) != 0u) return true; // a boundary voxel
    // The last boundary voxel in front.
    for (int w = w0; w >= 0; --w) {
        uint f = w == w0 ? f0 : vdsSlicemapWord(maps, column, 0, w);
        uint b = w == w0 ? b0 : vdsSlicemapWord(maps, column, map.backLayer, w);
        uint m = (f | b) & (w == w0 ? bit - 1u : 0xffffffffu);
        if (m == 0u) continue;
        uint k = uint(findMSB(m));
        bool front = ((f >> k) & 1u) != 0u, back = ((b >> k) & 1u) != 0u;
        if (!back) return true;   // after a front voxel: inside
        if (!front) return false; // after a back voxel: outside
        // After an ambiguous voxel: the next boundary voxel decides.
        for (int v = w0; v < words; ++v) {
            uint fv = v == w0 ? f0 : vdsSlicemapWord(maps, column, 0, v);
            uint bv = v == w0 ? b0 : vdsSlicemapWord(maps, column, map.backLayer, v);
            uint n = (fv | bv) & (v == w0 ? ~(bit | (bit - 1u)) : 0xffffffffu);
            if (n == 0u) continue;
            uint j = uint(findLSB(n));
            return ((bv >> j) & 1u) != 0u && ((fv >> j) & 1u) == 0u;
        }
        return false;
    }
    return false; // nothing in front
}

// The slice of a point's depth v.z in the range [near, far] with `perDepth`
// slices per unit; false outside the range.
bool vdsSlicemapLocate(VdsSlicemap map, vec3 v, float near, float far, float perDepth, out int slice) {
    slice = 0;
    if (!(v.z >= near && v.z <= far)) return false;
    precise float s = floor((v.z - near) * perDepth);
    slice = min(int(s), map.grid.size.z - 1);
    return true;
}

bool vdsSlicemapColumn(VdsSlicemap map, vec3 v, out ivec2 column) {
    vec2 f = floor(v.xy);
    column = ivec2(0);
    if (!(f.x >= 0.0 && f.x < float(map.grid.size.x) && f.y >= 0.0 && f.y < float(map.grid.size.y))) return false;
    column = ivec2(f);
    return true;
}

bool vdsSlicemapContains(usampler2DArray maps, VdsSlicemap map, vec3 world) {
    vec3 v = vdsToCells(map.grid, world);
    ivec2 column;
    int slice;
    if (!vdsSlicemapColumn(map, v, column)) return false;
    if (!vdsSlicemapLocate(map, v, 0.0, float(map.grid.size.z), 1.0, slice)) return false;
    return vdsSlicemapInside(maps, map, column, slice);
}

bool vdsSlicemapLocalContains(usampler2DArray maps, sampler2D ranges, VdsSlicemap map, vec3 world) {
    vec3 v = vdsToCells(map.grid, world);
    ivec2 column;
    int slice;
    if (!vdsSlicemapColumn(map, v, column)) return false;
    vec3 range = texelFetch(ranges, column, 0).xyz;
    if (!vdsSlicemapLocate(map, v, range.x, range.y, range.z, slice)) return false;
    return vdsSlicemapInside(maps, map, column, slice);
}

#endif
