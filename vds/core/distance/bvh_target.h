// vds: the start of a translation unit of the distance search compiled for
// one instruction set (bvh_avx2.cpp, bvh_avx512.cpp), named by the
// includer's VDS_BVH_TARGET (GCC's and Clang's target string). Every header
// bvh_search.h needs comes first, compiled as the rest of the build; then
// the instruction set is switched on for the rest of the file, and
// bvh_search.h read under it; bvh_target_end.h switches it off. Defines
// VDS_BVH_X86 where this can be done (x86 with GCC or Clang); elsewhere the
// includer answers with the 4-lane search. No include guard: each includer
// reads it once.
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include <glm/vec3.hpp>

#include <vds/detail/bvh.h>

#if (defined(__x86_64__) || defined(__i386__)) && defined(__GNUC__)
#define VDS_BVH_X86 1
#include <immintrin.h>
#define VDS_BVH_PRAGMA(text) _Pragma(#text)
#if defined(__clang__)
#define VDS_BVH_PUSH(isa) VDS_BVH_PRAGMA(clang attribute push(__attribute__((target(isa))), apply_to = function))
#else
#define VDS_BVH_PUSH(isa) VDS_BVH_PRAGMA(GCC push_options) VDS_BVH_PRAGMA(GCC target(isa))
#endif
VDS_BVH_PUSH(VDS_BVH_TARGET)
#include "bvh_search.h"
#endif
