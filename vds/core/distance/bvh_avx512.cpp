// vds: the distance hierarchy's search at 16 lanes (AVX-512F and VL),
// compiled for those instructions whatever the rest of the build targets
// (bvh_target.h); Bvh asks for it only where the CPU has them
// (bvhWidthAvailable).
#define VDS_BVH_AVX512 1
#define VDS_BVH_TARGET "avx512f,avx512vl,avx2,fma"
#include "bvh_target.h"

namespace vds::detail {

#if defined(VDS_BVH_X86)
BvhSearch bvhSearch16() { return Search<Avx512, 16>::table(); }
#else
BvhSearch bvhSearch16() { return bvhSearch4(); }
#endif

} // namespace vds::detail

#include "bvh_target_end.h"
