// vds: the distance hierarchy's search at 8 lanes (AVX2 and FMA), compiled
// for those instructions whatever the rest of the build targets
// (bvh_target.h); Bvh asks for it only where the CPU has them
// (bvhWidthAvailable).
#define VDS_BVH_AVX2 1
#define VDS_BVH_TARGET "avx2,fma"
#include "bvh_target.h"

namespace vds::detail {

#if defined(VDS_BVH_X86)
BvhSearch bvhSearch8() { return Search<Avx, 8>::table(); }
#else
BvhSearch bvhSearch8() { return bvhSearch4(); }
#endif

} // namespace vds::detail

#include "bvh_target_end.h"
