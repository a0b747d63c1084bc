// vds: the distance hierarchy's search at 4 lanes: SSE2, which every x86-64
// CPU has (one lane at a time elsewhere).
#include <vds/detail/bvh.h>

#include "bvh_search.h"

namespace vds::detail {

BvhSearch bvhSearch4() {
#if defined(__SSE2__)
    return Search<Sse, 4>::table();
#else
    return Search<Scalar, 4>::table();
#endif
}

} // namespace vds::detail
