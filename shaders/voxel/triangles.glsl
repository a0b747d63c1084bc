// voxel/triangles.glsl: the mesh as shader storage, for shaders that work per
// triangle (compute voxelizers, fragment shaders that refetch their triangle).
// Binding 0: positions, x y z floats tightly packed; binding 1: three vertex
// indices per triangle.
#ifndef VDS_VOXEL_TRIANGLES_GLSL
#define VDS_VOXEL_TRIANGLES_GLSL

layout(std430, binding = 0) readonly buffer VdsPositions { float vdsPositions[]; };
layout(std430, binding = 1) readonly buffer VdsIndices { uint vdsIndices[]; };

// Corner `corner` (0, 1, 2) of triangle `triangle`, mesh coordinates.
vec3 vdsTriangleVertex(uint triangle, uint corner) {
    uint v = vdsIndices[3u * triangle + corner];
    return vec3(vdsPositions[3u * v], vdsPositions[3u * v + 1u], vdsPositions[3u * v + 2u]);
}

#endif
