// vds/columns.glsl: the walk down a sprite's compact columns (GpuSprite's
// offsets and crossings buffers), for the library's compute programs
// (classify.comp's VDS_COLUMNS form, occupancy.comp).
//
// Include it after vds/vpt.glsl (whose vdsCountCrossing is the walk's one
// step, shared with the 3D texture's walk) and after declaring, at the
// program's own binding points,
//   buffer ... { uint offsets[]; };    // column c's crossings: [offsets[c], offsets[c + 1])
//   buffer ... { float crossings[]; }; // sorted front to back, sign bit set where leaving
#ifndef VDS_COLUMNS_GLSL
#define VDS_COLUMNS_GLSL

// Counts the crossings of [e, last) that lie in front of depth r, from e on,
// and leaves e at the first that does not (or at last): a walk resumed at
// increasing depths (occupancy's slices) passes each crossing once.
void vdsWalkColumn(inout uint e, uint last, float r, inout int parity, inout int winding) {
    for (; e < last && vdsCountCrossing(crossings[e], r, parity, winding); ++e) {
    }
}

#endif
