// Geometry-shader slicing voxelization: vertices to cell coordinates, x and y
// snapped like voxel/raster.vert. The instance picks a chunk of slices.
#include "voxel/grid.glsl"

layout(location = 0) in vec3 a_position;
uniform VdsVoxelGrid u_grid;
out vec3 v_cells;
flat out int v_instance;

void main() {
    vec3 v = vdsToCells(u_grid, a_position);
    v_cells = vec3(vdsSnapToSubcells(v.x), vdsSnapToSubcells(v.y), v.z);
    v_instance = gl_InstanceID;
}
