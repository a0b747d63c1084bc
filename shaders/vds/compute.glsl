// Shared by the compute passes of the bakers and the classifier. Include it
// after the local size declaration (it reads gl_WorkGroupSize).
#ifndef VDS_COMPUTE_GLSL
#define VDS_COMPUTE_GLSL

// This workgroup's number in a grid of workgroups dispatched as rows of up to
// 65535 (x), as the host's dispatchGroups() lays them out.
uint vdsWorkGroupIndex() { return gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x; }

// The step of a grid-stride loop over a one-dimensional dispatch.
uint vdsInvocationCount() { return gl_NumWorkGroups.x * gl_WorkGroupSize.x; }

// The next index of a grid-stride loop over [0, n): i + step, or n when that
// would pass n (so that i never wraps around for n close to 2^32).
uint vdsNextIndex(uint i, uint n) {
    uint step = vdsInvocationCount();
    return n - i > step ? i + step : n;
}

#endif
