// Geometry-shader slicing voxelization: each fragment adds (normal, 1) to its
// voxel (additive blending into RGBA32F): the fragment count gives the
// absorption coefficient, the normal sum the averaged normal (Chang et al.
// 2014, sections 4 and 5).
flat in vec3 g_normal;
layout(location = 0) out vec4 o_voxel;

void main() { o_voxel = vec4(g_normal, 1.0); }
