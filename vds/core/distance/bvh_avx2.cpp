// vds: the distance hierarchy's search at 8 lanes (AVX2 and FMA), compiled
// for those instructions whatever the rest of the build targets; Bvh asks
// for it only where the CPU has them (bvhWidthAvailable). Every header
// bvh_search.h needs comes first, so only this file's own functions are
// compiled for AVX2.
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include <glm/vec3.hpp>

#include <vds/detail/bvh.h>

#if (defined(__x86_64__) || defined(__i386__)) && defined(__GNUC__)
#include <immintrin.h>
#if defined(__clang__)
#pragma clang attribute push(__attribute__((target("avx2,fma"))), apply_to = function)
#else
#pragma GCC push_options
#pragma GCC target("avx2,fma")
#endif
#define VDS_BVH_AVX2 1
#include "bvh_search.h"

namespace vds::detail {
BvhSearch bvhSearch8() { return Search<Avx, 8>::table(); }
} // namespace vds::detail

#if defined(__clang__)
#pragma clang attribute pop
#else
#pragma GCC pop_options
#endif
#else
namespace vds::detail {
BvhSearch bvhSearch8() { return bvhSearch4(); }
} // namespace vds::detail
#endif
