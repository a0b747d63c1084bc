// Baking: mesh coordinates -> LDI texture space -> clip space. The window z is
// T.r / 2 so that the far face (T.r = 1) stays below the cleared depth 1.0
// and GL_LESS keeps the first of equal-depth fragments (lowest triangle).
#include "vds/vpt.glsl"

layout(location = 0) in vec3 a_position;
uniform VdsPlacement u_placement;

void main() {
    vec3 T = vdsToTexture(u_placement, a_position);
#ifdef VDS_CLIP_CONTROL
    gl_Position = vec4(2.0 * T.x - 1.0, 2.0 * T.y - 1.0, 0.5 * T.z, 1.0); // window z = clip z
#else
    gl_Position = vec4(2.0 * T.x - 1.0, 2.0 * T.y - 1.0, T.z - 1.0, 1.0); // window z = (z + 1) / 2
#endif
}
