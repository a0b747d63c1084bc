// voxel/grid.glsl: the cell grids of vds::voxel (see <vds/voxel/grid.h>).
//
// A mesh point p has cell coordinates v = (p - origin) * scale, origin
// being the VoxelGrid's box.lo and size its dims; cell (i, j, k) holds v in
// [i, i+1) x [j, j+1) x [k, k+1). Bit grids pack 32 cells along z into a
// word, then x, then y (Schwarz 2012, figure 2.4).
// Written with `precise` in the same order as the C++ (compiled without
// fused multiply-adds), so both map a point to the same cell.
#ifndef VDS_VOXEL_GRID_GLSL
#define VDS_VOXEL_GRID_GLSL

struct VdsVoxelGrid {
    vec3 origin; // mesh coordinates of the grid's low corner
    vec3 scale;  // cells per mesh unit along x, y, z
    ivec3 size;  // cells along x, y, z
};

vec3 vdsToCells(VdsVoxelGrid grid, vec3 world) {
    precise vec3 d = world - grid.origin;
    precise vec3 v = d * grid.scale;
    return v;
}

// Nearest multiple of 1/256 (ties upwards): the rasterizer's sub-pixel grid.
// Exact for |v| < 32768.
float vdsSnapToSubcells(float v) {
    precise float f = floor(v * 256.0 + 0.5);
    return f / 256.0;
}

// Words per column of a bit grid, and the word holding cell c.
int vdsZWords(ivec3 size) { return (size.z + 31) >> 5; }
int vdsWordIndex(ivec3 size, ivec3 c) { return (c.y * size.x + c.x) * vdsZWords(size) + (c.z >> 5); }

#endif
