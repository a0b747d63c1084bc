// Geometry-shader slicing voxelization (Chang et al. 2014, figure 2): the
// triangle is emitted once per slice its depth range spans, into layer k of
// the 3D texture, clipped to the slab [k - pad, k + 1 + pad] by two clip
// distances. One invocation handles VDS_SLICES_PER_INSTANCE slices, those of
// its instance's chunk. Defines: VDS_SLICES_PER_INSTANCE.
#include "voxel/grid.glsl"

layout(triangles) in;
layout(triangle_strip, max_vertices = 3 * VDS_SLICES_PER_INSTANCE) out;
in vec3 v_cells[];
flat in int v_instance[];
uniform VdsVoxelGrid u_grid;
uniform float u_viewport;
uniform float u_padding;
out float gl_ClipDistance[2];
flat out vec3 g_normal;

void main() {
    vec3 a = v_cells[0], b = v_cells[1], c = v_cells[2];
    vec3 n = cross(b - a, c - a);
    if (dot(n, n) == 0.0) return;
    n = normalize(n); // cells are cubes: the normal in cell space is the mesh's
    float zmin = min(a.z, min(b.z, c.z)), zmax = max(a.z, max(b.z, c.z));
    int chunk = v_instance[0] * VDS_SLICES_PER_INSTANCE;
    int first = max(max(int(floor(zmin - u_padding)), 0), chunk);
    int last = min(min(int(floor(zmax + u_padding)), u_grid.size.z - 1), chunk + VDS_SLICES_PER_INSTANCE - 1);
    for (int k = first; k <= last; ++k) {
        for (int i = 0; i < 3; ++i) {
            vec3 v = v_cells[i];
            precise vec2 clip = v.xy * (2.0 / u_viewport) - 1.0;
            gl_Position = vec4(clip, 0.0, 1.0);
            gl_ClipDistance[0] = v.z - (float(k) - u_padding);
            gl_ClipDistance[1] = (float(k + 1) + u_padding) - v.z;
            gl_Layer = k;
            g_normal = n;
            EmitVertex();
        }
        EndPrimitive();
    }
}
