// Rasterizing a mesh into voxel columns: one pixel per column, the pixel
// centre at the column centre. x and y are snapped to 1/256 of a cell here,
// and the viewport is a power of two (u_viewport pixels square), so that the
// viewport transform and the rasterizer's own snapping are exact: the
// rasterizer sees exactly the triangles the compute voxelizers see.
// v_depth is the cell coordinate along z (for a slicemap: the slice coordinate).
// Clip z is constant: nothing is ever clipped in depth.
#include "voxel/grid.glsl"

layout(location = 0) in vec3 a_position;
uniform VdsVoxelGrid u_grid;
uniform float u_viewport;
out float v_depth;

void main() {
    vec3 v = vdsToCells(u_grid, a_position);
    precise vec2 snapped = vec2(vdsSnapToSubcells(v.x), vdsSnapToSubcells(v.y));
    precise vec2 clip = snapped * (2.0 / u_viewport) - 1.0;
    gl_Position = vec4(clip, 0.0, 1.0);
    v_depth = v.z;
}
