// vds: the end of a translation unit that bvh_target.h began: the
// instruction set it switched on is switched off again.
#if defined(VDS_BVH_X86)
#if defined(__clang__)
#pragma clang attribute pop
#else
#pragma GCC pop_options
#endif
#endif
