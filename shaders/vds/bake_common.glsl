// Shared by the bakers' fragment shaders: one crossing per fragment.
// glFrontFace(GL_CW) is set so gl_FrontFacing means "the ray enters here".
#ifndef VDS_BAKE_COMMON_GLSL
#define VDS_BAKE_COMMON_GLSL

const uint VDS_ENTERING_BIT = 0x80000000u;

// Depth of this fragment's crossing in LDI texture space, in [0, 1].
float vdsFragmentDepth() { return clamp(gl_FragCoord.z * 2.0, 0.0, 1.0); }

// Triangle index and facing, packed: the sort key after the depth.
uint vdsFragmentKey() { return uint(gl_PrimitiveID) | (gl_FrontFacing ? VDS_ENTERING_BIT : 0u); }

#endif
